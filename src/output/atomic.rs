//! Files are written whole or not at all: into a temporary file beside the target, renamed
//! over it once complete. An interrupted or failed run leaves no half file.
//!
//! A command with several outputs stages each one ([`stage`]) and commits them together
//! once all are complete, so that one failing output leaves none of the others behind. Every
//! live temporary is registered: [`remove_temporaries`] deletes them (the binary calls it on
//! SIGINT and SIGTERM), and a [`Staged`] file that is dropped without being committed removes
//! its temporary.

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::Mutex;

/// Temporaries not yet committed or removed.
static LIVE: Mutex<Vec<PathBuf>> = Mutex::new(Vec::new());

fn live() -> std::sync::MutexGuard<'static, Vec<PathBuf>> {
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Deletes every temporary still live, files and folders (for a signal handler: the process
/// is about to end).
pub fn remove_temporaries() {
    for tmp in live().drain(..) {
        if tmp.is_dir() {
            let _ = std::fs::remove_dir_all(tmp);
        } else {
            let _ = std::fs::remove_file(tmp);
        }
    }
}

/// Registers a temporary of the run's own (a folder being filled) for [`remove_temporaries`].
pub fn track(path: &Path) {
    live().push(path.to_path_buf());
}

/// Withdraws a temporary registered by [`track`] (renamed into place or removed).
pub fn untrack(path: &Path) {
    live().retain(|t| t != path);
}

/// A complete temporary file waiting to replace its target.
#[derive(Debug)]
pub struct Staged {
    tmp: PathBuf,
    path: PathBuf,
    committed: bool,
}

impl Staged {
    /// The target this file will replace.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Renames the temporary over the target.
    pub fn commit(mut self) -> io::Result<()> {
        refuse_non_regular(&self.path)?;
        std::fs::rename(&self.tmp, &self.path)?;
        self.committed = true;
        live().retain(|t| t != &self.tmp);
        Ok(())
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        if !self.committed {
            let _ = std::fs::remove_file(&self.tmp);
            live().retain(|t| t != &self.tmp);
        }
    }
}

/// An existing target that is not a regular file (a directory, a device) is never replaced.
fn refuse_non_regular(path: &Path) -> io::Result<()> {
    match std::fs::metadata(path) {
        Ok(meta) if !meta.is_file() => Err(io::Error::new(
            io::ErrorKind::InvalidInput,
            "it exists and is not a regular file (a directory or a device): only regular files are written",
        )),
        _ => Ok(()),
    }
}

/// Writes the whole content of `path` into a temporary beside it through `fill`; on any
/// error the temporary is removed.
pub fn stage<E>(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<Staged, E>
where
    E: From<io::Error>,
{
    refuse_non_regular(path)?;
    let dir = match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    };
    let name = path
        .file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "it names no file"))?;
    let tmp = dir.join(format!(".{name}.{}.tmp", std::process::id()));
    live().push(tmp.clone());
    let staged = Staged {
        tmp,
        path: path.to_path_buf(),
        committed: false,
    };
    let file = std::fs::File::create(&staged.tmp)?;
    let mut w = BufWriter::new(file);
    fill(&mut w)?;
    let file = w.into_inner().map_err(|e| e.into_error())?;
    file.sync_all()?;
    Ok(staged)
}

/// Commits staged files in order (the outputs of one run, all complete by now); the error
/// names the file that could not be put in place.
pub fn commit_all(staged: Vec<Staged>) -> io::Result<()> {
    for file in staged {
        let path = file.path().to_path_buf();
        file.commit().map_err(|e| {
            io::Error::new(e.kind(), format!("{}: cannot write: {e}", path.display()))
        })?;
    }
    Ok(())
}

/// Writes `path` through `fill`; on any error the temporary file is removed and `path` is
/// left as it was.
pub fn write_atomically<E>(
    path: &Path,
    fill: impl FnOnce(&mut dyn Write) -> Result<(), E>,
) -> Result<(), E>
where
    E: From<io::Error>,
{
    Ok(stage(path, fill)?.commit()?)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("jointid-atomic-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn failure_leaves_neither_target_nor_temporary() {
        let dir = scratch("fail");
        let target = dir.join("out.csv");
        let r: Result<(), io::Error> = write_atomically(&target, |w| {
            w.write_all(b"half")?;
            Err(io::Error::other("boom"))
        });
        assert!(r.is_err());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 0);
        write_atomically::<io::Error>(&target, |w| w.write_all(b"whole")).unwrap();
        assert_eq!(std::fs::read_to_string(&target).unwrap(), "whole");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn staged_files_appear_only_on_commit_and_vanish_when_dropped() {
        let dir = scratch("staged");
        let a = stage::<io::Error>(&dir.join("a.csv"), |w| w.write_all(b"a")).unwrap();
        let b = stage::<io::Error>(&dir.join("b.csv"), |w| w.write_all(b"b")).unwrap();
        assert!(!dir.join("a.csv").exists() && !dir.join("b.csv").exists());
        a.commit().unwrap();
        drop(b);
        let names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert_eq!(names, vec!["a.csv".to_string()]);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_directory_is_never_replaced() {
        let dir = scratch("dir");
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let err =
            write_atomically::<io::Error>(&dir.join("sub"), |w| w.write_all(b"x")).unwrap_err();
        assert!(err.to_string().contains("not a regular file"), "{err}");
        assert!(dir.join("sub").is_dir());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

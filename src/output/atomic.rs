//! Files are written whole or not at all: into a temporary file beside the target, renamed
//! over it once complete. An interrupted or failed run leaves no half file.
//!
//! A temporary is created exclusively (`O_EXCL`, never through a symbolic link) in the
//! target's own folder under an unpredictable name (`.NAME.XXXXXX.tmp`, the `tempfile`
//! crate), so that no file planted in a shared folder can be overwritten through it, and the
//! run never deletes a file it did not create.
//!
//! A command with several outputs stages each one ([`stage`]) and commits them together
//! once all are complete, so that one failing output leaves none of the others behind. Every
//! live temporary, and every folder the run created ([`create_folders`]), is registered: on a
//! signal the binary calls [`remove_temporaries_and_exit`], on an error
//! [`remove_temporaries`]; a [`Staged`] file that is dropped without being committed removes
//! its temporary. A temporary is created and registered under one lock, and the signal path
//! keeps that lock until the process ends, so no temporary can appear after the clean-up.

use std::io::{self, BufWriter, Write};
use std::path::{Path, PathBuf};
use std::sync::{Mutex, MutexGuard};

/// What the run created and has not yet put in place: temporaries (files and staging
/// folders), and the folders it created, in creation order.
struct Live {
    temporaries: Vec<PathBuf>,
    folders: Vec<PathBuf>,
}

static LIVE: Mutex<Live> = Mutex::new(Live {
    temporaries: Vec::new(),
    folders: Vec::new(),
});

fn live() -> MutexGuard<'static, Live> {
    LIVE.lock().unwrap_or_else(|poisoned| poisoned.into_inner())
}

/// Deletes every temporary still live, then every folder the run created that is empty by
/// now, deepest first; a folder holding a finished output stays.
fn clean(live: &mut Live) {
    for tmp in live.temporaries.drain(..) {
        if tmp.is_dir() {
            let _ = std::fs::remove_dir_all(tmp);
        } else {
            let _ = std::fs::remove_file(tmp);
        }
    }
    for folder in live.folders.drain(..).rev() {
        let _ = std::fs::remove_dir(folder);
    }
}

/// Deletes every temporary still live and every empty folder the run created (after an
/// error: nothing of the failed run stays behind).
pub fn remove_temporaries() {
    clean(&mut live());
}

/// For a signal handler: cleans up as [`remove_temporaries`], then ends the process with
/// `code` while still holding the registry, so that no other thread can create a temporary
/// after the clean-up.
pub fn remove_temporaries_and_exit(code: i32) -> ! {
    let mut guard = live();
    clean(&mut guard);
    std::process::exit(code)
}

/// Registers a temporary of the run's own (a folder being filled) for the clean-up.
pub fn track(path: &Path) {
    live().temporaries.push(path.to_path_buf());
}

/// Withdraws a temporary registered by [`track`] (renamed into place or removed).
pub fn untrack(path: &Path) {
    live().temporaries.retain(|t| t != path);
}

/// The folder of `path` (`.` for a bare name).
fn folder_of(path: &Path) -> &Path {
    match path.parent() {
        Some(p) if !p.as_os_str().is_empty() => p,
        _ => Path::new("."),
    }
}

/// The file name of `path`, for temporaries beside it.
fn name_of(path: &Path) -> io::Result<String> {
    path.file_name()
        .map(|n| n.to_string_lossy().into_owned())
        .ok_or_else(|| io::Error::new(io::ErrorKind::InvalidInput, "it names no file"))
}

/// Creates `dir` and its missing ancestors, registering each folder this call created for the
/// clean-up after a signal or an error (a folder that already existed is never removed).
pub fn create_folders(dir: &Path) -> io::Result<()> {
    let mut missing = Vec::new();
    let mut at = Some(dir);
    while let Some(d) = at.filter(|d| !d.as_os_str().is_empty() && !d.exists()) {
        missing.push(d.to_path_buf());
        at = d.parent();
    }
    for d in missing.into_iter().rev() {
        // Registered before it is created, under the lock that a signal's clean-up keeps: no
        // moment exists when the folder is there and the clean-up does not know it.
        let mut guard = live();
        guard.folders.push(d.clone());
        match std::fs::create_dir(&d) {
            Ok(()) => {}
            Err(e) => {
                guard.folders.pop();
                if !(e.kind() == io::ErrorKind::AlreadyExists && d.is_dir()) {
                    return Err(e);
                }
            }
        }
    }
    if dir.as_os_str().is_empty() || dir.is_dir() {
        Ok(())
    } else {
        Err(io::Error::new(
            io::ErrorKind::AlreadyExists,
            "it exists and is not a folder",
        ))
    }
}

/// A new, empty folder beside `target` under an unpredictable name (`.NAME.XXXXXX.tmp`),
/// created exclusively and registered as a temporary: the staging folder of an output folder.
pub fn staging_folder(target: &Path) -> io::Result<PathBuf> {
    let name = name_of(target)?;
    let mut guard = live();
    let dir = tempfile::Builder::new()
        .prefix(&format!(".{name}."))
        .suffix(".tmp")
        .tempdir_in(folder_of(target))?
        .keep();
    guard.temporaries.push(dir.clone());
    Ok(dir)
}

/// Renames a filled staging folder of [`staging_folder`] to `target` and withdraws it from
/// the clean-up, under the registry's lock: a signal's clean-up either removes the whole
/// folder first or finds it already in place, never empties it half-way through the rename.
pub fn commit_folder(staging: &Path, target: &Path) -> io::Result<()> {
    let mut guard = live();
    std::fs::rename(staging, target)?;
    guard.temporaries.retain(|t| t != staging);
    Ok(())
}

/// A new file in a staging folder of [`staging_folder`], created exclusively under the
/// registry's lock, so that no file appears in the folder once a signal's clean-up began.
pub fn create_staged_file(path: &Path) -> io::Result<std::fs::File> {
    let _guard = live();
    std::fs::File::create_new(path)
}

/// A complete temporary file or folder waiting to replace its target.
#[derive(Debug)]
pub struct Staged {
    tmp: Option<Temporary>,
    path: PathBuf,
}

/// What a [`Staged`] output holds until its commit.
#[derive(Debug)]
enum Temporary {
    /// A file beside the target ([`stage`]).
    File(tempfile::NamedTempFile),
    /// A filled staging folder beside the target folder ([`stage_folder`]).
    Folder(PathBuf),
}

impl Staged {
    /// The target this file will replace.
    pub fn path(&self) -> &Path {
        &self.path
    }

    /// Renames the temporary over the target.
    pub fn commit(mut self) -> io::Result<()> {
        match self
            .tmp
            .take()
            .expect("a staged output holds its temporary")
        {
            Temporary::File(tmp) => {
                refuse_non_regular(&self.path)?;
                let tmp_path = tmp.path().to_path_buf();
                // Under the registry's lock: a signal's clean-up never meets a half-renamed
                // file.
                let mut guard = live();
                let result = tmp.persist(&self.path).map_err(|e| e.error);
                guard.temporaries.retain(|t| t != &tmp_path);
                result.map(|_| ())
            }
            Temporary::Folder(dir) => {
                let result = commit_folder(&dir, &self.path);
                if result.is_err() {
                    let _ = std::fs::remove_dir_all(&dir);
                    untrack(&dir);
                }
                result
            }
        }
    }
}

impl Drop for Staged {
    fn drop(&mut self) {
        let path = match self.tmp.take() {
            None => return,
            Some(Temporary::File(tmp)) => {
                let path = tmp.path().to_path_buf();
                drop(tmp);
                path
            }
            Some(Temporary::Folder(dir)) => {
                let _ = std::fs::remove_dir_all(&dir);
                dir
            }
        };
        live().temporaries.retain(|t| t != &path);
    }
}

/// The folder `dir` (absent) with `files` (name, content) in it, staged whole: the files
/// are written into a staging folder beside it ([`staging_folder`], its missing ancestors
/// made by [`create_folders`]), renamed to `dir` on commit. Until then `dir` does not exist,
/// so an interrupted or failed run never leaves it empty or half filled.
pub fn stage_folder(dir: &Path, files: &[(&str, &[u8])]) -> io::Result<Staged> {
    create_folders(folder_of(dir))?;
    let tmp = staging_folder(dir)?;
    let staged = Staged {
        tmp: Some(Temporary::Folder(tmp.clone())),
        path: dir.to_path_buf(),
    };
    for (name, bytes) in files {
        let mut f = create_staged_file(&tmp.join(name))?;
        f.write_all(bytes)?;
        f.sync_all()?;
    }
    Ok(staged)
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
    let name = name_of(path)?;
    let tmp = {
        let mut guard = live();
        let tmp = tempfile::Builder::new()
            .prefix(&format!(".{name}."))
            .suffix(".tmp")
            .tempfile_in(folder_of(path))?;
        guard.temporaries.push(tmp.path().to_path_buf());
        tmp
    };
    let mut staged = Staged {
        tmp: Some(Temporary::File(tmp)),
        path: path.to_path_buf(),
    };
    let Some(Temporary::File(tmp)) = staged.tmp.as_mut() else {
        unreachable!("just created as a file")
    };
    let mut w = BufWriter::new(tmp.as_file_mut());
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

    /// The tests share the registry: one at a time, so that a clean-up meets only its own.
    static SERIAL: Mutex<()> = Mutex::new(());

    fn serial() -> MutexGuard<'static, ()> {
        SERIAL.lock().unwrap_or_else(|p| p.into_inner())
    }

    fn scratch(name: &str) -> PathBuf {
        let dir =
            std::env::temp_dir().join(format!("jointid-atomic-{name}-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        dir
    }

    #[test]
    fn failure_leaves_neither_target_nor_temporary() {
        let _serial = serial();
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
        let _serial = serial();
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
        let _serial = serial();
        let dir = scratch("dir");
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let err =
            write_atomically::<io::Error>(&dir.join("sub"), |w| w.write_all(b"x")).unwrap_err();
        assert!(err.to_string().contains("not a regular file"), "{err}");
        assert!(dir.join("sub").is_dir());
        assert_eq!(std::fs::read_dir(&dir).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_planted_link_is_neither_followed_nor_removed() {
        let _serial = serial();
        let dir = scratch("planted");
        let victim = dir.join("model.toml");
        std::fs::write(&victim, "model").unwrap();
        // Links at every name a predictable temporary could have had.
        for pid in [std::process::id(), 1, 2] {
            let link = dir.join(format!(".out.csv.{pid}.tmp"));
            std::os::unix::fs::symlink(&victim, &link).unwrap();
        }
        write_atomically::<io::Error>(&dir.join("out.csv"), |w| w.write_all(b"out")).unwrap();
        assert_eq!(std::fs::read_to_string(&victim).unwrap(), "model");
        assert!(
            !std::fs::symlink_metadata(dir.join("out.csv"))
                .unwrap()
                .is_symlink()
        );
        assert_eq!(std::fs::read_to_string(dir.join("out.csv")).unwrap(), "out");
        let links = std::fs::read_dir(&dir)
            .unwrap()
            .filter(|e| e.as_ref().unwrap().file_type().unwrap().is_symlink())
            .count();
        assert_eq!(links, 3, "the planted links are not the run's to remove");
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn a_staged_folder_appears_whole_on_commit_and_never_empty() {
        let _serial = serial();
        let dir = scratch("folder");
        let target = dir.join("plots/deep");
        let files: [(&str, &[u8]); 2] = [("a.svg", b"a"), ("index.html", b"i")];
        let staged = stage_folder(&target, &files).unwrap();
        // Before the commit: the target does not exist, its staging folder is hidden.
        assert!(!target.exists());
        let inside: Vec<String> = std::fs::read_dir(dir.join("plots"))
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        assert!(
            inside.len() == 1 && inside[0].starts_with(".deep."),
            "{inside:?}"
        );
        staged.commit().unwrap();
        assert_eq!(
            std::fs::read_to_string(target.join("index.html")).unwrap(),
            "i"
        );
        // An interrupted one: the clean-up removes the staging folder and the folder made
        // for it.
        let other = dir.join("more/deep");
        std::mem::forget(stage_folder(&other, &files).unwrap());
        remove_temporaries();
        assert!(!dir.join("more").exists());
        assert!(target.join("a.svg").exists());
        // A dropped one leaves no staging folder.
        drop(stage_folder(&dir.join("plots/other"), &files).unwrap());
        assert_eq!(std::fs::read_dir(dir.join("plots")).unwrap().count(), 1);
        std::fs::remove_dir_all(&dir).unwrap();
    }

    #[test]
    fn the_clean_up_removes_temporaries_and_the_folders_created_but_no_output() {
        let _serial = serial();
        let dir = scratch("cleanup");
        let kept = dir.join("kept");
        create_folders(&kept).unwrap();
        write_atomically::<io::Error>(&kept.join("done.csv"), |w| w.write_all(b"x")).unwrap();
        let deep = dir.join("a/b/c");
        create_folders(&deep).unwrap();
        let pending = stage::<io::Error>(&deep.join("f.svg"), |w| w.write_all(b"x")).unwrap();
        std::mem::forget(pending);
        let staging = staging_folder(&dir.join("export")).unwrap();
        std::fs::write(staging.join("model.toml"), "x").unwrap();
        remove_temporaries();
        let mut names: Vec<String> = std::fs::read_dir(&dir)
            .unwrap()
            .map(|e| e.unwrap().file_name().to_string_lossy().into_owned())
            .collect();
        names.sort();
        assert_eq!(names, vec!["kept".to_string()]);
        assert!(kept.join("done.csv").exists());
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

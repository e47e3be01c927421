//! Output paths checked before any work starts: an output never replaces an input of the same
//! run (compared after resolving `.`, `..` and symbolic links), never replaces something that
//! is not a regular file, and two outputs of one run never share a path.

use std::path::{Path, PathBuf};

/// An output path the run must not write.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum OutputPathError {
    /// The output is one of the inputs.
    #[error("{output}: refused as output: it is the input {input}; choose another output path")]
    IsInput {
        /// The output as given.
        output: PathBuf,
        /// The input as given.
        input: PathBuf,
    },
    /// The output exists and is a directory, a device or another special file.
    #[error(
        "{0}: refused as output: it exists and is not a regular file (a directory or a device)"
    )]
    NotRegular(PathBuf),
    /// The output names no file.
    #[error("{0}: refused as output: the path names no file")]
    NoFileName(PathBuf),
    /// Two outputs of the run are the same file.
    #[error("{first} and {second} are the same file: each output needs its own path")]
    Twice {
        /// The first output.
        first: PathBuf,
        /// The second output.
        second: PathBuf,
    },
}

/// The path with every existing part resolved; a missing file keeps its name under its
/// resolved directory.
fn resolved(path: &Path) -> PathBuf {
    if let Ok(p) = std::fs::canonicalize(path) {
        return p;
    }
    match (path.parent(), path.file_name()) {
        (Some(dir), Some(name)) => {
            let dir = if dir.as_os_str().is_empty() {
                Path::new(".")
            } else {
                dir
            };
            resolved(dir).join(name)
        }
        _ => path.to_path_buf(),
    }
}

/// Checks every output of a run against its inputs and against each other.
pub fn check_outputs(outputs: &[&Path], inputs: &[&Path]) -> Result<(), OutputPathError> {
    let inputs: Vec<(PathBuf, &Path)> = inputs.iter().map(|p| (resolved(p), *p)).collect();
    let mut seen: Vec<(PathBuf, &Path)> = Vec::with_capacity(outputs.len());
    for &output in outputs {
        if output.file_name().is_none() {
            return Err(OutputPathError::NoFileName(output.to_path_buf()));
        }
        if std::fs::metadata(output).is_ok_and(|m| !m.is_file()) {
            return Err(OutputPathError::NotRegular(output.to_path_buf()));
        }
        let here = resolved(output);
        if let Some((_, input)) = inputs.iter().find(|(p, _)| *p == here) {
            return Err(OutputPathError::IsInput {
                output: output.to_path_buf(),
                input: input.to_path_buf(),
            });
        }
        if let Some((_, first)) = seen.iter().find(|(p, _)| *p == here) {
            return Err(OutputPathError::Twice {
                first: first.to_path_buf(),
                second: output.to_path_buf(),
            });
        }
        seen.push((here, output));
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn an_input_reached_by_another_spelling_is_refused() {
        let dir = std::env::temp_dir().join(format!("jointid-guard-{}", std::process::id()));
        std::fs::create_dir_all(dir.join("sub")).unwrap();
        let input = dir.join("model.toml");
        std::fs::write(&input, "x").unwrap();
        let other = dir.join("sub/../model.toml");
        assert!(matches!(
            check_outputs(&[&other], &[&input]),
            Err(OutputPathError::IsInput { .. })
        ));
        let fresh = dir.join("sub/new.csv");
        assert_eq!(check_outputs(&[&fresh], &[&input]), Ok(()));
        let again = dir.join("sub/./new.csv");
        assert!(matches!(
            check_outputs(&[&fresh, &again], &[&input]),
            Err(OutputPathError::Twice { .. })
        ));
        assert!(matches!(
            check_outputs(&[&dir.join("sub")], &[]),
            Err(OutputPathError::NotRegular(_))
        ));
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

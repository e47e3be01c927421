//! Output paths checked before any work starts: an output never replaces an input of the same
//! run (compared after resolving `.`, `..` and symbolic links, [`resolved`]), never replaces
//! something that is not a regular file, and two outputs of one run never share a path.
//!
//! The inputs of a run are every file it reads: for a model, the model file and every file an
//! external model names ([`model_inputs`]); for a cluster run, the study and its model.

use std::path::{Component, Path, PathBuf};

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

/// The path as the file system will resolve it when the run writes: made absolute, then
/// walked component by component, each existing prefix canonicalised (symbolic links, `.` and
/// `..` resolved as the system does) and each missing part taken lexically, so that
/// `nothere/../m.toml` is `m.toml` even though `nothere` does not exist.
pub fn resolved(path: &Path) -> PathBuf {
    let Ok(absolute) = std::path::absolute(path) else {
        return path.to_path_buf();
    };
    let mut out = PathBuf::new();
    for part in absolute.components() {
        match part {
            Component::Prefix(_) | Component::RootDir => out.push(part),
            Component::CurDir => {}
            Component::ParentDir => {
                out.pop();
            }
            Component::Normal(name) => {
                out.push(name);
                if let Ok(real) = std::fs::canonicalize(&out) {
                    out = real;
                }
            }
        }
    }
    out
}

/// The inputs a model file brings to a run: the file itself and, for an external model, every
/// file it names (K, M, the DOF table, each dK/dp and dM/dp). Outputs are checked against
/// them all.
///
/// The model file is read within the limits of a TOML input file; one that cannot be read
/// names no other file here, and its reader refuses it afterwards.
pub fn model_inputs(model_file: &Path) -> Vec<PathBuf> {
    let text = crate::input::read_file(model_file).unwrap_or_default();
    let mut files = vec![model_file.to_path_buf()];
    files.extend(crate::study::fingerprint::model_data_files(
        &text, model_file,
    ));
    files
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

    #[test]
    fn a_path_through_a_missing_folder_is_resolved() {
        let dir = std::env::temp_dir().join(format!("jointid-guard-miss-{}", std::process::id()));
        std::fs::create_dir_all(&dir).unwrap();
        let input = dir.join("m.toml");
        std::fs::write(&input, "x").unwrap();
        for spelling in [
            "nothere/../m.toml",
            "a/b/../../m.toml",
            "nothere/./../m.toml",
        ] {
            assert!(
                matches!(
                    check_outputs(&[&dir.join(spelling)], &[&input]),
                    Err(OutputPathError::IsInput { .. })
                ),
                "{spelling}"
            );
        }
        assert_eq!(
            resolved(&dir.join("x/../y/z.csv")),
            resolved(&dir).join("y/z.csv")
        );
        std::fs::remove_dir_all(&dir).unwrap();
    }
}

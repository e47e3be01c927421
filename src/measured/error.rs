//! The error of a measured-modes file, whatever its format: it names the file, the line where
//! the format has lines, what is wrong and what is allowed.
//!
//! May import: nothing of the crate.

use std::path::PathBuf;

/// A measured-modes file that cannot be used.
#[derive(Debug, thiserror::Error)]
pub enum MeasuredError {
    /// The file cannot be read.
    #[error("{file}: cannot read the file: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The cause.
        cause: std::io::Error,
    },
    /// A line is invalid.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// 1-based line number.
        line: u64,
        /// What is wrong and what is allowed.
        message: String,
    },
    /// The file holds no mode at all.
    #[error("{file}: no measured mode (only a header, or an empty file)")]
    Empty {
        /// The file.
        file: PathBuf,
    },
    /// Neither the file's extension nor its content is of a format known here.
    #[error("{file}: the format of these measured modes is not known: {allowed}")]
    UnknownFormat {
        /// The file.
        file: PathBuf,
        /// The formats known, with their extensions and how their content looks.
        allowed: String,
    },
}

//! Reading input files: TOML into raw serde structs with the field path of every error, and
//! the error type shared by every input file (model, study).
//!
//! Errors name the file, the line where known, the field path (`beam[1].length`), the value
//! and what is allowed.

use std::path::{Path, PathBuf};

use serde::de::DeserializeOwned;

/// An input file that cannot be used, with where and why.
#[derive(Debug, thiserror::Error)]
pub enum InputError {
    /// The file cannot be read.
    #[error("{file}: cannot read the file: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// The cause.
        cause: std::io::Error,
    },
    /// The file is not valid TOML, or does not have the expected keys and types.
    #[error("{file}{line}: {path}{message}", line = line_suffix(*.line), path = path_prefix(.path))]
    Format {
        /// The file.
        file: PathBuf,
        /// 1-based line, when known.
        line: Option<usize>,
        /// Field path such as `beam[1].length` (empty at the top level).
        path: String,
        /// What is wrong.
        message: String,
    },
    /// A value is out of its allowed range.
    #[error("{file}: {path} = {value} is invalid: {allowed}")]
    Invalid {
        /// The file.
        file: PathBuf,
        /// Field path.
        path: String,
        /// The value as written.
        value: String,
        /// What is allowed, with the unit.
        allowed: String,
    },
}

fn line_suffix(line: Option<usize>) -> String {
    line.map(|l| format!(":{l}")).unwrap_or_default()
}

fn path_prefix(path: &str) -> String {
    if path.is_empty() || path == "." {
        String::new()
    } else {
        format!("{path}: ")
    }
}

/// Reads a whole file, mapping the I/O error to [`InputError::Read`].
pub fn read_file(path: &Path) -> Result<String, InputError> {
    std::fs::read_to_string(path).map_err(|cause| InputError::Read {
        file: path.to_path_buf(),
        cause,
    })
}

/// Parses TOML text into `T`, reporting the field path and line of any error.
pub fn parse_toml<T: DeserializeOwned>(text: &str, file: &Path) -> Result<T, InputError> {
    let format_error = |line, path: String, message: &str| InputError::Format {
        file: file.to_path_buf(),
        line,
        path,
        message: message.trim().to_string(),
    };
    let de = toml::Deserializer::parse(text)
        .map_err(|e| format_error(span_line(text, e.span()), String::new(), e.message()))?;
    serde_path_to_error::deserialize(de).map_err(|e| {
        let path = e.path().to_string();
        let inner = e.into_inner();
        format_error(span_line(text, inner.span()), path, inner.message())
    })
}

fn span_line(text: &str, span: Option<std::ops::Range<usize>>) -> Option<usize> {
    let start = span?.start.min(text.len());
    Some(text[..start].bytes().filter(|&b| b == b'\n').count() + 1)
}

/// A check of one numeric field, producing [`InputError::Invalid`] with the allowed range.
pub struct FieldCheck<'a> {
    /// The file the value comes from.
    pub file: &'a Path,
}

impl FieldCheck<'_> {
    /// Requires a finite value > 0.
    pub fn positive(
        &self,
        path: impl Into<String>,
        value: f64,
        unit: &str,
    ) -> Result<f64, InputError> {
        if value.is_finite() && value > 0.0 {
            Ok(value)
        } else {
            Err(self.invalid(path, value, format!("it must be finite and > 0 ({unit})")))
        }
    }

    /// Requires a finite value >= 0.
    pub fn non_negative(
        &self,
        path: impl Into<String>,
        value: f64,
        unit: &str,
    ) -> Result<f64, InputError> {
        if value.is_finite() && value >= 0.0 {
            Ok(value)
        } else {
            Err(self.invalid(path, value, format!("it must be finite and >= 0 ({unit})")))
        }
    }

    /// Requires an integer in `lo..=hi`.
    pub fn int_range(
        &self,
        path: impl Into<String>,
        value: i64,
        lo: i64,
        hi: i64,
    ) -> Result<usize, InputError> {
        if (lo..=hi).contains(&value) {
            Ok(value as usize)
        } else {
            Err(self.invalid(
                path,
                value,
                format!("it must be an integer from {lo} to {hi}"),
            ))
        }
    }

    /// An [`InputError::Invalid`] for this file.
    pub fn invalid(
        &self,
        path: impl Into<String>,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> InputError {
        InputError::Invalid {
            file: self.file.to_path_buf(),
            path: path.into(),
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }
}

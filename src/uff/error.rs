//! The errors of the universal-file reader and writer.
//!
//! A reading error names the file, the record (1-based index in the file and its dataset
//! number) and the 1-based line, as `sed -n Np` counts lines (the bytes of a binary payload
//! count too), then says what was expected:
//! `frf.uff: record 3 (dataset 58), line 47: expected 8193 ordinate values, the record ends
//! after 4096`.

use std::path::PathBuf;

/// A universal file that cannot be read, or a dataset that cannot be written.
#[derive(Debug, thiserror::Error)]
pub enum UffError {
    /// The file cannot be opened or read.
    #[error("{}: cannot read the file: {cause}", file.display())]
    Read {
        /// The file.
        file: PathBuf,
        /// The cause (in the message, so not also a `source`: a chain would say it twice).
        cause: std::io::Error,
    },
    /// The text between datasets is not a universal file.
    #[error("{}: line {line}: {problem}", file.display())]
    Structure {
        /// The file.
        file: PathBuf,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        problem: Problem,
    },
    /// A dataset is malformed.
    #[error("{}: record {record} (dataset {dataset}), line {line}: {problem}", file.display())]
    Record {
        /// The file.
        file: PathBuf,
        /// 1-based index of the dataset in the file.
        record: usize,
        /// Dataset number (58 for a binary 58b too).
        dataset: u32,
        /// 1-based line number.
        line: usize,
        /// What is wrong.
        problem: Problem,
    },
    /// The writer's output failed.
    #[error("cannot write the universal file")]
    Write(#[from] std::io::Error),
    /// A value does not fit the fixed format of the dataset being written.
    #[error("cannot write dataset {dataset}: {field} = {value} is invalid: {allowed}")]
    Unwritable {
        /// Dataset number.
        dataset: u32,
        /// The field, by the format's name.
        field: &'static str,
        /// The offending value.
        value: String,
        /// What the format allows.
        allowed: &'static str,
    },
}

/// What is wrong at one line of a universal file.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum Problem {
    /// Text where a `-1` line must open a dataset.
    #[error("expected a `-1` line opening a dataset, found {found:?}")]
    NotADelimiter {
        /// The line found.
        found: String,
    },
    /// The line after an opening `-1` does not start with a dataset number.
    #[error("expected a dataset number after the opening `-1`, found {found:?}")]
    NoDatasetNumber {
        /// The line found.
        found: String,
    },
    /// The file ends inside a dataset.
    #[error("the file ends inside the dataset: no closing `-1`")]
    Unterminated,
    /// A dataset longer than any real one.
    #[error(
        "the dataset has more than {limit} lines before its closing `-1`, more than any dataset holds (a missing `-1`, or a damaged file)"
    )]
    TooManyLines {
        /// The most lines a dataset may have.
        limit: usize,
    },
    /// A required line of the dataset is missing.
    #[error("the record ends before {what}")]
    Truncated {
        /// The missing line, by the format's name.
        what: &'static str,
    },
    /// Fewer values than the dataset declares.
    #[error("expected {expected} {what}, the record ends after {found}")]
    TooFew {
        /// What is counted.
        what: &'static str,
        /// How many the dataset declares.
        expected: usize,
        /// How many it holds.
        found: usize,
    },
    /// More values than the dataset declares (zero padding of the last line is allowed).
    #[error("expected {expected} {what}, found {found}")]
    TooMany {
        /// What is counted.
        what: &'static str,
        /// How many the dataset declares.
        expected: usize,
        /// How many were found (at least).
        found: usize,
    },
    /// A field that must be a real number is not one.
    #[error("{field}: {text:?} is not a finite real number")]
    Number {
        /// The field, by the format's name.
        field: &'static str,
        /// Its text.
        text: String,
    },
    /// A field that must be an integer is not one.
    #[error("{field}: {text:?} is not an integer")]
    Integer {
        /// The field, by the format's name.
        field: &'static str,
        /// Its text.
        text: String,
    },
    /// A code outside the format's table.
    #[error("{field} = {value} is not a known code: allowed {allowed}")]
    Code {
        /// The field, by the format's name.
        field: &'static str,
        /// The code read.
        value: i64,
        /// The codes the format defines.
        allowed: &'static str,
    },
    /// A value outside its range.
    #[error("{field} = {value} is invalid: {allowed}")]
    Invalid {
        /// The field, by the format's name.
        field: &'static str,
        /// The value read.
        value: String,
        /// What is allowed.
        allowed: &'static str,
    },
    /// The bytes after a binary payload are not the closing `-1`.
    #[error(
        "no closing `-1` after the {expected} bytes of binary data that the header declares \
         (checked layouts: {layouts})"
    )]
    BinaryNotClosed {
        /// Payload length of the first layout tried, bytes.
        expected: usize,
        /// The payload lengths tried, bytes.
        layouts: String,
    },
}

/// A problem at a line, before the file and record are attached.
#[derive(Debug, Clone, PartialEq)]
pub(crate) struct Located {
    /// 1-based line number.
    pub line: usize,
    /// What is wrong.
    pub problem: Problem,
}

impl Located {
    pub(crate) fn new(line: usize, problem: Problem) -> Self {
        Located { line, problem }
    }
}

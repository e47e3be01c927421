//! Universal files (UFF/UNV, the I-DEAS "universal file format"): the exchange format of
//! modal-test acquisition software. Engineers bring their FRFs as dataset 58 (ASCII or binary
//! 58b), node coordinates as dataset 15 or 2411, and expect mode shapes back as dataset 55.
//!
//! A universal file is a sequence of datasets, each opened and closed by a `-1` line, the first
//! line inside naming the dataset number (`split.rs`). Each dataset is a sequence of Fortran
//! fixed-format records; the readers take numbers by blanks first and by columns when that
//! fails (`fields.rs`), since real files do both. Read here:
//! - [`function`]: 58/58b, functions at nodal DOF (time responses, FRFs, coherences, ...);
//! - [`shape`]: 55, data at nodes (mode shapes);
//! - [`nodes`]: 15 and 2411, node coordinates;
//! - [`units`]: 164 (units) and 151 (header);
//!
//! any other dataset is kept as [`Record::Other`]. [`mod@write`] writes 58 (ASCII), 55, 15, 2411,
//! 164 and 151, in the fixed formats (its docs state the digits of each field).
//!
//! Entry points: [`read`] (bytes) and [`read_path`] give the [`Record`]s of a file in order;
//! [`write_record`] and the `write_*` functions write one dataset into any `io::Write`.
//! Reading returns data, never prints; it never panics whatever the bytes: a malformed file
//! gives a [`UffError`] naming the file, the record and the line.
//!
//! The layouts follow the I-DEAS dataset descriptions as published by the Structural Dynamics
//! Research Lab of the University of Cincinnati (UC-SDRL universal file format pages),
//! which pyuff (ladisk/pyuff, `pyuff/datasets/dataset_*.py`) reproduces; pyuff's readers and its
//! issue tracker taught which liberties real files take (blank-separated fields, values run
//! together, zero padding of the last line, a line terminator before the closing `-1` of a
//! 58b). No code is taken from it.
//!
//! Layer 1 (foundations; see the crate docs): may import, without a circle, the other foundations:
//! [`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`].

pub mod error;
mod fields;
pub mod function;
pub mod nodes;
pub mod shape;
mod split;
pub mod units;
pub mod write;

use std::path::Path;

use faer::c64;

pub use error::{Problem, UffError};
pub use function::{Abscissa, Axis, Dof, Encoding, Function, FunctionType, Precision};
pub use nodes::{Node, NodeFormat, Nodes};
pub use shape::{Analysis, DataCharacteristic, ModeShape};
pub use units::{Header, UnitSystem, Units};
pub use write::{
    write_function, write_header, write_mode_shape, write_nodes, write_record, write_units,
};

/// Real or complex values (ordinates of a function, values of a mode shape).
#[derive(Debug, Clone, PartialEq)]
pub enum Values {
    /// Real values.
    Real(Vec<f64>),
    /// Complex values.
    Complex(Vec<c64>),
}

impl Values {
    /// Number of values (a complex value counts once).
    pub fn len(&self) -> usize {
        match self {
            Values::Real(v) => v.len(),
            Values::Complex(v) => v.len(),
        }
    }

    /// True when there is no value.
    pub fn is_empty(&self) -> bool {
        self.len() == 0
    }

    /// True for complex values.
    pub fn is_complex(&self) -> bool {
        matches!(self, Values::Complex(_))
    }

    /// The values as complex numbers (imaginary part 0 for real values).
    pub fn to_complex(&self) -> Vec<c64> {
        match self {
            Values::Real(v) => v.iter().map(|&x| c64::new(x, 0.0)).collect(),
            Values::Complex(v) => v.clone(),
        }
    }
}

/// One dataset of a universal file.
// A file holds tens of records: boxing the large variant would only burden matching.
#[allow(clippy::large_enum_variant)]
#[derive(Debug, Clone, PartialEq)]
pub enum Record {
    /// Dataset 58 or 58b.
    Function(Function),
    /// Dataset 55.
    ModeShape(ModeShape),
    /// Dataset 15 or 2411.
    Nodes(Nodes),
    /// Dataset 164.
    Units(Units),
    /// Dataset 151.
    Header(Header),
    /// Any other dataset, not interpreted.
    Other {
        /// Dataset number.
        kind: u32,
        /// Line of the dataset number (1-based).
        first_line: usize,
    },
}

/// The payload lengths of the binary datasets whose layout is known here: 58b, from its record
/// 7 ([`function`]); the declared byte count of any other.
fn payload_lengths(
    kind: u32,
    header: &[fields::Line<'_>],
    line: usize,
) -> Result<Option<Vec<usize>>, error::Located> {
    if kind == 58 {
        function::binary_lengths(header, line).map(Some)
    } else {
        Ok(None)
    }
}

/// Reads every dataset of a universal file held in `bytes`; `file` names it in errors.
pub fn read(bytes: &[u8], file: &Path) -> Result<Vec<Record>, UffError> {
    let mut records = Vec::new();
    for raw in split::Splitter::new(bytes, payload_lengths) {
        let raw = raw.map_err(|(record, located)| match record {
            Some((record, dataset)) => UffError::Record {
                file: file.to_path_buf(),
                record,
                dataset,
                line: located.line,
                problem: located.problem,
            },
            None => UffError::Structure {
                file: file.to_path_buf(),
                line: located.line,
                problem: located.problem,
            },
        })?;
        let record = match raw.kind {
            kind if raw.binary.is_some() && kind != 58 => Ok(Record::Other {
                kind,
                first_line: raw.number_line,
            }),
            58 => function::parse(&raw).map(Record::Function),
            55 => shape::parse(&raw).map(Record::ModeShape),
            15 => nodes::parse_15(&raw).map(Record::Nodes),
            2411 => nodes::parse_2411(&raw).map(Record::Nodes),
            164 => units::parse_164(&raw).map(Record::Units),
            151 => Ok(Record::Header(units::parse_151(&raw))),
            kind => Ok(Record::Other {
                kind,
                first_line: raw.number_line,
            }),
        };
        records.push(record.map_err(|located| UffError::Record {
            file: file.to_path_buf(),
            record: raw.index,
            dataset: raw.kind,
            line: located.line,
            problem: located.problem,
        })?);
    }
    Ok(records)
}

/// Reads every dataset of the universal file at `path`, within
/// [`crate::input::bounded::UFF`]'s limit (1 GiB): a larger file is refused before it is read.
pub fn read_path(path: &Path) -> Result<Vec<Record>, UffError> {
    use crate::input::bounded;
    let bytes = bounded::read_path(path, bounded::UFF).map_err(|cause| UffError::Read {
        file: path.to_path_buf(),
        cause,
    })?;
    read(&bytes, path)
}

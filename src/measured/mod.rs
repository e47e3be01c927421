//! Measured modes: the model of the paper's measured eigensolutions ([`modes`]), read from
//! files of any registered format.
//!
//! - [`modes`]: measured modes, their frequencies and partial shapes;
//! - [`error`]: the error of a measured-modes file, whatever its format;
//! - [`locate`](mod@locate): point resolution (node and DOF, position and DOF, label) shared by formats;
//! - [`format`](mod@format): the [`Format`] trait and the choice of a file's format;
//! - [`csv`]: the measured-modes CSV (by node, by position or by label), reader and writer.
//!
//! [`read`] chooses a file's format (its extension, else its content) among [`FORMATS`]. A new
//! format is one file implementing [`Format`], its `mod` line and its entry in [`FORMATS`].
//!
//! Layer 3 (models and measurements; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`]) and, without a circle, [`crate::model`], [`crate::extract`].

pub mod csv;
pub mod error;
pub mod format;
pub mod locate;
pub mod modes;

use crate::input::bounded::{Bounded, WHOLE};
use std::io::Read;
use std::path::Path;

pub use error::MeasuredError;
pub use format::Format;
pub use locate::{Location, locate};
pub use modes::{MAX_FREQUENCY_HZ, MAX_MODE, MeasuredMode, MeasuredModes, point_order};

use crate::structure::Structure;

/// The formats of measured-modes files, in the order their content is tried.
pub const FORMATS: &[&dyn Format] = &[&csv::Csv];

/// Reads and validates the measured modes of the file at `path` against `structure`, in the
/// format its extension names, else the one its content shows.
pub fn read(path: &Path, structure: &Structure) -> Result<MeasuredModes, MeasuredError> {
    let file = std::fs::File::open(path).map_err(|cause| MeasuredError::Read {
        file: path.to_path_buf(),
        cause,
    })?;
    from_reader(file, path, structure)
}

/// [`read`] from any reader, within [`WHOLE`]'s limits (line length, lines, bytes); `file`
/// names the source in errors and its extension chooses the format.
pub fn from_reader<R: Read>(
    reader: R,
    file: &Path,
    structure: &Structure,
) -> Result<MeasuredModes, MeasuredError> {
    let mut bytes = Vec::new();
    Bounded::new(reader, WHOLE)
        .read_to_end(&mut bytes)
        .map_err(|cause| MeasuredError::Read {
            file: file.to_path_buf(),
            cause,
        })?;
    read_bytes(&bytes, file, structure)
}

fn read_bytes(
    bytes: &[u8],
    file: &Path,
    structure: &Structure,
) -> Result<MeasuredModes, MeasuredError> {
    format::choose(FORMATS, file, bytes)?.read(bytes, file, structure)
}

impl MeasuredModes {
    /// Reads and validates a file against `structure`: [`read`].
    pub fn from_path(path: &Path, structure: &Structure) -> Result<Self, MeasuredError> {
        read(path, structure)
    }

    /// Reads and validates modes from any reader; `file` names them in errors and chooses
    /// the format: [`from_reader`].
    pub fn from_reader<R: Read>(
        reader: R,
        file: &Path,
        structure: &Structure,
    ) -> Result<Self, MeasuredError> {
        from_reader(reader, file, structure)
    }
}

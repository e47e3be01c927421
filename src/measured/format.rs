//! The formats of measured-modes files behind one trait, and the choice of a file's format:
//! by its extension, else by its content. The formats themselves are registered in
//! [`super::FORMATS`].
//!
//! May import: the measured-modes model and its error.

use std::path::Path;

use super::error::MeasuredError;
use super::modes::MeasuredModes;
use crate::structure::Structure;

/// A file format of measured modes: how its files are named, how its content looks, how it is
/// read against a structure (the points resolved by [`super::locate()`], the errors a
/// [`MeasuredError`] that names the file and, where the format has lines, the line).
pub trait Format: Sync {
    /// Its name in messages, lower case (`csv`).
    fn name(&self) -> &'static str;

    /// The extensions of its files, lower case without the dot (`["csv"]`).
    fn extensions(&self) -> &'static [&'static str];

    /// How its content looks, for the message that lists the formats.
    fn signature(&self) -> &'static str;

    /// Whether `bytes` look like this format (asked for a file whose extension names no
    /// format).
    fn recognises(&self, bytes: &[u8]) -> bool;

    /// Reads and validates the modes in `bytes` against `structure`; `file` names them in
    /// errors.
    fn read(
        &self,
        bytes: &[u8],
        file: &Path,
        structure: &Structure,
    ) -> Result<MeasuredModes, MeasuredError>;
}

/// The format of `file` among `formats`: the one its extension names (any case), else the
/// first that recognises its content `bytes`; otherwise an error that names the file and lists
/// the formats.
pub fn choose<'a>(
    formats: &[&'a dyn Format],
    file: &Path,
    bytes: &[u8],
) -> Result<&'a dyn Format, MeasuredError> {
    let extension = file.extension().map(|e| e.to_string_lossy().to_lowercase());
    let by_name = formats.iter().find(|f| {
        extension
            .as_deref()
            .is_some_and(|e| f.extensions().contains(&e))
    });
    if let Some(format) = by_name.or_else(|| formats.iter().find(|f| f.recognises(bytes))) {
        return Ok(*format);
    }
    let known: Vec<String> = formats
        .iter()
        .map(|f| {
            let names: Vec<String> = f.extensions().iter().map(|e| format!("*.{e}")).collect();
            format!("{} ({}, or {})", f.name(), names.join(", "), f.signature())
        })
        .collect();
    Err(MeasuredError::UnknownFormat {
        file: file.to_path_buf(),
        allowed: format!("the formats known are {}", known.join("; ")),
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A format of files named `extensions` whose content starts with `start`.
    struct Fake {
        name: &'static str,
        extensions: &'static [&'static str],
        start: &'static str,
    }

    impl Format for Fake {
        fn name(&self) -> &'static str {
            self.name
        }
        fn extensions(&self) -> &'static [&'static str] {
            self.extensions
        }
        fn signature(&self) -> &'static str {
            self.start
        }
        fn recognises(&self, bytes: &[u8]) -> bool {
            bytes.starts_with(self.start.as_bytes())
        }
        fn read(&self, _: &[u8], _: &Path, _: &Structure) -> Result<MeasuredModes, MeasuredError> {
            Ok(MeasuredModes::new(Vec::new()))
        }
    }

    const TAB: Fake = Fake {
        name: "tab",
        extensions: &["tab", "tsv"],
        start: "TAB",
    };
    const BAR: Fake = Fake {
        name: "bar",
        extensions: &["bar"],
        start: "BAR",
    };

    fn chosen(file: &str, bytes: &[u8]) -> Result<&'static str, String> {
        choose(&[&TAB, &BAR], Path::new(file), bytes)
            .map(|f| f.name())
            .map_err(|e| e.to_string())
    }

    #[test]
    fn the_extension_chooses_first_then_the_content() {
        assert_eq!(chosen("m.bar", b"TAB"), Ok("bar"));
        assert_eq!(chosen("m.TSV", b"BAR"), Ok("tab"));
        assert_eq!(chosen("m.txt", b"BAR 1"), Ok("bar"));
        assert_eq!(chosen("m", b"TAB 1 2"), Ok("tab"));
    }

    #[test]
    fn an_unknown_format_names_the_file_and_the_formats() {
        assert_eq!(
            chosen("modes.json", b"{}").unwrap_err(),
            "modes.json: the format of these measured modes is not known: the formats known are \
             tab (*.tab, *.tsv, or TAB); bar (*.bar, or BAR)"
        );
        assert!(chosen("empty", b"").is_err());
    }
}

//! Reading input files: TOML into raw serde structs with the field path of every error, and
//! the error type shared by every input file (model, study); and [`SettingError`], a setting
//! given in code (or on a command line) outside its range.
//!
//! Errors name the file, the line where known, the field path (`beam[1].length`), the value
//! and what is allowed. A table that comes in kinds (`kind = "spring"`, each kind with its own
//! fields) is kept as read in a [`TaggedTable`] and parsed into a serde enum afterwards, so the
//! errors inside a kind keep their field path and line.
//!
//! Layer 1 (foundations; see the crate docs): may import, without a circle, the other foundations:
//! [`crate::stats`], [`crate::random`], [`crate::structure`], [`crate::uff`].

pub mod bounded;
pub mod safe;

use std::collections::BTreeMap;
use std::path::{Path, PathBuf};

use serde::Deserialize;
use serde::de::DeserializeOwned;
use serde::de::value::{MapAccessDeserializer, MapDeserializer};
use serde_path_to_error::Segment;
use toml::Spanned;

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

/// A setting outside its range, checked where it is set (a settings constructor of the
/// library): the setting's name, the value given and what is allowed.
///
/// Its message reads `n = 39 is invalid: it must be from 3 to 38 ...`; a command line that
/// takes the setting as a flag says the same with the flag's name,
/// [`SettingError::with_name`]: `--n 39 is invalid: ...`.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{setting} = {value} is invalid: {allowed}")]
pub struct SettingError {
    /// The setting, as the library names it (`n`, `shape_noise`, ...).
    pub setting: &'static str,
    /// The value given, as written.
    pub value: String,
    /// What is allowed (a clause: `it must be ...`).
    pub allowed: String,
}

impl SettingError {
    /// The setting `setting` given as `value`, with what is allowed.
    pub fn new(
        setting: &'static str,
        value: impl std::fmt::Display,
        allowed: impl Into<String>,
    ) -> Self {
        SettingError {
            setting,
            value: value.to_string(),
            allowed: allowed.into(),
        }
    }

    /// The message with the setting called `name` (a command-line flag) and no `=`:
    /// `{name} {value} is invalid: {allowed}`.
    pub fn with_name(&self, name: &str) -> String {
        format!("{name} {} is invalid: {}", self.value, self.allowed)
    }
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

/// The range of a relative standard error, wherever data state one: of a frequency
/// (`frequency_std` over `frequency_hz`), of a shape value (`value_std` over the shape's
/// largest magnitude), of the stated noise (`--frequency-noise`, `--shape-noise`). Below 1e-12 a residual at the
/// precision of a double (about 1e-16 of the value) is already thousands of standard errors
/// and the weights 1 / sigma^2 of a chi^2 head for overflow; no measurement comes near it.
/// Above 1 the error exceeds the value it qualifies and the first-order propagation means
/// nothing.
pub const RELATIVE_STD: (f64, f64) = (1e-12, 1.0);

/// Whether `std` is a relative standard error within [`RELATIVE_STD`] of `scale` (> 0).
pub fn relative_std_in_range(std: f64, scale: f64) -> bool {
    let r = std / scale;
    r.is_finite() && (RELATIVE_STD.0..=RELATIVE_STD.1).contains(&r)
}

/// Reads a whole TOML input file within [`bounded::TOML`]'s limits (16 MiB, lines of 1 MiB),
/// mapping the I/O error, a limit passed or text that is not UTF-8 to [`InputError::Read`].
pub fn read_file(path: &Path) -> Result<String, InputError> {
    let read_error = |cause| InputError::Read {
        file: path.to_path_buf(),
        cause,
    };
    let bytes = bounded::read_path(path, bounded::TOML).map_err(read_error)?;
    String::from_utf8(bytes).map_err(|_| {
        read_error(std::io::Error::new(
            std::io::ErrorKind::InvalidData,
            "stream did not contain valid UTF-8",
        ))
    })
}

/// Parses TOML text into `T`, reporting the field path and line of any error.
pub fn parse_toml<T: DeserializeOwned>(text: &str, file: &Path) -> Result<T, InputError> {
    let format_error = |line, path: String, message: &str| InputError::Format {
        file: file.to_path_buf(),
        line,
        path,
        message: safe::clip_quotes(message.trim().to_string()),
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

/// A TOML table whose `kind` (or another tag key) says which of several kinds it is, each kind
/// with its own fields: kept as read, with the span of every value, until [`TaggedTable::parse`]
/// turns it into a serde enum.
///
/// serde's internally tagged enums (`#[serde(tag = "kind")]`) would check the same fields, but
/// they buffer the table before choosing the variant and lose the field path and line of an
/// error inside it (`support[1]` instead of `support[1].rotational`); parsing the kept table
/// as an externally tagged enum keeps both.
#[derive(Debug, Deserialize)]
#[serde(transparent)]
pub struct TaggedTable(Spanned<BTreeMap<String, Spanned<toml::Value>>>);

impl TaggedTable {
    /// Parses the table into `T`, an externally tagged serde enum with one struct variant per
    /// kind (`rename_all`, `deny_unknown_fields`): the value of `tag` names the variant, the
    /// other keys are its fields. Errors are [`InputError::Format`] with the file, the line
    /// (from `text`, the file's text), the field path below `path` (`support[1].rotational`,
    /// `support[0].kind`) and, for a field of a kind, the kind.
    pub fn parse<T: DeserializeOwned>(
        self,
        tag: &str,
        path: &str,
        file: &Path,
        text: &str,
    ) -> Result<T, InputError> {
        let (table_span, mut entries) = (self.0.span(), self.0.into_inner());
        let format_error =
            |span: std::ops::Range<usize>, path: String, message: String| InputError::Format {
                file: file.to_path_buf(),
                line: span_line(text, Some(span)),
                path,
                message,
            };
        let Some(kind) = entries.remove(tag) else {
            return Err(format_error(
                table_span,
                path.to_string(),
                format!("missing field `{tag}`"),
            ));
        };
        let kind_span = kind.span();
        let spans: BTreeMap<String, std::ops::Range<usize>> =
            entries.iter().map(|(k, v)| (k.clone(), v.span())).collect();
        let fields: toml::Table = entries
            .into_iter()
            .map(|(k, v)| (k, v.into_inner()))
            .collect();
        let tagged = MapDeserializer::<_, toml::de::Error>::new(std::iter::once((
            kind.into_inner(),
            toml::Value::Table(fields),
        )));
        serde_path_to_error::deserialize(MapAccessDeserializer::new(tagged)).map_err(|e| {
            let segments: Vec<&Segment> = e.path().iter().collect();
            let message = e.inner().message().to_string();
            let Some((Segment::Enum { variant }, inside)) = segments.split_first() else {
                // The tag itself: an unknown kind, or not a string.
                return format_error(kind_span.clone(), format!("{path}.{tag}"), message);
            };
            let mut at = path.to_string();
            for segment in inside {
                match segment {
                    Segment::Seq { .. } => at += &segment.to_string(),
                    _ => at += &format!(".{segment}"),
                }
            }
            let span = match inside.first() {
                Some(Segment::Map { key }) => spans.get(key).cloned(),
                _ => None,
            };
            format_error(
                span.unwrap_or(table_span.clone()),
                at,
                format!("{message} ({tag} = \"{variant}\")"),
            )
        })
    }
}

/// A number as a message shows it, compact: the shortest form that reads back to the same
/// value when that is short (a value as the user typed it), else six significant digits; in
/// exponent form when it is very large or very small (never 309 digits, never 17). Data
/// outputs write their numbers in full, never through this.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Number(pub f64);

/// The longest shortest-round-trip form [`Number`] shows as it is.
const NUMBER_CHARS: usize = 12;

impl Number {
    fn shortest(v: f64) -> String {
        if v == 0.0 || !v.is_finite() || (1e-4..1e9).contains(&v.abs()) {
            format!("{v}")
        } else {
            format!("{v:e}")
        }
    }
}

impl std::fmt::Display for Number {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        let exact = Self::shortest(self.0);
        if exact.len() <= NUMBER_CHARS {
            return f.write_str(&exact);
        }
        // Six significant digits, then the shortest form of that rounded value.
        let rounded: f64 = format!("{:.5e}", self.0).parse().unwrap_or(self.0);
        f.write_str(&Self::shortest(rounded))
    }
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
            Err(self.invalid(
                path,
                Number(value),
                format!("it must be finite and > 0 ({unit})"),
            ))
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
            Err(self.invalid(
                path,
                Number(value),
                format!("it must be finite and >= 0 ({unit})"),
            ))
        }
    }

    /// Requires a relative level: finite, from 0 to below 1 (100%).
    pub fn relative_level(
        &self,
        path: impl Into<String>,
        value: f64,
        what: &str,
    ) -> Result<f64, InputError> {
        if value.is_finite() && (0.0..1.0).contains(&value) {
            Ok(value)
        } else {
            Err(self.invalid(
                path,
                Number(value),
                format!("it must be a {what} from 0 to below 1 (100%)"),
            ))
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

#[cfg(test)]
mod tests {
    use super::Number;

    #[test]
    fn numbers_in_messages_are_short_and_exact_when_typed_short() {
        assert_eq!(Number(1e300).to_string(), "1e300");
        assert_eq!(Number(-2.5e-7).to_string(), "-2.5e-7");
        assert_eq!(Number(0.04).to_string(), "0.04");
        assert_eq!(Number(20000000.0).to_string(), "20000000");
        assert_eq!(Number(f64::MAX).to_string(), "1.79769e308");
        assert_eq!(Number(f64::NAN).to_string(), "NaN");
        for v in [1e300, 3.3e-200, 0.1, 12345.678, 1e9, 9.99e8] {
            assert_eq!(Number(v).to_string().parse::<f64>().unwrap(), v);
        }
    }
}

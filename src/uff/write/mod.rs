//! Writing universal files: datasets 58 (ASCII), 55, 15, 2411, 164 and 151.
//!
//! Each dataset is written in the fixed format of its description (see the reading modules),
//! fields right-justified in their columns, text left-justified, LF line ends, so that
//! column-based readers (Fortran, pyuff) and blank-based readers both read it. Reals are
//! written as `1PEw.d` (one digit before the point, `d` after: d + 1 significant digits) and
//! always keep a leading blank:
//! - 58: record 7 abscissa minimum, increment and z value `E13.5` (6 significant digits, so
//!   an even step is exact only when it has at most 6: 0.0625, 0.25, 1.0); values of a double
//!   precision function `E20.12` (13 significant digits), an uneven abscissa `E13.5`; a single
//!   precision function `6E13.5`. Always ASCII, whatever [`Function::encoding`](crate::uff::Function::encoding) says;
//! - 55: record 8 and the nodal values `E13.5` (6 significant digits), data type 2 (real) or
//!   5 (complex) whatever [`ModeShape::precision`](crate::uff::ModeShape::precision) says;
//! - 15: coordinates `E13.5` (6 significant digits); 2411: `E25.16` (17 significant digits,
//!   exact for `f64`); 164: factors `E25.17`.
//!
//! A value read back equals the value written rounded to those digits (to the nearest, as
//! Rust's `{:.*e}` rounds). Text longer than its field, integers too wide for theirs and
//! non-finite reals are refused with [`UffError::Unwritable`]; an empty ID line or label is
//! written `NONE`, as the format asks.

mod function;
mod shape;

use std::io::Write;

pub use function::write_function;
pub use shape::write_mode_shape;

use super::Record;
use super::error::UffError;
use super::nodes::{NodeFormat, Nodes};
use super::units::{Header, Units};

/// `x` in `1PEwidth.decimals`, right-justified, exponent of at least two digits. A three-digit
/// exponent takes one decimal, so that a leading blank always remains.
pub(super) fn e(x: f64, width: usize, decimals: usize) -> String {
    let format = |d: usize| {
        let s = format!("{x:.d$e}");
        let (mantissa, exp) = s.split_once('e').unwrap_or((&s, "0"));
        let exp: i32 = exp.parse().unwrap_or(0);
        let sign = if exp < 0 { '-' } else { '+' };
        format!("{mantissa}E{sign}{:02}", exp.abs())
    };
    let mut s = format(decimals);
    if s.len() >= width && decimals > 0 {
        s = format(decimals - 1);
    }
    format!("{s:>width$}")
}

/// Writer of one dataset: checks fields against their format.
pub(super) struct Out<'w, W: Write> {
    pub w: &'w mut W,
    pub dataset: u32,
}

impl<W: Write> Out<'_, W> {
    pub(super) fn unwritable(
        &self,
        field: &'static str,
        value: String,
        allowed: &'static str,
    ) -> UffError {
        UffError::Unwritable {
            dataset: self.dataset,
            field,
            value,
            allowed,
        }
    }

    pub(super) fn line(&mut self, s: &str) -> Result<(), UffError> {
        self.w.write_all(s.as_bytes())?;
        self.w.write_all(b"\n")?;
        Ok(())
    }

    /// An integer right-justified in `width` columns.
    pub(super) fn int(
        &self,
        v: i64,
        width: usize,
        field: &'static str,
    ) -> Result<String, UffError> {
        let s = format!("{v:>width$}");
        if s.len() > width {
            return Err(self.unwritable(field, v.to_string(), "it does not fit its integer field"));
        }
        Ok(s)
    }

    /// A text field of at most `width` characters (`NONE` when empty), left-justified and
    /// padded to `width` when `pad`.
    pub(super) fn text(
        &self,
        s: &str,
        width: usize,
        pad: bool,
        field: &'static str,
    ) -> Result<String, UffError> {
        if s.contains(['\n', '\r']) || s.chars().count() > width {
            return Err(self.unwritable(
                field,
                format!("{s:?}"),
                "text must fit its field (80 characters for an ID line, 10 for an entity name, 20 for a label) on one line",
            ));
        }
        let s = if s.trim().is_empty() { "NONE" } else { s };
        Ok(if pad {
            format!("{s:<width$}")
        } else {
            s.to_string()
        })
    }

    /// A finite real in `Ewidth.decimals`.
    pub(super) fn real(
        &self,
        x: f64,
        width: usize,
        decimals: usize,
        field: &'static str,
    ) -> Result<String, UffError> {
        if !x.is_finite() {
            return Err(self.unwritable(field, x.to_string(), "it must be finite"));
        }
        Ok(e(x, width, decimals))
    }

    /// Reals in `Ewidth.decimals`, `per_line` to a line.
    pub(super) fn reals(
        &mut self,
        xs: &[f64],
        width: usize,
        decimals: usize,
        per_line: usize,
        field: &'static str,
    ) -> Result<(), UffError> {
        for chunk in xs.chunks(per_line.max(1)) {
            let mut s = String::with_capacity(chunk.len() * width);
            for &x in chunk {
                s.push_str(&self.real(x, width, decimals, field)?);
            }
            self.line(&s)?;
        }
        Ok(())
    }

    pub(super) fn open(&mut self) -> Result<(), UffError> {
        let head = format!("{:>6}\n{:>6}", -1, self.dataset);
        self.line(&head)
    }

    pub(super) fn close(&mut self) -> Result<(), UffError> {
        self.line(&format!("{:>6}", -1))
    }

    pub(super) fn id_lines(&mut self, ids: &[String; 5]) -> Result<(), UffError> {
        for id in ids {
            let s = self.text(id, 80, false, "ID line")?;
            self.line(&s)?;
        }
        Ok(())
    }
}

/// Writes nodes as a dataset 15 or 2411, as their [`Nodes::format`] says.
pub fn write_nodes<W: Write>(w: &mut W, nodes: &Nodes) -> Result<(), UffError> {
    let dataset = match nodes.format {
        NodeFormat::Single15 => 15,
        NodeFormat::Double2411 => 2411,
    };
    let mut out = Out { w, dataset };
    out.open()?;
    for n in &nodes.nodes {
        let as_i64 = |v: u64| i64::try_from(v).unwrap_or(i64::MAX);
        let ints = format!(
            "{}{}{}{}",
            out.int(as_i64(n.label), 10, "node label (I10)")?,
            out.int(
                as_i64(n.definition_cs),
                10,
                "definition coordinate system (I10)"
            )?,
            out.int(
                as_i64(n.displacement_cs),
                10,
                "displacement coordinate system (I10)"
            )?,
            out.int(n.color, 10, "color (I10)")?,
        );
        let (width, decimals) = if dataset == 15 { (13, 5) } else { (25, 16) };
        let xyz = n
            .coordinates
            .iter()
            .map(|&c| out.real(c, width, decimals, "node coordinate"))
            .collect::<Result<String, _>>()?;
        if dataset == 15 {
            out.line(&format!("{ints}{xyz}"))?;
        } else {
            out.line(&ints)?;
            out.line(&xyz)?;
        }
    }
    out.close()
}

/// Writes units as a dataset 164.
pub fn write_units<W: Write>(w: &mut W, u: &Units) -> Result<(), UffError> {
    let mut out = Out { w, dataset: 164 };
    let mut record1 = format!(
        "{:>10}{}",
        u.system.code(),
        out.text(
            &u.description,
            20,
            u.temperature_mode.is_some(),
            "units description (A20)"
        )?
    );
    if let Some(mode) = u.temperature_mode {
        record1.push_str(&out.int(i64::from(mode), 10, "temperature mode (I10)")?);
    }
    let field = "unit factor";
    let factors = format!(
        "{}{}{}",
        out.real(u.length, 25, 17, field)?,
        out.real(u.force, 25, 17, field)?,
        out.real(u.temperature, 25, 17, field)?
    );
    let offset = out.real(u.temperature_offset, 25, 17, field)?;
    out.open()?;
    out.line(&record1)?;
    out.line(&factors)?;
    out.line(&offset)?;
    out.close()
}

/// Writes a header as a dataset 151.
pub fn write_header<W: Write>(w: &mut W, h: &Header) -> Result<(), UffError> {
    let mut out = Out { w, dataset: 151 };
    let lines = [
        &h.model_file,
        &h.description,
        &h.database_program,
        &h.database_created,
        &h.database_saved,
        &h.program,
        &h.written,
    ]
    .iter()
    .map(|s| out.text(s, 80, false, "header record (A80)"))
    .collect::<Result<Vec<_>, _>>()?;
    out.open()?;
    for l in &lines {
        out.line(l)?;
    }
    out.close()
}

/// Writes any record this module writes; [`Record::Other`] holds nothing to write.
pub fn write_record<W: Write>(w: &mut W, record: &Record) -> Result<(), UffError> {
    match record {
        Record::Function(f) => write_function(w, f),
        Record::ModeShape(s) => write_mode_shape(w, s),
        Record::Nodes(n) => write_nodes(w, n),
        Record::Units(u) => write_units(w, u),
        Record::Header(h) => write_header(w, h),
        Record::Other { kind, .. } => Err(UffError::Unwritable {
            dataset: *kind,
            field: "record",
            value: format!("dataset {kind}"),
            allowed: "only the datasets read (58, 55, 15, 2411, 164, 151) can be written",
        }),
    }
}

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
//!   precision function `6E13.5`. Always ASCII, whatever [`Function::encoding`] says;
//! - 55: record 8 and the nodal values `E13.5` (6 significant digits), data type 2 (real) or
//!   5 (complex) whatever [`ModeShape::precision`] says;
//! - 15: coordinates `E13.5` (6 significant digits); 2411: `E25.16` (17 significant digits,
//!   exact for `f64`); 164: factors `E25.17`.
//!
//! A value read back equals the value written rounded to those digits (to the nearest, as
//! Rust's `{:.*e}` rounds). Text longer than its field, integers too wide for theirs and
//! non-finite reals are refused with [`UffError::Unwritable`]; an empty ID line or label is
//! written `NONE`, as the format asks.

use std::io::Write;

use super::error::UffError;
use super::function::{Abscissa, Axis, Dof, Function, Precision};
use super::nodes::{NodeFormat, Nodes};
use super::shape::{Analysis, ModeShape};
use super::units::{Header, Units};
use super::{Record, Values};

/// `x` in `1PEwidth.decimals`, right-justified, exponent of at least two digits. A three-digit
/// exponent takes one decimal, so that a leading blank always remains.
fn e(x: f64, width: usize, decimals: usize) -> String {
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
struct Out<'w, W: Write> {
    w: &'w mut W,
    dataset: u32,
}

impl<W: Write> Out<'_, W> {
    fn unwritable(&self, field: &'static str, value: String, allowed: &'static str) -> UffError {
        UffError::Unwritable {
            dataset: self.dataset,
            field,
            value,
            allowed,
        }
    }

    fn line(&mut self, s: &str) -> Result<(), UffError> {
        self.w.write_all(s.as_bytes())?;
        self.w.write_all(b"\n")?;
        Ok(())
    }

    /// An integer right-justified in `width` columns.
    fn int(&self, v: i64, width: usize, field: &'static str) -> Result<String, UffError> {
        let s = format!("{v:>width$}");
        if s.len() > width {
            return Err(self.unwritable(field, v.to_string(), "it does not fit its integer field"));
        }
        Ok(s)
    }

    /// A text field of at most `width` characters (`NONE` when empty), left-justified and
    /// padded to `width` when `pad`.
    fn text(
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
    fn real(
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
    fn reals(
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

    fn open(&mut self) -> Result<(), UffError> {
        let head = format!("{:>6}\n{:>6}", -1, self.dataset);
        self.line(&head)
    }

    fn close(&mut self) -> Result<(), UffError> {
        self.line(&format!("{:>6}", -1))
    }

    fn id_lines(&mut self, ids: &[String; 5]) -> Result<(), UffError> {
        for id in ids {
            let s = self.text(id, 80, false, "ID line")?;
            self.line(&s)?;
        }
        Ok(())
    }
}

fn dof<W: Write>(out: &Out<W>, d: &Dof, which: &'static str) -> Result<String, UffError> {
    let node = i64::try_from(d.node).unwrap_or(i64::MAX);
    Ok(format!(
        " {}{}{}",
        out.text(&d.entity, 10, true, which)?,
        out.int(node, 10, "node (record 6, I10)")?,
        out.int(i64::from(d.direction), 4, "direction (record 6, I4)")?,
    ))
}

fn axis<W: Write>(out: &Out<W>, a: &Axis) -> Result<String, UffError> {
    Ok(format!(
        "{}{}{}{} {} {}",
        out.int(
            i64::from(a.data_type),
            10,
            "specific data type (records 8-11, I10)"
        )?,
        out.int(
            i64::from(a.length_exponent),
            5,
            "length units exponent (records 8-11, I5)"
        )?,
        out.int(
            i64::from(a.force_exponent),
            5,
            "force units exponent (records 8-11, I5)"
        )?,
        out.int(
            i64::from(a.temperature_exponent),
            5,
            "temperature units exponent (records 8-11, I5)"
        )?,
        out.text(&a.label, 20, true, "axis label (records 8-11)")?,
        out.text(&a.units, 20, true, "axis units label (records 8-11)")?,
    ))
}

/// Writes a function as an ASCII dataset 58.
pub fn write_function<W: Write>(w: &mut W, f: &Function) -> Result<(), UffError> {
    let mut out = Out { w, dataset: 58 };
    let n = f.len();
    if let Abscissa::Uneven(x) = &f.abscissa
        && x.len() != n
    {
        return Err(out.unwritable(
            "abscissa values",
            format!("{} for {n} ordinate values", x.len()),
            "an uneven abscissa has one value per ordinate value",
        ));
    }
    let complex = f.ordinate.is_complex();
    let double = f.precision == Precision::Double;
    let ord_type = match (complex, double) {
        (false, false) => 2,
        (false, true) => 4,
        (true, false) => 5,
        (true, true) => 6,
    };
    let (even, start, step) = match f.abscissa {
        Abscissa::Even { start, step } => (1, start, step),
        Abscissa::Uneven(_) => (0, 0.0, 0.0),
    };
    let record6 = format!(
        "{}{}{}{}{}{}",
        out.int(
            i64::from(f.function_type.code()),
            5,
            "function type (record 6, I5)"
        )?,
        out.int(
            f.function_id,
            10,
            "function identification number (record 6, I10)"
        )?,
        out.int(f.version, 5, "version number (record 6, I5)")?,
        out.int(f.load_case, 10, "load case (record 6, I10)")?,
        dof(&out, &f.response, "response entity name (record 6)")?,
        dof(&out, &f.reference, "reference entity name (record 6)")?,
    );
    let record7 = format!(
        "{:>10}{}{:>10}{}{}{}",
        ord_type,
        out.int(
            i64::try_from(n).unwrap_or(i64::MAX),
            10,
            "number of points (record 7, I10)"
        )?,
        even,
        out.real(start, 13, 5, "abscissa minimum (record 7)")?,
        out.real(step, 13, 5, "abscissa increment (record 7)")?,
        out.real(f.z_value, 13, 5, "z-axis value (record 7)")?,
    );
    let axes = [
        axis(&out, &f.abscissa_axis)?,
        axis(&out, &f.ordinate_axis)?,
        axis(&out, &f.denominator_axis)?,
        axis(&out, &f.z_axis)?,
    ];
    out.open()?;
    out.id_lines(&f.id_lines)?;
    out.line(&record6)?;
    out.line(&record7)?;
    for a in &axes {
        out.line(a)?;
    }
    // Record 12: x (uneven), Re, Im per point, flattened.
    let ordinate: Vec<[f64; 2]> = match &f.ordinate {
        Values::Real(v) => v.iter().map(|&y| [y, 0.0]).collect(),
        Values::Complex(v) => v.iter().map(|y| [y.re, y.im]).collect(),
    };
    let parts = 1 + usize::from(complex);
    let field = "data value (record 12)";
    match (&f.abscissa, double) {
        (Abscissa::Even { .. }, true) => {
            let flat: Vec<f64> = ordinate.iter().flat_map(|y| y[..parts].to_vec()).collect();
            out.reals(&flat, 20, 12, 4, field)?;
        }
        (Abscissa::Uneven(x), true) => {
            let per_line = if complex { 1 } else { 2 };
            for (xs, ys) in x.chunks(per_line).zip(ordinate.chunks(per_line)) {
                let mut s = String::new();
                for (&xi, yi) in xs.iter().zip(ys) {
                    s.push_str(&out.real(xi, 13, 5, "abscissa value (record 12)")?);
                    for &part in &yi[..parts] {
                        s.push_str(&out.real(part, 20, 12, field)?);
                    }
                }
                out.line(&s)?;
            }
        }
        (abscissa, false) => {
            let flat: Vec<f64> = match abscissa {
                Abscissa::Even { .. } => {
                    ordinate.iter().flat_map(|y| y[..parts].to_vec()).collect()
                }
                Abscissa::Uneven(x) => x
                    .iter()
                    .zip(&ordinate)
                    .flat_map(|(&xi, y)| std::iter::once(xi).chain(y[..parts].iter().copied()))
                    .collect(),
            };
            out.reals(&flat, 13, 5, 6, field)?;
        }
    }
    out.close()
}

/// Writes data at nodes as a dataset 55.
pub fn write_mode_shape<W: Write>(w: &mut W, s: &ModeShape) -> Result<(), UffError> {
    let mut out = Out { w, dataset: 55 };
    let ndv = s.values_per_node;
    if ndv == 0 || s.values.len() != s.nodes.len().saturating_mul(ndv) {
        return Err(out.unwritable(
            "values",
            format!(
                "{} for {} nodes of {ndv} values",
                s.values.len(),
                s.nodes.len()
            ),
            "there must be values_per_node (>= 1) values per node",
        ));
    }
    let (code, ints, reals): (i32, Vec<i64>, Vec<f64>) = match &s.analysis {
        Analysis::NormalMode {
            load_case,
            mode,
            frequency_hz,
            modal_mass,
            viscous_damping,
            hysteretic_damping,
        } => (
            2,
            vec![*load_case, *mode],
            vec![
                *frequency_hz,
                *modal_mass,
                *viscous_damping,
                *hysteretic_damping,
            ],
        ),
        Analysis::ComplexMode {
            second_order,
            load_case,
            mode,
            eigenvalue,
            modal_a,
            modal_b,
        } => (
            if *second_order { 7 } else { 3 },
            vec![*load_case, *mode],
            vec![
                eigenvalue.re,
                eigenvalue.im,
                modal_a.re,
                modal_a.im,
                modal_b.re,
                modal_b.im,
            ],
        ),
        Analysis::FrequencyResponse {
            load_case,
            step,
            frequency_hz,
        } => (5, vec![*load_case, *step], vec![*frequency_hz]),
        Analysis::Other {
            code,
            integers,
            reals,
        } => (*code, integers.clone(), reals.clone()),
    };
    let data_type = if s.values.is_complex() { 5 } else { 2 };
    let record6 = [
        i64::from(s.model_type),
        i64::from(code),
        i64::from(s.characteristic.code()),
        i64::from(s.specific_data_type),
        data_type,
        i64::try_from(ndv).unwrap_or(i64::MAX),
    ]
    .iter()
    .map(|&v| out.int(v, 10, "data definition parameter (record 6, I10)"))
    .collect::<Result<String, _>>()?;
    let counts = [ints.len() as i64, reals.len() as i64];
    let record7: Vec<String> = counts
        .iter()
        .chain(&ints)
        .map(|&v| out.int(v, 10, "integer parameter (record 7, I10)"))
        .collect::<Result<_, _>>()?;
    out.open()?;
    out.id_lines(&s.id_lines)?;
    out.line(&record6)?;
    for chunk in record7.chunks(8) {
        out.line(&chunk.concat())?;
    }
    out.reals(&reals, 13, 5, 6, "real parameter (record 8)")?;
    let flat: Vec<f64> = match &s.values {
        Values::Real(v) => v.clone(),
        Values::Complex(v) => v.iter().flat_map(|c| [c.re, c.im]).collect(),
    };
    let per_node = flat.len() / s.nodes.len().max(1);
    for (node, values) in s.nodes.iter().zip(flat.chunks(per_node.max(1))) {
        let label = out.int(
            i64::try_from(*node).unwrap_or(i64::MAX),
            10,
            "node number (record 9, I10)",
        )?;
        out.line(&label)?;
        out.reals(values, 13, 5, 6, "data value (record 10)")?;
    }
    out.close()
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

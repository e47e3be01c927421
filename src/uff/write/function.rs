//! Dataset 58 (ASCII) out: records 1-12 in their fixed formats.

use std::io::Write;

use super::Out;
use crate::uff::Values;
use crate::uff::error::UffError;
use crate::uff::function::{Abscissa, Axis, Dof, Function, Precision};

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

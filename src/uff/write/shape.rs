//! Dataset 55 out: records 1-10 in their fixed formats.

use std::io::Write;

use super::Out;
use crate::uff::Values;
use crate::uff::error::UffError;
use crate::uff::shape::{Analysis, ModeShape};

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

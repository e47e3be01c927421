//! Dataset 58, "Function at Nodal DOF": FRFs, coherences, time responses, ... (ASCII and the
//! binary variant 58b).
//!
//! Records 1-5 are the ID lines (`80A1`); record 6 the DOF identification,
//! `Format(2(I5,I10),2(1X,10A1,I10,I4))`: function type, function id, version, load case, then
//! entity name, node and direction of the response and of the reference; record 7 the data
//! form, `Format(3I10,3E13.5)`: ordinate data type (2 real single, 4 real double, 5 complex
//! single, 6 complex double), number of points, abscissa spacing (0 uneven, 1 even),
//! abscissa minimum, increment and z value; records 8-11 the abscissa, ordinate (numerator),
//! ordinate denominator and z-axis characteristics, `Format(I10,3I5,2(1X,20A1))`: specific data
//! type, length, force and temperature exponents, axis label, axis units label. Record 12
//! holds the values, point by point: `x` (uneven only; always written single precision in
//! ASCII), then the real part, then the imaginary part (complex only), in `6E13.5` (single),
//! `4E20.12` (double even), `2(E13.5,E20.12)` (real double uneven) or `E13.5,2E20.12` (complex
//! double uneven). The number of points counts complex values once.
//!
//! In 58b the same values follow as raw IEEE numbers of the ordinate's precision. The UC-SDRL
//! description says the abscissa is always single precision, while pyuff writes it in the
//! ordinate's precision; both layouts are tried for an uneven abscissa, and the one after which
//! the closing `-1` stands is read.
//!
//! Records 6-11 are read in `records.rs`, the 58b payload in `binary.rs`, record 12 here.
//!
//! Layout after the I-DEAS / UC-SDRL "Universal Dataset Number 58" description (as reproduced
//! in pyuff's `dataset_58.py`).

mod binary;
mod records;

pub(crate) use binary::lengths as binary_lengths;

use faer::c64;

use records::{DataForm, axis, data_form, dof_fields};

use super::Values;
use super::error::{Located, Problem};
use super::fields::{Cursor, collect_reals, reals};
use super::split::RawDataset;

/// The function type of record 6, field 1.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum FunctionType {
    /// 1: time response.
    TimeResponse,
    /// 4: frequency response function.
    Frf,
    /// 6: (ordinary) coherence.
    Coherence,
    /// Any other code (0 general, 2 auto spectrum, 3 cross spectrum, 5 transmissibility, ...).
    Other(i32),
}

impl FunctionType {
    /// The code of the format.
    pub fn code(self) -> i32 {
        match self {
            FunctionType::TimeResponse => 1,
            FunctionType::Frf => 4,
            FunctionType::Coherence => 6,
            FunctionType::Other(c) => c,
        }
    }

    /// The type of a code.
    pub fn from_code(code: i32) -> Self {
        match code {
            1 => FunctionType::TimeResponse,
            4 => FunctionType::Frf,
            6 => FunctionType::Coherence,
            c => FunctionType::Other(c),
        }
    }
}

/// A response or reference DOF (record 6).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Dof {
    /// Entity name (`A10`, "NONE" if unused), trimmed.
    pub entity: String,
    /// Node number.
    pub node: u64,
    /// Direction: 0 scalar, 1/2/3 +X/+Y/+Z translation, 4/5/6 +X/+Y/+Z rotation, negative for
    /// the opposite sense.
    pub direction: i32,
}

/// The characteristics of one axis (records 8-11).
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Axis {
    /// Specific data type: 0 unknown, 1 general, 8 displacement, 11 velocity, 12 acceleration,
    /// 13 excitation force, 17 time, 18 frequency, ...
    pub data_type: i32,
    /// Length units exponent.
    pub length_exponent: i32,
    /// Force units exponent.
    pub force_exponent: i32,
    /// Temperature units exponent.
    pub temperature_exponent: i32,
    /// Axis label (`A20`, "NONE" if unused), trimmed.
    pub label: String,
    /// Axis units label (`A20`, "NONE" if unused), trimmed, e.g. "m/s^2/V".
    pub units: String,
}

/// Precision of the ordinate, as the file declares it (values are held as `f64`).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Precision {
    /// Single precision (codes 2, 5).
    Single,
    /// Double precision (codes 4, 6).
    Double,
}

/// The abscissa of a function.
#[derive(Debug, Clone, PartialEq)]
pub enum Abscissa {
    /// Even spacing: x_i = start + i step.
    Even {
        /// Abscissa minimum.
        start: f64,
        /// Abscissa increment.
        step: f64,
    },
    /// One abscissa value per point, as stored.
    Uneven(Vec<f64>),
}

/// How a dataset 58 was stored.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Encoding {
    /// ASCII (dataset 58).
    Ascii,
    /// Binary (dataset 58b) with the given byte order.
    Binary {
        /// Big endian (else little endian).
        big_endian: bool,
    },
}

/// A function at nodal DOF (dataset 58).
#[derive(Debug, Clone, PartialEq)]
pub struct Function {
    /// ID lines 1-5 (records 1-5), trailing blanks removed.
    pub id_lines: [String; 5],
    /// Function type.
    pub function_type: FunctionType,
    /// Function identification number.
    pub function_id: i64,
    /// Version or sequence number.
    pub version: i64,
    /// Load case identification number (0: single point excitation).
    pub load_case: i64,
    /// Response DOF.
    pub response: Dof,
    /// Reference DOF.
    pub reference: Dof,
    /// Declared precision of the ordinate.
    pub precision: Precision,
    /// Abscissa.
    pub abscissa: Abscissa,
    /// Z-axis value (0 if unused).
    pub z_value: f64,
    /// Abscissa characteristics (record 8).
    pub abscissa_axis: Axis,
    /// Ordinate (numerator) characteristics (record 9).
    pub ordinate_axis: Axis,
    /// Ordinate denominator characteristics (record 10).
    pub denominator_axis: Axis,
    /// Z-axis characteristics (record 11).
    pub z_axis: Axis,
    /// The ordinate, real or complex, one value per point.
    pub ordinate: Values,
    /// ASCII or binary.
    pub encoding: Encoding,
}

impl Function {
    /// Number of points.
    pub fn len(&self) -> usize {
        self.ordinate.len()
    }

    /// True when the function has no point.
    pub fn is_empty(&self) -> bool {
        self.ordinate.is_empty()
    }

    /// The abscissa value of every point.
    pub fn abscissa_values(&self) -> Vec<f64> {
        match &self.abscissa {
            Abscissa::Even { start, step } => {
                (0..self.len()).map(|i| start + i as f64 * step).collect()
            }
            Abscissa::Uneven(x) => x.clone(),
        }
    }

    /// Start and step of the abscissa when its points are evenly spaced: an even abscissa as
    /// stored; an uneven one when every x_i lies within the rounding of the written digits of
    /// x_0 + i step, step = (x_last - x_0) / (n - 1). Each value written to `rel_tol` relative
    /// is off by up to `rel_tol` max(|x_i|, step) itself, and the line from the written first
    /// and last values by up to `rel_tol` ((1 - t) |x_0| + t |x_last|) at t = i / (n - 1): the
    /// tolerance is their sum. Exported FRFs often store an even frequency axis as uneven
    /// values of 6 significant digits (`E13.5`): `rel_tol = 5e-6` accepts them. `None` for
    /// fewer than two points or an uneven spacing.
    pub fn even_abscissa(&self, rel_tol: f64) -> Option<(f64, f64)> {
        match &self.abscissa {
            Abscissa::Even { start, step } => Some((*start, *step)),
            Abscissa::Uneven(x) => even_values(x, rel_tol),
        }
    }
}

/// The start and step of abscissa values `x` that are evenly spaced within `rel_tol`
/// ([`Function::even_abscissa`]); None when they are not, or fewer than two.
pub fn even_values(x: &[f64], rel_tol: f64) -> Option<(f64, f64)> {
    let (&first, &last) = (x.first()?, x.last()?);
    if x.len() < 2 {
        return None;
    }
    let span = (x.len() - 1) as f64;
    let step = (last - first) / span;
    let even = step != 0.0
        && x.iter().enumerate().all(|(i, &xi)| {
            let t = i as f64 / span;
            let ends = (1.0 - t) * first.abs() + t * last.abs();
            let tolerance = rel_tol * (xi.abs().max(step.abs()) + ends);
            (xi - (first + i as f64 * step)).abs() <= tolerance
        });
    even.then_some((first, step))
}

/// Reads a dataset 58 or 58b.
pub(crate) fn parse(ds: &RawDataset) -> Result<Function, Located> {
    let mut cursor = Cursor::new(&ds.lines, ds.end_line);
    let mut id_lines: [String; 5] = Default::default();
    for id in &mut id_lines {
        *id = cursor
            .next("the ID lines (records 1-5)")?
            .text
            .trim_end()
            .to_string();
    }
    let (function_type, [function_id, version, load_case], response, reference) =
        dof_fields(cursor.next("the DOF identification (record 6)")?)?;
    let form = data_form(cursor.next("the data form (record 7)")?)?;
    let abscissa_axis = axis(
        cursor.next("record 8")?,
        "abscissa characteristics (record 8)",
    )?;
    let ordinate_axis = axis(
        cursor.next("record 9")?,
        "ordinate characteristics (record 9)",
    )?;
    let denominator_axis = axis(
        cursor.next("record 10")?,
        "denominator characteristics (record 10)",
    )?;
    let z_axis = axis(
        cursor.next("record 11")?,
        "z-axis characteristics (record 11)",
    )?;

    let per_point = form.per_point();
    let (flat, encoding) = match (ds.binary, ds.payload) {
        (Some(header), Some((bytes, line))) => (
            binary::values(&form, bytes, header.big_endian, line)?,
            Encoding::Binary {
                big_endian: header.big_endian,
            },
        ),
        _ => {
            let widths: &[usize] = match (form.precision, form.even, form.complex) {
                (Precision::Single, _, _) => &[13],
                (Precision::Double, true, _) => &[20],
                (Precision::Double, false, false) => &[13, 20],
                (Precision::Double, false, true) => &[13, 20, 20],
            };
            let total = form.count.checked_mul(per_point).ok_or(Located::new(
                ds.lines[6].number,
                Problem::Invalid {
                    field: "number of points (record 7)",
                    value: form.count.to_string(),
                    allowed: "too large",
                },
            ))?;
            let what = "ordinate values";
            let flat = collect_reals(
                &mut cursor,
                total,
                per_point,
                widths,
                what,
                "data value (record 12)",
            )?;
            if let Some(extra) = cursor.next_non_blank() {
                let more: usize = std::iter::once(extra)
                    .chain(cursor.rest())
                    .map(|l| reals(&l.text, widths, "").map_or(1, |v| v.len()))
                    .sum();
                return Err(Located::new(
                    extra.number,
                    Problem::TooMany {
                        what,
                        expected: form.count,
                        found: form.count + more.div_ceil(per_point),
                    },
                ));
            }
            (flat, Encoding::Ascii)
        }
    };
    let (abscissa, ordinate) = split_points(&form, &flat);
    Ok(Function {
        id_lines,
        function_type,
        function_id,
        version,
        load_case,
        response,
        reference,
        precision: form.precision,
        abscissa,
        z_value: form.z,
        abscissa_axis,
        ordinate_axis,
        denominator_axis,
        z_axis,
        ordinate,
        encoding,
    })
}

/// The flat values of record 12 (x, Re, Im per point) as abscissa and ordinate.
fn split_points(form: &DataForm, flat: &[f64]) -> (Abscissa, Values) {
    let per_point = form.per_point();
    let first = usize::from(!form.even);
    let points = flat.chunks_exact(per_point);
    let abscissa = if form.even {
        Abscissa::Even {
            start: form.start,
            step: form.step,
        }
    } else {
        Abscissa::Uneven(points.clone().map(|p| p[0]).collect())
    };
    let ordinate = if form.complex {
        Values::Complex(points.map(|p| c64::new(p[first], p[first + 1])).collect())
    } else {
        Values::Real(points.map(|p| p[first]).collect())
    };
    (abscissa, ordinate)
}

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
//! Layout after the I-DEAS / UC-SDRL "Universal Dataset Number 58" description (as reproduced
//! in pyuff's `dataset_58.py`).

use faer::c64;

use super::Values;
use super::error::{Located, Problem};
use super::fields::{Cursor, Line, collect_reals, column, integer, integers, real, reals};
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
}

/// Record 7.
struct DataForm {
    complex: bool,
    precision: Precision,
    count: usize,
    even: bool,
    start: f64,
    step: f64,
    z: f64,
}

impl DataForm {
    /// Values per point in record 12: x (uneven), Re, Im (complex).
    fn per_point(&self) -> usize {
        usize::from(!self.even) + 1 + usize::from(self.complex)
    }
}

fn data_form(line: &Line) -> Result<DataForm, Located> {
    let at = |p| Located::new(line.number, p);
    let t = &line.text;
    let tokens: Vec<&str> = t.split_whitespace().collect();
    let by_blanks = tokens.len() >= 3
        && tokens[..3].iter().all(|s| integer(s, "").is_ok())
        && tokens[3..].iter().all(|s| real(s, "").is_ok());
    let (ints, reals_): (Vec<&str>, Vec<&str>) = if by_blanks {
        (tokens[..3].to_vec(), tokens[3..].to_vec())
    } else {
        let cols = [(0, 10), (10, 10), (20, 10), (30, 13), (43, 13), (56, 13)];
        let f: Vec<&str> = cols.iter().map(|&(s, w)| column(t, s, w)).collect();
        let n_reals = f[3..]
            .iter()
            .rposition(|s| !s.is_empty())
            .map_or(0, |i| i + 1);
        (f[..3].to_vec(), f[3..3 + n_reals].to_vec())
    };
    let int = |s: &str, field| {
        if s.is_empty() {
            Err(at(Problem::Truncated { what: field }))
        } else {
            integer(s, field).map_err(at)
        }
    };
    let ord_type = int(ints[0], "ordinate data type (record 7)")?;
    let (complex, precision) = match ord_type {
        2 => (false, Precision::Single),
        4 => (false, Precision::Double),
        5 => (true, Precision::Single),
        6 => (true, Precision::Double),
        v => {
            return Err(at(Problem::Code {
                field: "ordinate data type (record 7)",
                value: v,
                allowed: "2 real single, 4 real double, 5 complex single, 6 complex double",
            }));
        }
    };
    let n = int(ints[1], "number of points (record 7)")?;
    let count = usize::try_from(n).map_err(|_| {
        at(Problem::Invalid {
            field: "number of points (record 7)",
            value: n.to_string(),
            allowed: "it must be >= 0",
        })
    })?;
    let even = match int(ints[2], "abscissa spacing (record 7)")? {
        0 => false,
        1 => true,
        v => {
            return Err(at(Problem::Code {
                field: "abscissa spacing (record 7)",
                value: v,
                allowed: "0 uneven, 1 even",
            }));
        }
    };
    let mut r = [0.0; 3];
    for (slot, s) in r.iter_mut().zip(&reals_) {
        *slot = real(s, "abscissa minimum, increment or z value (record 7)").map_err(at)?;
    }
    if even && reals_.len() < 2 {
        return Err(at(Problem::Truncated {
            what: "the abscissa minimum and increment of record 7 (even spacing)",
        }));
    }
    if even && count > 1 && r[1] == 0.0 {
        return Err(at(Problem::Invalid {
            field: "abscissa increment (record 7)",
            value: "0".into(),
            allowed: "it must be nonzero for an even abscissa",
        }));
    }
    Ok(DataForm {
        complex,
        precision,
        count,
        even,
        start: r[0],
        step: r[1],
        z: r[2],
    })
}

fn dof_fields(line: &Line) -> Result<(FunctionType, [i64; 3], Dof, Dof), Located> {
    let at = |p| Located::new(line.number, p);
    let t = &line.text;
    let tokens: Vec<&str> = t.split_whitespace().collect();
    let int_at = [0, 1, 2, 3, 5, 6, 8, 9];
    let f: Vec<&str> =
        if tokens.len() == 10 && int_at.iter().all(|&i| integer(tokens[i], "").is_ok()) {
            tokens
        } else {
            let cols = [
                (0, 5),
                (5, 10),
                (15, 5),
                (20, 10),
                (31, 10),
                (41, 10),
                (51, 4),
                (56, 10),
                (66, 10),
                (76, 4),
            ];
            cols.iter().map(|&(s, w)| column(t, s, w)).collect()
        };
    let int = |s: &str, field| {
        if s.is_empty() {
            Ok(0)
        } else {
            integer(s, field).map_err(at)
        }
    };
    let node = |s: &str, field| -> Result<u64, Located> {
        let v = int(s, field)?;
        u64::try_from(v).map_err(|_| {
            at(Problem::Invalid {
                field,
                value: v.to_string(),
                allowed: "a node number must be >= 0",
            })
        })
    };
    let direction = |s: &str, field| -> Result<i32, Located> {
        let v = int(s, field)?;
        if (-6..=6).contains(&v) {
            Ok(v as i32)
        } else {
            Err(at(Problem::Code {
                field,
                value: v,
                allowed: "-6..6 (0 scalar, 1-3 translations, 4-6 rotations)",
            }))
        }
    };
    if t.trim().is_empty() {
        return Err(at(Problem::Truncated {
            what: "the function type (record 6)",
        }));
    }
    let code = int(f[0], "function type (record 6)")?;
    let function_type = i32::try_from(code)
        .map(FunctionType::from_code)
        .map_err(|_| {
            at(Problem::Invalid {
                field: "function type (record 6)",
                value: code.to_string(),
                allowed: "a code of the format's table (0-27)",
            })
        })?;
    let ids = [
        int(f[1], "function identification number (record 6)")?,
        int(f[2], "version number (record 6)")?,
        int(f[3], "load case identification number (record 6)")?,
    ];
    let response = Dof {
        entity: f[4].to_string(),
        node: node(f[5], "response node (record 6)")?,
        direction: direction(f[6], "response direction (record 6)")?,
    };
    let reference = Dof {
        entity: f[7].to_string(),
        node: node(f[8], "reference node (record 6)")?,
        direction: direction(f[9], "reference direction (record 6)")?,
    };
    Ok((function_type, ids, response, reference))
}

fn axis(line: &Line, field: &'static str) -> Result<Axis, Located> {
    let at = |p| Located::new(line.number, p);
    let t = &line.text;
    // By columns (I10,3I5) when they hold integers; else by blanks.
    let by_cols: Option<Vec<i64>> = [(0, 10), (10, 5), (15, 5), (20, 5)]
        .iter()
        .map(|&(s, w)| {
            let c = column(t, s, w);
            if c.is_empty() {
                Some(0)
            } else {
                integer(c, field).ok()
            }
        })
        .collect();
    let (ints, label, units) = match by_cols {
        Some(ints) if !column(t, 0, 10).is_empty() => (
            ints,
            column(t, 25, 21).to_string(),
            column(t, 46, 21).to_string(),
        ),
        _ => {
            let tokens: Vec<&str> = t.split_whitespace().collect();
            if tokens.len() < 4 {
                return Err(at(Problem::Truncated { what: field }));
            }
            let ints = integers(&tokens[..4].join(" "), &[], field).map_err(at)?;
            let label = tokens.get(4).copied().unwrap_or("").to_string();
            let units = tokens.get(5..).map(|u| u.join(" ")).unwrap_or_default();
            (ints, label, units)
        }
    };
    let small = |v: i64| {
        i32::try_from(v).map_err(|_| {
            at(Problem::Invalid {
                field,
                value: v.to_string(),
                allowed: "a data type code or units exponent fits 32 bits",
            })
        })
    };
    Ok(Axis {
        data_type: small(ints[0])?,
        length_exponent: small(ints[1])?,
        force_exponent: small(ints[2])?,
        temperature_exponent: small(ints[3])?,
        label,
        units,
    })
}

/// Payload lengths (bytes) of the 58b layouts that record 7 allows: for an uneven abscissa,
/// x in the ordinate's precision (pyuff) first, then x single precision (UC-SDRL).
pub(crate) fn binary_lengths(header: &[Line], number_line: usize) -> Result<Vec<usize>, Located> {
    if header.len() != 11 {
        return Err(Located::new(
            number_line,
            Problem::Invalid {
                field: "number of ASCII lines (58b header)",
                value: header.len().to_string(),
                allowed: "dataset 58 has 11 header lines",
            },
        ));
    }
    let form = data_form(&header[6])?;
    let size = if form.precision == Precision::Double {
        8
    } else {
        4
    };
    let ordinate = size * (1 + usize::from(form.complex));
    let per_point: Vec<usize> = if form.even {
        vec![ordinate]
    } else if size == 4 {
        vec![ordinate + 4]
    } else {
        vec![ordinate + size, ordinate + 4]
    };
    per_point
        .into_iter()
        .map(|p| {
            p.checked_mul(form.count).ok_or(Located::new(
                header[6].number,
                Problem::Invalid {
                    field: "number of points (record 7)",
                    value: form.count.to_string(),
                    allowed: "the binary payload length overflows",
                },
            ))
        })
        .collect()
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
            binary_values(&form, bytes, header.big_endian, line)?,
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
                        found: form.count + more / per_point.max(1),
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

/// The flat values of a 58b payload, whose length the splitter matched to one layout.
fn binary_values(
    form: &DataForm,
    bytes: &[u8],
    big_endian: bool,
    line: usize,
) -> Result<Vec<f64>, Located> {
    let size = if form.precision == Precision::Double {
        8
    } else {
        4
    };
    let ordinate = size * (1 + usize::from(form.complex));
    let x_size = if form.even || Some(bytes.len()) == form.count.checked_mul(ordinate + size) {
        size
    } else {
        4
    };
    let point = ordinate + if form.even { 0 } else { x_size };
    let needed = form.count.saturating_mul(point);
    if bytes.len() < needed {
        return Err(Located::new(
            line,
            Problem::TooFew {
                what: "bytes of binary data",
                expected: needed,
                found: bytes.len(),
            },
        ));
    }
    let mut flat = Vec::with_capacity(bytes.len() / 4);
    let mut pos = 0;
    let mut take = |n: usize| -> f64 {
        let b = &bytes[pos..pos + n];
        pos += n;
        match (n, big_endian) {
            (4, false) => f64::from(f32::from_le_bytes([b[0], b[1], b[2], b[3]])),
            (4, true) => f64::from(f32::from_be_bytes([b[0], b[1], b[2], b[3]])),
            (_, false) => f64::from_le_bytes(b.try_into().unwrap_or([0; 8])),
            (_, true) => f64::from_be_bytes(b.try_into().unwrap_or([0; 8])),
        }
    };
    for _ in 0..form.count {
        if !form.even {
            flat.push(take(x_size));
        }
        for _ in 0..1 + usize::from(form.complex) {
            flat.push(take(size));
        }
    }
    if let Some(i) = flat.iter().position(|v| !v.is_finite()) {
        return Err(Located::new(
            line,
            Problem::Invalid {
                field: "binary data value (record 12)",
                value: format!(
                    "{} (value {} of point {})",
                    flat[i],
                    i % form.per_point() + 1,
                    i / form.per_point() + 1
                ),
                allowed: "it must be finite",
            },
        ));
    }
    Ok(flat)
}

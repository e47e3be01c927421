//! Dataset 55, "Data at Nodes": mode shapes (and other nodal results).
//!
//! Records 1-5 are the ID lines; record 6, `Format(6I10)`: model type, analysis type (2 normal
//! mode, 3 complex eigenvalue first order, 5 frequency response, 7 complex eigenvalue second
//! order, ...), data characteristic (1 scalar, 2 three-DOF translation vector X Y Z, 3 six-DOF
//! translation and rotation vector X Y Z RX RY RZ, 4 symmetric and 5 general tensor), specific
//! data type (8 displacement, 11 velocity, 12 acceleration, ...), data type (2 real, 5 complex;
//! 4 and 6 are read as their double-precision twins) and the number of values per node NDV.
//! Record 7, `Format(8I10)`: the counts NINT and NRVAL of integer and real parameters, then
//! the integers; record 8, `Format(6E13.5)`: the reals. For a normal mode the integers are the
//! load case and the mode number and the reals the frequency (Hz), modal mass, modal viscous
//! damping ratio and modal hysteretic damping ratio; for a complex mode the reals are the
//! eigenvalue, modal A and modal B (real, imaginary parts). Records 9 (`I10`, node number) and
//! 10 (`6E13.5`, NDV values, or 2 NDV for complex data as Re, Im pairs) repeat per node; a
//! node whose values are all zero may be absent.
//!
//! NDV, not the data characteristic, sets how many values a node holds (writers are known to
//! put the one where the other belongs); the first three are the X, Y, Z translations for
//! characteristics 2 and 3.
//!
//! Layout after the I-DEAS / UC-SDRL "Universal Dataset Number 55" description (as reproduced
//! in pyuff's `dataset_55.py`).

use faer::c64;

use super::Values;
use super::error::{Located, Problem};
use super::fields::{Cursor, Line, collect_reals, integers, integers_n};
use super::function::Precision;
use super::split::RawDataset;

/// The data characteristic of record 6, field 3.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum DataCharacteristic {
    /// 0.
    Unknown,
    /// 1: one value per node.
    Scalar,
    /// 2: three-DOF global translation vector X, Y, Z.
    Translation,
    /// 3: six-DOF global translation and rotation vector X, Y, Z, RX, RY, RZ.
    TranslationRotation,
    /// Any other code (4 symmetric tensor, 5 general tensor, ...).
    Other(i32),
}

impl DataCharacteristic {
    /// The code of the format.
    pub fn code(self) -> i32 {
        match self {
            DataCharacteristic::Unknown => 0,
            DataCharacteristic::Scalar => 1,
            DataCharacteristic::Translation => 2,
            DataCharacteristic::TranslationRotation => 3,
            DataCharacteristic::Other(c) => c,
        }
    }

    /// The characteristic of a code.
    pub fn from_code(code: i32) -> Self {
        match code {
            0 => DataCharacteristic::Unknown,
            1 => DataCharacteristic::Scalar,
            2 => DataCharacteristic::Translation,
            3 => DataCharacteristic::TranslationRotation,
            c => DataCharacteristic::Other(c),
        }
    }
}

/// The analysis type (record 6, field 2) with its parameters (records 7 and 8).
#[derive(Debug, Clone, PartialEq)]
pub enum Analysis {
    /// 2: a real normal mode.
    NormalMode {
        /// Load case number.
        load_case: i64,
        /// Mode number.
        mode: i64,
        /// Natural frequency, Hz.
        frequency_hz: f64,
        /// Modal mass (0 when the file gives fewer reals).
        modal_mass: f64,
        /// Modal viscous damping ratio (0 when absent).
        viscous_damping: f64,
        /// Modal hysteretic damping ratio (0 when absent).
        hysteretic_damping: f64,
    },
    /// 3 (first order) or 7 (second order): a complex mode.
    ComplexMode {
        /// Analysis type 7 (second order) rather than 3.
        second_order: bool,
        /// Load case number.
        load_case: i64,
        /// Mode number.
        mode: i64,
        /// Eigenvalue (rad/s).
        eigenvalue: c64,
        /// Modal A.
        modal_a: c64,
        /// Modal B.
        modal_b: c64,
    },
    /// 5: a frequency response step.
    FrequencyResponse {
        /// Load case number.
        load_case: i64,
        /// Frequency step number.
        step: i64,
        /// Frequency, Hz.
        frequency_hz: f64,
    },
    /// Any other analysis type, with its raw parameters.
    Other {
        /// Analysis type code.
        code: i32,
        /// Type-specific integers (record 7, after the two counts).
        integers: Vec<i64>,
        /// Type-specific reals (record 8).
        reals: Vec<f64>,
    },
}

/// Data at nodes (dataset 55), usually one mode shape.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeShape {
    /// ID lines 1-5, trailing blanks removed.
    pub id_lines: [String; 5],
    /// Model type: 0 unknown, 1 structural, 2 heat transfer, 3 fluid flow.
    pub model_type: i32,
    /// Analysis type and its parameters.
    pub analysis: Analysis,
    /// Data characteristic.
    pub characteristic: DataCharacteristic,
    /// Specific data type: 8 displacement, 11 velocity, 12 acceleration, ...
    pub specific_data_type: i32,
    /// Declared precision (data type 2/5 single, 4/6 double).
    pub precision: Precision,
    /// Number of values per node (NDV).
    pub values_per_node: usize,
    /// Node numbers, in file order.
    pub nodes: Vec<u64>,
    /// The values, node by node, `values_per_node` per node.
    pub values: Values,
}

impl ModeShape {
    /// Value `component` (0-based, < NDV) at the node of index `node_index`, as a complex
    /// number (imaginary part 0 for real data).
    pub fn value(&self, node_index: usize, component: usize) -> Option<c64> {
        if component >= self.values_per_node {
            return None;
        }
        let i = node_index.checked_mul(self.values_per_node)? + component;
        match &self.values {
            Values::Real(v) => v.get(i).map(|&x| c64::new(x, 0.0)),
            Values::Complex(v) => v.get(i).copied(),
        }
    }
}

/// `count` integers spread over the next lines (`Format(8I10)`).
fn collect_ints(
    cursor: &mut Cursor<'_, '_>,
    count: usize,
    field: &'static str,
) -> Result<Vec<i64>, Located> {
    let mut out = Vec::new();
    while out.len() < count {
        let line = cursor.next(field)?;
        let ints = integers(&line.text, &[10], field).map_err(|p| Located::new(line.number, p))?;
        if ints.is_empty() {
            return Err(Located::new(
                line.number,
                Problem::Truncated { what: field },
            ));
        }
        out.extend(ints);
    }
    Ok(out)
}

fn small(v: i64, field: &'static str, line: &Line) -> Result<i32, Located> {
    i32::try_from(v).map_err(|_| {
        Located::new(
            line.number,
            Problem::Invalid {
                field,
                value: v.to_string(),
                allowed: "a code fits 32 bits",
            },
        )
    })
}

fn count(
    v: i64,
    field: &'static str,
    line: usize,
    allowed: &'static str,
) -> Result<usize, Located> {
    usize::try_from(v).map_err(|_| {
        Located::new(
            line,
            Problem::Invalid {
                field,
                value: v.to_string(),
                allowed,
            },
        )
    })
}

/// Reads a dataset 55.
pub(crate) fn parse(ds: &RawDataset) -> Result<ModeShape, Located> {
    let mut cursor = Cursor::new(&ds.lines, ds.end_line);
    let mut id_lines: [String; 5] = Default::default();
    for id in &mut id_lines {
        *id = cursor
            .next("the ID lines (records 1-5)")?
            .text
            .trim_end()
            .to_string();
    }
    let r6 = cursor.next("the data definition parameters (record 6)")?;
    let at6 = |p| Located::new(r6.number, p);
    let f = integers_n(&r6.text, 6, &[10], "data definition parameters (record 6)").map_err(at6)?;
    let model_type = small(f[0], "model type (record 6)", r6)?;
    let analysis_code = small(f[1], "analysis type (record 6)", r6)?;
    let characteristic =
        DataCharacteristic::from_code(small(f[2], "data characteristic (record 6)", r6)?);
    let specific_data_type = small(f[3], "specific data type (record 6)", r6)?;
    let (complex, precision) = match f[4] {
        2 => (false, Precision::Single),
        4 => (false, Precision::Double),
        5 => (true, Precision::Single),
        6 => (true, Precision::Double),
        v => {
            return Err(at6(Problem::Code {
                field: "data type (record 6)",
                value: v,
                allowed: "2 real, 5 complex (4, 6 double precision)",
            }));
        }
    };
    let ndv = count(
        f[5],
        "number of values per node (record 6)",
        r6.number,
        "it must be >= 1",
    )?;
    if ndv == 0 {
        return Err(at6(Problem::Invalid {
            field: "number of values per node (record 6)",
            value: "0".into(),
            allowed: "it must be >= 1",
        }));
    }

    let analysis = parameters(&mut cursor, analysis_code)?;

    let per_node = ndv.saturating_mul(1 + usize::from(complex));
    let (nodes, flat) = node_values(&mut cursor, per_node)?;
    let values = if complex {
        Values::Complex(flat.chunks_exact(2).map(|p| c64::new(p[0], p[1])).collect())
    } else {
        Values::Real(flat)
    };
    Ok(ModeShape {
        id_lines,
        model_type,
        analysis,
        characteristic,
        specific_data_type,
        precision,
        values_per_node: ndv,
        nodes,
        values,
    })
}

/// Records 7 and 8: the integer and real parameters of the analysis of type `code`.
fn parameters(cursor: &mut Cursor, code: i32) -> Result<Analysis, Located> {
    let r7_line = cursor
        .rest()
        .first()
        .map_or(cursor.end_line(), |l| l.number);
    let head = collect_ints(cursor, 2, "the parameter counts (record 7)")?;
    let allowed = "it must be >= 0";
    let nint = count(
        head[0],
        "number of integer values (record 7)",
        r7_line,
        allowed,
    )?;
    let nrval = count(
        head[1],
        "number of real values (record 7)",
        r7_line,
        allowed,
    )?;
    let mut ints = head[2..].to_vec();
    if ints.len() < nint {
        ints.extend(collect_ints(
            cursor,
            nint - ints.len(),
            "the integer parameters (record 7)",
        )?);
    }
    if ints.len() > nint {
        return Err(Located::new(
            r7_line,
            Problem::TooMany {
                what: "integer parameters (record 7)",
                expected: nint,
                found: ints.len(),
            },
        ));
    }
    let reals = collect_reals(
        cursor,
        nrval,
        1,
        &[13],
        "real parameters (record 8)",
        "real parameter (record 8)",
    )?;
    analysis(code, ints, reals, r7_line)
}

/// Records 9 and 10 of every node: its number and its `per_node` values.
fn node_values(cursor: &mut Cursor, per_node: usize) -> Result<(Vec<u64>, Vec<f64>), Located> {
    let mut nodes = Vec::new();
    let mut flat = Vec::new();
    while let Some(line) = cursor.next_non_blank() {
        let at = |p| Located::new(line.number, p);
        let ids = integers(&line.text, &[10], "node number (record 9)").map_err(at)?;
        if ids.len() != 1 {
            return Err(at(Problem::Invalid {
                field: "node number (record 9)",
                value: line.text.trim().chars().take(80).collect(),
                allowed: "record 9 holds the node number alone (I10)",
            }));
        }
        nodes.push(count(
            ids[0],
            "node number (record 9)",
            line.number,
            "a node number must be >= 0",
        )? as u64);
        flat.extend(collect_reals(
            cursor,
            per_node,
            1,
            &[13],
            "data values of the node (record 10)",
            "data value (record 10)",
        )?);
    }
    Ok((nodes, flat))
}

fn analysis(code: i32, ints: Vec<i64>, reals: Vec<f64>, line: usize) -> Result<Analysis, Located> {
    let need = |n_int: usize, n_real: usize, what: &'static str| -> Result<(), Located> {
        if ints.len() < n_int {
            return Err(Located::new(
                line,
                Problem::TooFew {
                    what,
                    expected: n_int,
                    found: ints.len(),
                },
            ));
        }
        if reals.len() < n_real {
            return Err(Located::new(
                line,
                Problem::TooFew {
                    what,
                    expected: n_real,
                    found: reals.len(),
                },
            ));
        }
        Ok(())
    };
    let real_or_zero = |i: usize| reals.get(i).copied().unwrap_or(0.0);
    Ok(match code {
        2 => {
            need(
                2,
                1,
                "parameters of a normal mode (load case, mode; frequency)",
            )?;
            Analysis::NormalMode {
                load_case: ints[0],
                mode: ints[1],
                frequency_hz: reals[0],
                modal_mass: real_or_zero(1),
                viscous_damping: real_or_zero(2),
                hysteretic_damping: real_or_zero(3),
            }
        }
        3 | 7 => {
            need(
                2,
                6,
                "parameters of a complex mode (load case, mode; eigenvalue, modal A, modal B)",
            )?;
            Analysis::ComplexMode {
                second_order: code == 7,
                load_case: ints[0],
                mode: ints[1],
                eigenvalue: c64::new(reals[0], reals[1]),
                modal_a: c64::new(reals[2], reals[3]),
                modal_b: c64::new(reals[4], reals[5]),
            }
        }
        5 => {
            need(
                2,
                1,
                "parameters of a frequency response (load case, step; frequency)",
            )?;
            Analysis::FrequencyResponse {
                load_case: ints[0],
                step: ints[1],
                frequency_hz: reals[0],
            }
        }
        code => Analysis::Other {
            code,
            integers: ints,
            reals,
        },
    })
}

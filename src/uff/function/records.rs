//! Records 6-11 of dataset 58: DOF identification, data form, axis characteristics.
//!
//! Numbers are read by blanks when the line splits into the right fields, else by the columns
//! of the record's format; a line that fits neither is reported whole, with its format.

use super::{Axis, Dof, FunctionType, Precision};
use crate::uff::error::{Located, Problem};
use crate::uff::fields::{Line, column, integer, integers, real};

/// Record 7, the data form.
pub(super) struct DataForm {
    pub complex: bool,
    pub precision: Precision,
    /// Number of points (a complex value counts once).
    pub count: usize,
    pub even: bool,
    pub start: f64,
    pub step: f64,
    pub z: f64,
}

impl DataForm {
    /// Values per point in record 12: x (uneven), Re, Im (complex).
    pub fn per_point(&self) -> usize {
        usize::from(!self.even) + 1 + usize::from(self.complex)
    }
}

/// The whole line as the offending value of a record that fits neither by blanks nor by
/// columns.
fn layout(line: &Line, field: &'static str, allowed: &'static str) -> Located {
    Located::new(
        line.number,
        Problem::Invalid {
            field,
            value: format!("{:?}", line.text.trim_end()),
            allowed,
        },
    )
}

/// The three integers and up to three reals of record 7.
fn data_form_fields(line: &Line) -> Option<([i64; 3], Vec<f64>)> {
    let t = &line.text;
    let tokens: Vec<&str> = t.split_whitespace().collect();
    let by_blanks = || -> Option<([i64; 3], Vec<f64>)> {
        if !(3..=6).contains(&tokens.len()) {
            return None;
        }
        let ints: Vec<i64> = tokens[..3]
            .iter()
            .map(|s| integer(s, "").ok())
            .collect::<Option<_>>()?;
        let reals: Vec<f64> = tokens[3..]
            .iter()
            .map(|s| real(s, "").ok())
            .collect::<Option<_>>()?;
        Some(([ints[0], ints[1], ints[2]], reals))
    };
    let by_columns = || -> Option<([i64; 3], Vec<f64>)> {
        let f: Vec<&str> = [(0, 10), (10, 10), (20, 10), (30, 13), (43, 13), (56, 13)]
            .iter()
            .map(|&(s, w)| column(t, s, w))
            .collect();
        let ints: Vec<i64> = f[..3]
            .iter()
            .map(|s| integer(s, "").ok())
            .collect::<Option<_>>()?;
        let n_reals = f[3..]
            .iter()
            .rposition(|s| !s.is_empty())
            .map_or(0, |i| i + 1);
        let reals: Vec<f64> = f[3..3 + n_reals]
            .iter()
            .map(|s| real(s, "").ok())
            .collect::<Option<_>>()?;
        Some(([ints[0], ints[1], ints[2]], reals))
    };
    by_blanks().or_else(by_columns)
}

pub(super) fn data_form(line: &Line) -> Result<DataForm, Located> {
    let at = |p| Located::new(line.number, p);
    let ([ord_type, n, spacing], r) = data_form_fields(line).ok_or_else(|| {
        layout(
            line,
            "data form (record 7)",
            "it must hold the ordinate data type, number of points, abscissa spacing, \
             abscissa minimum, increment and z value (3I10,3E13.5)",
        )
    })?;
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
    let count = usize::try_from(n).map_err(|_| {
        at(Problem::Invalid {
            field: "number of points (record 7)",
            value: n.to_string(),
            allowed: "it must be >= 0",
        })
    })?;
    let even = match spacing {
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
    if even && r.len() < 2 {
        return Err(at(Problem::Truncated {
            what: "the abscissa minimum and increment of record 7 (even spacing)",
        }));
    }
    let (start, step) = (
        r.first().copied().unwrap_or(0.0),
        r.get(1).copied().unwrap_or(0.0),
    );
    if even && count > 1 && step == 0.0 {
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
        start,
        step,
        z: r.get(2).copied().unwrap_or(0.0),
    })
}

/// The ten fields of record 6 as text: by blanks when there are ten with integers where
/// integers belong, else by columns (`2(I5,I10),2(1X,10A1,I10,I4)`), a blank integer being 0.
fn dof_texts(t: &str) -> Option<Vec<&str>> {
    const INTS: [usize; 8] = [0, 1, 2, 3, 5, 6, 8, 9];
    let tokens: Vec<&str> = t.split_whitespace().collect();
    if tokens.len() == 10 && INTS.iter().all(|&i| integer(tokens[i], "").is_ok()) {
        return Some(tokens);
    }
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
    let f: Vec<&str> = cols.iter().map(|&(s, w)| column(t, s, w)).collect();
    let ints_ok = INTS
        .iter()
        .all(|&i| f[i].is_empty() || integer(f[i], "").is_ok());
    (ints_ok && !f[0].is_empty()).then_some(f)
}

pub(super) fn dof_fields(line: &Line) -> Result<(FunctionType, [i64; 3], Dof, Dof), Located> {
    let at = |p| Located::new(line.number, p);
    let f = dof_texts(&line.text).ok_or_else(|| {
        layout(
            line,
            "DOF identification (record 6)",
            "it must hold the function type, function id, version, load case, then entity name, \
             node and direction of the response and of the reference (2(I5,I10),2(1X,10A1,I10,I4))",
        )
    })?;
    let int = |s: &str| {
        if s.is_empty() {
            0
        } else {
            integer(s, "").unwrap_or(0)
        }
    };
    let node = |s: &str, field| {
        let v = int(s);
        u64::try_from(v).map_err(|_| {
            at(Problem::Invalid {
                field,
                value: v.to_string(),
                allowed: "a node number must be >= 0",
            })
        })
    };
    let direction = |s: &str, field| {
        let v = int(s);
        match i32::try_from(v) {
            Ok(d) if (-6..=6).contains(&d) => Ok(d),
            _ => Err(at(Problem::Code {
                field,
                value: v,
                allowed: "-6..6 (0 scalar, 1-3 translations, 4-6 rotations)",
            })),
        }
    };
    let code = int(f[0]);
    let function_type = i32::try_from(code)
        .map(FunctionType::from_code)
        .map_err(|_| {
            at(Problem::Invalid {
                field: "function type (record 6)",
                value: code.to_string(),
                allowed: "a code of the format's table (0-27)",
            })
        })?;
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
    Ok((
        function_type,
        [int(f[1]), int(f[2]), int(f[3])],
        response,
        reference,
    ))
}

/// Records 8-11: by columns (`I10,3I5,2(1X,20A1)`) when they hold the integers, else by
/// blanks (four integers, the label, then the units).
pub(super) fn axis(line: &Line, field: &'static str) -> Result<Axis, Located> {
    let at = |p| Located::new(line.number, p);
    let t = &line.text;
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
            let ints = (tokens.len() >= 4)
                .then(|| integers(&tokens[..4].join(" "), &[], field).ok())
                .flatten()
                .ok_or_else(|| {
                    layout(
                        line,
                        field,
                        "it must hold the specific data type, length, force and temperature \
                         exponents, axis label and units label (I10,3I5,2(1X,20A1))",
                    )
                })?;
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

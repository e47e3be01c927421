//! Datasets 164 ("Units") and 151 ("Header").
//!
//! Dataset 164: record 1, `Format(I10,20A1,I10)`: units code (1 SI, 2 BG, 3 MG, 4 BA, 5 MM,
//! 6 CM, 7 IN, 8 GM, 9 user defined), description, temperature mode (1 absolute, 2 relative;
//! often absent); record 2, `Format(3D25.17)`: the factors that convert the file's units to SI
//! (SI value = file value / factor) for length, force, temperature, then the temperature
//! offset on a line of its own.
//!
//! Dataset 151: seven text records: model file name, model file description, program that
//! created the database, date/time created (with versions and file type), date/time last
//! saved, program that wrote the universal file, date/time written. The header is informative:
//! records missing at its end are read as empty.
//!
//! Layouts after the I-DEAS / UC-SDRL descriptions of datasets 164 and 151 (as reproduced in
//! pyuff's `dataset_164.py` and `dataset_151.py`).

use super::error::{Located, Problem};
use super::fields::{Cursor, collect_reals, column, integer};
use super::split::RawDataset;

/// The unit system of a dataset 164 (record 1, field 1).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum UnitSystem {
    /// 1 SI: meter, newton.
    Si,
    /// 2 BG: foot, pound force.
    BritishGravitational,
    /// 3 MG: meter, kilogram force.
    MetricGravitational,
    /// 4 BA: foot, poundal.
    BritishAbsolute,
    /// 5 MM: millimeter, millinewton.
    MillimeterMillinewton,
    /// 6 CM: centimeter, centinewton.
    CentimeterCentinewton,
    /// 7 IN: inch, pound force.
    InchPoundForce,
    /// 8 GM: millimeter, kilogram force.
    MillimeterKilogramForce,
    /// 9 US: user defined (the factors say what).
    UserDefined,
}

impl UnitSystem {
    /// The code of the format.
    pub fn code(self) -> i32 {
        self as i32 + 1
    }

    /// The system of a code 1-9.
    pub fn from_code(code: i64) -> Option<Self> {
        use UnitSystem::*;
        const ALL: [UnitSystem; 9] = [
            Si,
            BritishGravitational,
            MetricGravitational,
            BritishAbsolute,
            MillimeterMillinewton,
            CentimeterCentinewton,
            InchPoundForce,
            MillimeterKilogramForce,
            UserDefined,
        ];
        usize::try_from(code - 1)
            .ok()
            .and_then(|i| ALL.get(i).copied())
    }
}

/// The units of the data that follow (dataset 164).
#[derive(Debug, Clone, PartialEq)]
pub struct Units {
    /// Unit system.
    pub system: UnitSystem,
    /// Description (documentation only), trimmed.
    pub description: String,
    /// Temperature mode: 1 absolute, 2 relative; `None` when the field is blank.
    pub temperature_mode: Option<i32>,
    /// Length factor: SI length = file length / factor.
    pub length: f64,
    /// Force factor: SI force = file force / factor.
    pub force: f64,
    /// Temperature factor.
    pub temperature: f64,
    /// Temperature offset.
    pub temperature_offset: f64,
}

/// The header of a universal file (dataset 151), as text.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Header {
    /// Model file name.
    pub model_file: String,
    /// Model file description.
    pub description: String,
    /// Program that created the database.
    pub database_program: String,
    /// Date and time the database was created (with versions and file type), as written.
    pub database_created: String,
    /// Date and time the database was last saved, as written.
    pub database_saved: String,
    /// Program that wrote the universal file.
    pub program: String,
    /// Date and time the universal file was written, as written.
    pub written: String,
}

/// Reads a dataset 164.
pub(crate) fn parse_164(ds: &RawDataset) -> Result<Units, Located> {
    let mut cursor = Cursor::new(&ds.lines, ds.end_line);
    let r1 = cursor.next("the units code (record 1)")?;
    let at = |p| Located::new(r1.number, p);
    let t = &r1.text;
    let code_text = column(t, 0, 10);
    let code_text = if code_text.is_empty() {
        t.split_whitespace().next().unwrap_or("")
    } else {
        code_text
    };
    let code = integer(code_text, "units code (record 1)").map_err(at)?;
    let system = UnitSystem::from_code(code).ok_or(at(Problem::Code {
        field: "units code (record 1)",
        value: code,
        allowed: "1 SI, 2 BG, 3 MG, 4 BA, 5 MM, 6 CM, 7 IN, 8 GM, 9 user defined",
    }))?;
    let mode_text = column(t, 30, 10);
    let temperature_mode = if mode_text.is_empty() {
        None
    } else {
        let m = integer(mode_text, "temperature mode (record 1)").map_err(at)?;
        Some(i32::try_from(m).map_err(|_| {
            at(Problem::Code {
                field: "temperature mode (record 1)",
                value: m,
                allowed: "1 absolute, 2 relative",
            })
        })?)
    };
    let f = collect_reals(
        &mut cursor,
        4,
        1,
        &[25],
        "unit factors (record 2: length, force, temperature, temperature offset)",
        "unit factor (record 2)",
    )?;
    if let Some(extra) = cursor.next_non_blank() {
        return Err(Located::new(
            extra.number,
            Problem::Invalid {
                field: "line after the unit factors",
                value: format!("{:?}", extra.text.trim()),
                allowed: "a dataset 164 ends after record 2",
            },
        ));
    }
    for (v, field) in f[..3]
        .iter()
        .zip(["length factor", "force factor", "temperature factor"])
    {
        if *v == 0.0 {
            return Err(Located::new(
                ds.end_line,
                Problem::Invalid {
                    field,
                    value: "0".into(),
                    allowed: "a conversion factor must be nonzero",
                },
            ));
        }
    }
    Ok(Units {
        system,
        description: column(t, 10, 20).to_string(),
        temperature_mode,
        length: f[0],
        force: f[1],
        temperature: f[2],
        temperature_offset: f[3],
    })
}

/// Reads a dataset 151.
pub(crate) fn parse_151(ds: &RawDataset) -> Header {
    let line = |i: usize| {
        ds.lines
            .get(i)
            .map(|l| l.text.trim().to_string())
            .unwrap_or_default()
    };
    Header {
        model_file: line(0),
        description: line(1),
        database_program: line(2),
        database_created: line(3),
        database_saved: line(4),
        program: line(5),
        written: line(6),
    }
}

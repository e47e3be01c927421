//! The result of `jointid identify`: one row per (mode, parameter).
//!
//! CSV columns: `mode,param,initial,correction,corrected,relative_correction,
//! frequency_measured_hz,frequency_model_hz,condition,resolution,identified`. Numbers are
//! written in the shortest form that reads back to the same f64. A mode whose S_r is rank
//! deficient has empty `correction`, `corrected` and `relative_correction` and
//! `condition = inf`; a parameter held on a mode (`--params auto`) has `identified = held`, a
//! zero correction, and the condition of the parameters the mode identified. When the measured
//! modes carry standard errors, two more columns: `correction_std,relative_correction_std`,
//! their first-order propagation (module `identify::propagation`); the projection is then
//! weighted by them.

use std::io::{self, Write};

use super::table::{sci, write_table};
use crate::identify::{MIN_RESOLUTION, ModeOutcome};
use crate::structure::Parameter;

/// The CSV header.
pub const HEADER: [&str; 11] = [
    "mode",
    "param",
    "initial",
    "correction",
    "corrected",
    "relative_correction",
    "frequency_measured_hz",
    "frequency_model_hz",
    "condition",
    "resolution",
    "identified",
];

/// The columns after [`HEADER`] when the data carry standard errors: the standard deviation
/// of the correction and of the relative correction.
pub const STD_COLUMNS: [&str; 2] = ["correction_std", "relative_correction_std"];

/// One output row.
#[derive(Debug, Clone, PartialEq)]
pub struct IdentifyRow {
    /// Mode r.
    pub mode: usize,
    /// Parameter name.
    pub param: String,
    /// p_i.
    pub initial: f64,
    /// Z_r(i), `None` when S_r is rank deficient.
    pub relative: Option<f64>,
    /// Measured frequency, Hz.
    pub frequency_measured_hz: f64,
    /// Paired nominal frequency, Hz.
    pub frequency_model_hz: f64,
    /// cond(W S_r) of the identified parameters.
    pub condition: f64,
    /// Resolution of the parameter on this mode (1: seen apart from the others, 0: not).
    pub resolution: f64,
    /// Whether it was identified on this mode (false: held at its value).
    pub identified: bool,
    /// Standard deviation of Z_r(i) from the data's own standard errors, when they carry them.
    pub relative_std: Option<f64>,
}

impl IdentifyRow {
    /// Delta p_i = p_i Z_r(i).
    pub fn correction(&self) -> Option<f64> {
        self.relative.map(|z| self.initial * z)
    }

    /// p_i + Delta p_i.
    pub fn corrected(&self) -> Option<f64> {
        self.correction().map(|d| self.initial + d)
    }
}

/// The rows of a set of identified modes.
pub fn rows(outcomes: &[ModeOutcome], params: &[Parameter]) -> Vec<IdentifyRow> {
    outcomes
        .iter()
        .flat_map(|o| {
            params.iter().enumerate().map(move |(i, p)| IdentifyRow {
                mode: o.mode,
                param: p.name.clone(),
                initial: p.value,
                relative: o.relative.as_ref().ok().map(|z| z[i]),
                frequency_measured_hz: o.frequency_measured_hz,
                frequency_model_hz: o.frequency_model_hz,
                condition: o.condition,
                resolution: o.resolution[i],
                identified: o.solved[i],
                relative_std: o.std.as_ref().map(|s| s[i]),
            })
        })
        .collect()
}

fn opt(x: Option<f64>) -> String {
    x.map(|v| v.to_string()).unwrap_or_default()
}

/// Writes the rows as CSV.
pub fn write_csv(out: &mut dyn Write, rows: &[IdentifyRow]) -> io::Result<()> {
    let mut w = csv::Writer::from_writer(out);
    let std = rows.iter().any(|r| r.relative_std.is_some());
    let mut header = HEADER.to_vec();
    if std {
        header.extend(STD_COLUMNS);
    }
    w.write_record(&header)?;
    for r in rows {
        let mut row = vec![
            r.mode.to_string(),
            r.param.clone(),
            r.initial.to_string(),
            opt(r.correction()),
            opt(r.corrected()),
            opt(r.relative),
            r.frequency_measured_hz.to_string(),
            r.frequency_model_hz.to_string(),
            r.condition.to_string(),
            r.resolution.to_string(),
            if r.identified { "yes" } else { "held" }.to_string(),
        ];
        if std {
            row.push(opt(r.relative_std.map(|s| s * r.initial)));
            row.push(opt(r.relative_std));
        }
        w.write_record(&row)?;
    }
    w.flush()
}

/// Writes the rows as an aligned terminal table.
pub fn write_text(out: &mut dyn Write, rows: &[IdentifyRow]) -> io::Result<()> {
    let header = [
        "mode",
        "param",
        "initial",
        "correction",
        "corrected",
        "rel. corr.",
        "f meas (Hz)",
        "f model (Hz)",
        "cond(WS)",
        "resolution",
    ];
    let std = rows.iter().any(|r| r.relative_std.is_some());
    let mut header = header.to_vec();
    if std {
        header.push("+- (std)");
    }
    let na = || "rank-deficient".to_string();
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            vec![
                r.mode.to_string(),
                r.param.clone(),
                sci(r.initial),
                match (r.identified, r.correction()) {
                    (false, _) => "held".to_string(),
                    (true, c) => c.map(sci).unwrap_or_else(na),
                },
                r.corrected().map(sci).unwrap_or_else(na),
                r.relative.map(|z| format!("{z:+.4}")).unwrap_or_else(na),
                format!("{:.3}", r.frequency_measured_hz),
                format!("{:.3}", r.frequency_model_hz),
                format!("{:.3e}", r.condition),
                format!("{:.1e}", r.resolution),
            ]
            .into_iter()
            .chain(std.then(|| {
                r.relative_std
                    .map(|s| sci(s * r.initial))
                    .unwrap_or_default()
            }))
            .collect()
        })
        .collect();
    write_table(out, &header, &cells)
}

/// Writes what each mode could not identify, one sentence per mode with its cause and remedy.
pub fn write_notes(
    out: &mut dyn Write,
    outcomes: &[ModeOutcome],
    params: &[Parameter],
) -> io::Result<()> {
    for o in outcomes {
        let unresolved: Vec<String> = params
            .iter()
            .zip(&o.resolution)
            .filter(|(_, r)| **r < MIN_RESOLUTION)
            .map(|(p, r)| format!("{} (resolution {r:.1e})", p.name))
            .collect();
        let held: Vec<&str> = params
            .iter()
            .zip(&o.solved)
            .filter(|(_, s)| !**s)
            .map(|(p, _)| p.name.as_str())
            .collect();
        match (&o.relative, held.is_empty()) {
            (Err(rd), _) => writeln!(
                out,
                "warning: mode {}: S_r has rank {} < q = {}, its corrections are left empty: this mode does not tell apart {}; identify the parameters it determines with --params auto, or retain more equations (--m) or measure more points",
                o.mode,
                rd.rank,
                params.len(),
                if unresolved.is_empty() {
                    "its parameters".to_string()
                } else {
                    unresolved.join(", ")
                },
            )?,
            (Ok(_), false) => writeln!(
                out,
                "note: mode {}: {} held at {} value: this mode does not determine {} ({})",
                o.mode,
                held.join(", "),
                if held.len() == 1 { "its" } else { "their" },
                if held.len() == 1 { "it" } else { "them" },
                unresolved.join(", "),
            )?,
            (Ok(_), true) => {}
        }
    }
    Ok(())
}

//! The result of `jointid identify`: one row per (mode, parameter).
//!
//! CSV columns: `mode,param,initial,correction,corrected,relative_correction,
//! frequency_measured_hz,frequency_model_hz,condition,resolution,identified`. Numbers are
//! written in the shortest form that reads back to the same f64. A mode identify cannot stand
//! behind, its S_r rank deficient or its frequency beyond what its parameter reaches, has
//! empty `correction`, `corrected`, `relative_correction` and `condition` (a warning on stderr
//! says why); a parameter held on a mode (`--params auto`) has `identified = held`, a zero
//! correction, and the condition of the parameters the mode identified. A mode identified from
//! its frequency alone (module `identify::frequency_only`) has `identified = frequency` on its
//! one parameter (condition 1, resolution 1: one equation, one unknown) and `held` on the
//! others (resolution 0). When the measured modes carry standard errors, two more columns:
//! `correction_std,relative_correction_std`, their first-order propagation (module
//! `identify::propagation`); the projection is then weighted by them.

use std::io::{self, Write};

use super::table::{sci, write_table};
use crate::identify::frequency_only::{Fallback, FrequencyOutcome, Source};
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
    /// cond(W S_r) of the identified parameters; `None` where the corrections are empty (no
    /// solution to condition).
    pub condition: Option<f64>,
    /// Resolution of the parameter on this mode (1: seen apart from the others, 0: not).
    pub resolution: f64,
    /// How it was determined on this mode (or held at its value).
    pub source: Source,
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
                condition: o.relative.is_ok().then_some(o.condition),
                resolution: o.resolution[i],
                source: if o.solved[i] {
                    Source::Shape
                } else {
                    Source::Held
                },
                relative_std: o.std.as_ref().map(|s| s[i]),
            })
        })
        .collect()
}

/// The rows of a mode identified from its frequency alone: its parameter, the others held.
pub fn frequency_rows(o: &FrequencyOutcome, f_hz: f64, params: &[Parameter]) -> Vec<IdentifyRow> {
    params
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let own = i == o.param;
            IdentifyRow {
                mode: o.mode,
                param: p.name.clone(),
                initial: p.value,
                relative: Some(if own { o.relative } else { 0.0 }),
                frequency_measured_hz: f_hz,
                frequency_model_hz: o.frequency_model_hz,
                condition: Some(1.0),
                resolution: if own { 1.0 } else { 0.0 },
                source: if own { Source::Frequency } else { Source::Held },
                relative_std: if own { o.std } else { None },
            }
        })
        .collect()
}

fn opt(x: Option<f64>) -> String {
    x.map(|v| v.to_string()).unwrap_or_default()
}

/// The rows of a mode whose frequency could not give its parameter: corrections empty.
pub fn unsolved_rows(
    mode: usize,
    f_hz: f64,
    f_model_hz: f64,
    params: &[Parameter],
) -> Vec<IdentifyRow> {
    params
        .iter()
        .map(|p| IdentifyRow {
            mode,
            param: p.name.clone(),
            initial: p.value,
            relative: None,
            frequency_measured_hz: f_hz,
            frequency_model_hz: f_model_hz,
            condition: None,
            resolution: 0.0,
            source: Source::Frequency,
            relative_std: None,
        })
        .collect()
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
            opt(r.condition),
            r.resolution.to_string(),
            match r.source {
                Source::Shape => "yes",
                Source::Frequency => "frequency",
                Source::Held => "held",
            }
            .to_string(),
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
    let cells: Vec<Vec<String>> = rows
        .iter()
        .map(|r| {
            let na = || match r.source {
                Source::Frequency => "no solution".to_string(),
                _ => "rank-deficient".to_string(),
            };
            vec![
                r.mode.to_string(),
                r.param.clone(),
                sci(r.initial),
                match (r.source, r.correction()) {
                    (Source::Held, _) => "held".to_string(),
                    (Source::Frequency, Some(c)) => format!("{} f", sci(c)),
                    (_, c) => c.map(sci).unwrap_or_else(na),
                },
                r.corrected().map(sci).unwrap_or_else(na),
                r.relative.map(|z| format!("{z:+.4}")).unwrap_or_else(na),
                format!("{:.3}", r.frequency_measured_hz),
                format!("{:.3}", r.frequency_model_hz),
                r.condition
                    .map(|c| format!("{c:.3e}"))
                    .unwrap_or_else(|| "-".to_string()),
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

/// Writes, for every mode identified from its frequency alone, which parameter, its
/// sensitivity and why.
pub fn write_frequency_notes(
    out: &mut dyn Write,
    fallbacks: &[(FrequencyOutcome, Fallback)],
    params: &[Parameter],
) -> io::Result<()> {
    for (f, why) in fallbacks {
        let why = match why {
            Fallback::Asked => "--from-frequency".to_string(),
            Fallback::RankDeficient(o) => format!(
                "its S_r has rank {} < q",
                o.relative.as_ref().err().map(|r| r.rank).unwrap_or(0)
            ),
        };
        writeln!(
            out,
            "note: mode {}: {} from the frequency alone ({why}), d ln lambda / d ln p = {:.3e}; the other parameters held{}",
            f.mode,
            params[f.param].name,
            f.sensitivity,
            if f.std.is_none() {
                "; no standard deviation: give --frequency-noise or frequency_std in the data"
            } else {
                ""
            }
        )?;
    }
    Ok(())
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::identify::RankDeficient;
    use crate::structure::{Role, SparseSym};

    fn params() -> Vec<Parameter> {
        ["k1", "k2"]
            .into_iter()
            .map(|name| Parameter {
                name: name.to_string(),
                unit: "N/m",
                value: 1e4,
                stiffness: SparseSym::zero(),
                mass: SparseSym::zero(),
                role: Role::Identified,
            })
            .collect()
    }

    fn csv(rows: &[IdentifyRow]) -> String {
        let mut buf = Vec::new();
        write_csv(&mut buf, rows).unwrap();
        String::from_utf8(buf).unwrap()
    }

    #[test]
    fn a_mode_without_corrections_has_an_empty_condition_not_inf() {
        let rank_deficient = ModeOutcome {
            mode: 2,
            basis_index: 3,
            frequency_measured_hz: 100.0,
            frequency_model_hz: 99.0,
            g: vec![1.0],
            condition: f64::INFINITY,
            relative: Err(RankDeficient { rank: 1 }),
            resolution: vec![0.0, 0.0],
            solved: vec![true, true],
            std: None,
        };
        let mut rows = rows(&[rank_deficient], &params());
        rows.extend(unsolved_rows(3, 500.0, 200.0, &params()));
        let text = csv(&rows);
        let lines: Vec<&str> = text.lines().collect();
        assert_eq!(lines.len(), 5, "{text}");
        for line in &lines[1..] {
            let f: Vec<&str> = line.split(',').collect();
            assert_eq!(&f[3..6], ["", "", ""], "{line}");
            assert_eq!(f[8], "", "condition of {line}");
        }
        assert!(!text.contains("inf"), "{text}");
        let mut table = Vec::new();
        write_text(&mut table, &rows).unwrap();
        assert!(!String::from_utf8(table).unwrap().contains("inf"));
    }

    #[test]
    fn a_solved_mode_keeps_its_condition() {
        let solved = ModeOutcome {
            mode: 1,
            basis_index: 2,
            frequency_measured_hz: 100.0,
            frequency_model_hz: 99.0,
            g: vec![1.0],
            condition: 12.5,
            relative: Ok(vec![0.1, 0.2]),
            resolution: vec![1.0, 1.0],
            solved: vec![true, true],
            std: None,
        };
        let text = csv(&rows(&[solved], &params()));
        for line in text.lines().skip(1) {
            assert_eq!(line.split(',').nth(8), Some("12.5"), "{line}");
        }
    }
}

/// The rows of every mode of an identification, with the outcomes its notes are about.
#[derive(Debug, Clone)]
pub struct Gathered {
    /// The rows, mode by mode.
    pub rows: Vec<IdentifyRow>,
    /// The paper's outcomes (a rank-deficient one whose frequency failed too included).
    pub outcomes: Vec<ModeOutcome>,
    /// The modes identified from their frequency alone, and why.
    pub fallbacks: Vec<(FrequencyOutcome, Fallback)>,
    /// One warning per mode left unsolved, saying why.
    pub warnings: Vec<String>,
}

/// Each mode's rows in mode order: its paper's outcome, else its frequency-only outcome, else
/// empty corrections with a warning.
pub fn gathered(identified: &crate::identify::run::Identified) -> Gathered {
    use crate::identify::run::Way;
    let (params, all) = (&identified.params, &identified.all);
    let mut g = Gathered {
        rows: Vec::new(),
        outcomes: Vec::new(),
        fallbacks: Vec::new(),
        warnings: Vec::new(),
    };
    for mode in &identified.modes {
        match &mode.way {
            Way::Paper(o) | Way::Unsolved(Fallback::RankDeficient(o), _) => {
                g.rows.extend(rows(std::slice::from_ref(o), params));
                g.outcomes.push(o.clone());
            }
            Way::Frequency(f, why) => {
                g.rows.extend(frequency_rows(f, mode.frequency_hz, all));
                g.fallbacks.push((f.clone(), why.clone()));
            }
            Way::Unsolved(Fallback::Asked, _) => g.rows.extend(unsolved_rows(
                mode.mode,
                mode.frequency_hz,
                mode.model_frequency_hz,
                all,
            )),
        }
        if let Way::Unsolved(_, e) = &mode.way {
            g.warnings
                .push(format!("{e}; its corrections are left empty"));
        }
    }
    g
}

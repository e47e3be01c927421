//! The CI gate on estimator bias: in the cells selected by `[check].where`, every
//! (mode, parameter) must have |relative bias| (of the mean, or of the median) within the
//! threshold, up to 3 Monte-Carlo standard errors:
//!
//! ```text
//!   fail  <=>  |x / t - 1| > max_abs_relative_bias + 3 se / |t|
//! ```
//! with x the mean (se = bias_se) or the median (se = median_se) and t the introduced value.

use std::path::PathBuf;

use super::CellResult;
use super::config::{CheckSpec, GateStatistic, Study};
use super::plan::Cell;

/// Number of Monte-Carlo standard errors the gate allows beyond the threshold.
pub const STANDARD_ERRORS: f64 = 3.0;

/// One (cell, mode, parameter) that fails the gate, with its figures.
#[derive(Debug, Clone, PartialEq)]
pub struct GateFailure {
    /// The cell.
    pub cell: Cell,
    /// Mode r.
    pub mode: usize,
    /// Parameter name.
    pub param: String,
    /// Why, with the figures.
    pub reason: String,
}

/// Outcome of the gate.
#[derive(Debug, Clone, PartialEq)]
pub struct GateReport {
    /// Rows the selection matched.
    pub checked: usize,
    /// Rows that failed.
    pub failures: Vec<GateFailure>,
}

fn selected<T: PartialEq>(filter: &Option<Vec<T>>, value: &T) -> bool {
    filter.as_ref().is_none_or(|v| v.contains(value))
}

fn cell_selected(spec: &CheckSpec, cell: &Cell) -> bool {
    selected(&spec.n, &cell.n.0)
        && selected(&spec.m, &cell.m.0)
        && selected(&spec.nf, &cell.nf())
        && selected(&spec.weighting, &cell.weighting)
        && selected(&spec.shape_noise, &cell.shape_noise)
        && selected(&spec.frequency_noise, &cell.frequency_noise)
}

/// How many (cell, mode, parameter) rows of the grid the gate selects, before anything is
/// computed: `modes` are the study's modes, `names` its parameter names.
pub fn selected_rows(spec: &CheckSpec, cells: &[Cell], modes: &[usize], names: &[String]) -> usize {
    let cells = cells.iter().filter(|c| cell_selected(spec, c)).count();
    let modes = modes.iter().filter(|m| selected(&spec.modes, m)).count();
    let params = names.iter().filter(|n| selected(&spec.params, n)).count();
    cells * modes * params
}

/// A study that cannot be held to a gate.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum GateError {
    /// The study file has no `[check]` table.
    #[error("{}: there is no [check] table: nothing to hold the study to", file.display())]
    NoCheck {
        /// The study file.
        file: PathBuf,
    },
    /// `[check].where` selects nothing of the grid.
    #[error(
        "{}: [check].where selects no (cell, mode, parameter) of the grid",
        file.display()
    )]
    SelectsNothing {
        /// The study file.
        file: PathBuf,
    },
}

/// The gate of `study`, checked before anything is computed: its `[check]` table, which must
/// select some (cell, mode, parameter) of the grid.
pub fn gate(study: &Study) -> Result<&CheckSpec, GateError> {
    let Some(spec) = &study.check else {
        return Err(GateError::NoCheck {
            file: study.file.clone(),
        });
    };
    let names = study.model.identified_names();
    if selected_rows(spec, &study.cells(), &study.modes, &names) == 0 {
        return Err(GateError::SelectsNothing {
            file: study.file.clone(),
        });
    }
    Ok(spec)
}

/// Evaluates the gate over the results of a study; `names` are the parameter names.
pub fn evaluate(spec: &CheckSpec, results: &[CellResult], names: &[String]) -> GateReport {
    let mut checked = 0;
    let mut failures = Vec::new();
    for result in results.iter().filter(|r| cell_selected(spec, &r.cell)) {
        for row in &result.rows {
            let name = &names[row.param];
            if !selected(&spec.modes, &row.mode) || !selected(&spec.params, name) {
                continue;
            }
            checked += 1;
            let t = row.introduced;
            let reason = match &row.summary {
                None => Some(format!(
                    "no successful trial ({} of {} rank deficient)",
                    row.failures, row.trials
                )),
                Some(_) if t == 0.0 => {
                    Some("the introduced value is 0: a relative bias is undefined".to_string())
                }
                Some(s) => {
                    let (label, x, se) = match spec.statistic {
                        GateStatistic::Mean => ("mean", s.mean, s.bias_se),
                        GateStatistic::Median => ("median", s.median, s.median_se),
                    };
                    let relative = x / t - 1.0;
                    let allowed = spec.max_abs_relative_bias + STANDARD_ERRORS * se / t.abs();
                    // A NaN compares false: only a finite bias within its bound passes.
                    let within = relative.abs() <= allowed;
                    (!within).then(|| {
                        format!(
                            "relative bias of the {label} {relative:+.4} (x = {x:.4e}, introduced {t:.4e}, se {se:.3e}) exceeds {:.4} + 3 se = {allowed:.4}",
                            spec.max_abs_relative_bias
                        )
                    })
                }
            };
            if let Some(reason) = reason {
                failures.push(GateFailure {
                    cell: result.cell.clone(),
                    mode: row.mode,
                    param: name.clone(),
                    reason,
                });
            }
        }
    }
    GateReport { checked, failures }
}

#[cfg(test)]
mod tests {
    use std::path::Path;

    use super::*;

    #[test]
    fn a_gate_must_exist_and_select_some_row() {
        let mut study = Study::from_path(Path::new("studies/ci-bias.toml")).unwrap();
        assert_eq!(gate(&study).unwrap().max_abs_relative_bias, 0.05);
        if let Some(spec) = &mut study.check {
            spec.modes = Some(vec![99]);
        }
        assert_eq!(
            gate(&study).unwrap_err().to_string(),
            "studies/ci-bias.toml: [check].where selects no (cell, mode, parameter) of the grid"
        );
        study.check = None;
        assert_eq!(
            gate(&study).unwrap_err().to_string(),
            "studies/ci-bias.toml: there is no [check] table: nothing to hold the study to"
        );
    }
}

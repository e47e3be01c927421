//! A study's result CSV read back as the statistics of its cells, so that `jointid check
//! --results F.csv` holds a merged (or any earlier) result to the study's `[check]` without
//! running a trial.
//!
//! The file must be the result of this very study: every cell of the study present, each
//! with its conditions (n, m, nf, weighting, noise levels, noise distribution, introduced
//! value) as the study file gives them, and one row per (mode, parameter). The numbers are
//! read as written (Rust's shortest round-trip decimal), so they are the computed bits.

use std::io::Read;
use std::path::{Path, PathBuf};

use crate::output::study::RESULT_HEADER;
use crate::stats::Summary;
use crate::study::{CellResult, RowStats, Study};

/// A result CSV that does not belong to the study or cannot be read.
#[derive(Debug, thiserror::Error)]
pub enum ResultsError {
    /// Cannot read.
    #[error("{file}: cannot read: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// Why.
        cause: std::io::Error,
    },
    /// A bad line.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// Line, 1-based.
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// Rows missing.
    #[error(
        "{file}: cell {cell} ({describe}) has {found} of its {expected} rows: the file is not a complete result of {study}"
    )]
    Incomplete {
        /// The file.
        file: PathBuf,
        /// The cell.
        cell: usize,
        /// Its conditions.
        describe: String,
        /// Rows found.
        found: usize,
        /// Rows expected.
        expected: usize,
        /// The study file.
        study: PathBuf,
    },
}

/// Reads a result CSV of `study` from a file.
pub fn read_results_path(path: &Path, study: &Study) -> Result<Vec<CellResult>, ResultsError> {
    let file = std::fs::File::open(path).map_err(|cause| ResultsError::Read {
        file: path.into(),
        cause,
    })?;
    read_results(std::io::BufReader::new(file), path, study)
}

/// Reads a result CSV of `study`; `file` names it in errors.
pub fn read_results<R: Read>(
    reader: R,
    file: &Path,
    study: &Study,
) -> Result<Vec<CellResult>, ResultsError> {
    let bad = |line: u64, message: String| ResultsError::Line {
        file: file.into(),
        line,
        message,
    };
    let mut csv = csv::Reader::from_reader(reader);
    let header = csv.headers().map_err(|e| bad(1, e.to_string()))?.clone();
    if header.iter().ne(RESULT_HEADER) {
        return Err(bad(
            1,
            format!(
                "the columns are not those of a study result: expected {}",
                RESULT_HEADER.join(",")
            ),
        ));
    }
    let names: Vec<String> = study
        .model
        .identified()
        .into_iter()
        .map(|p| p.name)
        .collect();
    let mut results: Vec<CellResult> = study
        .cells()
        .into_iter()
        .map(|cell| CellResult {
            cell,
            rows: Vec::new(),
        })
        .collect();
    for record in csv.records() {
        let record =
            record.map_err(|e| bad(e.position().map_or(0, |p| p.line()), e.to_string()))?;
        let line = record.position().map_or(0, |p| p.line());
        let field = |column: &str| {
            record
                .get(RESULT_HEADER.iter().position(|c| *c == column).unwrap_or(0))
                .unwrap_or("")
        };
        let parse = |column: &str| -> Result<f64, ResultsError> {
            field(column).parse::<f64>().map_err(|_| {
                bad(
                    line,
                    format!("{column} = `{}` is not a number", field(column)),
                )
            })
        };
        let optional = |column: &str| -> Result<Option<f64>, ResultsError> {
            if field(column).is_empty() {
                Ok(None)
            } else {
                parse(column).map(Some)
            }
        };
        let whole = |column: &str| -> Result<usize, ResultsError> {
            field(column).parse::<usize>().map_err(|_| {
                bad(
                    line,
                    format!("{column} = `{}` is not a whole number", field(column)),
                )
            })
        };
        let index = whole("cell")?;
        let Some(result) = results.get_mut(index) else {
            return Err(bad(
                line,
                format!(
                    "cell = {index}: {} has {} cells",
                    study.file.display(),
                    study.cells().len()
                ),
            ));
        };
        let c = &result.cell;
        let introduced = |i: usize| study.delta[i].to_string();
        let mode = whole("mode")?;
        let param = names
            .iter()
            .position(|n| n == field("param"))
            .ok_or_else(|| {
                bad(
                    line,
                    format!(
                        "param = `{}`: the study identifies {}",
                        field("param"),
                        names.join(", ")
                    ),
                )
            })?;
        let expected = [
            ("n", c.n.0.to_string()),
            ("m", c.m.0.to_string()),
            ("nf", c.nf().to_string()),
            ("weighting", c.weighting.to_string()),
            ("shape_noise", c.shape_noise.to_string()),
            ("frequency_noise", c.frequency_noise.to_string()),
            ("noise", study.noise.to_string()),
            ("introduced", introduced(param)),
            ("trials", study.trials.to_string()),
            ("unidentified", c.unidentified_names()),
        ];
        for (column, want) in expected {
            if field(column) != want {
                return Err(bad(
                    line,
                    format!(
                        "{column} = `{}` but cell {index} of {} has {want}: the results are not of this study",
                        field(column),
                        study.file.display()
                    ),
                ));
            }
        }
        if !study.modes.contains(&mode) {
            return Err(bad(
                line,
                format!("mode = {mode} is not a mode of {}", study.file.display()),
            ));
        }
        let trials = whole("trials")?;
        let failures = whole("failures")?;
        let summary = match optional("mean")? {
            None => None,
            Some(mean) => Some(Summary {
                count: trials.saturating_sub(failures),
                mean,
                bias: parse("bias")?,
                relative_bias: optional("relative_bias")?,
                std: parse("std")?,
                rmse: parse("rmse")?,
                median: parse("median")?,
                mad: parse("mad")?,
                q05: parse("q05")?,
                q25: parse("q25")?,
                q75: parse("q75")?,
                q95: parse("q95")?,
                bias_se: parse("bias_se")?,
                median_se: parse("median_se")?,
            }),
        };
        let row = RowStats {
            mode,
            param,
            introduced: study.delta[param],
            trials,
            failures,
            summary,
            predicted_std: optional("predicted_std")?,
        };
        if result
            .rows
            .iter()
            .any(|r| r.mode == mode && r.param == param)
        {
            return Err(bad(
                line,
                format!("cell {index}, mode {mode}, {} appears twice", names[param]),
            ));
        }
        result.rows.push(row);
    }
    let expected = study.modes.len() * names.len();
    for r in &results {
        if r.rows.len() != expected {
            return Err(ResultsError::Incomplete {
                file: file.into(),
                cell: r.cell.index,
                describe: r.cell.describe(),
                found: r.rows.len(),
                expected,
                study: study.file.clone(),
            });
        }
    }
    Ok(results)
}

//! A study's result CSV read back as the statistics of its cells, so that `jointid check
//! --results F.csv` holds a merged (or any earlier) result to the study's `[check]` without
//! running a trial.
//!
//! The file must be the result of this very study: every cell of the study present, each
//! with its conditions (n, m, nf, weighting, noise levels, noise distribution, introduced
//! value) as the study file gives them, and one row per (mode, parameter). The numbers are
//! read as written (Rust's shortest round-trip decimal), so they are the computed bits; a
//! number that is not finite (NaN, inf), or statistics that contradict the trial counts
//! (a mean given although every trial failed, or missing although some succeeded), make the
//! file damaged, not a result. The file is read within [`TABLE`]'s limits.

use std::io::Read;
use std::path::{Path, PathBuf};

use crate::input::bounded::{Bounded, TABLE};
use crate::input::safe::quoted;
use crate::stats::Summary;
use crate::study::results::{Column, RESULT_HEADER};
use crate::study::{Cell, CellResult, RowStats, Study};

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
        message: crate::input::safe::clip_quotes(message),
    };
    let mut csv = csv::Reader::from_reader(Bounded::new(reader, TABLE));
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
    let names = study.model.identified_names();
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
        let fields = Fields {
            record: &record,
            line: record.position().map_or(0, |p| p.line()),
            file,
        };
        read_row(&fields, study, &names, &mut results)?;
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

/// The fields of one row, read by column.
struct Fields<'a> {
    record: &'a csv::StringRecord,
    /// Its line, 1-based.
    line: u64,
    file: &'a Path,
}

impl Fields<'_> {
    fn bad(&self, message: String) -> ResultsError {
        ResultsError::Line {
            file: self.file.into(),
            line: self.line,
            message: crate::input::safe::clip_quotes(message),
        }
    }

    fn text(&self, column: Column) -> &str {
        self.record.get(column.index()).unwrap_or("")
    }

    /// The field parsed as a `T`; else an error saying it is not `what` (`a number`).
    fn parse<T: std::str::FromStr>(&self, column: Column, what: &str) -> Result<T, ResultsError> {
        self.text(column).parse::<T>().map_err(|_| {
            self.bad(format!(
                "{} = {} is not {what}",
                column.name(),
                quoted(self.text(column))
            ))
        })
    }

    /// A finite number (NaN and inf are damage, never a statistic).
    fn number(&self, column: Column) -> Result<f64, ResultsError> {
        let v: f64 = self.parse(column, "a number")?;
        if v.is_finite() {
            Ok(v)
        } else {
            Err(self.bad(format!(
                "{} = {} is not a finite number: the results are damaged",
                column.name(),
                quoted(self.text(column))
            )))
        }
    }

    fn optional(&self, column: Column) -> Result<Option<f64>, ResultsError> {
        if self.text(column).is_empty() {
            Ok(None)
        } else {
            self.number(column).map(Some)
        }
    }

    fn whole(&self, column: Column) -> Result<usize, ResultsError> {
        self.parse(column, "a whole number")
    }
}

/// Reads one row into its cell of `results`, after checking that it belongs to `study`
/// (`names`: its parameters) and is not there already.
fn read_row(
    f: &Fields,
    study: &Study,
    names: &[String],
    results: &mut [CellResult],
) -> Result<(), ResultsError> {
    let cell_count = results.len();
    let index = f.whole(Column::Cell)?;
    let Some(result) = results.get_mut(index) else {
        return Err(f.bad(format!(
            "cell = {index}: {} has {cell_count} cells",
            study.file.display(),
        )));
    };
    let mode = f.whole(Column::Mode)?;
    let param = names
        .iter()
        .position(|n| n == f.text(Column::Param))
        .ok_or_else(|| {
            f.bad(format!(
                "param = `{}`: the study identifies {}",
                f.text(Column::Param),
                names.join(", ")
            ))
        })?;
    check_conditions(f, study, &result.cell, index, param)?;
    if !study.modes.contains(&mode) {
        return Err(f.bad(format!(
            "mode = {mode} is not a mode of {}",
            study.file.display()
        )));
    }
    let trials = f.whole(Column::Trials)?;
    let failures = f.whole(Column::Failures)?;
    if failures > trials {
        return Err(f.bad(format!(
            "failures = {failures} is more than trials = {trials}: the results are damaged"
        )));
    }
    let row = RowStats {
        mode,
        param,
        introduced: study.delta[param],
        trials,
        failures,
        summary: summary(f, trials.saturating_sub(failures))?,
        predicted_std: f.optional(Column::PredictedStd)?,
    };
    if result
        .rows
        .iter()
        .any(|r| r.mode == mode && r.param == param)
    {
        return Err(f.bad(format!(
            "cell {index}, mode {mode}, {} appears twice",
            names[param]
        )));
    }
    result.rows.push(row);
    Ok(())
}

/// Checks that a row of cell `index`, parameter `param`, states the conditions the study
/// gives the cell.
fn check_conditions(
    f: &Fields,
    study: &Study,
    c: &Cell,
    index: usize,
    param: usize,
) -> Result<(), ResultsError> {
    // n to frequency_noise, as Cell::condition_fields gives them.
    let conditions = Column::ALL[Column::N.index()..=Column::FrequencyNoise.index()]
        .iter()
        .copied()
        .zip(c.condition_fields());
    let expected = conditions.chain([
        (Column::Noise, study.noise_name().to_string()),
        (Column::Introduced, study.delta[param].to_string()),
        (Column::Trials, study.trials.to_string()),
        (Column::Unidentified, c.unidentified_names()),
    ]);
    for (column, want) in expected {
        if f.text(column) != want {
            return Err(f.bad(format!(
                "{} = `{}` but cell {index} of {} has {want}: the results are not of this study",
                column.name(),
                f.text(column),
                study.file.display()
            )));
        }
    }
    Ok(())
}

/// The statistics of a row over its `count` successful trials; None when `mean` is empty,
/// which it must be exactly when every trial failed.
fn summary(f: &Fields, count: usize) -> Result<Option<Summary>, ResultsError> {
    let mean = f.optional(Column::Mean)?;
    if mean.is_none() != (count == 0) {
        return Err(f.bad(format!(
            "mean is {} although {count} trial(s) succeeded: the results are damaged",
            if count == 0 { "given" } else { "empty" }
        )));
    }
    let Some(mean) = mean else {
        return Ok(None);
    };
    Ok(Some(Summary {
        count,
        mean,
        bias: f.number(Column::Bias)?,
        relative_bias: f.optional(Column::RelativeBias)?,
        std: f.number(Column::Std)?,
        rmse: f.number(Column::Rmse)?,
        median: f.number(Column::Median)?,
        mad: f.number(Column::Mad)?,
        q05: f.number(Column::Q05)?,
        q25: f.number(Column::Q25)?,
        q75: f.number(Column::Q75)?,
        q95: f.number(Column::Q95)?,
        bias_se: f.number(Column::BiasSe)?,
        median_se: f.number(Column::MedianSe)?,
    }))
}

//! Reading a study result CSV back for reports: the rows, the conditions of every cell, and
//! which grid axes vary.
//!
//! Layer 6 (diagnosis and results; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`], [`crate::model`], [`crate::measured`], [`crate::extract`],
//! [`crate::identify`], [`crate::simulate`], [`crate::study`]) and, without a circle,
//! [`crate::diagnose`], [`crate::cluster`].

use std::collections::BTreeMap;
use std::io::Read;
use std::path::{Path, PathBuf};

use crate::input::bounded::{self, Bounded, TABLE};
use crate::input::safe::clip_quotes;
use crate::study::results::Column;

/// Columns a report needs from a study CSV (of [`crate::study::results`]): those that say
/// which row it is and how it was run (`cell` to `failures`), the quantiles and the relative
/// bias.
pub fn required() -> Vec<Column> {
    let conditions = &Column::ALL[..=Column::Failures.index()];
    conditions
        .iter()
        .copied()
        .chain([
            Column::Median,
            Column::Q05,
            Column::Q25,
            Column::Q75,
            Column::Q95,
            Column::RelativeBias,
        ])
        .collect()
}

/// A study CSV that cannot be reported.
#[derive(Debug, thiserror::Error)]
pub enum ReportError {
    /// Cannot read.
    #[error("{file}: cannot read: {cause}")]
    Read {
        /// The file.
        file: PathBuf,
        /// Why.
        cause: std::io::Error,
    },
    /// Not a jointid study output.
    #[error("{file} is not a jointid study output: missing column(s) {missing}")]
    MissingColumns {
        /// The file.
        file: PathBuf,
        /// The missing columns, comma separated.
        missing: String,
    },
    /// A bad field.
    #[error("{file}:{line}: {message}")]
    Line {
        /// The file.
        file: PathBuf,
        /// Line.
        line: u64,
        /// What is wrong.
        message: String,
    },
    /// No row.
    #[error("{file}: no result row")]
    Empty {
        /// The file.
        file: PathBuf,
    },
}

/// The conditions of a cell.
#[derive(Debug, Clone, PartialEq)]
pub struct Conditions {
    /// Basis size n.
    pub n: usize,
    /// Retained equations m.
    pub m: usize,
    /// Unidentified DOFs.
    pub nf: usize,
    /// Weighting name.
    pub weighting: String,
    /// Shape noise level.
    pub shape_noise: f64,
    /// Frequency noise level.
    pub frequency_noise: f64,
}

impl Conditions {
    /// The paper's W number of the weighting (1 equal, 2 inverse, 3 inverse-sqrt).
    pub fn w(&self) -> &str {
        match self.weighting.as_str() {
            "equal" => "1",
            "inverse" => "2",
            "inverse-sqrt" => "3",
            other => other,
        }
    }

    /// `n/m/NF/W` for tick labels.
    pub fn short(&self) -> String {
        format!("{}/{}/{}/{}", self.n, self.m, self.nf, self.w())
    }
}

/// One (cell, mode, parameter) row.
#[derive(Debug, Clone, PartialEq)]
pub struct ResultRow {
    /// Cell index.
    pub cell: usize,
    /// Mode r.
    pub mode: usize,
    /// Parameter name.
    pub param: String,
    /// Introduced value.
    pub introduced: f64,
    /// Trials run.
    pub trials: usize,
    /// Rank-deficient trials.
    pub failures: usize,
    /// q05, q25, median, q75, q95 (None when every trial failed).
    pub quantiles: Option<[f64; 5]>,
    /// Relative bias of the mean.
    pub relative_bias: Option<f64>,
}

/// A study CSV, read back.
#[derive(Debug, Clone, PartialEq)]
pub struct StudyResults {
    /// Rows in file order.
    pub rows: Vec<ResultRow>,
    /// Conditions of every cell.
    pub cells: BTreeMap<usize, Conditions>,
    /// Noise distribution.
    pub noise: String,
}

/// Where each [`required`] column is in `header`; the missing ones named when some are.
fn required_columns(
    header: &csv::StringRecord,
    file: &Path,
) -> Result<BTreeMap<Column, usize>, ReportError> {
    let required = required();
    let missing: Vec<&str> = required
        .iter()
        .map(|c| c.name())
        .filter(|c| !header.iter().any(|h| h == *c))
        .collect();
    if !missing.is_empty() {
        return Err(ReportError::MissingColumns {
            file: file.into(),
            missing: missing.join(", "),
        });
    }
    Ok(required
        .iter()
        .map(|&c| {
            (
                c,
                header
                    .iter()
                    .position(|h| h == c.name())
                    .expect("checked above"),
            )
        })
        .collect())
}

impl StudyResults {
    /// Reads a study CSV.
    pub fn from_path(path: &Path) -> Result<Self, ReportError> {
        let file = bounded::open(path, TABLE).map_err(|cause| ReportError::Read {
            file: path.into(),
            cause,
        })?;
        Self::from_reader(file, path)
    }

    /// Reads a study CSV from any reader, within [`TABLE`]'s limits (lines of 1 MiB, 4 GiB);
    /// `file` names it in errors.
    pub fn from_reader<R: Read>(reader: R, file: &Path) -> Result<Self, ReportError> {
        let mut csv = csv::Reader::from_reader(Bounded::new(reader, TABLE));
        let line_error = |line: u64, message: String| ReportError::Line {
            file: file.into(),
            line,
            message: clip_quotes(message),
        };
        // A limit passed or a failed read is the file's, not a line's.
        let csv_error = |e: csv::Error, line: u64| {
            let line = e.position().map_or(line, |p| p.line());
            let message = e.to_string();
            match e.into_kind() {
                csv::ErrorKind::Io(cause) => ReportError::Read {
                    file: file.into(),
                    cause,
                },
                _ => line_error(line, message),
            }
        };
        let header = csv.headers().map_err(|e| csv_error(e, 1))?.clone();
        let at = required_columns(&header, file)?;
        let (mut rows, mut cells, mut noise) = (Vec::new(), BTreeMap::new(), String::new());
        for record in csv.records() {
            let record = record.map_err(|e| csv_error(e, 0))?;
            let line = record.position().map_or(0, |p| p.line());
            let field = |column: Column| record.get(at[&column]).unwrap_or("");
            let number = |column: Column| -> Result<f64, ReportError> {
                field(column)
                    .parse::<f64>()
                    .ok()
                    .filter(|v| v.is_finite())
                    .ok_or_else(|| {
                        line_error(
                            line,
                            format!(
                                "{} = `{}` is not a finite number",
                                column.name(),
                                field(column)
                            ),
                        )
                    })
            };
            let optional = |column: Column| -> Result<Option<f64>, ReportError> {
                if field(column).is_empty() {
                    Ok(None)
                } else {
                    number(column).map(Some)
                }
            };
            let integer = |column: Column| -> Result<usize, ReportError> {
                field(column).parse().map_err(|_| {
                    line_error(
                        line,
                        format!("{} = `{}` is not a count", column.name(), field(column)),
                    )
                })
            };
            let cell = integer(Column::Cell)?;
            cells.entry(cell).or_insert(Conditions {
                n: integer(Column::N)?,
                m: integer(Column::M)?,
                nf: integer(Column::Nf)?,
                weighting: field(Column::Weighting).to_string(),
                shape_noise: number(Column::ShapeNoise)?,
                frequency_noise: number(Column::FrequencyNoise)?,
            });
            noise = field(Column::Noise).to_string();
            let q = [
                Column::Q05,
                Column::Q25,
                Column::Median,
                Column::Q75,
                Column::Q95,
            ]
            .map(optional);
            let quantiles = match q {
                [
                    Ok(Some(a)),
                    Ok(Some(b)),
                    Ok(Some(c)),
                    Ok(Some(d)),
                    Ok(Some(e)),
                ] => Some([a, b, c, d, e]),
                [Ok(None), Ok(None), Ok(None), Ok(None), Ok(None)] => None,
                _ => return Err(line_error(
                    line,
                    "the quantiles q05, q25, median, q75, q95 must all be numbers or all be empty"
                        .into(),
                )),
            };
            rows.push(ResultRow {
                cell,
                mode: integer(Column::Mode)?,
                param: field(Column::Param).to_string(),
                introduced: number(Column::Introduced)?,
                trials: integer(Column::Trials)?,
                failures: integer(Column::Failures)?,
                quantiles,
                relative_bias: optional(Column::RelativeBias)?,
            });
        }
        if rows.is_empty() {
            return Err(ReportError::Empty { file: file.into() });
        }
        Ok(Self { rows, cells, noise })
    }

    /// The modes, ascending.
    pub fn modes(&self) -> Vec<usize> {
        let mut v: Vec<usize> = self.rows.iter().map(|r| r.mode).collect();
        v.sort_unstable();
        v.dedup();
        v
    }

    /// The parameters, in file order.
    pub fn params(&self) -> Vec<String> {
        let mut v: Vec<String> = Vec::new();
        for r in &self.rows {
            if !v.contains(&r.param) {
                v.push(r.param.clone());
            }
        }
        v
    }

    /// The row of (cell, mode, param).
    pub fn row(&self, cell: usize, mode: usize, param: &str) -> Option<&ResultRow> {
        self.rows
            .iter()
            .find(|r| r.cell == cell && r.mode == mode && r.param == param)
    }
}

/// A grid axis of a study.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Axis {
    /// Basis size.
    N,
    /// Retained equations.
    M,
    /// Unidentified DOFs.
    Nf,
    /// Weighting.
    Weighting,
    /// Shape noise.
    ShapeNoise,
    /// Frequency noise.
    FrequencyNoise,
}

impl Axis {
    /// Every axis.
    pub const ALL: [Axis; 6] = [
        Axis::N,
        Axis::M,
        Axis::Nf,
        Axis::Weighting,
        Axis::ShapeNoise,
        Axis::FrequencyNoise,
    ];

    /// File-name-safe name.
    pub fn name(self) -> &'static str {
        match self {
            Axis::N => "n",
            Axis::M => "m",
            Axis::Nf => "nf",
            Axis::Weighting => "weighting",
            Axis::ShapeNoise => "shape_noise",
            Axis::FrequencyNoise => "frequency_noise",
        }
    }

    /// Axis label with unit.
    pub fn label(self) -> &'static str {
        match self {
            Axis::N => "basis size n (eigenpairs)",
            Axis::M => "retained equations m",
            Axis::Nf => "unidentified DOFs NF",
            Axis::Weighting => "weighting W (1 equal, 2 = 16-a, 3 = 16-b)",
            Axis::ShapeNoise => "shape noise (relative)",
            Axis::FrequencyNoise => "frequency noise (relative std)",
        }
    }

    /// The value of this axis in `c`, as a number for plotting (W as 1, 2, 3).
    pub fn value(self, c: &Conditions) -> f64 {
        match self {
            Axis::N => c.n as f64,
            Axis::M => c.m as f64,
            Axis::Nf => c.nf as f64,
            Axis::Weighting => c.w().parse().unwrap_or(0.0),
            Axis::ShapeNoise => c.shape_noise,
            Axis::FrequencyNoise => c.frequency_noise,
        }
    }

    /// Whether the axis takes more than one value in the study.
    pub fn varies(self, results: &StudyResults) -> bool {
        let mut values: Vec<f64> = results.cells.values().map(|c| self.value(c)).collect();
        values.sort_by(f64::total_cmp);
        values.dedup();
        values.len() > 1
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn every_required_column_is_written_by_the_study() {
        for column in required() {
            assert!(
                crate::study::results::RESULT_HEADER.contains(&column.name()),
                "{column:?}"
            );
        }
    }

    #[test]
    fn a_csv_without_the_study_columns_names_what_is_missing() {
        let err = StudyResults::from_reader(
            "mode,param,initial,correction\n1,k1,1,2\n".as_bytes(),
            Path::new("x.csv"),
        )
        .unwrap_err();
        let text = err.to_string();
        assert!(
            text.starts_with(
                "x.csv is not a jointid study output: missing column(s) cell, n, m, nf, weighting"
            ),
            "{text}"
        );
    }
}

//! The study's result CSV: its columns ([`Column`], [`RESULT_HEADER`]) and the writer of its
//! rows, one per (cell, mode, parameter). The study owns this schema: [`crate::cluster`] reads
//! results and shards back by it and [`crate::report`] picks its columns from it.
//!
//! Columns: `cell,mode,param,n,m,nf,weighting,shape_noise,frequency_noise,noise,
//! introduced,trials,failures,mean,bias,relative_bias,std,rmse,median,mad,q05,q25,q75,q95,
//! bias_se,predicted_std,median_se,unidentified`. Statistics are over the `trials - failures`
//! successful trials; a statistic that does not exist (every trial failed, a relative bias
//! of a zero introduction) is an empty field, never NaN. Numbers are Rust's shortest
//! round-trip decimals, so a result read back is the computed bits.

use std::io::{self, Write};

use super::{CellResult, RowStats};

/// A column of the result CSV, in file order.
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord)]
pub enum Column {
    /// The cell's index in the grid.
    Cell,
    /// Mode r.
    Mode,
    /// Parameter name.
    Param,
    /// Basis size n.
    N,
    /// Retained equations m.
    M,
    /// Unidentified DOFs NF.
    Nf,
    /// Weighting name.
    Weighting,
    /// Shape noise level.
    ShapeNoise,
    /// Frequency noise level.
    FrequencyNoise,
    /// Noise distribution.
    Noise,
    /// Introduced modification.
    Introduced,
    /// Trials run.
    Trials,
    /// Rank-deficient trials.
    Failures,
    /// Mean correction.
    Mean,
    /// Bias of the mean.
    Bias,
    /// Relative bias of the mean.
    RelativeBias,
    /// Standard deviation.
    Std,
    /// Root-mean-square error.
    Rmse,
    /// Median.
    Median,
    /// Median absolute deviation.
    Mad,
    /// 5% quantile.
    Q05,
    /// 25% quantile.
    Q25,
    /// 75% quantile.
    Q75,
    /// 95% quantile.
    Q95,
    /// Standard error of the bias.
    BiasSe,
    /// First-order predicted standard deviation.
    PredictedStd,
    /// Standard error of the median.
    MedianSe,
    /// The unidentified DOFs by name.
    Unidentified,
}

impl Column {
    /// Every column, in file order.
    pub const ALL: [Column; 28] = [
        Column::Cell,
        Column::Mode,
        Column::Param,
        Column::N,
        Column::M,
        Column::Nf,
        Column::Weighting,
        Column::ShapeNoise,
        Column::FrequencyNoise,
        Column::Noise,
        Column::Introduced,
        Column::Trials,
        Column::Failures,
        Column::Mean,
        Column::Bias,
        Column::RelativeBias,
        Column::Std,
        Column::Rmse,
        Column::Median,
        Column::Mad,
        Column::Q05,
        Column::Q25,
        Column::Q75,
        Column::Q95,
        Column::BiasSe,
        Column::PredictedStd,
        Column::MedianSe,
        Column::Unidentified,
    ];

    /// The column's name in the header.
    pub const fn name(self) -> &'static str {
        match self {
            Column::Cell => "cell",
            Column::Mode => "mode",
            Column::Param => "param",
            Column::N => "n",
            Column::M => "m",
            Column::Nf => "nf",
            Column::Weighting => "weighting",
            Column::ShapeNoise => "shape_noise",
            Column::FrequencyNoise => "frequency_noise",
            Column::Noise => "noise",
            Column::Introduced => "introduced",
            Column::Trials => "trials",
            Column::Failures => "failures",
            Column::Mean => "mean",
            Column::Bias => "bias",
            Column::RelativeBias => "relative_bias",
            Column::Std => "std",
            Column::Rmse => "rmse",
            Column::Median => "median",
            Column::Mad => "mad",
            Column::Q05 => "q05",
            Column::Q25 => "q25",
            Column::Q75 => "q75",
            Column::Q95 => "q95",
            Column::BiasSe => "bias_se",
            Column::PredictedStd => "predicted_std",
            Column::MedianSe => "median_se",
            Column::Unidentified => "unidentified",
        }
    }

    /// Position in the file's columns.
    pub fn index(self) -> usize {
        self as usize
    }
}

/// The header of the result CSV: every [`Column`]'s name, in file order.
pub const RESULT_HEADER: [&str; 28] = {
    let mut names = [""; 28];
    let mut i = 0;
    while i < names.len() {
        names[i] = Column::ALL[i].name();
        i += 1;
    }
    names
};

fn opt(x: Option<f64>) -> String {
    x.map(|v| v.to_string()).unwrap_or_default()
}

/// The fields `mean` to `bias_se`: empty when every trial failed.
fn stat_fields(row: &RowStats) -> Vec<String> {
    match &row.summary {
        None => vec![String::new(); 12],
        Some(s) => vec![
            s.mean.to_string(),
            s.bias.to_string(),
            opt(s.relative_bias),
            s.std.to_string(),
            s.rmse.to_string(),
            s.median.to_string(),
            s.mad.to_string(),
            s.q05.to_string(),
            s.q25.to_string(),
            s.q75.to_string(),
            s.q95.to_string(),
            s.bias_se.to_string(),
        ],
    }
}

/// Writes the result CSV: the header, then every row of every cell of `results`; `names`
/// are the parameter names, `noise` the study's noise ([`super::Study::noise_name`]).
pub fn write_results(
    out: &mut dyn Write,
    results: &[CellResult],
    names: &[String],
    noise: &str,
) -> io::Result<()> {
    let mut w = csv::Writer::from_writer(out);
    w.write_record(RESULT_HEADER)?;
    for r in results {
        let c = &r.cell;
        for row in &r.rows {
            let mut record = vec![
                c.index.to_string(),
                row.mode.to_string(),
                names[row.param].clone(),
            ];
            record.extend(c.condition_fields());
            record.extend([
                noise.to_string(),
                row.introduced.to_string(),
                row.trials.to_string(),
                row.failures.to_string(),
            ]);
            record.extend(stat_fields(row));
            record.push(opt(row.predicted_std));
            record.push(opt(row.summary.as_ref().map(|s| s.median_se)));
            record.push(c.unidentified_names());
            w.write_record(&record)?;
        }
    }
    w.flush()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_header_names_every_column_once_in_order() {
        for (i, column) in Column::ALL.iter().enumerate() {
            assert_eq!(column.index(), i);
            assert_eq!(RESULT_HEADER[i], column.name());
        }
        let mut names = RESULT_HEADER.to_vec();
        names.sort_unstable();
        names.dedup();
        assert_eq!(names.len(), RESULT_HEADER.len());
        assert_eq!(
            RESULT_HEADER.join(","),
            "cell,mode,param,n,m,nf,weighting,shape_noise,frequency_noise,noise,introduced,\
             trials,failures,mean,bias,relative_bias,std,rmse,median,mad,q05,q25,q75,q95,\
             bias_se,predicted_std,median_se,unidentified"
        );
    }
}

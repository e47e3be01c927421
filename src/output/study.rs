//! Study outputs beside the result CSV (whose schema and writer are the study's,
//! [`crate::study::results`]): the optional per-trial CSV, and the summary in the paper's
//! table layout.

use std::io::{self, Write};

use super::table::{sci, write_table};
use crate::study::measured_noise::MeasuredNoise;
use crate::study::{CellResult, CellSamples, Study};

/// The study's noise in words: `uniform noise`, or, for a noise taken from a measured file,
/// the file and each mode's relative errors that the grid's levels multiply.
pub fn noise_description(study: &Study) -> String {
    match &study.measured_noise {
        None => format!("{} noise", study.noise),
        Some(m) => measured_description(m),
    }
}

fn measured_description(m: &MeasuredNoise) -> String {
    let modes: Vec<String> = m
        .modes
        .iter()
        .map(|e| {
            format!(
                "mode {} shape {:.3}%, frequency {:.4}%",
                e.mode,
                100.0 * e.shape,
                100.0 * e.frequency
            )
        })
        .collect();
    format!(
        "normal noise of the standard errors of {} ({}), times the grid's shape_noise and frequency_noise",
        m.file.display(),
        modes.join("; ")
    )
}

/// Header of the per-trial CSV.
pub const TRIALS_HEADER: [&str; 6] = ["cell", "trial", "mode", "param", "correction", "failed"];

/// A CSV writer of every trial of every cell, fed cell by cell.
pub struct TrialsWriter<W: Write> {
    w: csv::Writer<W>,
}

impl<W: Write> TrialsWriter<W> {
    /// Starts the file with its header.
    pub fn new(out: W) -> io::Result<Self> {
        let mut w = csv::Writer::from_writer(out);
        w.write_record(TRIALS_HEADER)?;
        Ok(Self { w })
    }

    /// Appends the trials of one cell; a failed trial has an empty correction.
    pub fn write_cell(
        &mut self,
        cell: usize,
        modes: &[usize],
        names: &[String],
        samples: &CellSamples,
    ) -> io::Result<()> {
        let (k_count, q) = (samples.modes, samples.q);
        for t in 0..samples.trials() {
            for (k, mode) in modes.iter().enumerate() {
                let failed = samples.failed[t * k_count + k];
                for (i, name) in names.iter().enumerate() {
                    let value = if failed {
                        String::new()
                    } else {
                        samples.values[(t * k_count + k) * q + i].to_string()
                    };
                    self.w.write_record([
                        cell.to_string(),
                        t.to_string(),
                        mode.to_string(),
                        name.clone(),
                        value,
                        (failed as u8).to_string(),
                    ])?;
                }
            }
        }
        Ok(())
    }

    /// Flushes everything written.
    pub fn finish(mut self) -> io::Result<()> {
        self.w.flush()
    }
}

/// The summary in the paper's layout (its Tables 1 and 2): one row per condition, and per
/// mode and parameter the median with the [q05, q95] interval.
pub fn write_paper_table(
    out: &mut dyn Write,
    results: &[CellResult],
    names: &[String],
    modes: &[usize],
) -> io::Result<()> {
    let mut header: Vec<String> = ["cell", "n", "m", "NF", "W", "noise", "f.noise"]
        .iter()
        .map(|s| s.to_string())
        .collect();
    for r in modes {
        for name in names {
            header.push(format!("r={r} d{name}"));
        }
    }
    let rows: Vec<Vec<String>> = results
        .iter()
        .map(|res| {
            let c = &res.cell;
            let mut cells = vec![c.index.to_string()];
            cells.extend(c.condition_fields());
            for row in &res.rows {
                cells.push(match &row.summary {
                    Some(s) => format!("{} [{}, {}]", sci(s.median), sci(s.q05), sci(s.q95)),
                    None => "all failed".to_string(),
                });
            }
            cells
        })
        .collect();
    let header_refs: Vec<&str> = header.iter().map(String::as_str).collect();
    write_table(out, &header_refs, &rows)
}

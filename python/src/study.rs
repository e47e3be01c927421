//! `study`: a Monte-Carlo robustness study, the result table as the CLI's CSV text. Stopped
//! within a block of trials by Ctrl-C.

use std::path::PathBuf;

use pyo3::prelude::*;

use jointid::study::results::write_results;
use jointid::study::{Study, StudyRun};

use crate::errors;
use crate::work;

/// Runs the study of TOML `text` (`file` names it in errors and anchors its relative paths)
/// and returns the CLI's result CSV.
#[pyfunction]
#[pyo3(signature = (text, file, *, threads=None))]
pub fn study(
    py: Python<'_>,
    text: String,
    file: PathBuf,
    threads: Option<usize>,
) -> PyResult<String> {
    work::run(py, threads, move |stop| {
        let study = Study::from_toml(&text, &file).map_err(errors::input)?;
        let run = StudyRun::new(study).map_err(errors::computation)?;
        let names: Vec<String> = run.context.params.iter().map(|p| p.name.clone()).collect();
        let mut results = Vec::with_capacity(run.cells.len());
        for cell in &run.cells {
            match run.run_cell_until(cell, &|_| {}, stop) {
                Some((result, _)) => results.push(result),
                // interrupted: the caller has raised already, nobody reads this
                None => return Err(errors::computation("the study was interrupted")),
            }
        }
        let mut csv = Vec::new();
        write_results(&mut csv, &results, &names, run.study.noise_name())
            .map_err(errors::computation)?;
        String::from_utf8(csv).map_err(errors::computation)
    })
}

/// A study given as JSON (a Python dict) in TOML text: the study file's tables and keys.
#[pyfunction]
pub fn json_to_toml(json: &str) -> PyResult<String> {
    let value: serde_json::Value = serde_json::from_str(json).map_err(errors::input)?;
    toml::to_string(&value).map_err(|e| errors::input(format!("study: {e}")))
}

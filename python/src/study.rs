//! `study`: a Monte-Carlo robustness study, the result table as the CLI's CSV text. Stopped
//! within a block of trials by Ctrl-C.

use std::path::PathBuf;
use std::sync::Arc;
use std::sync::atomic::{AtomicU64, Ordering};

use pyo3::prelude::*;

use jointid::study::results::write_results;
use jointid::study::{Study, StudyRun};

use crate::errors;
use crate::work;

/// Runs the study of TOML `text` (`file` names it in errors and anchors its relative paths)
/// and returns the CLI's result CSV; `progress(done, total)` is called with the trials done
/// when they change, from the calling thread, at most every tick.
#[pyfunction]
#[pyo3(signature = (text, file, *, threads=None, progress=None))]
pub fn study(
    py: Python<'_>,
    text: String,
    file: PathBuf,
    threads: Option<usize>,
    progress: Option<Py<PyAny>>,
) -> PyResult<String> {
    // trials done and in all, told to `progress(done, total)` when they change
    let counts = Arc::new((AtomicU64::new(0), AtomicU64::new(0)));
    let seen = Arc::clone(&counts);
    let mut told = (u64::MAX, u64::MAX);
    let tick = move |py: Python<'_>| {
        let now = (
            seen.0.load(Ordering::Relaxed),
            seen.1.load(Ordering::Relaxed),
        );
        match &progress {
            Some(callback) if now != told && now.1 > 0 => {
                told = now;
                callback.call1(py, now).map(drop)
            }
            _ => Ok(()),
        }
    };
    let work = move |stop: &std::sync::atomic::AtomicBool| {
        let study = Study::from_toml(&text, &file).map_err(errors::input)?;
        let run = StudyRun::new(study).map_err(errors::computation)?;
        let names: Vec<String> = run.context.params.iter().map(|p| p.name.clone()).collect();
        counts.1.store(run.trial_count(), Ordering::Relaxed);
        let done = |count: u64| {
            counts.0.fetch_add(count, Ordering::Relaxed);
        };
        let mut results = Vec::with_capacity(run.cells.len());
        for cell in &run.cells {
            match run.run_cell_until(cell, &done, stop) {
                Some((result, _)) => results.push(result),
                // interrupted: the caller has raised already, nobody reads this
                None => return Err(errors::computation("the study was interrupted")),
            }
        }
        let mut csv = Vec::new();
        write_results(&mut csv, &results, &names, run.study.noise_name())
            .map_err(errors::computation)?;
        String::from_utf8(csv).map_err(errors::computation)
    };
    work::run_watched(py, threads, work, tick)
}

/// A study given as JSON (a Python dict) in TOML text: the study file's tables and keys.
#[pyfunction]
pub fn json_to_toml(json: &str) -> PyResult<String> {
    let value: serde_json::Value = serde_json::from_str(json).map_err(errors::input)?;
    toml::to_string(&value).map_err(|e| errors::input(format!("study: {e}")))
}

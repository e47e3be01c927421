//! `identify`: the paper's per-mode corrections of measured modes (the library's
//! `identify::run`), returned as the CLI's CSV text with the warnings and notes it prints.

use std::sync::Arc;

use pyo3::prelude::*;

use jointid::identify::run::{Request, RunError, identify_modes};
use jointid::output::identify as out;

use crate::errors;
use crate::measured::Measured;
use crate::model::Model;
use crate::work;

/// The rows (the CLI's `--out` CSV), the warnings (modes left unsolved) and the notes (the
/// CLI's stderr lines on held parameters and frequency fallbacks).
type Identified = (String, Vec<String>, String);

/// Identifies `measured` on `model` (see `jointid.identify`).
#[pyfunction]
#[pyo3(signature = (model, measured, *, n=None, m=None, weighting=None, params=None, modes=None, frequency_noise=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn identify(
    py: Python<'_>,
    model: &Model,
    measured: &Measured,
    n: Option<usize>,
    m: Option<usize>,
    weighting: Option<String>,
    params: Option<Vec<String>>,
    modes: Option<Vec<usize>>,
    frequency_noise: Option<f64>,
    threads: Option<usize>,
) -> PyResult<Identified> {
    let weighting = weighting
        .map(|w| {
            w.parse().map_err(|allowed: String| {
                errors::setting(format!("weighting = {w:?} is invalid: {allowed}"))
            })
        })
        .transpose()?;
    if [n.is_some(), m.is_some(), weighting.is_some()]
        .iter()
        .any(|&b| b)
        && !(n.is_some() && m.is_some() && weighting.is_some())
    {
        return Err(errors::setting(
            "n, m and weighting go together: give all three, or none to identify every mode from its frequency alone",
        ));
    }
    let request = Request {
        n,
        m,
        weighting,
        params,
        modes,
        frequency_noise,
    };
    let (structure, data) = (Arc::clone(&model.inner), Arc::clone(&measured.inner));
    work::run(py, threads, move |_| {
        let identified = identify_modes(&structure, &data, &request).map_err(|e| match e {
            RunError::Setting(e) => errors::setting(e),
            e @ RunError::Measured(_) | e @ RunError::Beyond(_) => errors::input(e),
            e => errors::computation(e),
        })?;
        let gathered = out::gathered(&identified);
        let mut csv = Vec::new();
        out::write_csv(&mut csv, &gathered.rows).map_err(errors::computation)?;
        let mut notes = Vec::new();
        out::write_notes(&mut notes, &gathered.outcomes, &identified.params)
            .and_then(|()| {
                out::write_frequency_notes(&mut notes, &gathered.fallbacks, &identified.all)
            })
            .map_err(errors::computation)?;
        Ok((
            String::from_utf8_lossy(&csv).into_owned(),
            gathered.warnings,
            String::from_utf8_lossy(&notes).into_owned(),
        ))
    })
}

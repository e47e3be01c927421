//! `diagnose`: calibrate the model on every mode, trace what it still misses to a candidate
//! effect, report; the report as the CLI's `--json` text and its terminal text.

use std::sync::Arc;

use pyo3::prelude::*;

use jointid::diagnose::absorbed::absorbed;
use jointid::diagnose::{
    DiagnoseError, DiagnoseSettings, Noise, PairingRule, Watch, diagnose_watched,
};
use jointid::identify::Settings;
use jointid::output::diagnose as out;
use jointid::output::diagnose_plots::diagnose_figures;

use crate::errors;
use crate::measured::Measured;
use crate::model::Model;
use crate::work;

/// The report's JSON, its text and, on request, its figures: (file name, caption, SVG).
type Diagnosed = (String, String, Vec<(String, String, String)>);

/// Diagnoses `measured` on `model` (see `jointid.diagnose`): the report's JSON, its text and
/// (with `figures`) the figures of the CLI's `--plots`.
#[pyfunction]
#[pyo3(signature = (model, measured, *, frequency_noise=0.001, shape_noise=0.02, stated_noise=false, n=None, m=None, weighting="inverse".to_string(), pairing_window=jointid::diagnose::pairing::DEFAULT_WINDOW, pair=Vec::new(), extended=false, causes=Vec::new(), figures=false, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn diagnose(
    py: Python<'_>,
    model: &Model,
    measured: &Measured,
    frequency_noise: f64,
    shape_noise: f64,
    stated_noise: bool,
    n: Option<usize>,
    m: Option<usize>,
    weighting: String,
    pairing_window: f64,
    pair: Vec<(usize, usize)>,
    extended: bool,
    causes: Vec<String>,
    figures: bool,
    threads: Option<usize>,
) -> PyResult<Diagnosed> {
    let weighting = weighting.parse().map_err(|allowed: String| {
        errors::setting(format!("weighting = {weighting:?} is invalid: {allowed}"))
    })?;
    let per_mode = match (n, m) {
        (None, None) => None,
        (Some(n), Some(m)) => Some(Settings { n, m, weighting }),
        _ => {
            return Err(errors::setting(
                "n and m go together (or leave both out for the defaults)",
            ));
        }
    };
    let settings = DiagnoseSettings {
        noise: Noise {
            frequency: frequency_noise,
            shape: shape_noise,
        },
        pairing: PairingRule {
            window: pairing_window,
            given: pair,
        },
        per_mode,
        extended,
        full_model: false,
        causes: causes
            .iter()
            .map(|c| c.split('+').map(|n| n.trim().to_string()).collect())
            .collect(),
    };
    settings.check().map_err(errors::setting)?;
    let structure = Arc::clone(&model.inner);
    let typed = model.typed.clone();
    let data = Arc::clone(&measured.inner);
    work::run(py, threads, move |_| {
        let data = if stated_noise {
            data.as_ref().clone().without_std()
        } else {
            data.as_ref().clone()
        };
        let mut report = diagnose_watched(&structure, &data, settings.clone(), Watch::silent())
            .map_err(|e| match e {
                DiagnoseError::Settings(e) => errors::setting(e),
                e => errors::computation(e),
            })?;
        if let Some(typed) = typed.as_deref() {
            let a = absorbed(&typed.0, &typed.1, &data, &settings, &report).map_err(|e| {
                errors::computation(format!(
                    "the joint on the beams as typed (before their calibration): {e}"
                ))
            })?;
            report.reference = Some(a);
        }
        let json = serde_json::to_string_pretty(&report).map_err(errors::computation)?;
        let mut text = Vec::new();
        out::write_text(&mut text, &report).map_err(errors::computation)?;
        let drawn = if figures {
            diagnose_figures(&report, &data)
                .map_err(errors::computation)?
                .into_iter()
                .map(|f| (f.name, f.caption, f.svg))
                .collect()
        } else {
            Vec::new()
        };
        Ok((json, String::from_utf8_lossy(&text).into_owned(), drawn))
    })
}

//! `simulate` (measured modes of a model, with effects and errors) and `amplitude` (the
//! amplitude dependence across the levels of a levels file, as the CLI's CSV tables).

use std::collections::BTreeMap;
use std::path::PathBuf;
use std::sync::Arc;

use pyo3::prelude::*;

use jointid::amplitude::{AmplitudeFit, Levels, fit_levels};
use jointid::input::SettingError;
use jointid::output::amplitude as out;
use jointid::simulate::{Errors, Measure, first_modes, measured_points, simulate as run};
use jointid::study::NoiseKind;

use crate::errors;
use crate::measured::Measured;
use crate::model::Model;
use crate::work;

/// Simulated measured modes of `model` (see `jointid.simulate`).
#[pyfunction]
#[pyo3(signature = (model, modes, *, effects=Vec::new(), shape_noise=0.0, frequency_noise=0.0, noise="gaussian".to_string(), seed=0, measure="all"))]
#[allow(clippy::too_many_arguments)]
pub fn simulate(
    py: Python<'_>,
    model: &Model,
    modes: usize,
    effects: Vec<(String, f64)>,
    shape_noise: f64,
    frequency_noise: f64,
    noise: String,
    seed: u64,
    measure: &str,
) -> PyResult<Measured> {
    let structure = Arc::clone(&model.inner);
    let modes = first_modes(&structure, modes).map_err(errors::setting)?;
    let kind: NoiseKind = noise
        .parse()
        .map_err(|allowed: String| errors::setting(SettingError::new("noise", &noise, allowed)))?;
    let errors = Errors::new(shape_noise, frequency_noise, kind, seed).map_err(errors::setting)?;
    let measure = match measure {
        "w" => Measure::W,
        "theta" => Measure::Theta,
        "all" => Measure::All,
        "sensors" => Measure::Sensors,
        other => {
            return Err(errors::setting(format!(
                "measure = {other:?} is invalid: it must be \"w\", \"theta\", \"all\" or \"sensors\""
            )));
        }
    };
    let Some(points) = measured_points(&structure, measure) else {
        return Err(errors::setting(
            "measure = \"sensors\" is invalid: the model declares no sensor",
        ));
    };
    let model = Arc::clone(&structure);
    let inner = work::run(py, None, move |_| {
        run(&structure, &effects, &modes, &points, errors).map_err(errors::computation)
    })?;
    Ok(Measured {
        inner: Arc::new(inner),
        model,
    })
}

/// A table of the amplitude fit and its writer.
type Table = (
    &'static str,
    fn(&mut dyn std::io::Write, &AmplitudeFit) -> std::io::Result<()>,
);

/// The CSV tables of `jointid amplitude` (with `joint`, the joint's too) and its summary.
#[pyfunction]
#[pyo3(signature = (levels, *, joint=None, threads=None))]
pub fn amplitude(
    py: Python<'_>,
    levels: PathBuf,
    joint: Option<String>,
    threads: Option<usize>,
) -> PyResult<(BTreeMap<String, String>, String)> {
    work::run(py, threads, move |_| {
        let levels = Levels::from_path(&levels).map_err(errors::input)?;
        let fit = fit_levels(&levels, joint.as_deref()).map_err(errors::computation)?;
        let mut tables: Vec<Table> = vec![
            ("amplitude_levels.csv", out::write_levels),
            ("amplitude_laws.csv", out::write_laws),
            ("amplitude_parameters.csv", out::write_parameters),
            ("amplitude_bands.csv", out::write_bands),
        ];
        if joint.is_some() {
            tables.extend::<[Table; 5]>([
                ("joint_levels.csv", out::write_joint_levels),
                ("joint_laws.csv", out::write_joint_laws),
                ("joint_parameters.csv", out::write_joint_parameters),
                ("joint_bands.csv", out::write_joint_bands),
                ("joint_errors.csv", out::write_joint_errors),
            ]);
        }
        let mut texts = BTreeMap::new();
        for (name, write) in tables {
            let mut text = Vec::new();
            write(&mut text, &fit).map_err(errors::computation)?;
            texts.insert(
                name.to_string(),
                String::from_utf8_lossy(&text).into_owned(),
            );
        }
        Ok((texts, out::summary(&fit)))
    })
}

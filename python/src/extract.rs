//! `extract`: modal parameters from FRFs given as arrays (the library's `extract`), returned
//! as arrays: frequencies, damping ratios, real and complex shapes, their standard errors.

use numpy::{Complex64, PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;
use pyo3::types::PyDict;

use jointid::extract::{ExtractError, Extraction, FrfSet, Quantity, Settings, extract as run};
use jointid::input::Number;

use crate::errors;
use crate::work;

/// The response quantity by name.
fn quantity(name: &str) -> PyResult<Quantity> {
    match name {
        "displacement" => Ok(Quantity::Displacement),
        "velocity" => Ok(Quantity::Velocity),
        "acceleration" => Ok(Quantity::Acceleration),
        other => Err(errors::setting(format!(
            "quantity = {other:?} is invalid: it must be \"displacement\", \"velocity\" or \"acceleration\""
        ))),
    }
}

/// Extracts the modes of the FRFs `frf` (responses x lines) on the lines `frequencies` (Hz)
/// (see `jointid.extract`).
#[pyfunction]
#[pyo3(signature = (frequencies, frf, *, coherence=None, quantity="acceleration", band=None, modes=None, max_order=None, averages=None, mpc_min=None, threads=None))]
#[allow(clippy::too_many_arguments)]
pub fn extract<'py>(
    py: Python<'py>,
    frequencies: PyReadonlyArray1<'py, f64>,
    frf: PyReadonlyArray2<'py, Complex64>,
    coherence: Option<PyReadonlyArray2<'py, f64>>,
    quantity: &str,
    band: Option<(f64, f64)>,
    modes: Option<usize>,
    max_order: Option<usize>,
    averages: Option<usize>,
    mpc_min: Option<f64>,
    threads: Option<usize>,
) -> PyResult<Bound<'py, PyDict>> {
    let defaults = Settings::default();
    let settings = Settings {
        band_hz: band,
        n_modes: modes,
        max_order: max_order.unwrap_or(defaults.max_order),
        averages,
        mpc_min: mpc_min.unwrap_or(defaults.mpc_min),
        ..defaults
    };
    settings.check().map_err(errors::setting)?;
    let rows = |a: &PyReadonlyArray2<'py, f64>| -> Vec<Vec<f64>> {
        a.as_array()
            .rows()
            .into_iter()
            .map(|r| r.to_vec())
            .collect()
    };
    let set = FrfSet {
        frequencies_hz: frequencies.as_slice()?.to_vec(),
        responses: frf
            .as_array()
            .rows()
            .into_iter()
            .map(|r| r.iter().map(|z| faer::c64::new(z.re, z.im)).collect())
            .collect(),
        coherence: coherence.as_ref().map(rows),
        quantity: self::quantity(quantity)?,
    };
    set.validate().map_err(errors::input)?;
    let ex = work::run(py, threads, move |_| {
        run(&set, &settings, &|_, _| {}).map_err(|e| match e {
            ExtractError::NoExcitation { lo, hi, .. } => errors::setting(format!(
                "band = ({}, {}) is refused: {e}",
                Number(lo),
                Number(hi)
            )),
            e => errors::computation(e),
        })
    })?;
    arrays(py, &ex)
}

/// The extraction as a dict of arrays, one entry per mode (shapes: responses x modes).
fn arrays<'py>(py: Python<'py>, ex: &Extraction) -> PyResult<Bound<'py, PyDict>> {
    let per_mode = |f: &dyn Fn(&jointid::extract::Mode) -> f64| -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(py, ex.modes.iter().map(f).collect())
    };
    let responses = ex.modes.first().map_or(0, |m| m.real_shape.len());
    let shape = |f: &dyn Fn(&jointid::extract::Mode, usize) -> f64| {
        let a = numpy::ndarray::Array2::from_shape_fn((responses, ex.modes.len()), |(o, r)| {
            f(&ex.modes[r], o)
        });
        PyArray2::from_owned_array(py, a)
    };
    let complex = numpy::ndarray::Array2::from_shape_fn((responses, ex.modes.len()), |(o, r)| {
        let z = ex.modes[r].complex_shape[o];
        Complex64::new(z.re, z.im)
    });
    let d = PyDict::new(py);
    d.set_item("frequency_hz", per_mode(&|m| m.frequency_hz))?;
    d.set_item("damping_ratio", per_mode(&|m| m.damping_ratio))?;
    d.set_item("frequency_std", per_mode(&|m| m.std.frequency_hz))?;
    d.set_item("damping_std", per_mode(&|m| m.std.damping_ratio))?;
    d.set_item("mpc", per_mode(&|m| m.mpc))?;
    d.set_item("mpd_deg", per_mode(&|m| m.mpd_deg))?;
    d.set_item("shapes", shape(&|m, o| m.real_shape[o]))?;
    d.set_item("shape_std", shape(&|m, o| m.std.shape[o]))?;
    d.set_item("complex_shapes", PyArray2::from_owned_array(py, complex))?;
    d.set_item("band_hz", ex.band_hz)?;
    Ok(d)
}

/// The frequency lines of abscissa values evenly spaced within the universal files'
/// tolerance (as the library reads a file's uneven 6-digit axis); None when they are not.
#[pyfunction]
pub fn even_lines<'py>(
    py: Python<'py>,
    x: PyReadonlyArray1<'py, f64>,
) -> PyResult<Option<Bound<'py, PyArray1<f64>>>> {
    Ok(jointid::extract::universal::even_lines(x.as_slice()?).map(|v| PyArray1::from_vec(py, v)))
}

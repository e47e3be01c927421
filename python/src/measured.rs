//! `Measured`: measured modes (frequencies and partial shapes) read against a model, from the
//! measured-modes CSV or from arrays. Arrays are written once into the CSV's text in Rust
//! (every number in its shortest round-trip form, so the bits are kept) and read by the
//! library's reader: the same checks and messages as a file.

use std::fmt::Write as _;
use std::path::{Path, PathBuf};
use std::sync::Arc;

use numpy::{PyArray1, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use jointid::measured::MeasuredModes;
use jointid::structure::Structure;

use crate::errors;
use crate::model::Model;

/// Measured modes, checked against the model they were read for.
#[pyclass(module = "jointid._jointid", frozen)]
pub struct Measured {
    /// The modes.
    pub inner: Arc<MeasuredModes>,
    /// The model they were read against.
    pub model: Arc<Structure>,
}

impl Measured {
    fn of(text: &str, name: &str, model: &Model) -> PyResult<Measured> {
        let inner = MeasuredModes::from_reader(text.as_bytes(), Path::new(name), &model.inner)
            .map_err(errors::input)?;
        Ok(Measured {
            inner: Arc::new(inner),
            model: Arc::clone(&model.inner),
        })
    }
}

#[pymethods]
impl Measured {
    /// Reads a measured-modes CSV against `model`.
    #[staticmethod]
    fn from_csv(py: Python<'_>, path: PathBuf, model: &Model) -> PyResult<Measured> {
        py.detach(|| {
            let inner = MeasuredModes::from_path(&path, &model.inner).map_err(errors::input)?;
            Ok(Measured {
                inner: Arc::new(inner),
                model: Arc::clone(&model.inner),
            })
        })
    }

    /// Measured modes from arrays, already checked for shapes and finite values by the
    /// Python wrapper (`jointid.Measured.from_arrays`).
    #[staticmethod]
    #[pyo3(signature = (model, modes, frequencies, shapes, labels=None, x=None, xyz=None, directions=None, frequency_std=None, shape_std=None))]
    #[allow(clippy::too_many_arguments)]
    fn _from_columns(
        model: &Model,
        modes: Vec<usize>,
        frequencies: PyReadonlyArray1<'_, f64>,
        shapes: PyReadonlyArray2<'_, f64>,
        labels: Option<Vec<String>>,
        x: Option<PyReadonlyArray1<'_, f64>>,
        xyz: Option<PyReadonlyArray2<'_, f64>>,
        directions: Option<Vec<String>>,
        frequency_std: Option<PyReadonlyArray1<'_, f64>>,
        shape_std: Option<PyReadonlyArray2<'_, f64>>,
    ) -> PyResult<Measured> {
        let f = frequencies.as_slice()?;
        let shapes = shapes.as_array();
        let f_std = frequency_std.as_ref().map(|a| a.as_slice()).transpose()?;
        let v_std = shape_std.as_ref().map(|a| a.as_array());
        let dof = directions.unwrap_or_default();
        let (location, cells): (&str, Vec<String>) = match (labels, x, xyz) {
            (Some(labels), None, None) => ("label", labels),
            (None, Some(x), None) => (
                "x,dof",
                x.as_slice()?
                    .iter()
                    .zip(&dof)
                    .map(|(x, d)| format!("{x},{d}"))
                    .collect(),
            ),
            (None, None, Some(xyz)) => (
                "x,y,z,dof",
                xyz.as_array()
                    .rows()
                    .into_iter()
                    .zip(&dof)
                    .map(|(r, d)| format!("{},{},{},{d}", r[0], r[1], r[2]))
                    .collect(),
            ),
            _ => {
                return Err(errors::setting(
                    "points: give exactly one of labels, x (with directions) or xyz (with directions)",
                ));
            }
        };
        let mut text = format!("mode,frequency_hz,{location},value");
        text.push_str(if f_std.is_some() {
            ",frequency_std"
        } else {
            ""
        });
        text.push_str(if v_std.is_some() {
            ",value_std\n"
        } else {
            "\n"
        });
        for (j, &mode) in modes.iter().enumerate() {
            for (i, cell) in cells.iter().enumerate() {
                let _ = write!(text, "{mode},{},{cell},{}", f[j], shapes[(i, j)]);
                if let Some(s) = f_std {
                    let _ = write!(text, ",{}", s[j]);
                }
                if let Some(s) = &v_std {
                    let _ = write!(text, ",{}", s[(i, j)]);
                }
                text.push('\n');
            }
        }
        Measured::of(&text, "measured", model)
    }

    /// The measured-modes CSV of these modes (the text `jointid simulate` writes).
    fn to_csv(&self) -> PyResult<String> {
        let mut out = Vec::new();
        self.inner
            .write_csv(&mut out, &self.model)
            .map_err(errors::input)?;
        String::from_utf8(out).map_err(errors::input)
    }

    /// The mode numbers (1 = the first elastic mode).
    #[getter]
    fn modes(&self) -> Vec<usize> {
        self.inner.modes().iter().map(|m| m.mode).collect()
    }

    /// The measured frequencies, Hz.
    #[getter]
    fn frequencies<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray1<f64>> {
        PyArray1::from_vec(
            py,
            self.inner.modes().iter().map(|m| m.frequency_hz).collect(),
        )
    }

    fn __len__(&self) -> usize {
        self.inner.modes().len()
    }

    fn __repr__(&self) -> String {
        format!("Measured(modes {:?})", self.modes())
    }
}

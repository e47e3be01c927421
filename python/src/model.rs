//! `Model`: a structure read from a model file or built from matrices in memory, and its
//! modes.

use std::path::PathBuf;
use std::sync::Arc;

use numpy::{PyArray1, PyArray2, PyReadonlyArray1, PyReadonlyArray2};
use pyo3::prelude::*;

use jointid::modal::ModalSolution;
use jointid::model::Chain;
use jointid::model::chain::BeamCalibration;
use jointid::model::matrices::build::{MatricesData, ParameterData};
use jointid::model::matrices::config::UNITS;
use jointid::model::matrices::dof_table;
use jointid::model::matrix_market::{self, LowerEntries, MatrixMarketError};
use jointid::structure::{Role, Structure};

use crate::{errors, work};

/// A model: the structure every command works on.
#[pyclass(module = "jointid._jointid", frozen)]
pub struct Model {
    /// The structure.
    pub inner: Arc<Structure>,
    /// A chain whose beams were calibrated on a reference test: the chain as typed, and the
    /// calibration (the diagnosis then says what the calibration absorbed).
    pub typed: Option<Arc<(Structure, Vec<BeamCalibration>)>>,
}

/// Frequencies (Hz) and shapes (DOFs x modes).
type Modes<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray2<f64>>);

/// A matrix given by coordinates: (row, column, value) arrays, 0-based, both triangles.
type Coordinates<'py> = (
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, i64>,
    PyReadonlyArray1<'py, f64>,
);

/// One parameter: name, value, unit, identified, dK/dp, dM/dp.
type ParameterInput<'py> = (
    String,
    f64,
    String,
    bool,
    Coordinates<'py>,
    Option<Coordinates<'py>>,
);

/// The lower triangle of a matrix given by coordinates, checked (finite, in range,
/// symmetric); `name` names it in errors.
fn lower(size: usize, (rows, cols, vals): &Coordinates<'_>, name: &str) -> PyResult<LowerEntries> {
    let (rows, cols, vals) = (rows.as_slice()?, cols.as_slice()?, vals.as_slice()?);
    let index = |i: i64| usize::try_from(i).unwrap_or(usize::MAX);
    let entries: Vec<(usize, usize, f64)> = rows
        .iter()
        .zip(cols)
        .zip(vals)
        .map(|((&r, &c), &v)| (index(r), index(c), v))
        .collect();
    matrix_market::from_coordinates(size, &entries, std::path::Path::new(name)).map_err(|e| match e {
        // said with the 0-based indices of the array handed over
        MatrixMarketError::NotSymmetric {
            row,
            col,
            value,
            mirror,
            ..
        } => errors::input(format!(
            "{name} is not symmetric: {name}[{}, {}] = {value:e} but {name}[{}, {}] = {mirror:e} (duplicates summed; |a_ij - a_ji| must be <= {:e} max |a|)",
            row - 1,
            col - 1,
            col - 1,
            row - 1,
            matrix_market::SYMMETRY_TOLERANCE
        )),
        e => errors::input(e),
    })
}

#[pymethods]
impl Model {
    /// Reads and validates a model file (TOML): a beam chain, matrices, or a solid.
    #[staticmethod]
    fn from_toml(py: Python<'_>, path: PathBuf) -> PyResult<Model> {
        py.detach(|| {
            let structure = jointid::model::from_path(&path).map_err(errors::input)?;
            let typed = jointid::input::read_file(&path)
                .ok()
                .and_then(|text| jointid::model::chain_from_toml(&text, &path).ok())
                .filter(|chain: &Chain| !chain.calibration.is_empty())
                .map(|chain| Arc::new((chain.typed().build(), chain.calibration)));
            Ok(Model {
                inner: Arc::new(structure),
                typed,
            })
        })
    }

    /// Builds a model from matrices given by coordinates (see `jointid.Model.from_matrices`).
    #[staticmethod]
    #[pyo3(signature = (size, k, m, parameters, labels, positions, directions, rigid_body_modes=None, sensor_tolerance=None))]
    #[allow(clippy::too_many_arguments)]
    fn _from_coordinates(
        py: Python<'_>,
        size: usize,
        k: Coordinates<'_>,
        m: Coordinates<'_>,
        parameters: Vec<ParameterInput<'_>>,
        labels: Vec<String>,
        positions: PyReadonlyArray2<'_, f64>,
        directions: Vec<String>,
        rigid_body_modes: Option<usize>,
        sensor_tolerance: Option<f64>,
    ) -> PyResult<Model> {
        let k = lower(size, &k, "K")?;
        let m = lower(size, &m, "M")?;
        let mut params = Vec::with_capacity(parameters.len());
        for (name, value, unit, identified, dk, dm) in &parameters {
            let Some(unit) = UNITS.into_iter().find(|u| u == unit) else {
                return Err(errors::setting(format!(
                    "dK[{name:?}] unit = {unit:?} is invalid: it must be one of \"{}\"",
                    UNITS.join("\", \"")
                )));
            };
            params.push(ParameterData {
                name: name.clone(),
                unit,
                value: *value,
                role: if *identified {
                    Role::Identified
                } else {
                    Role::Fixed
                },
                dk: lower(size, dk, &format!("dK[{name:?}]"))?,
                dm: dm
                    .as_ref()
                    .map(|dm| lower(size, dm, &format!("dM[{name:?}]")))
                    .transpose()?,
            });
        }
        let xyz: Vec<[f64; 3]> = positions
            .as_array()
            .rows()
            .into_iter()
            .map(|r| [r[0], r[1], r[2]])
            .collect();
        let dofs = dof_table::from_columns(&labels, &xyz, &directions, "dofs".as_ref())
            .map_err(errors::input)?;
        let data = MatricesData {
            k,
            m,
            dofs,
            parameters: params,
            rigid_body_modes,
            sensor_tolerance,
        };
        py.detach(|| {
            let structure = data.build().map_err(errors::input)?;
            Ok(Model {
                inner: Arc::new(structure),
                typed: None,
            })
        })
    }

    /// The `n` lowest elastic modes (after the rigid-body ones): frequencies (Hz, ascending)
    /// and M-normalised shapes (one column per mode, one row per DOF).
    #[pyo3(signature = (n, *, threads=None))]
    fn modes<'py>(
        &self,
        py: Python<'py>,
        n: usize,
        threads: Option<usize>,
    ) -> PyResult<Modes<'py>> {
        let structure = Arc::clone(&self.inner);
        let (rigid, elastic) = (structure.rigid, structure.elastic_count());
        if !(1..=elastic).contains(&n) {
            return Err(errors::setting(format!(
                "n = {n} is invalid: it must be from 1 to {elastic} (the model's {} DOFs less its {rigid} rigid-body modes)",
                structure.dof_count()
            )));
        }
        let (frequencies, shapes) = work::run(py, threads, move |_| {
            let modal = ModalSolution::lowest_of(&structure.assemble(), n + rigid)
                .map_err(errors::computation)?;
            let frequencies: Vec<f64> = (rigid..rigid + n).map(|i| modal.frequency_hz(i)).collect();
            let y = modal.vectors();
            let shapes =
                numpy::ndarray::Array2::from_shape_fn((y.nrows(), n), |(i, j)| y[(i, rigid + j)]);
            Ok((frequencies, shapes))
        })?;
        Ok((
            PyArray1::from_vec(py, frequencies),
            PyArray2::from_owned_array(py, shapes),
        ))
    }

    /// Number of DOFs.
    #[getter]
    fn dof_count(&self) -> usize {
        self.inner.dof_count()
    }

    /// Number of rigid-body modes.
    #[getter]
    fn rigid_body_modes(&self) -> usize {
        self.inner.rigid
    }

    /// The DOF labels, in index order.
    #[getter]
    fn labels(&self) -> Vec<String> {
        self.inner
            .dofs
            .dofs()
            .iter()
            .map(|d| d.label.clone())
            .collect()
    }

    /// The DOFs' positions (DOFs x 3), m, in index order.
    #[getter]
    fn positions<'py>(&self, py: Python<'py>) -> Bound<'py, PyArray2<f64>> {
        let dofs = self.inner.dofs.dofs();
        let a =
            numpy::ndarray::Array2::from_shape_fn((dofs.len(), 3), |(i, k)| dofs[i].position[k]);
        PyArray2::from_owned_array(py, a)
    }

    /// The DOFs' directions (w, theta, x, y, z, rx, ry, rz), in index order.
    #[getter]
    fn directions(&self) -> Vec<&'static str> {
        self.inner
            .dofs
            .dofs()
            .iter()
            .map(|d| d.direction.name())
            .collect()
    }

    /// The parameters: (name, value, unit, identified).
    #[getter]
    fn parameters(&self) -> Vec<(String, f64, String, bool)> {
        self.inner
            .parameters
            .iter()
            .map(|p| {
                (
                    p.name.clone(),
                    p.value,
                    p.unit.to_string(),
                    p.role == Role::Identified,
                )
            })
            .collect()
    }

    fn __repr__(&self) -> String {
        format!(
            "Model({} DOFs, {} rigid-body modes, parameters {:?})",
            self.inner.dof_count(),
            self.inner.rigid,
            self.inner
                .parameters
                .iter()
                .map(|p| p.name.as_str())
                .collect::<Vec<_>>()
        )
    }
}

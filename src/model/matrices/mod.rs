//! External finite-element models: K and M from another code, in Matrix Market files, one
//! dK/dp (and optionally dM/dp) per parameter with its nominal value, and a DOF table that
//! names every row. The paper's K and M are "obtained by the finite element method" (section
//! 2); this builder takes them from any code that writes Matrix Market (Boisvert, Pozo,
//! Remington, "The Matrix Market Exchange Formats: Initial Design", NIST 1996).
//!
//! - [`config`]: the model TOML (`kind = "matrices"`), paths relative to it;
//! - [`dof_table`]: the DOF table CSV `dof,label,x,y,z,direction`;
//! - [`build`]: the files read, checked and assembled into a [`Structure`];
//! - [`coincident`]: DOFs at the same position and direction must be tied;
//! - [`mod@export`]: any structure written as such a model (`jointid export`).
//!
//! The structure is the one every command takes: identify, simulate, study and diagnose do
//! not know where it came from. An external model has no beam elements: measured files name
//! its DOFs by label, and the effects that act on joints, elements or free ends of a beam
//! chain do not apply to it.

pub mod build;
pub mod coincident;
pub mod config;
pub mod dof_table;
pub mod export;

use std::path::Path;

pub use config::{MatricesFile, ParameterFile};
pub use export::{Export, ExportError, export};

use crate::input::{InputError, parse_toml};
use crate::model::matrix_market::MatrixMarketError;
use crate::structure::Structure;
use dof_table::DofTableError;

/// An external model whose files do not fit together. The model TOML is named by the
/// conversion into [`InputError`].
#[derive(Debug, thiserror::Error)]
pub enum MatricesError {
    /// The TOML file itself.
    #[error(transparent)]
    Input(#[from] InputError),
    /// A Matrix Market file.
    #[error("{field}: {problem}")]
    Matrix {
        /// The TOML field that names the file.
        field: String,
        /// What is wrong in it (in the message, so not also a `source`: a chain would say
        /// it twice).
        problem: MatrixMarketError,
    },
    /// The DOF table.
    #[error("dofs: {problem}")]
    Dofs {
        /// What is wrong in it.
        problem: DofTableError,
    },
    /// A matrix of another size than K.
    #[error(
        "{field}: the matrix is {size} x {size}, but K (stiffness) is {stiffness} x {stiffness}: every matrix must have the size of K"
    )]
    Size {
        /// The TOML field that names the file.
        field: String,
        /// Its size.
        size: usize,
        /// The size of K.
        stiffness: usize,
    },
    /// K larger than the reader takes.
    #[error(
        "stiffness: the matrix is {size} x {size}: an external model may have at most {} DOFs",
        build::MAX_DOFS
    )]
    TooLarge {
        /// Its size.
        size: usize,
    },
    /// A parameter whose derivatives are zero.
    #[error(
        "parameter[{index}] ({name}): dK/dp (and dM/dp) has no nonzero entry: a parameter the matrices do not depend on cannot be identified"
    )]
    ZeroDerivative {
        /// The parameter.
        name: String,
        /// Its place in the file.
        index: usize,
    },
    /// A DOF without mass.
    #[error(
        "mass: M (with the parameters' p dM/dp) has M[{dof},{dof}] = {value:e} at dof {dof} (`{label}`): M must be positive definite, every DOF must carry mass"
    )]
    MassDiagonal {
        /// 1-based DOF.
        dof: usize,
        /// Its label.
        label: String,
        /// The diagonal entry.
        value: f64,
    },
    /// M is indefinite.
    #[error(
        "mass: M (with the parameters' p dM/dp) is not positive definite (its Cholesky factorisation fails: {cause}): M must be positive definite"
    )]
    MassNotPositiveDefinite {
        /// faer's report.
        cause: String,
    },
    /// K has a negative eigenvalue.
    #[error(
        "stiffness: K (with the parameters' p dK/dp) is not positive semidefinite: its lowest eigenvalue is {lambda:e} rad^2/s^2, below -{tolerance:e}"
    )]
    StiffnessIndefinite {
        /// The lowest eigenvalue.
        lambda: f64,
        /// The rigid-body tolerance.
        tolerance: f64,
    },
    /// The declared rigid-body count is not the model's.
    #[error("rigid_body_modes = {declared} is invalid: the model has {counted} (eigenvalues below the rigid-body tolerance, {tolerance_hz:.3e} Hz), and its {declared} lowest eigenvalues are not all below 1e-2 times the next; its lowest frequencies are {} Hz: declare the count the model has, or find why it differs (more: a part or a DOF that nothing ties to the rest; fewer: a support or a spring to the ground)", fmt_list(.lowest_hz))]
    Rigid {
        /// Declared.
        declared: usize,
        /// Counted.
        counted: usize,
        /// The tolerance, as a frequency.
        tolerance_hz: f64,
        /// The lowest frequencies, Hz.
        lowest_hz: Vec<f64>,
    },
    /// The eigen-solution failed.
    #[error("modal solution: {message}")]
    Modal {
        /// The solver's message.
        message: String,
    },
}

fn fmt_list(values: &[f64]) -> String {
    let v: Vec<String> = values.iter().map(|f| format!("{f:.4e}")).collect();
    v.join(", ")
}

impl MatricesError {
    /// The shared input error, naming the model file `file`.
    pub fn into_input(self, file: &Path) -> InputError {
        match self {
            MatricesError::Input(e) => e,
            other => InputError::Format {
                file: file.to_path_buf(),
                line: None,
                path: String::new(),
                message: other.to_string(),
            },
        }
    }
}

/// Parses and validates the TOML text of an external model (`file` names it and is where
/// relative paths start), then reads and checks its files.
pub fn from_toml(text: &str, file: &Path) -> Result<Structure, MatricesError> {
    Ok(from_toml_solved(text, file, &|_| 0)?.0)
}

/// [`from_toml`], and the lowest pairs its rigid-body check computed, at least `elastic` of
/// the structure beyond the declared rigid-body modes ([`build::MatricesData::build_solved`]).
pub fn from_toml_solved(
    text: &str,
    file: &Path,
    elastic: build::Elastic,
) -> Result<(Structure, crate::modal::ModalSolution), MatricesError> {
    let raw: config::RawMatrices = parse_toml(text, file)?;
    raw.validate(file)?.build_solved(elastic)
}

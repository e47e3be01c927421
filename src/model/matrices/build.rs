//! The [`Structure`] of an external model: the files read, checked against each other, and
//! assembled.
//!
//! Checks, in order: every matrix is square, symmetric and finite (the Matrix Market reader);
//! every matrix and the DOF table have the size N of K; dK/dp (or dM/dp) of every parameter is
//! not zero; M at the parameter values has a positive diagonal and a Cholesky factor (positive
//! definite); K is positive semidefinite and its rigid-body modes (zero eigenvalues) are
//! counted: eigenvalue i is zero when lambda_i <= tol = [`RIGID_TOLERANCE`] * s, with
//! s = max_j K_jj / M_jj, a Rayleigh quotient, a lower bound of lambda_max of the same order.
//! Measured on free-free two-beam chains (dense solution): the rigid-body eigenvalues are
//! 3.1e-16 s (N = 38), 4.6e-17 s (N = 504), 3.0e-17 s (N = 2004); the first elastic one
//! 4.0e-7 s, 9.5e-12 s, 3.7e-14 s. The tolerance 1e-14 s sits between them up to about
//! N = 2000 for a beam; a finer model's lowest elastic modes fall below it (and below what a
//! dense solution resolves, see the modal module). A declared `rigid_body_modes` = r is
//! accepted when it is the count, or when the r lowest eigenvalues are all below
//! [`RIGID_GAP`] times the next one (a clear gap: the way to state the count of a model whose
//! elastic eigenvalues are below the tolerance).

use super::MatricesError;
use super::config::{MatricesFile, ParameterFile};
use super::dof_table;
use crate::modal::{DENSE_MAX_DOFS, ModalError, ModalSolution, lambda_to_hz};
use crate::model::matrix_market::{self, LowerEntries};
use crate::structure::{
    Direction, DofMap, Matrices, Parameter, Sites, SparseSym, Structure, SymMatrix,
};

/// Relative size of a rigid-body eigenvalue: see the module docs.
pub const RIGID_TOLERANCE: f64 = 1e-14;

/// A declared rigid-body count r is accepted when max_{i<r} |lambda_i| <= RIGID_GAP lambda_r.
pub const RIGID_GAP: f64 = 1e-2;

/// Largest number of DOFs of an external model (the large models have 1e4 to 1e5).
pub const MAX_DOFS: usize = 1_000_000;

/// The elastic pairs a caller wants beyond the declared rigid-body modes, of the structure
/// read (before its solve: its rigid-body count the declared one, 0 when none is declared):
/// [`MatricesData::build_solved`] solves for them too.
pub type Elastic<'a> = &'a dyn Fn(&Structure) -> usize;

/// How many of the lowest eigenvalues are looked at for rigid-body modes (a free body in
/// space has six).
pub const RIGID_SEARCH: usize = 12;

/// An external model's matrices and DOFs in memory (read from its files, or handed over by a
/// caller that holds them, such as the Python package), before the checks of the module docs.
#[derive(Debug, Clone, PartialEq)]
pub struct MatricesData {
    /// K without the parameters' terms.
    pub k: LowerEntries,
    /// M without the parameters' terms.
    pub m: LowerEntries,
    /// The DOFs, in index order.
    pub dofs: Vec<crate::structure::DofInfo>,
    /// The parameters, in order.
    pub parameters: Vec<ParameterData>,
    /// The declared number of rigid-body modes, if any.
    pub rigid_body_modes: Option<usize>,
    /// How far a sensor given by coordinates may lie from its nearest DOF, m.
    pub sensor_tolerance: Option<f64>,
}

/// One parameter with its derivative matrices.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterData {
    /// Name in output files.
    pub name: String,
    /// Unit, one of [`super::config::UNITS`].
    pub unit: &'static str,
    /// Nominal value p_i.
    pub value: f64,
    /// Identified or fixed.
    pub role: crate::structure::Role,
    /// dK/dp_i.
    pub dk: LowerEntries,
    /// dM/dp_i, if the parameter changes the mass.
    pub dm: Option<LowerEntries>,
}

impl MatricesFile {
    /// Reads the files and builds the structure, with every check of the module docs.
    pub fn build(&self) -> Result<Structure, MatricesError> {
        Ok(self.build_solved(&|_| 0)?.0)
    }

    /// [`MatricesFile::build`], and the lowest pairs of the structure at its parameter values
    /// that the rigid-body check computed, at least `elastic` beyond the declared rigid-body
    /// modes ([`MatricesData::build_solved`]).
    pub fn build_solved(
        &self,
        elastic: Elastic,
    ) -> Result<(Structure, ModalSolution), MatricesError> {
        let read = |field: &str, path: &std::path::Path| {
            matrix_market::from_path(path).map_err(|problem| MatricesError::Matrix {
                field: field.to_string(),
                problem,
            })
        };
        // K on one thread, M and the derivatives on another (the 212,562-DOF lap's K is
        // 250 MB of text); the errors in the order of the sequential reading.
        let (k, (m, parameters)) = rayon::join(
            || read("stiffness", &self.stiffness),
            || {
                let m = read("mass", &self.mass);
                let parameters: Result<Vec<ParameterData>, MatricesError> = (self.parameters)
                    .iter()
                    .enumerate()
                    .map(|(i, p)| Self::parameter(i, p, &read))
                    .collect();
                (m, parameters)
            },
        );
        let k = k?;
        let n = k.size;
        if n > MAX_DOFS {
            return Err(MatricesError::TooLarge { size: n });
        }
        let m = m?;
        let dofs = dof_table::from_path(&self.dofs, n)
            .map_err(|problem| MatricesError::Dofs { problem })?;
        let parameters = parameters?;
        MatricesData {
            k,
            m,
            dofs,
            parameters,
            rigid_body_modes: self.rigid_body_modes,
            sensor_tolerance: self.sensor_tolerance,
        }
        .build_solved(elastic)
    }

    fn parameter(
        i: usize,
        p: &ParameterFile,
        read: &(dyn Fn(&str, &std::path::Path) -> Result<LowerEntries, MatricesError> + Sync),
    ) -> Result<ParameterData, MatricesError> {
        let dk = read(&format!("parameter[{i}].dk"), &p.dk)?;
        let dm = match &p.dm {
            Some(path) => Some(read(&format!("parameter[{i}].dm"), path)?),
            None => None,
        };
        Ok(ParameterData {
            name: p.name.clone(),
            unit: p.unit,
            value: p.value,
            role: p.role,
            dk,
            dm,
        })
    }
}

impl MatricesData {
    /// Builds the structure, with every check of the module docs (the sizes against K's first).
    pub fn build(self) -> Result<Structure, MatricesError> {
        Ok(self.build_solved(&|_| 0)?.0)
    }

    /// [`MatricesData::build`], and the solution its rigid-body check computed: the lowest
    /// max([`RIGID_SEARCH`], r + e) pairs of K and M at the parameter values (r the declared
    /// rigid-body count, 0 when none is declared; e = `elastic` of the structure before the
    /// solve, its rigid-body count r; every pair of a model small enough for the dense
    /// solution), with the factor of K - sigma M the solve made
    /// ([`ModalSolution::take_factor`]). A caller that will solve the same structure for e
    /// modes takes them from here: one factorisation and one solve where there were two (the
    /// 212,562-DOF lap: 13-15 s each).
    pub fn build_solved(
        self,
        elastic: Elastic,
    ) -> Result<(Structure, ModalSolution), MatricesError> {
        let n = self.k.size;
        if n > MAX_DOFS {
            return Err(MatricesError::TooLarge { size: n });
        }
        same_size("mass", &self.m, n)?;
        if self.dofs.len() != n {
            return Err(MatricesError::Size {
                field: "dofs".into(),
                size: self.dofs.len(),
                stiffness: n,
            });
        }
        let mut parameters = Vec::with_capacity(self.parameters.len());
        for (i, p) in self.parameters.iter().enumerate() {
            parameters.push(parameter(i, p, n)?);
        }
        let open_faces = open_faces(&self.dofs, &self.k, &parameters);
        let dofs = DofMap::new(self.dofs, Vec::new(), Vec::new())
            .with_sensor_tolerance(self.sensor_tolerance);
        let (k, m) = rayon::join(
            || SymMatrix::from_lower(n, &self.k.entries),
            || SymMatrix::from_lower(n, &self.m.entries),
        );
        let base = Matrices { k, m };
        let mut structure = Structure {
            base: base.into(),
            parameters,
            dofs: dofs.into(),
            rigid: 0,
            sites: Sites::default(),
            sensors: Vec::new(),
            alternatives: Vec::new(),
            open_faces,
            reduced: None,
        };
        let assembled = structure.assemble();
        check_mass_diagonal(&assembled, &structure.dofs)?;
        let declared = self.rigid_body_modes.unwrap_or(0);
        structure.rigid = declared;
        let count = RIGID_SEARCH.max(declared + elastic(&structure));
        let modal = lowest(&assembled, count)?;
        structure.rigid = rigid_body_modes(self.rigid_body_modes, &assembled, &modal)?;
        structure.sites.beam_mass = translational_mass(&assembled.m, &structure.dofs);
        Ok((structure, modal))
    }
}

/// The pairs of coincident DOFs that neither K nor a dK/dp ties: open faces
/// ([`super::coincident`]).
fn open_faces(
    infos: &[crate::structure::DofInfo],
    k: &LowerEntries,
    parameters: &[Parameter],
) -> usize {
    let lists = std::iter::once(k.entries.as_slice())
        .chain(parameters.iter().map(|p| p.stiffness.entries()));
    super::coincident::untied(infos, lists).len()
}

fn same_size(field: &str, matrix: &LowerEntries, n: usize) -> Result<(), MatricesError> {
    if matrix.size == n {
        Ok(())
    } else {
        Err(MatricesError::Size {
            field: field.to_string(),
            size: matrix.size,
            stiffness: n,
        })
    }
}

fn parameter(i: usize, p: &ParameterData, n: usize) -> Result<Parameter, MatricesError> {
    same_size(&format!("parameter[{i}].dk"), &p.dk, n)?;
    if let Some(dm) = &p.dm {
        same_size(&format!("parameter[{i}].dm"), dm, n)?;
    }
    let nonzero = |m: &LowerEntries| m.entries.iter().any(|e| e.2 != 0.0);
    if !nonzero(&p.dk) && !p.dm.as_ref().is_some_and(nonzero) {
        return Err(MatricesError::ZeroDerivative {
            name: p.name.clone(),
            index: i,
        });
    }
    let sparse = |m: &LowerEntries| {
        let mut s = SparseSym::zero();
        for (r, c, v) in m.both_triangles() {
            s.push(r, c, v);
        }
        s
    };
    Ok(Parameter {
        name: p.name.clone(),
        unit: p.unit,
        value: p.value,
        stiffness: sparse(&p.dk),
        mass: p.dm.as_ref().map_or_else(SparseSym::zero, sparse),
        role: p.role,
    })
}

/// The lowest `count` pairs (at most N) of `mats`: the solver checks that M is positive
/// definite (its Cholesky factorisation, which the shift-invert solver needs anyway and
/// keeps for the next solve of the same M, [`crate::modal::memo`]).
fn lowest(mats: &Matrices, count: usize) -> Result<ModalSolution, MatricesError> {
    ModalSolution::lowest_of_factored(mats, count.min(mats.size())).map_err(|e| match e {
        ModalError::MassNotPositiveDefinite => MatricesError::MassNotPositiveDefinite {
            cause: "a pivot is not positive".into(),
        },
        other => MatricesError::Modal {
            message: other.to_string(),
        },
    })
}

/// The number of rigid-body modes: counted on the lowest pairs `modal` (at least
/// [`RIGID_SEARCH`] of them, or all), and checked against the declared one.
fn rigid_body_modes(
    declared: Option<usize>,
    mats: &Matrices,
    modal: &ModalSolution,
) -> Result<usize, MatricesError> {
    let (kd, md) = (mats.k.diagonal(), mats.m.diagonal());
    let scale = kd.iter().zip(&md).map(|(k, m)| k / m).fold(0.0, f64::max);
    let tolerance = RIGID_TOLERANCE * scale;
    // Every pair of a dense solution, the first RIGID_SEARCH of a sparse one (of more, when
    // a caller asked for more: the same check).
    let searched = if mats.size() <= DENSE_MAX_DOFS {
        modal.len()
    } else {
        RIGID_SEARCH.min(modal.len())
    };
    let values = &modal.values()[..searched];
    let lowest: Vec<f64> = values.iter().take(RIGID_SEARCH).copied().collect();
    if values[0] < -tolerance {
        return Err(MatricesError::StiffnessIndefinite {
            lambda: values[0],
            tolerance,
        });
    }
    let counted = values.iter().take_while(|&&l| l <= tolerance).count();
    let gap = |r: usize| {
        r > 0 && r < values.len() && values[..r].iter().all(|l| l.abs() <= RIGID_GAP * values[r])
    };
    match declared {
        Some(declared) if declared == counted || gap(declared) => Ok(declared),
        Some(declared) => Err(MatricesError::Rigid {
            declared,
            counted,
            tolerance_hz: lambda_to_hz(tolerance),
            lowest_hz: lowest.iter().map(|&l| lambda_to_hz(l)).collect(),
        }),
        None => Ok(counted),
    }
}

/// M must have a positive diagonal (every DOF carries mass; its Cholesky factor is checked
/// by the solve that counts the rigid-body modes).
fn check_mass_diagonal(mats: &Matrices, dofs: &DofMap) -> Result<(), MatricesError> {
    match mats
        .m
        .diagonal()
        .iter()
        .enumerate()
        .find(|(_, v)| **v <= 0.0)
    {
        Some((i, &v)) => Err(MatricesError::MassDiagonal {
            dof: i + 1,
            label: dofs.get(i).label.clone(),
            value: v,
        }),
        None => Ok(()),
    }
}

/// The model's mass in its heaviest translation direction: u^T M u with u = 1 on every DOF of
/// that direction (the rigid translation), kg. The scale of the effects' sizes.
fn translational_mass(m: &SymMatrix, dofs: &DofMap) -> f64 {
    [Direction::W, Direction::X, Direction::Y, Direction::Z]
        .into_iter()
        .map(|direction| {
            let u: Vec<f64> = dofs
                .dofs()
                .iter()
                .map(|d| f64::from(u8::from(d.direction == direction)))
                .collect();
            let mut mu = vec![0.0; u.len()];
            m.apply(&u, &mut mu);
            u.iter().zip(&mu).map(|(a, b)| a * b).sum::<f64>()
        })
        .fold(0.0, f64::max)
}

//! The model-agnostic structure every command works on: the matrices K and M, the parameters
//! p_i with their derivatives dK/dp_i and dM/dp_i (eq. (8)), identified or held fixed, the DOF
//! map, the number of rigid-body modes, and the sites where effects can act.
//!
//! K and M are linear in the parameters: K(p) = K_base + sum_i p_i dK/dp_i, and the same for
//! M, so the first-order expansion of eq. (8) is exact in them. Builders make a structure:
//! the beam chain ([`crate::model::chain`]) and external matrices
//! ([`crate::model::matrices`]); identify, study, simulate and diagnose never ask which.
//!
//! - [`sparse`]: derivative matrices, a list of entries;
//! - [`matrix`]: K and M, compressed sparse columns;
//! - [`dofs`]: the DOF map (labels, positions, directions, line elements);
//! - [`observation`]: what a sensor reads, c^T u, at a DOF or between nodes;
//! - [`nearest`]: a sensor given by coordinates in space, resolved to the nearest DOF;
//! - [`sites`]: joints, elements and free ends, for the effects;
//! - [`reduced`]: a reduction basis with the matrices projected on it, which a structure may
//!   carry to every solve of its eigenproblem;
//! - [`columns`]: a tall matrix in blocks of columns that copies share (the reduction's basis).
//!
//! Layer 1 (foundations; see the crate docs): may import, without a circle, the other foundations:
//! [`crate::stats`], [`crate::input`], [`crate::random`], [`crate::uff`].

pub mod columns;
pub mod dofs;
pub mod matrix;
pub mod nearest;
pub mod observation;
pub mod reduced;
pub mod sites;
pub mod sparse;

pub use dofs::{Direction, DofInfo, DofMap, LineElement};
pub use matrix::SymMatrix;
pub use observation::{LocateError, Observation, observe, terms_at};
pub use sites::{
    ElementSite, EndSite, HeldCoupling, HeldMotions, JointSite, Section, Shear, Sites, SupportSite,
};
pub use sparse::SparseSym;

/// Largest number of identified parameters a structure may have: the most the per-mode
/// identification solves for (eight joints of two parameters; its least-squares solver keeps
/// R on the stack, [`crate::identify::wls::MAX_Q`]). The beam-chain builder refuses more.
pub const MAX_IDENTIFIED: usize = 16;

/// A measured mode the model has no elastic mode to pair with by order.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
#[error(
    "mode {mode} is beyond the model: it has {elastic} elastic modes ({dofs} DOFs, {rigid} rigid-body modes)"
)]
pub struct ModeBeyondModel {
    /// The measured mode (from 1).
    pub mode: usize,
    /// The model's elastic modes.
    pub elastic: usize,
    /// The model's DOFs.
    pub dofs: usize,
    /// The model's rigid-body modes.
    pub rigid: usize,
}

/// Whether a parameter is identified or held at its value.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Role {
    /// Identified (the default): a column of the sensitivity system.
    Identified,
    /// Held fixed: part of the model, never corrected.
    Fixed,
}

/// A model parameter p_i with the derivatives of the global matrices with respect to it.
#[derive(Debug, Clone)]
pub struct Parameter {
    /// Name in output files (`k1`, `joint2.k2`, ...).
    pub name: String,
    /// Unit, for reports.
    pub unit: &'static str,
    /// Current value p_i.
    pub value: f64,
    /// dK/dp_i.
    pub stiffness: SparseSym,
    /// dM/dp_i (zero for a stiffness parameter).
    pub mass: SparseSym,
    /// Identified or fixed.
    pub role: Role,
}

/// Global K (N x N, symmetric positive semidefinite) and M (symmetric positive definite).
#[derive(Debug, Clone)]
pub struct Matrices {
    /// Stiffness matrix K.
    pub k: SymMatrix,
    /// Mass matrix M.
    pub m: SymMatrix,
}

impl Matrices {
    /// These matrices plus `scale` times each (dK, dM) of `terms`.
    pub fn plus(&self, terms: &[(&SparseSym, &SparseSym, f64)]) -> Matrices {
        let k: Vec<(&SparseSym, f64)> = terms.iter().map(|t| (t.0, t.2)).collect();
        let m: Vec<(&SparseSym, f64)> = terms.iter().map(|t| (t.1, t.2)).collect();
        Matrices {
            k: self.k.plus(&k),
            m: self.m.plus(&m),
        }
    }

    /// N.
    pub fn size(&self) -> usize {
        self.k.size()
    }

    /// The eigenvalue below which a computed lambda is zero to round-off: 1e3 eps times the
    /// largest Rayleigh quotient of a unit vector, max K_ii / M_ii, which bounds the largest
    /// eigenvalue from below and sets the size of the solver's rounding errors.
    pub fn zero_eigenvalue_level(&self) -> f64 {
        let scale = self
            .k
            .diagonal()
            .iter()
            .zip(self.m.diagonal())
            .filter(|(_, m)| *m > 0.0)
            .map(|(k, m)| k.abs() / m)
            .fold(0.0, f64::max);
        1e3 * f64::EPSILON * scale
    }
}

/// A structure: see the module docs.
#[derive(Debug, Clone)]
pub struct Structure {
    /// K and M without the parameters' contributions (shared: a structure with other
    /// parameter values is a cheap clone, whatever the size of the model).
    pub base: std::sync::Arc<Matrices>,
    /// Every parameter, identified and fixed, in model order.
    pub parameters: Vec<Parameter>,
    /// The DOFs (shared, like `base`).
    pub dofs: std::sync::Arc<DofMap>,
    /// Number of rigid-body modes (zero eigenvalues), from the model.
    pub rigid: usize,
    /// Where effects can act.
    pub sites: Sites,
    /// The sensors the model declares (what `simulate --measure sensors` reads).
    pub sensors: Vec<Observation>,
    /// Other models of the same test that the builder knows (a joint modelled otherwise).
    pub alternatives: Vec<Alternative>,
    /// Pairs of coincident DOFs (same position and direction) that nothing ties: open faces
    /// of an external model (a lap's notch, a crack), which change no entry of K or M; a
    /// sensor position on one asks for the DOF's label.
    pub open_faces: usize,
    /// The reduced model every solve of this structure's eigenproblem uses in place of the
    /// full one ([`crate::modal::reduced`]), when one is attached (none: the full model).
    /// Shared by the structures made from this one with other parameter values.
    pub reduced: Option<std::sync::Arc<reduced::Reduced>>,
}

/// Another model of the same test, made by the builder that made a structure: every DOF of
/// that structure keeps its index, label and meaning in it (it may add DOFs after them), so
/// that observations of the one read the other.
#[derive(Debug, Clone)]
pub struct Alternative {
    /// Its name (the diagnosis candidate that fits it: `layered_lap`).
    pub name: &'static str,
    /// The structure, its parameters at their nominal values.
    pub structure: std::sync::Arc<Structure>,
}

impl Structure {
    /// K and M at the current parameter values: the base matrices, then p_i dK/dp_i and
    /// p_i dM/dp_i in parameter order.
    pub fn assemble(&self) -> Matrices {
        let terms: Vec<(&SparseSym, &SparseSym, f64)> = self
            .parameters
            .iter()
            .map(|p| (&p.stiffness, &p.mass, p.value))
            .collect();
        self.base.plus(&terms)
    }

    /// Number of DOFs N.
    pub fn dof_count(&self) -> usize {
        self.dofs.len()
    }

    /// The number of elastic modes: N less the rigid-body modes.
    pub fn elastic_count(&self) -> usize {
        self.dof_count().saturating_sub(self.rigid)
    }

    /// The model mode (0-based, rigid-body modes counted) that measured elastic mode `mode`
    /// (from 1) pairs with by order; an error when the model has no such mode.
    pub fn model_mode(&self, mode: usize) -> Result<usize, ModeBeyondModel> {
        if (1..=self.elastic_count()).contains(&mode) {
            Ok(mode - 1 + self.rigid)
        } else {
            Err(ModeBeyondModel {
                mode,
                elastic: self.elastic_count(),
                dofs: self.dof_count(),
                rigid: self.rigid,
            })
        }
    }

    /// The identified parameters, in model order (the columns of the sensitivity system).
    pub fn identified(&self) -> Vec<Parameter> {
        self.parameters
            .iter()
            .filter(|p| p.role == Role::Identified)
            .cloned()
            .collect()
    }

    /// The names of the identified parameters, in model order.
    pub fn identified_names(&self) -> Vec<String> {
        self.identified().into_iter().map(|p| p.name).collect()
    }

    /// Positions in [`Structure::parameters`] of the identified parameters.
    pub fn identified_indices(&self) -> Vec<usize> {
        (0..self.parameters.len())
            .filter(|&i| self.parameters[i].role == Role::Identified)
            .collect()
    }

    /// The same structure with the identified parameters shifted by `delta` (in the order of
    /// [`Structure::identified`]).
    pub fn with_delta(&self, delta: &[f64]) -> Structure {
        let at = self.identified_indices();
        assert_eq!(delta.len(), at.len(), "one delta per identified parameter");
        let mut out = self.clone();
        for (&i, d) in at.iter().zip(delta) {
            out.parameters[i].value += d;
        }
        out
    }

    /// The same structure with the identified parameters at `values`.
    pub fn with_values(&self, values: &[f64]) -> Structure {
        let at = self.identified_indices();
        assert_eq!(values.len(), at.len(), "one value per identified parameter");
        let mut out = self.clone();
        for (&i, v) in at.iter().zip(values) {
            out.parameters[i].value = *v;
        }
        out
    }
}

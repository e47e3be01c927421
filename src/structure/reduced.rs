//! The data of a parametric reduced model of a structure: a basis V of N x r columns, the
//! base matrices and every parameter's derivative matrices projected on it. The algorithms
//! that build it, solve on it, check its pairs against the full model and enrich it are the
//! eigensolution's ([`crate::modal::reduced`]); this module only holds what they share, so
//! that a [`super::Structure`] can carry it to every place that solves its eigenproblem.
//!
//! Why the parameters stay exact: K and M are affine in the parameters (module docs of
//! [`super`]), so V^T K(p) V = V^T K_base V + sum_i p_i V^T dK_i V for any V: a reduced model
//! at new parameter values is a sum of r x r matrices, with no approximation beyond the choice
//! of V. What V must hold for the reduced pairs to be the full ones is the eigensolution's
//! business, and what decides whether they are is the residual of each reduced pair in the
//! full model, which [`Reduced::k_basis`] and [`Reduced::m_basis`] give at the cost of a
//! product of N x r by r, measured through [`Reduced::precondition`].
//!
//! Layer 1 (foundations), like [`super`].

use std::sync::{Arc, Mutex};

use faer::{Mat, MatMut};

use super::Matrices;
use super::columns::Columns;

/// The preconditioner of the enrichment and of the residual check: (K - sigma M)^-1 of the
/// nominal model applied to the columns of a block, in place. Every copy of a reduction shares
/// it, and it holds the factor until [`Precondition::release`]: a caller that has done its
/// last reduced solve frees the factor before it solves the full model (the check of a
/// diagnosis's final model), where both would otherwise be held at once. A reduction whose
/// preconditioner is released serves no more solves ([`Reduced::serves`]).
#[derive(Clone)]
pub struct Precondition(Arc<Mutex<Option<Solve>>>);

/// The factor's solve of a block in place.
type Solve = Arc<dyn Fn(MatMut<'_, f64>) + Send + Sync>;

impl Precondition {
    /// The preconditioner applying `solve`.
    pub fn new(solve: impl Fn(MatMut<'_, f64>) + Send + Sync + 'static) -> Self {
        Self(Arc::new(Mutex::new(Some(Arc::new(solve)))))
    }

    /// Applies it to the columns of `x` in place; false (x untouched) once released.
    pub fn apply(&self, x: MatMut<'_, f64>) -> bool {
        let solve = self.0.lock().map(|s| s.clone()).unwrap_or(None);
        solve.map(|f| f(x)).is_some()
    }

    /// Drops the factor, for every copy of the reduction.
    pub fn release(&self) {
        if let Ok(mut s) = self.0.lock() {
            *s = None;
        }
    }

    /// Whether it still holds the factor.
    pub fn held(&self) -> bool {
        self.0.lock().map(|s| s.is_some()).unwrap_or(false)
    }
}

/// A reduction basis and the projected matrices (module docs).
#[derive(Clone)]
pub struct Reduced {
    /// The base matrices the basis was built for: the reduction serves a structure only when
    /// its base is this one (the same allocation).
    pub base: Arc<Matrices>,
    /// How many parameters the structure has (each one's projections below).
    pub parameter_count: usize,
    /// V, N x r, orthonormal in the base mass matrix: V^T M_base V = I. Its columns, and
    /// those of the two products below, are in blocks that the enriched copies of a
    /// reduction share ([`Columns`]).
    pub basis: Columns,
    /// K_base V.
    pub k_basis: Columns,
    /// M_base V.
    pub m_basis: Columns,
    /// V^T K_base V.
    pub k: Mat<f64>,
    /// V^T M_base V.
    pub m: Mat<f64>,
    /// Per parameter of the structure, in model order: V^T dK_i V and V^T dM_i V.
    pub parameters: Vec<(Mat<f64>, Mat<f64>)>,
    /// The eigenvalue that scales the residuals of pairs below it (the first elastic one of
    /// the nominal model): the rigid-body pairs' residual is measured against it.
    pub scale: f64,
    /// Largest relative error estimate r^T (K_0 - sigma M_0)^-1 r / max(lambda, scale) of a
    /// reduced pair accepted.
    pub tolerance: f64,
    /// (K - sigma M)^-1 of the nominal model, for the enrichment.
    pub precondition: Precondition,
    /// Columns added since the basis was built, by enrichment.
    pub enriched: usize,
}

impl Reduced {
    /// r, the number of basis vectors.
    pub fn dimension(&self) -> usize {
        self.basis.ncols()
    }

    /// N.
    pub fn dof_count(&self) -> usize {
        self.basis.nrows()
    }

    /// Whether it serves a structure with base `base` and `parameters` parameters: built for
    /// them, its preconditioner still held.
    pub fn serves(&self, base: &Arc<Matrices>, parameters: usize) -> bool {
        Arc::ptr_eq(&self.base, base)
            && self.parameter_count == parameters
            && self.precondition.held()
    }
}

impl std::fmt::Debug for Reduced {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("Reduced")
            .field("dofs", &self.dof_count())
            .field("dimension", &self.dimension())
            .field("enriched", &self.enriched)
            .field("tolerance", &self.tolerance)
            .finish()
    }
}

//! A parametric reduced model for the repeated solves of one structure's eigenproblem (a
//! diagnosis's fits, identify's frequency fallbacks): the lowest pairs of K(p) y = lambda M(p)
//! y by Rayleigh-Ritz on a basis V built once on the nominal model, every pair checked by its
//! residual in the full model, the basis enriched where a residual is too large.
//!
//! - The basis ([`basis`]): the nominal model's lowest pairs and, for every direction the
//!   model moves in (a joint parameter, a candidate effect), the static corrections of the
//!   wanted modes. Its data ([`Reduced`]) ride on the structure
//!   ([`crate::structure::Structure::reduced`]); structures made from it with other parameter
//!   values share it.
//! - A solve ([`lowest`]): V^T K(p) V and V^T M(p) V from the projections of the base matrices
//!   and of every dK/dp, dM/dp (exact in p: K and M are affine in it), plus any extra term
//!   (a candidate's contribution, projected entry by entry); the r x r pencil solved densely;
//!   the lowest pairs lifted, x = V y, with the sign convention of [`ModalSolution`].
//! - The check: each lifted pair's residual r = K x - lambda M x in the full model, measured
//!   as eta = ||r||_W / max(lambda, lambda_1) with W = diag(M)^-1 and lambda_1 the nominal
//!   first elastic eigenvalue. For an M-normalised x, lambda is within about ||r||_M^-1 of an
//!   eigenvalue (first order) and within ||r||^2 / gap of it (second order), so eta below
//!   [`TOLERANCE`] = 1e-6 puts the frequency within about 1e-12 lambda / gap of the full
//!   model's, and the vector within about 1e-6 lambda / gap.
//! - The enrichment: where a pair's eta exceeds the tolerance, its residual through
//!   (K_0 - sigma M_0)^-1 of the nominal model (a step of preconditioned inverse iteration, as
//!   in Davidson's method) joins the basis, and the solve is repeated, up to
//!   [`MAX_ROUNDS`] times; then the full model is solved instead. A caller that solves in
//!   sequence keeps the enriched basis ([`lowest_keeping`]); one that solves in parallel lets
//!   it go, so that results never depend on the order in which threads finish.
//!
//! A structure without a reduction (or one built for another base) is solved in full, by
//! [`ModalSolution::lowest_of`], exactly as before.
//!
//! Layer 2 (eigensolution), like [`super`].

pub mod basis;
pub mod derivative;
mod solve;

use std::sync::Arc;

use faer::Mat;

pub use basis::build;

use super::{ModalError, ModalSolution};
use crate::structure::reduced::Reduced;
use crate::structure::{Matrices, SparseSym, Structure};

/// Largest relative residual eta of a reduced pair accepted (module docs).
pub const TOLERANCE: f64 = 1e-6;

/// Rounds of enrichment tried in one solve before the full model is solved.
pub const MAX_ROUNDS: usize = 3;

/// Extra terms of K and M beside the structure's parameters: (dK, dM, scale).
pub type Extra<'a> = [(&'a SparseSym, &'a SparseSym, f64)];

/// What a reduced solve leaves beside its lifted pairs: the reduced pencil's pairs (all of
/// them, for the derivatives, [`derivative`]) and the residuals of the lifted ones.
#[derive(Debug, Clone)]
pub struct ReducedPairs {
    /// The reduction solved on.
    pub reduced: Arc<Reduced>,
    /// Every eigenvalue of the reduced pencil, ascending.
    pub values: Vec<f64>,
    /// Its vectors (r x r', V^T M V-normalised), the lifted ones' signs as theirs.
    pub vectors: Mat<f64>,
    /// eta of every lifted pair (module docs).
    pub residuals: Vec<f64>,
}

/// The reduction `structure` carries, when it serves it.
pub fn usable(structure: &Structure) -> Option<&Arc<Reduced>> {
    structure
        .reduced
        .as_ref()
        .filter(|r| r.serves(&structure.base, structure.parameters.len()))
}

/// The lowest `count` pairs of `structure` plus `extra`: on its reduction when it carries one
/// (module docs), else in full.
pub fn lowest(
    structure: &Structure,
    extra: &Extra,
    count: usize,
) -> Result<ModalSolution, ModalError> {
    Ok(lowest_keeping(structure, extra, count)?.0)
}

/// As [`lowest`], with the enriched reduction when the solve enriched it (a caller that solves
/// in sequence attaches it to its next structures).
pub fn lowest_keeping(
    structure: &Structure,
    extra: &Extra,
    count: usize,
) -> Result<(ModalSolution, Option<Arc<Reduced>>), ModalError> {
    let Some(start) = usable(structure) else {
        return Ok((full(structure, extra, count)?, None));
    };
    if count > start.dimension() {
        return Ok((full(structure, extra, count)?, None));
    }
    let mut reduced = Arc::clone(start);
    let mut enriched = false;
    for round in 0..=MAX_ROUNDS {
        let solved = solve::solve(&reduced, structure, extra, count)?;
        let bad: Vec<usize> = residuals(&solved.modal)
            .iter()
            .enumerate()
            .filter(|(_, eta)| !(**eta <= reduced.tolerance))
            .map(|(j, _)| j)
            .collect();
        if bad.is_empty() {
            return Ok((solved.modal, enriched.then_some(reduced)));
        }
        if round == MAX_ROUNDS {
            break;
        }
        match enrich(&reduced, structure, &solved.residual, &bad) {
            Some(next) => {
                reduced = next;
                enriched = true;
            }
            None => break,
        }
    }
    Ok((full(structure, extra, count)?, None))
}

/// The lowest pairs up to `f_max_hz`, at least `count` of them (as
/// [`ModalSolution::covering`]), on the reduction when it reaches that far, with the enriched
/// reduction as [`lowest_keeping`].
pub fn covering(
    structure: &Structure,
    extra: &Extra,
    count: usize,
    f_max_hz: f64,
) -> Result<(ModalSolution, Option<Arc<Reduced>>), ModalError> {
    let Some(reduced) = usable(structure) else {
        return Ok((full_covering(structure, extra, count, f_max_hz)?, None));
    };
    let (r, n) = (reduced.dimension(), structure.dof_count());
    let mut count = count.clamp(1, n);
    let mut kept: Option<Arc<Reduced>> = None;
    let mut current = structure.clone();
    while count <= r {
        let (sol, next) = lowest_keeping(&current, extra, count)?;
        if let Some(next) = next {
            current.reduced = Some(Arc::clone(&next));
            kept = Some(next);
        }
        let top = sol.frequency_hz(sol.len() - 1);
        if sol.len() == n || top > f_max_hz || f_max_hz.is_nan() || sol.reduced().is_none() {
            return Ok((sol, kept));
        }
        count = (count + count.div_ceil(2)).min(n);
    }
    Ok((full_covering(structure, extra, count, f_max_hz)?, kept))
}

/// The lowest `count` pairs of the full model (the structure assembled, `extra` added).
pub fn full(
    structure: &Structure,
    extra: &Extra,
    count: usize,
) -> Result<ModalSolution, ModalError> {
    ModalSolution::lowest_of(&assembled(structure, extra), count)
}

fn full_covering(
    structure: &Structure,
    extra: &Extra,
    count: usize,
    f_max_hz: f64,
) -> Result<ModalSolution, ModalError> {
    ModalSolution::covering(&assembled(structure, extra), count, f_max_hz)
}

/// K and M of `structure` plus `extra` (as [`crate::model::effects::Configured::assemble`]:
/// the extra terms added after the parameters).
fn assembled(structure: &Structure, extra: &Extra) -> Matrices {
    let mats = structure.assemble();
    if extra.is_empty() {
        mats
    } else {
        mats.plus(extra)
    }
}

/// eta of every pair of a reduced solution (empty for a full one).
pub fn residuals(modal: &ModalSolution) -> &[f64] {
    modal.reduced().map_or(&[], |p| p.residuals.as_slice())
}

/// The reduction with the preconditioned residuals of pairs `bad` added; none when they add
/// no direction.
fn enrich(
    reduced: &Arc<Reduced>,
    structure: &Structure,
    residual: &Mat<f64>,
    bad: &[usize],
) -> Option<Arc<Reduced>> {
    let mut w = Mat::from_fn(residual.nrows(), bad.len(), |i, c| residual[(i, bad[c])]);
    (reduced.precondition)(w.as_mut());
    let mut next = (**reduced).clone();
    let added = basis::extend(&mut next, structure, w.as_ref());
    next.enriched += added;
    (added > 0).then(|| Arc::new(next))
}

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
//! - The check: each lifted pair's residual r = K x - lambda M x in the full model, and its
//!   correction d = (K_0 - sigma M_0)^-1 r through the nominal model's factor (sigma below
//!   the spectrum). The Rayleigh-Ritz residual is orthogonal to the basis, which holds the
//!   low modes, so r lives in the modes above them, where (K - lambda M)^-1 and
//!   (K_0 - sigma M_0)^-1 nearly agree; and the eigenvalue's error is, to second order,
//!   r^T (K - lambda M)^-1 r. The estimate e = |r^T d| / max(lambda, lambda_1) (lambda_1 the
//!   nominal first elastic eigenvalue, for the rigid-body pairs) is the eigenvalue's relative
//!   error, the frequency's is half of it, and sqrt(e) the vector's in the energy norm.
//!   Measured on the 23,958-DOF lap with every spring halved (the nominal basis, 53
//!   vectors): frequency errors 1e-8 to 1e-5 against the full solve, e 1.4 to 1.7 times them
//!   in each of the ten elastic pairs. [`TOLERANCE`] = 1e-8 keeps frequencies within about
//!   1e-8 and shapes within about 1e-4 of the full model's.
//! - The enrichment: where a pair's e exceeds the tolerance, its correction d (a step of
//!   preconditioned inverse iteration, as in Davidson's method) joins the basis, and the
//!   solve is repeated, up to
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

use super::sparse_llt::SparseLlt;
use super::{ModalError, ModalSolution};
use crate::structure::reduced::Reduced;
use crate::structure::{Matrices, SparseSym, Structure};

/// Largest error estimate e of a reduced pair accepted (module docs).
pub const TOLERANCE: f64 = 1e-8;

/// Rounds of enrichment tried in one solve before the full model is solved.
pub const MAX_ROUNDS: usize = 4;

/// A pair whose error estimate exceeds this is beyond what enrichment restores in a few
/// rounds (the model far from the one the basis was built on: a joint a thousand times
/// stiffer): the full model is solved at once.
pub const HOPELESS: f64 = 1.0;

/// Fewest DOFs of a model solved on a reduced model ([`applies`]).
pub const MIN_DOFS: usize = 2000;

/// Whether repeated solves of `structure` go through a reduced model: a model solved sparsely
/// whose DOFs are not a beam chain's (no line elements: the 3D solids and other external
/// models), from [`MIN_DOFS`] DOFs, that carries none yet. Beam chains stay on the full
/// solve: a banded model of a few thousand DOFs solves in milliseconds, and their derivatives
/// are exact.
pub fn applies(structure: &Structure) -> bool {
    structure.dof_count() >= MIN_DOFS
        && structure.dofs.lines().is_empty()
        && structure.reduced.is_none()
}

/// `structure` carrying the basis of [`build`] (the tolerance [`TOLERANCE`]; `factor` as
/// there).
pub fn attach(
    structure: &Structure,
    nominal: &ModalSolution,
    factor: Option<Arc<SparseLlt>>,
    directions: &[(&SparseSym, &SparseSym)],
    modes: std::ops::Range<usize>,
) -> Result<Structure, ModalError> {
    let built = build(structure, nominal, factor, directions, modes, TOLERANCE)?;
    let mut out = structure.clone();
    out.reduced = Some(Arc::new(built));
    Ok(out)
}

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
    /// The error estimate e of every lifted pair (module docs).
    pub residuals: Vec<f64>,
}

/// The reduction `structure` carries, when it serves it.
pub fn usable(structure: &Structure) -> Option<&Arc<Reduced>> {
    structure
        .reduced
        .as_ref()
        .filter(|r| r.serves(&structure.base, structure.parameters.len()))
}

/// Frees the factor that `structure`'s reduction keeps for its checks, for every copy of the
/// reduction ([`crate::structure::reduced::Precondition::release`]): solves after it are
/// full ones. For a caller done with its reduced solves, before it solves the full model.
pub fn release(structure: &Structure) {
    if let Some(r) = &structure.reduced {
        r.precondition.release();
    }
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
    lowest_checking(structure, extra, count, None)
}

/// As [`lowest_keeping`], the errors of the pairs `checked` alone checked when given (a
/// caller that reads those alone: the frequency-dependent joint's mode at its own frequency,
/// a fit's pairs below the pairing window's); the others' estimates are then 0.
pub fn lowest_checking(
    structure: &Structure,
    extra: &Extra,
    count: usize,
    checked: Option<std::ops::Range<usize>>,
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
        let solved = solve::solve(&reduced, structure, extra, count, checked.clone())?;
        let bad: Vec<usize> = residuals(&solved.modal)
            .iter()
            .enumerate()
            .filter(|(_, e)| e.is_nan() || **e > reduced.tolerance)
            .map(|(j, _)| j)
            .collect();
        if bad.is_empty() {
            return Ok((solved.modal, enriched.then_some(reduced)));
        }
        let worst = residuals(&solved.modal)
            .iter()
            .fold(0.0, |a: f64, &e| a.max(e));
        if round == MAX_ROUNDS || worst.is_nan() || worst > HOPELESS {
            break;
        }
        let bad: Vec<usize> = bad.iter().map(|j| j - solved.first).collect();
        match enrich(&reduced, structure, &solved.correction, &bad) {
            Some(next) => {
                reduced = next;
                enriched = true;
            }
            None => break,
        }
    }
    Ok((full(structure, extra, count)?, None))
}

/// The lowest `count` pairs of `structure` plus `extra` from one solve on its reduction as it
/// is, neither enriched nor replaced by the full solve whatever their error estimates
/// ([`residuals`]: every pair's), for a caller that needs less than [`TOLERANCE`] and judges
/// them itself; none when the structure carries no usable reduction or `count` exceeds its
/// dimension. The reduced eigenvalues are Rayleigh-Ritz values: each lies at or above the
/// full model's of the same index.
pub fn estimated(
    structure: &Structure,
    extra: &Extra,
    count: usize,
) -> Result<Option<ModalSolution>, ModalError> {
    match usable(structure) {
        Some(reduced) if count <= reduced.dimension() => Ok(Some(
            solve::solve(reduced, structure, extra, count, None)?.modal,
        )),
        _ => Ok(None),
    }
}

/// The lowest pairs up to `f_max_hz`, at least `count` of them (as
/// [`ModalSolution::covering`]), on the reduction when it reaches that far, with the enriched
/// reduction as [`lowest_keeping`]; the first `checked` pairs checked (the others are the
/// window's: a pair missed there shows in the final check against the full model).
pub fn covering(
    structure: &Structure,
    extra: &Extra,
    count: usize,
    f_max_hz: f64,
    checked: usize,
) -> Result<(ModalSolution, Option<Arc<Reduced>>), ModalError> {
    let Some(reduced) = usable(structure) else {
        return Ok((full_covering(structure, extra, count, f_max_hz)?, None));
    };
    let (r, n) = (reduced.dimension(), structure.dof_count());
    let mut count = count.clamp(1, n);
    let mut kept: Option<Arc<Reduced>> = None;
    let mut current = structure.clone();
    // The first `checked` pairs are checked; those beyond, solved for the window, only lie
    // there.
    let checked = 0..checked;
    while count <= r {
        let (sol, next) = lowest_checking(&current, extra, count, Some(checked.clone()))?;
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

/// The error estimate e of every pair of a reduced solution (empty for a full one).
pub fn residuals(modal: &ModalSolution) -> &[f64] {
    modal.reduced().map_or(&[], |p| p.residuals.as_slice())
}

/// The reduction with the preconditioned residuals of pairs `bad` added; none when they add
/// no direction.
fn enrich(
    reduced: &Arc<Reduced>,
    structure: &Structure,
    correction: &Mat<f64>,
    bad: &[usize],
) -> Option<Arc<Reduced>> {
    let w = Mat::from_fn(correction.nrows(), bad.len(), |i, c| {
        correction[(i, bad[c])]
    });
    let mut next = (**reduced).clone();
    let added = basis::extend(&mut next, structure, w.as_ref());
    next.enriched += added;
    (added > 0).then(|| Arc::new(next))
}

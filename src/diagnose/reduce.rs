//! The reduced model of a diagnosis: built once on the nominal model before the calibration,
//! shared by every fit (the calibration, each candidate, the frequency-dependent joint's
//! per-mode solves) and the per-mode tables; and the check of the final model by one full
//! solve (module [`crate::modal::reduced`] for the method).
//!
//! Which models: those of [`reduced::applies`] (the 3D solids and other external models of
//! [`reduced::MIN_DOFS`] DOFs or more); beam chains stay on the full solve.
//!
//! The basis: the nominal model's lowest rigid + 2 m + 2 pairs (m measured modes), and the
//! static corrections of the rigid + m + 2 lowest in the direction of every joint parameter
//! and of every candidate effect of the library (at its typical size).

use std::sync::Arc;

use serde::Serialize;

use super::fit::Fitted;
use crate::measured::MeasuredModes;
use crate::modal::reduced;
use crate::modal::sparse_llt::SparseLlt;
use crate::modal::{ModalError, ModalSolution};
use crate::model::effects::{EffectContext, Tier, registry};
use crate::structure::{SparseSym, Structure};

/// Largest relative frequency difference between the reduced and the full model at the final
/// parameters accepted without solving the diagnosis again in full.
pub const FREQUENCY_TOLERANCE: f64 = 1e-6;

/// How many of the nominal model's lowest pairs the reduced model of `structure` is built on
/// (module docs), when one applies.
pub fn nominal_pairs(structure: &Structure, measured: &MeasuredModes) -> Option<usize> {
    reduced::applies(structure)
        .then(|| (structure.rigid + 2 * measured.modes().len() + 2).min(structure.dof_count()))
}

/// `ctx` with its structure carrying the reduced model of the module docs, when it applies;
/// `ctx` itself otherwise. `nominal`: the nominal model's lowest pairs, solved again only when
/// it holds fewer than [`nominal_pairs`]; `factor`: the factor of K - sigma M its solve made
/// ([`ModalSolution::lowest_of_factored`]), which the basis keeps rather than factorise the
/// model again. `extended`: the library's extended tier is searched too, and its effects'
/// directions join the basis.
pub fn attach(
    ctx: Arc<EffectContext>,
    nominal: &ModalSolution,
    factor: Option<Arc<SparseLlt>>,
    measured: &MeasuredModes,
    extended: bool,
) -> Result<Arc<EffectContext>, ModalError> {
    let structure = &ctx.structure;
    let Some(wanted) = nominal_pairs(structure, measured) else {
        return Ok(ctx);
    };
    let (rigid, m) = (structure.rigid, measured.modes().len());
    // A sparse solution's first `wanted` pairs (a dense one holds every pair, as before).
    let solved;
    let nominal = if nominal.len() == wanted || nominal.len() == structure.dof_count() {
        nominal
    } else if nominal.len() > wanted {
        let (vectors, values) = nominal.sub_basis(wanted);
        solved = ModalSolution::from_parts(values, vectors, None);
        &solved
    } else {
        solved = ModalSolution::lowest_of(&structure.assemble(), wanted)?;
        &solved
    };
    let effects: Vec<(SparseSym, SparseSym)> = registry()
        .into_iter()
        .filter(|e| e.tier() == Tier::Default || (extended && e.tier() == Tier::Extended))
        .filter(|e| e.applies(&ctx))
        .flat_map(|e| {
            let theta: Vec<f64> = e.parameters(&ctx).iter().map(|p| p.scale).collect();
            e.derivatives(&ctx, &theta)
        })
        .collect();
    let params = structure.identified();
    let directions: Vec<(&SparseSym, &SparseSym)> = params
        .iter()
        .map(|p| (&p.stiffness, &p.mass))
        .chain(effects.iter().map(|(k, m)| (k, m)))
        .collect();
    let attached = reduced::attach(
        structure,
        nominal,
        factor,
        &directions,
        rigid..(rigid + m + 2).min(nominal.len()),
    )?;
    let mut with = (*ctx).clone();
    with.structure = attached;
    Ok(Arc::new(with))
}

/// `ctx` with the reduced model as `fitted`'s solves left it (enriched on their way), when it
/// differs from `ctx`'s: the fits after it start from there.
pub fn recentred(ctx: &Arc<EffectContext>, fitted: &Fitted) -> Arc<EffectContext> {
    let current = reduced::usable(&ctx.structure);
    match fitted.configured.structure.reduced.as_ref() {
        Some(r) if current.is_some_and(|c| !Arc::ptr_eq(c, r)) => {
            let mut with = (**ctx).clone();
            with.structure.reduced = Some(Arc::clone(r));
            Arc::new(with)
        }
        _ => Arc::clone(ctx),
    }
}

/// The reduced against the full model at a fit's final parameters (module
/// [`crate::modal::reduced`]): per measured mode, its partner's frequency and vector from
/// both, and the reduced pair's residual in the full model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ReductionCheck {
    /// Basis vectors of the reduced model at the end (the enrichment included).
    pub dimension: usize,
    /// Of them, added by enrichment.
    pub enriched: usize,
    /// Per measured mode.
    pub modes: Vec<CheckedMode>,
    /// The largest |f_reduced / f_full - 1| over them.
    pub largest_frequency_difference: f64,
    /// The largest 1 - MAC(reduced, full) over them (the vectors over every DOF).
    pub largest_mac_difference: f64,
    /// The largest relative residual of a reduced pair in the full model.
    pub largest_residual: f64,
    /// Whether every frequency agrees within [`FREQUENCY_TOLERANCE`].
    pub verified: bool,
}

/// One measured mode's partner in the reduced and the full model.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CheckedMode {
    /// The measured mode.
    pub mode: usize,
    /// Its partner (1-based, rigid-body modes counted).
    pub model_mode: usize,
    /// Its frequency on the reduced model, Hz.
    pub reduced_hz: f64,
    /// On the full model, Hz.
    pub full_hz: f64,
    /// f_reduced / f_full - 1.
    pub frequency_difference: f64,
    /// 1 - MAC of the two vectors over every DOF.
    pub mac_difference: f64,
    /// The reduced pair's relative residual in the full model.
    pub residual: f64,
}

/// The check of `fitted` by one full solve of its model (one per measured mode read from a
/// model of its own); none when its pairs were not solved on a reduced model. The diagnosis's
/// last step: it first frees the nominal factor that the reduced solves kept
/// ([`reduced::release`]), so that the full model's factor is not held beside it (at half a
/// million DOFs each takes gigabytes).
pub fn check(
    fitted: &Fitted,
    measured: &MeasuredModes,
) -> Result<Option<ReductionCheck>, ModalError> {
    reduced::release(&fitted.configured.structure);
    if fitted.modal.reduced().is_none() && fitted.own.iter().all(|o| o.modal.reduced().is_none()) {
        return Ok(None);
    }
    let contributions = fitted.configured.contributions();
    let extra: Vec<(&SparseSym, &SparseSym, f64)> =
        contributions.iter().map(|(k, m)| (k, m, 1.0)).collect();
    let shared = if fitted.own.is_empty() {
        Some(reduced::full(
            &fitted.configured.structure,
            &extra,
            fitted.modal.len(),
        )?)
    } else {
        None
    };
    let mut modes = Vec::new();
    let mut dimension = (0, 0);
    for (r, m) in measured.modes().iter().enumerate() {
        let s = fitted.pairing.model_index[r];
        let modal = fitted.modal_of(r);
        let own;
        let full = match &shared {
            Some(full) => full,
            None => {
                own = reduced::full(fitted.structure_of(r), &[], modal.len())?;
                &own
            }
        };
        if let Some(pairs) = modal.reduced() {
            dimension = (pairs.reduced.dimension(), pairs.reduced.enriched);
        }
        let (fr, ff) = (modal.frequency_hz(s), full.frequency_hz(s));
        modes.push(CheckedMode {
            mode: m.mode,
            model_mode: s + 1,
            reduced_hz: fr,
            full_hz: ff,
            frequency_difference: fr / ff - 1.0,
            mac_difference: 1.0
                - mac(
                    modal.vectors().col_as_slice(s),
                    full.vectors().col_as_slice(s),
                ),
            residual: reduced::residuals(modal).get(s).copied().unwrap_or(0.0),
        });
    }
    let largest = |f: fn(&CheckedMode) -> f64| modes.iter().map(f).fold(0.0, f64::max);
    let largest_frequency_difference = largest(|c| c.frequency_difference.abs());
    Ok(Some(ReductionCheck {
        dimension: dimension.0,
        enriched: dimension.1,
        largest_frequency_difference,
        largest_mac_difference: largest(|c| c.mac_difference.abs()),
        largest_residual: largest(|c| c.residual),
        verified: largest_frequency_difference <= FREQUENCY_TOLERANCE,
        modes,
    }))
}

/// (a . b)^2 / ((a . a)(b . b)).
fn mac(a: &[f64], b: &[f64]) -> f64 {
    let dot = |x: &[f64], y: &[f64]| x.iter().zip(y).map(|(u, v)| u * v).sum::<f64>();
    let ab = dot(a, b);
    ab * ab / (dot(a, a) * dot(b, b)).max(f64::MIN_POSITIVE)
}

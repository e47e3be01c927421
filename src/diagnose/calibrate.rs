//! The first step of a diagnosis: the model checked against what a diagnosis needs, and the
//! invariant joint calibrated on every measured mode (module `fit`) with its own discrepancy
//! (module `discrepancy`).
//!
//! Pairing survives a poor starting model: a measured mode that no model mode resembles (the
//! pairing's error) is set aside and the joint calibrated on the others; with the calibrated
//! joint every mode set aside is paired again and, where it now has a partner, taken back
//! and the joint calibrated again on all of them. A mode kept that loses its partner in that
//! calibration (the joint moved by the modes taken back) is set aside in its turn; a mode
//! taken back stays ([`take_back`]). A mode that still has none is left out of the diagnosis
//! and reported with the reason. The diagnosis is refused only when fewer modes
//! remain than the joint has parameters, with the first pairing error.

use std::sync::Arc;

use super::DiagnoseError;
use super::discrepancy;
use super::fit::{self, Calibration, Discrepancy, FitError, Fitted};
use super::pairing::{PairingRule, Unpaired, pair};
use super::report::LeftOut;
use super::settings::DiagnoseSettings;
use crate::identify::Identifier;
use crate::measured::MeasuredModes;
use crate::modal::{ModalSolution, check_elastic};
use crate::model::effects::EffectContext;
use crate::optim::Silent;
use crate::structure::Structure;

/// How many of the nominal model's lowest pairs [`prepare`] solves for `measured` (rigid-body
/// modes included): those the checks, the per-mode basis and the reduced model need (all of
/// them up to the dense solver's reach, the model's size at most).
pub fn nominal_count(
    model: &Structure,
    measured: &MeasuredModes,
    settings: &DiagnoseSettings,
) -> usize {
    settings
        .per_mode
        .as_ref()
        .map_or(0, |s| s.n)
        .max(model.rigid + 1)
        .max(super::reduce::nominal_pairs(model, measured).unwrap_or(0))
        .min(model.dof_count())
}

/// The effects' context of `model` measured as `measured`, after checking that the model has
/// joint parameters to calibrate and at most as many as measured modes, an elastic nominal
/// eigensolution, and a per-mode basis (when given) that reaches every measured mode; with
/// that nominal eigensolution, which holds the pairs the reduced model is built on when one
/// applies ([`super::reduce::nominal_pairs`]), and then the factor of K - sigma M its solve
/// made ([`ModalSolution::take_factor`]): the nominal model is solved and factorised once.
/// `given`: the model's lowest pairs solved already (the check of an external model's
/// rigid-body modes, [`crate::model::from_path_solved`], with its factor), taken when it holds
/// [`nominal_count`] of them: the same pairs, not solved twice.
pub fn prepare(
    model: &Structure,
    measured: &MeasuredModes,
    settings: &DiagnoseSettings,
    given: Option<ModalSolution>,
) -> Result<(Arc<EffectContext>, ModalSolution), DiagnoseError> {
    let rigid = model.rigid;
    let joint_parameters = model.identified().len();
    if joint_parameters == 0 {
        return Err(DiagnoseError::NoParameters);
    }
    if measured.modes().len() < joint_parameters {
        return Err(DiagnoseError::TooFewModes {
            modes: measured.modes().len(),
            parameters: joint_parameters,
        });
    }
    let matrices = model.assemble();
    let wanted = nominal_count(model, measured, settings);
    // Where a reduced model will be built on these pairs, the solve keeps its factor for it.
    let nominal = match given.filter(|n| n.len() == wanted) {
        Some(given) => given,
        None if super::reduce::nominal_pairs(model, measured).is_some() => {
            ModalSolution::lowest_of_factored(&matrices, wanted)?
        }
        None => ModalSolution::lowest_of(&matrices, wanted)?,
    };
    check_elastic(&matrices, &nominal, rigid)?;
    if let Some(per_mode) = settings.per_mode {
        let identifier = Identifier::for_structure(model, &nominal, per_mode)?;
        let highest = measured.modes().iter().map(|m| m.mode).max().unwrap_or(1);
        identifier.basis_index(highest)?;
    }
    let ctx = Arc::new(EffectContext::new(
        model.clone(),
        &measured.points(),
        nominal.frequency_hz(rigid),
    ));
    Ok((ctx, nominal))
}

/// The model as given and the invariant joint calibrated, on the modes kept.
#[derive(Debug, Clone)]
pub struct Calibrated {
    /// The measured modes the diagnosis keeps.
    pub measured: MeasuredModes,
    /// The modes left out: no model mode resembles them.
    pub left_out: Vec<LeftOut>,
    /// The model as given, only the shape scales fitted (under the measurement error).
    pub initial: Fitted,
    /// The joint calibrated on every mode kept, no effect, with its own discrepancy.
    pub base: Fitted,
}

/// The joint of `ctx` calibrated on `measured` under the measurement error `calibration`
/// (module docs: modes without a partner set aside, paired again, left out); refused when
/// its chi^2 under the measurement error ends above the model as given's beyond round-off
/// (the pairing changed on the way).
pub fn calibrate(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> Result<Calibrated, DiagnoseError> {
    let joints = ctx.structure.identified().len();
    let mut kept = measured.clone();
    let mut aside: Vec<LeftOut> = Vec::new();
    let measurement = Calibration {
        discrepancy: Discrepancy::default(),
        ..calibration.clone()
    };
    let (initial, base) = loop {
        let fitted = fit::as_given(ctx, &kept, &measurement).and_then(|initial| {
            let start = discrepancy::estimate(&initial, &kept, &measurement);
            Ok((initial, joint_only(ctx, &kept, calibration, start, None)?))
        });
        match fitted {
            Ok(both) => break both,
            Err(FitError::Unpaired(e)) => {
                let Some(left) = set_aside(&e) else {
                    return Err(FitError::Unpaired(e).into());
                };
                // Setting it aside would leave fewer modes than the joint has parameters.
                if kept.modes().len() <= joints.max(1) {
                    return Err(FitError::Unpaired(e).into());
                }
                kept = without(&kept, left.mode);
                aside.push(left);
            }
            Err(e) => return Err(e.into()),
        }
    };
    let (measured, initial, base) = take_back(
        ctx,
        measured,
        calibration,
        (kept, initial, base),
        &mut aside,
    );
    let left_out = aside
        .into_iter()
        .filter(|left| measured.get(left.mode).is_none())
        .collect();
    // Growth beyond round-off (relative, and absolute for data the model fits exactly) of the
    // deviance, each with its own discrepancy: the calibration can only lower it unless the
    // pairing changed on the way.
    let given = discrepancy::profile_deviance(&initial, &measured, &measurement);
    if base.deviance > given + 1e-9 * given.abs() + 1e-9 * base.dof as f64 {
        return Err(DiagnoseError::ErrorGrew {
            before: given,
            after: base.deviance,
        });
    }
    // The model as given with the discrepancy of its residuals, for the report.
    let initial = Fitted {
        discrepancy: discrepancy::estimate(&initial, &measured, &measurement),
        deviance: given,
        ..initial
    };
    Ok(Calibrated {
        measured,
        left_out,
        initial,
        base,
    })
}

/// The modes set aside taken back where the calibrated joint pairs them (module docs), from
/// `calibrated` (the modes kept, the model as given and the joint calibrated on them): each
/// mode set aside is paired again with the calibrated joint and, where it has a partner, taken
/// back and the joint calibrated again on all. A mode kept that loses its partner on the way
/// (the joint moved by the modes taken back) is set aside in its turn, into `aside`, and may
/// come back in a later round. A mode comes back at most once and is not set aside again:
/// where the calibration fails otherwise, the last one stands. Every round takes at least one
/// mode back, so there are at most as many rounds as modes.
fn take_back(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    calibrated: (MeasuredModes, Fitted, Fitted),
    aside: &mut Vec<LeftOut>,
) -> (MeasuredModes, Fitted, Fitted) {
    let (mut kept, mut initial, mut base) = calibrated;
    let joints = ctx.structure.identified().len();
    let mut returned: Vec<usize> = Vec::new();
    loop {
        let back: Vec<usize> = aside
            .iter()
            .map(|left| left.mode)
            .filter(|mode| !returned.contains(mode) && kept.get(*mode).is_none())
            .filter(|&mode| {
                let trial = with(&kept, measured, mode);
                pair(
                    &base.modal,
                    &trial,
                    ctx.structure.rigid,
                    &calibration.pairing,
                )
                .is_ok()
            })
            .collect();
        if back.is_empty() {
            return (kept, initial, base);
        }
        returned.extend(&back);
        let mut all = back
            .iter()
            .fold(kept.clone(), |m, &r| with(&m, measured, r));
        let mut dropped = Vec::new();
        let refitted = loop {
            match again(ctx, &all, calibration, &base) {
                Ok(fits) => break Some(fits),
                Err(FitError::Unpaired(e)) => match set_aside(&e) {
                    Some(left)
                        if !returned.contains(&left.mode) && all.modes().len() > joints.max(1) =>
                    {
                        all = without(&all, left.mode);
                        dropped.push(left);
                    }
                    _ => break None,
                },
                Err(_) => break None,
            }
        };
        let Some((again_initial, again_base)) = refitted else {
            return (kept, initial, base);
        };
        (kept, initial, base) = (all, again_initial, again_base);
        aside.extend(dropped);
    }
}

/// The measured mode a pairing error `e` leaves without a partner, with the reason, where the
/// error is that one (not a pair given that does not exist).
fn set_aside(e: &Unpaired) -> Option<LeftOut> {
    match e {
        Unpaired::NoPartner {
            mode, frequency_hz, ..
        } => Some(LeftOut {
            mode: *mode,
            frequency_hz: *frequency_hz,
            reason: e.to_string(),
        }),
        _ => None,
    }
}

/// The model as given and the joint calibrated again on `all`, the modes kept with those taken
/// back, from the joint of `base`: the model as given cannot pair the modes taken back, so it
/// is read with the pairs the calibrated joint gives.
fn again(
    ctx: &Arc<EffectContext>,
    all: &MeasuredModes,
    calibration: &Calibration,
    base: &Fitted,
) -> Result<(Fitted, Fitted), FitError> {
    let rigid = ctx.structure.rigid;
    let pairs = pair(&base.modal, all, rigid, &calibration.pairing)?;
    let read = Calibration {
        discrepancy: Discrepancy::default(),
        pairing: PairingRule {
            given: all
                .modes()
                .iter()
                .zip(&pairs.model_index)
                .map(|(m, &s)| (m.mode, s + 1 - rigid))
                .collect(),
            ..calibration.pairing.clone()
        },
        ..calibration.clone()
    };
    let measurement = Calibration {
        discrepancy: Discrepancy::default(),
        ..calibration.clone()
    };
    let initial = fit::as_given(ctx, all, &read)?;
    let start = discrepancy::estimate(&initial, all, &measurement);
    let joints = ctx.structure.identified().len();
    let base = joint_only(ctx, all, calibration, start, Some(&base.solution[..joints]))?;
    Ok((initial, base))
}

/// The joint-only fit of `measured` with its own discrepancy (from `start`), from the nominal
/// joint or the joint unknowns `joint_start`.
fn joint_only(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    start: Discrepancy,
    joint_start: Option<&[f64]>,
) -> Result<Fitted, FitError> {
    discrepancy::fit_with(measured, calibration, start, |cal, from| {
        match (from, joint_start) {
            (Some(from), _) => fit::refit(ctx, measured, cal, &[], from, &mut Silent),
            (None, Some(x0)) => fit::fit_from(ctx, measured, cal, &[], x0, &mut Silent),
            (None, None) => fit::fit(ctx, measured, cal, &[], &mut Silent),
        }
    })
}

/// `measured` without mode `mode`.
fn without(measured: &MeasuredModes, mode: usize) -> MeasuredModes {
    MeasuredModes::new(
        measured
            .modes()
            .iter()
            .filter(|m| m.mode != mode)
            .cloned()
            .collect(),
    )
}

/// `kept` with mode `mode` of `all` taken back.
fn with(kept: &MeasuredModes, all: &MeasuredModes, mode: usize) -> MeasuredModes {
    let mut modes = kept.modes().to_vec();
    modes.extend(all.modes().iter().filter(|m| m.mode == mode).cloned());
    MeasuredModes::new(modes)
}

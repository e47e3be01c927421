//! The first step of a diagnosis: the model checked against what a diagnosis needs, and the
//! invariant joint calibrated on every measured mode (module `fit`).

use std::sync::Arc;

use super::DiagnoseError;
use super::fit::{self, Calibration, Fitted};
use super::settings::DiagnoseSettings;
use crate::identify::Identifier;
use crate::measured::MeasuredModes;
use crate::modal::{ModalSolution, check_elastic};
use crate::model::effects::EffectContext;
use crate::optim::Silent;
use crate::structure::Structure;

/// The effects' context of `model` measured as `measured`, after checking that the model has
/// joint parameters to calibrate and at most as many as measured modes, an elastic nominal
/// eigensolution, and a per-mode basis (when given) that reaches every measured mode.
pub fn prepare(
    model: &Structure,
    measured: &MeasuredModes,
    settings: &DiagnoseSettings,
) -> Result<Arc<EffectContext>, DiagnoseError> {
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
    // The lowest pairs the checks and the per-mode basis need (all of them up to
    // DENSE_MAX_DOFS).
    let wanted = settings
        .per_mode
        .as_ref()
        .map_or(0, |s| s.n)
        .max(rigid + 1)
        .min(matrices.size());
    let nominal = ModalSolution::lowest_of(&matrices, wanted)?;
    check_elastic(&matrices, &nominal, rigid)?;
    if let Some(per_mode) = settings.per_mode {
        let identifier = Identifier::for_structure(model, &nominal, per_mode)?;
        let highest = measured.modes().iter().map(|m| m.mode).max().unwrap_or(1);
        identifier.basis_index(highest)?;
    }
    Ok(Arc::new(EffectContext::new(
        model.clone(),
        &measured.points(),
        nominal.frequency_hz(rigid),
    )))
}

/// The model as given and the invariant joint calibrated, under one calibration.
#[derive(Debug, Clone)]
pub struct Calibrated {
    /// The model as given, only the shape scales fitted.
    pub initial: Fitted,
    /// The joint calibrated on every mode, no effect.
    pub base: Fitted,
}

/// The joint calibrated under `calibration`, starting from `from` (an optimum of the same
/// model under another calibration), or `done`, that calibration made already; refused when
/// its chi^2 ends above the model as given's beyond round-off (the pairing changed on the
/// way).
pub fn calibrate(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    from: &Fitted,
    done: Option<Fitted>,
) -> Result<Calibrated, DiagnoseError> {
    let initial = fit::as_given(ctx, measured, calibration)?;
    let base = match done {
        Some(base) => base,
        None => fit::refit(ctx, measured, calibration, &[], from, &mut Silent)?,
    };
    // Growth beyond round-off (relative, and absolute for data the model fits exactly).
    if base.chi2 > initial.chi2 * (1.0 + 1e-9) + 1e-9 * base.dof as f64 {
        return Err(DiagnoseError::ErrorGrew {
            before: initial.chi2,
            after: base.chi2,
        });
    }
    Ok(Calibrated { initial, base })
}

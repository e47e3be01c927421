//! Any effect of the model library as a candidate: its parameters fitted with the joints'
//! (module `fit`) and its own discrepancy (module `discrepancy`), the size and its standard
//! error, and whether the fitted size is physical.

use std::sync::Arc;

use super::{Candidate, CandidateError, Fit, Part, Stage, Tier, implausible};
use crate::diagnose::discrepancy;
use crate::diagnose::fit::{self, Calibration, Estimate, Fitted};
use crate::diagnose::progress::Iterations;
use crate::model::effects::{Effect, EffectContext};

/// An [`Effect`] as a candidate.
#[derive(Debug, Clone)]
pub struct EffectCandidate {
    effect: Arc<dyn Effect>,
}

impl EffectCandidate {
    /// The candidate of `effect`.
    pub fn new(effect: Arc<dyn Effect>) -> Self {
        Self { effect }
    }
}

impl Candidate for EffectCandidate {
    fn name(&self) -> &'static str {
        self.effect.name()
    }

    fn tier(&self) -> Tier {
        self.effect.tier()
    }

    fn describe(&self) -> &'static str {
        self.effect.describe()
    }

    fn applies(&self, ctx: &EffectContext) -> bool {
        self.effect.applies(ctx)
    }

    fn part(&self) -> Option<Part> {
        Some(Part::Effect(self.effect.clone()))
    }

    fn fit(&self, stage: &Stage) -> Result<Fit, CandidateError> {
        fit_effect(&self.effect, stage, true)
    }
}

/// `effect` fitted with the joints on `stage` from the joint-only optimum (the effect at
/// zero), with its own discrepancy when `own_discrepancy` (else under the joint-only fit's:
/// the members of a scan, ranked on one error model).
pub(super) fn fit_effect(
    effect: &Arc<dyn Effect>,
    stage: &Stage,
    own_discrepancy: bool,
) -> Result<Fit, CandidateError> {
    let effects = std::slice::from_ref(effect);
    let (ctx, measured) = (stage.ctx, stage.measured);
    let mut told = Iterations {
        watch: stage.watch,
        candidate: effect.name(),
        variant: None,
    };
    let x0 = fit::extended(stage.base, effect.parameters(ctx).len());
    let fitted = if own_discrepancy {
        discrepancy::fit_with(
            measured,
            stage.calibration,
            stage.start(),
            |cal, from| match from {
                Some(from) => fit::refit(ctx, measured, cal, effects, from, &mut told),
                // From the joint-only optimum, or, where the solver does not settle from there
                // (a valley along a bound), from the nominal joint.
                None => fit::fit_from(ctx, measured, cal, effects, &x0, &mut told)
                    .or_else(|_| fit::fit(ctx, measured, cal, effects, &mut told)),
            },
        )?
    } else {
        let calibration = Calibration {
            discrepancy: stage.start(),
            ..stage.calibration.clone()
        };
        fit::fit_from(ctx, measured, &calibration, effects, &x0, &mut told)?
    };
    let joints = stage.base.estimates.len();
    let parameters = fitted.estimates[joints..].to_vec();
    let (size, excluded) = judged(effect.as_ref(), ctx, &fitted, &parameters);
    let mut fit = Fit::of_model(
        measured,
        fitted,
        parameters,
        size,
        effect.describe().to_string(),
        effect.parameters(ctx).len(),
        excluded,
    );
    fit.bounded = bounded(effect.as_ref(), ctx);
    Ok(fit)
}

/// Whether every parameter of `effect` is held non-negative: its zero, the model without it,
/// is on the edge of its range.
pub(super) fn bounded(effect: &dyn Effect, ctx: &EffectContext) -> bool {
    let parameters = effect.parameters(ctx);
    !parameters.is_empty() && parameters.iter().all(|p| p.non_negative)
}

/// The size of `effect` at its fitted `parameters` in `fitted` (the size's standard error by
/// linear propagation of theirs), and why it is not physical if it is not.
pub(super) fn judged(
    effect: &dyn Effect,
    ctx: &EffectContext,
    fitted: &Fitted,
    parameters: &[Estimate],
) -> ((f64, f64), Option<String>) {
    let theta: Vec<f64> = parameters.iter().map(|e| e.value).collect();
    let size = effect.size_of_theta(ctx, &theta);
    let size_se = parameters
        .iter()
        .enumerate()
        .map(|(i, e)| {
            let h = 1e-6 * e.value.abs().max(e.se).max(f64::MIN_POSITIVE);
            let mut t = theta.clone();
            t[i] += h;
            ((effect.size_of_theta(ctx, &t) - size) / h * e.se).powi(2)
        })
        .sum::<f64>()
        .sqrt();
    let excluded = implausible(effect, ctx, fitted, &theta);
    ((size, size_se), excluded)
}

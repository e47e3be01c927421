//! Any effect of the model library as a candidate: its parameters fitted with the joints'
//! (module `fit`), the likelihood-ratio statistic against the joint-only fit, the size and its
//! standard error, and whether the fitted size is physical.

use std::sync::Arc;

use super::{Candidate, CandidateError, Fit, Stage, Tier, implausible};
use crate::diagnose::fit::{self, Fitted};
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

    fn fit(&self, stage: &Stage, earlier: Option<&Fit>) -> Result<Fit, CandidateError> {
        fit_effect(&self.effect, stage, earlier.and_then(|e| e.model.as_ref()))
    }
}

/// `effect` fitted with the joints on `stage`, from the optimum `from` of an earlier stage
/// when given.
pub(super) fn fit_effect(
    effect: &Arc<dyn Effect>,
    stage: &Stage,
    from: Option<&Fitted>,
) -> Result<Fit, CandidateError> {
    let effects = std::slice::from_ref(effect);
    let (ctx, measured, calibration) = (stage.ctx, stage.measured, stage.calibration);
    let mut told = Iterations {
        watch: stage.watch,
        candidate: effect.name(),
        variant: None,
    };
    let fitted = match from {
        Some(from) => fit::refit(ctx, measured, calibration, effects, from, &mut told)?,
        None => fit::fit(ctx, measured, calibration, effects, &mut told)?,
    };
    let joints = stage.base.estimates.len();
    let parameters = fitted.estimates[joints..].to_vec();
    let theta: Vec<f64> = parameters.iter().map(|e| e.value).collect();
    let size = effect.size_of_theta(ctx, &theta);
    // Linear propagation of the parameters' standard errors to the size.
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
    let excluded = implausible(effect.as_ref(), ctx, &fitted, &theta);
    let added = parameters.len();
    let describe = effect.describe().to_string();
    Ok(Fit::of_model(
        stage,
        fitted,
        parameters,
        (size, size_se),
        describe,
        added,
        excluded,
    ))
}

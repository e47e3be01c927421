//! The candidate explanations a diagnosis tries, behind one trait.
//!
//! A [`Candidate`] is fitted on a [`Stage`] (the data, the effects' context, a calibration and
//! the joint-only fit under it) and returns a [`Fit`]: its parameters, its chi^2, the
//! likelihood-ratio statistic against the joint-only fit, its residuals and, when it has one,
//! the refitted model that becomes the diagnosis's "after". Four kinds implement it:
//! - [`EffectCandidate`]: any [`Effect`] of the model library, fitted with the joints;
//! - [`FrequencyDependence`]: the paper's frequency-dependent joint, every mode solved with
//!   the joint at its own frequency;
//! - [`Scan`]: a family of effects indexed by a coordinate (a position along the beams, the
//!   length of a joint region), each member fitted, the best kept, with the profile of chi^2
//!   along the coordinate.
//!
//! [`registry`] lists every candidate once, in report order, each with its [`Tier`]: the
//! default library, the `--extended` one. A candidate is registered by one line there (an
//! effect by its line in [`crate::model::effects::registry`]).
//!
//! Layer: diagnose; imports the model (effects), measured data, modal solutions and the
//! diagnosis's own fit, never output.

mod effect;
pub mod frequency_dependence;
mod layered_lap;
mod scan;

use std::sync::Arc;

use serde::Serialize;

pub use effect::EffectCandidate;
pub use frequency_dependence::FrequencyDependence;
pub use layered_lap::LayeredLap;
pub use scan::Scan;

use super::fit::{Calibration, Estimate, FitError, Fitted, Residuals};
use super::noise::NoiseEstimate;
use super::progress::{Step, Watch};
use super::report::Verdict;
use crate::measured::MeasuredModes;
pub use crate::model::effects::Tier;
use crate::model::effects::{self, Effect, EffectContext};

/// What a candidate is fitted against: one stage of the diagnosis (under the stated noise
/// first, to estimate the noise; then under the working noise, to select).
#[derive(Debug, Clone, Copy)]
pub struct Stage<'a> {
    /// The nominal structure and the sensors.
    pub ctx: &'a Arc<EffectContext>,
    /// The measured modes.
    pub measured: &'a MeasuredModes,
    /// The noise and the pairing of the stage.
    pub calibration: &'a Calibration,
    /// The joint-only fit under that calibration: the model every candidate extends.
    pub base: &'a Fitted,
    /// The noise estimate whose working noise the calibration holds, when it does (None:
    /// the stated noise, taken as known).
    pub estimate: Option<&'a NoiseEstimate>,
    /// Where the steps of the fits go.
    pub watch: Watch<'a>,
}

impl Stage<'_> {
    /// P-value of a likelihood-ratio statistic `lrt` of `k` more unknowns on this stage: F
    /// under an estimated noise scale, chi-square under a known one (the selection's test).
    pub fn lrt_p_value(&self, lrt: f64, k: usize) -> f64 {
        match self.estimate {
            Some(e) => e.lrt_p_value(lrt, k),
            None => crate::stats::chi2_sf(lrt, k.max(1) as f64),
        }
    }
}

/// A candidate fitted on a stage.
#[derive(Debug, Clone)]
pub struct Fit {
    /// The candidate's own parameters (the joints' are in the model), with standard errors.
    pub parameters: Vec<Estimate>,
    /// Its size in the unit of its description, and the standard error of the size.
    pub size: (f64, f64),
    /// What the candidate is and what its size means.
    pub describe: String,
    /// chi^2 of the model with the candidate.
    pub chi2: f64,
    /// Its degrees of freedom.
    pub dof: usize,
    /// The likelihood-ratio statistic chi^2(joint only) - chi^2(with the candidate), >= 0.
    pub lrt: f64,
    /// Unknowns the candidate adds to the joint-only fit: the degrees of freedom of the
    /// likelihood-ratio test.
    pub added: usize,
    /// The model's unknowns besides the shape scales (joints and candidate): the lack of fit
    /// of the frequencies discounts them.
    pub unknowns: usize,
    /// The unweighted residuals of the model with the candidate.
    pub residuals: Residuals,
    /// The refitted model, for a candidate that has one (the "after" of an `effect` verdict).
    pub model: Option<Fitted>,
    /// Why the fitted size is not a physical explanation, if it is not.
    pub excluded: Option<String>,
    /// A scan's chi^2 along its coordinate.
    pub profile: Option<super::report::Profile>,
    /// A scan's member optima (None where a member failed): the starts of its refits on the
    /// next stage.
    pub members: Vec<Option<Fitted>>,
}

impl Fit {
    /// The fit of a candidate whose refitted model is `fitted` on `stage`: its chi^2, degrees
    /// of freedom, likelihood-ratio statistic against the joint-only fit and residuals, with
    /// its own `parameters`, `size` (value, standard error), description, `added` unknowns and
    /// reason for exclusion; no profile, no members.
    pub(crate) fn of_model(
        stage: &Stage,
        fitted: Fitted,
        parameters: Vec<Estimate>,
        size: (f64, f64),
        describe: String,
        added: usize,
        excluded: Option<String>,
    ) -> Fit {
        Fit {
            size,
            describe,
            chi2: fitted.chi2,
            dof: fitted.dof,
            lrt: (stage.base.chi2 - fitted.chi2).max(0.0),
            added,
            unknowns: fitted.estimates.len(),
            residuals: super::fit::residuals(&fitted, stage.measured),
            excluded,
            parameters,
            model: Some(fitted),
            profile: None,
            members: Vec::new(),
        }
    }
}

/// Why a candidate could not be fitted.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum CandidateError {
    /// Its nonlinear least squares failed.
    #[error(transparent)]
    Fit(#[from] FitError),
    /// The data do not determine it.
    #[error("{0}")]
    Undetermined(String),
}

/// A candidate explanation of what the calibrated joint leaves (see the module docs).
pub trait Candidate: Send + Sync + std::fmt::Debug {
    /// Name in reports and on the command line.
    fn name(&self) -> &'static str;

    /// Whether the default library or `--extended` searches it.
    fn tier(&self) -> Tier;

    /// What the candidate is and what its size means.
    fn describe(&self) -> &'static str;

    /// Hypotheses it tests at once, for the multiple-testing count of the selection: 1, or
    /// the members of a scan (the best of N positions is the largest of N statistics).
    fn hypotheses(&self, _ctx: &EffectContext) -> usize {
        1
    }

    /// Whether it can act on this structure.
    fn applies(&self, ctx: &EffectContext) -> bool;

    /// The verdict that names it when it is selected alone.
    fn verdict(&self) -> Verdict {
        Verdict::Effect
    }

    /// Fits it on `stage`, from `earlier` (its fit on the previous stage) when given.
    fn fit(&self, stage: &Stage, earlier: Option<&Fit>) -> Result<Fit, CandidateError>;
}

/// A candidate with the outcome of its fit on a stage.
pub type Tried = (Arc<dyn Candidate>, Result<Fit, CandidateError>);

/// The hypotheses a search of `library` on `ctx` tests: the multiple-testing count.
pub fn hypotheses(library: &[Arc<dyn Candidate>], ctx: &EffectContext) -> usize {
    library.iter().map(|c| c.hypotheses(ctx)).sum()
}

/// Every candidate, in report order: the registered effects of the default and extended
/// tiers, the frequency-dependent joint, the scans.
pub fn registry() -> Vec<Arc<dyn Candidate>> {
    let library = effects::registry()
        .into_iter()
        .filter(|e| e.tier() != Tier::Outside)
        .map(|e| Arc::new(EffectCandidate::new(e)) as Arc<dyn Candidate>);
    library
        .chain([
            Arc::new(FrequencyDependence) as Arc<dyn Candidate>,
            Arc::new(LayeredLap),
            Arc::new(scan::joint_region()),
            Arc::new(scan::local_stiffness()),
        ])
        .collect()
}

/// The candidates a diagnosis of `ctx` tries: the default tier, and the extended one when
/// `extended`, that apply to the structure; in report order.
pub fn library(ctx: &EffectContext, extended: bool) -> Vec<Arc<dyn Candidate>> {
    registry()
        .into_iter()
        .filter(|c| c.tier() == Tier::Default || (extended && c.tier() == Tier::Extended))
        .filter(|c| c.applies(ctx))
        .collect()
}

/// One row of the catalogue of everything a user can name: a candidate of the diagnosis, an
/// effect simulate can put into data, or both.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Entry {
    /// Name.
    pub name: &'static str,
    /// The diagnosis's tier (`outside` for an effect no diagnosis searches).
    pub tier: Tier,
    /// Whether `jointid simulate --effect` accepts it.
    pub simulate: bool,
    /// What it is and what its size means.
    pub describe: &'static str,
}

/// Every candidate and every effect, in registry order (the candidates, then the effects
/// outside the library, then `extra`, simulate's names that are not effects).
pub fn catalogue(extra: &[(&'static str, &'static str)]) -> Vec<Entry> {
    let simulated: Vec<&'static str> = effects::registry().iter().map(|e| e.name()).collect();
    let candidates = registry().into_iter().map(|c| Entry {
        name: c.name(),
        tier: c.tier(),
        simulate: simulated.contains(&c.name()),
        describe: c.describe(),
    });
    let outside = effects::of_tier(Tier::Outside).into_iter().map(|e| Entry {
        name: e.name(),
        tier: Tier::Outside,
        simulate: true,
        describe: e.describe(),
    });
    let extra = extra.iter().map(|&(name, describe)| Entry {
        name,
        tier: Tier::Outside,
        simulate: true,
        describe,
    });
    candidates.chain(outside).chain(extra).collect()
}

/// Fits every candidate of `library` on `stage` (in parallel), each from its fit in
/// `earlier` when that succeeded, but for the one `done` gives (its index, its fit on this
/// stage, made already), taken as it is; each fit told to the stage's watch as it finishes.
pub fn fit_all(
    library: &[Arc<dyn Candidate>],
    stage: &Stage,
    earlier: Option<&[Tried]>,
    done: Option<(usize, &Fit)>,
) -> Vec<Tried> {
    use rayon::prelude::*;
    library
        .par_iter()
        .enumerate()
        .map(|(i, c)| {
            let from = earlier.and_then(|e| e[i].1.as_ref().ok());
            let fit = match done {
                Some((j, fit)) if j == i => Ok(fit.clone()),
                _ => c.fit(stage, from),
            };
            tell_fitted(&stage.watch, c.as_ref(), &fit);
            (c.clone(), fit)
        })
        .collect()
}

/// Tells `watch` that `candidate` was fitted: `fit`'s chi^2, or why it has none.
pub(crate) fn tell_fitted(
    watch: &Watch,
    candidate: &dyn Candidate,
    fit: &Result<Fit, CandidateError>,
) {
    watch.tell(&Step::Fitted {
        candidate: candidate.name(),
        outcome: match fit {
            Ok(f) => Ok(f.chi2),
            Err(e) => Err(e),
        },
    });
}

/// Why the fitted theta of `effect` is not a physical explanation, if it is not: a negative
/// value of a non-negative parameter, a theta the calibrated structure does not admit, a size
/// outside the effect's plausible range.
pub fn implausible(
    effect: &dyn Effect,
    ctx: &EffectContext,
    fitted: &Fitted,
    theta: &[f64],
) -> Option<String> {
    let negative = effect
        .parameters(ctx)
        .iter()
        .zip(theta)
        .find(|(p, t)| p.non_negative && **t < 0.0)
        .map(|(p, t)| format!("{} = {t:.4e} {} is negative", p.name, p.unit));
    negative
        .or_else(|| {
            effect
                .admissible(ctx, &fitted.configured.structure, theta)
                .err()
        })
        .or_else(|| effect.plausible(ctx, theta).err())
}

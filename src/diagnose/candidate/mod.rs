//! The candidate explanations a diagnosis tries, behind one trait.
//!
//! A [`Candidate`] is fitted on a [`Stage`] (the data, the effects' context, the measurement
//! error and the joint-only fit) once, with its own model discrepancy (module
//! `discrepancy`), and returns a [`Fit`]: its parameters, its deviance under its error model,
//! its residuals and, when it has one, the fitted model that becomes the diagnosis's "after".
//! Four kinds implement it:
//! - [`EffectCandidate`]: any [`Effect`] of the model library, fitted with the joints;
//! - [`FrequencyDependence`]: the paper's frequency-dependent joint, every mode solved with
//!   the joint at its own frequency;
//! - [`LayeredLap`]: the point joints whose overlap the model gives replaced by the lap;
//! - [`Scan`]: a family of effects indexed by a coordinate (a position along the beams, the
//!   length of a joint region), each member fitted, the best kept, with the profile of its
//!   deviance along the coordinate.
//!
//! Effects and the layered lap also combine ([`Candidate::part`], module `combined`): the
//! search adds causes one after another (module `search`).
//!
//! [`registry`] lists every candidate once, in report order, each with its [`Tier`]: the
//! default library, the `--extended` one. A candidate is registered by one line there (an
//! effect by its line in [`crate::model::effects::registry`]).
//!
//! Layer: diagnose; imports the model (effects), measured data, modal solutions and the
//! diagnosis's own fit, never output.

mod combined;
mod effect;
pub mod frequency_dependence;
mod layered_lap;
mod scan;

use std::sync::Arc;

use serde::Serialize;

pub use combined::{Part, combine};
pub use effect::EffectCandidate;
pub use frequency_dependence::FrequencyDependence;
pub use layered_lap::LayeredLap;
pub use scan::Scan;

use super::fit::{Calibration, Discrepancy, Estimate, FitError, Fitted, Residuals};
use super::progress::{Step, Watch};
use super::report::Verdict;
use crate::measured::MeasuredModes;
pub use crate::model::effects::Tier;
use crate::model::effects::{self, Effect, EffectContext};

/// What a candidate is fitted against.
#[derive(Debug, Clone, Copy)]
pub struct Stage<'a> {
    /// The nominal structure and the sensors.
    pub ctx: &'a Arc<EffectContext>,
    /// The measured modes.
    pub measured: &'a MeasuredModes,
    /// The measurement error and the pairing (no discrepancy: each fit estimates its own).
    pub calibration: &'a Calibration,
    /// The joint-only fit: the model every candidate extends, and its discrepancy the start
    /// of theirs.
    pub base: &'a Fitted,
    /// Where the steps of the fits go.
    pub watch: Watch<'a>,
}

impl Stage<'_> {
    /// The discrepancy a candidate's fit starts from: the joint-only fit's.
    pub fn start(&self) -> Discrepancy {
        self.base.discrepancy.clone()
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
    /// The deviance of the model with the candidate under its own error model (module
    /// `discrepancy`).
    pub deviance: f64,
    /// The discrepancy estimated with it.
    pub discrepancy: Discrepancy,
    /// Its degrees of freedom (data less unknowns).
    pub dof: usize,
    /// Unknowns the candidate adds to the model it extends: the degrees of freedom of the
    /// likelihood-ratio test.
    pub added: usize,
    /// The model's unknowns besides the shape scales (joints and candidate): the lack of fit
    /// of the frequencies discounts them.
    pub unknowns: usize,
    /// Whether every unknown it adds is held non-negative and is zero in the model it extends
    /// (a mass, a spring, an Euler-Bernoulli beam's shear flexibility): its likelihood-ratio
    /// test is then one-sided ([`crate::stats::lr_sf`]).
    pub bounded: bool,
    /// The unweighted residuals of the model with the candidate.
    pub residuals: Residuals,
    /// The fitted model, for a candidate that has one (the "after" when it is selected).
    pub model: Option<Fitted>,
    /// Why the fitted size is not a physical explanation, if it is not.
    pub excluded: Option<String>,
    /// A scan's deviance along its coordinate.
    pub profile: Option<super::report::Profile>,
}

impl Fit {
    /// The fit of a candidate whose fitted model is `fitted`: its deviance, discrepancy,
    /// degrees of freedom and residuals on `measured`, with its own `parameters`, `size`
    /// (value, standard error), description, `added` unknowns and reason for exclusion; no
    /// profile.
    pub(crate) fn of_model(
        measured: &MeasuredModes,
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
            deviance: fitted.deviance,
            discrepancy: fitted.discrepancy.clone(),
            dof: fitted.dof,
            added,
            unknowns: fitted.estimates.len(),
            bounded: false,
            residuals: super::fit::residuals(&fitted, measured),
            excluded,
            parameters,
            model: Some(fitted),
            profile: None,
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

    /// What it adds to a model that another cause extends, when it combines with others
    /// (module `combined`); None: it stands alone.
    fn part(&self) -> Option<Part> {
        None
    }

    /// Fits it on `stage`, with its own discrepancy.
    fn fit(&self, stage: &Stage) -> Result<Fit, CandidateError>;
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

/// Fits every candidate of `library` on `stage` (in parallel), each told to the stage's watch
/// as it finishes.
pub fn fit_all(library: &[Arc<dyn Candidate>], stage: &Stage) -> Vec<Tried> {
    use rayon::prelude::*;
    library
        .par_iter()
        .map(|c| {
            let fit = c.fit(stage);
            tell_fitted(&stage.watch, c.name(), &fit);
            (c.clone(), fit)
        })
        .collect()
}

/// Tells `watch` that `candidate` was fitted: `fit`'s chi^2, or why it has none.
pub(crate) fn tell_fitted(watch: &Watch, name: &str, fit: &Result<Fit, CandidateError>) {
    watch.tell(&Step::Fitted {
        candidate: name,
        outcome: match fit {
            Ok(f) => Ok(f.deviance),
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

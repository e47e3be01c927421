//! Causes together: a model that extends another by one more cause, as the search adds them
//! one after another (module `search`). Lap and shear together is the common case of a real
//! lapped specimen modelled with Euler-Bernoulli beams.
//!
//! The parts that combine are the effects of the library (each its own parameters beside the
//! others') and the layered lap (the structure whose joints it replaces, on which the effects
//! then act). A combination is fitted once, with its own discrepancy (module `discrepancy`),
//! from the optimum of the model it extends with the new cause at zero; a lap added to
//! effects starts from the lap's own fit, the effects at their values in the model extended.
//! Its size and parameters are the added cause's; it is excluded when any of its causes' sizes
//! is not physical (module `effect`'s rules, the lap's axial pairing).

use std::sync::Arc;

use super::effect::{bounded, judged};
use super::layered_lap::{axial_pair, summary};
use super::{CandidateError, Fit, Stage};
use crate::diagnose::discrepancy;
use crate::diagnose::fit::{self, Fitted};
use crate::diagnose::progress::Iterations;
use crate::model::effects::Effect;

/// What a candidate adds when it combines with others.
#[derive(Debug, Clone)]
pub enum Part {
    /// An effect of the library, fitted beside the others.
    Effect(Arc<dyn Effect>),
    /// The layered lap in place of the point joints it replaces.
    Lap,
}

/// The model `from` (the fit of the causes so far; whether it holds the lap is its own) with
/// `added` fitted beside, named `name`. `lap` is the layered lap's own fit, the start of a
/// lap added to effects.
pub fn combine(
    stage: &Stage,
    from: &Fitted,
    added: &Part,
    lap: Option<&Fitted>,
    name: &str,
) -> Result<Fit, CandidateError> {
    let measured = stage.measured;
    let effects_before: Vec<Arc<dyn Effect>> = from
        .configured
        .effects
        .iter()
        .map(|(e, _)| e.clone())
        .collect();
    let (ctx, effects, x0) = match added {
        Part::Effect(effect) => {
            let ctx = from.configured.ctx.clone();
            let k = effect.parameters(&ctx).len();
            let mut effects = effects_before;
            effects.push(effect.clone());
            (ctx, effects, fit::extended(from, k))
        }
        Part::Lap => {
            let lap = lap.ok_or_else(|| {
                CandidateError::Undetermined("the layered lap has no fit of its own".into())
            })?;
            let joints_lap = lap.configured.structure.identified_indices().len();
            let joints_from = from.configured.structure.identified_indices().len();
            let effect_unknowns = from.solution.len() - from.scales.len() - joints_from;
            let mut x0 = lap.solution[..joints_lap].to_vec();
            x0.extend(&from.solution[joints_from..joints_from + effect_unknowns]);
            x0.extend(&lap.scales);
            (lap.configured.ctx.clone(), effects_before, x0)
        }
    };
    let mut told = Iterations {
        watch: stage.watch,
        candidate: name,
        variant: None,
    };
    let fitted = discrepancy::fit_with(
        measured,
        stage.calibration,
        from.discrepancy.clone(),
        |cal, start| match start {
            Some(start) => fit::refit(&ctx, measured, cal, &effects, start, &mut told),
            None => fit::fit_from(&ctx, measured, cal, &effects, &x0, &mut told),
        },
    )?;
    let joints = fitted.configured.structure.identified_indices().len();
    // Every effect's size judged; the added cause's parameters and size reported.
    let mut at = joints;
    let mut excluded = None;
    let mut last = (Vec::new(), (0.0, 0.0));
    for effect in &effects {
        let k = effect.parameters(&ctx).len();
        let parameters = fitted.estimates[at..at + k].to_vec();
        let (size, reason) = judged(effect.as_ref(), &ctx, &fitted, &parameters);
        excluded = excluded.or(reason);
        last = (parameters, size);
        at += k;
    }
    let holds_lap = fitted
        .configured
        .ctx
        .structure
        .sites
        .joints
        .iter()
        .any(|j| j.lap);
    if holds_lap {
        excluded = excluded.or_else(|| {
            axial_pair(&fitted).map(|r| {
                format!("the fit pairs measured mode {r} with an axial mode of the layers")
            })
        });
    }
    let (parameters, size, added_unknowns, describe) = match added {
        Part::Effect(effect) => (
            last.0,
            last.1,
            effect.parameters(&ctx).len(),
            effect.describe().to_string(),
        ),
        Part::Lap => {
            let (parameters, added, size) = summary(&fitted);
            (
                parameters,
                size,
                added,
                "the layered lap in place of the point joint".to_string(),
            )
        }
    };
    let mut fit = Fit::of_model(
        measured,
        fitted,
        parameters,
        size,
        describe,
        added_unknowns,
        excluded,
    );
    fit.bounded = match added {
        Part::Effect(effect) => bounded(effect.as_ref(), &ctx),
        Part::Lap => false,
    };
    Ok(fit)
}

//! Diagnosis of measured data: calibrate the invariant joint on every measured mode, search
//! the candidate explanations of what it leaves (each with its own model discrepancy, causes
//! added one after another), judge them against the measurement error, decide, and report
//! before and after.
//!
//! The pipeline ([`diagnose`]), one step per module, each returning plain data, none
//! re-entering an earlier one:
//! 1. [`calibrate`]: the model checked, the effects' context, the joint calibrated with its own
//!    discrepancy (modes without a partner set aside, paired again, left out);
//! 2. [`search`]: every candidate fitted once with its own discrepancy ([`discrepancy`]), the
//!    clearly best one, causes added one after another while the model does not fit within
//!    the measurement error;
//! 3. [`score`]: every model judged against the measurement error ([`yardstick`]: the data's
//!    own standard errors, or the noise estimated from the largest model's residuals
//!    ([`noise`]) when they pass the checks that do not stand on the noise level, else the
//!    stated noise): goodness of fit, lack of fit of the frequencies, whiteness of the shape
//!    residuals ([`whiteness`]);
//! 4. [`decide`]: the rules: which explanation is best (relative), whether it is adequate
//!    (absolute), the graded verdict;
//! 5. [`assemble`]: the [`report`] assembled: errors before and after, what remains, the
//!    paper's per-mode corrections, the misfit's pattern.
//!
//! Beside them: [`settings`] (checked where set), [`pairing`] (MAC pairing of measured and
//! model modes), [`sensitivity`] (eigenpair derivatives), [`fit`] (the weighted nonlinear
//! least squares of a model on the data, on the solver of [`crate::optim`]; the joints' ranges
//! and limits), [`along`] (residuals in sensor order), [`candidate`] (the registry of
//! candidates and their combinations).
//!
//! The fits keep what of the plausible range is a linear inequality (non-negative masses and
//! springs, a rotary inertia within its mass's largest gyration:
//! `EffectParameter::non_negative`, `Effect::inequalities`; a joint stiffness between free and
//! rigid); a candidate whose fitted size is still not physically plausible
//! (`Effect::plausible`, `Effect::admissible`) is excluded, with the reason.
//!
//! Layer 6 (diagnosis and results; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`], [`crate::model`], [`crate::measured`], [`crate::extract`],
//! [`crate::identify`], [`crate::simulate`], [`crate::study`]) and, without a circle,
//! [`crate::report`], [`crate::cluster`].

pub mod absorbed;
pub mod along;
pub mod assemble;
pub mod calibrate;
pub mod candidate;
pub mod decide;
pub mod discrepancy;
pub mod fit;
pub mod noise;
pub mod pairing;
pub mod progress;
pub mod reduce;
pub mod report;
pub mod score;
pub mod search;
pub mod sensitivity;
pub mod settings;
pub mod whiteness;
pub mod yardstick;

pub use calibrate::nominal_count;
pub use candidate::{Candidate, Tier, catalogue, registry};
pub use decide::{ALPHA, AMBIGUITY_MARGIN, FIT_ALPHA, MAX_CAUSES, TREND_SIGMAS};
pub use fit::{
    Calibration, Discrepancy, Estimate, FitError, Fitted, Limit, LimitKind, Noise, Residuals,
    residuals,
};
pub use noise::NoiseEstimate;
pub use pairing::PairingRule;
pub use progress::{Pass, Step, Watch};
pub use report::{
    CandidateReport, ErrorSummary, LeftOut, Remainder, Report, ResidualPattern, Verdict,
};
pub use settings::DiagnoseSettings;
pub use whiteness::Whiteness;

use std::sync::Arc;

use crate::measured::MeasuredModes;
use crate::modal::{ModalError, ModalSolution};
use crate::model::effects::EffectContext;
use crate::structure::Structure;
use assemble::Findings;
use candidate::Stage;
use score::Judge;

/// Why a diagnosis cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DiagnoseError {
    /// A setting is out of its range.
    #[error(transparent)]
    Settings(#[from] crate::input::SettingError),
    /// The nominal model has no eigensolution.
    #[error("the model has no eigensolution")]
    Modal(#[from] ModalError),
    /// The joint-only calibration failed.
    #[error("calibration of the joint")]
    Fit(#[from] FitError),
    /// The calibration ended with a larger error than the model as given.
    #[error(
        "the calibration of the joint ended with deviance {after:.4e} above the model as given ({before:.4e}), each with its own discrepancy: refused (the pairing of modes changed on the way; check it with --pair)"
    )]
    ErrorGrew {
        /// Deviance of the model as given.
        before: f64,
        /// Deviance after the calibration.
        after: f64,
    },
    /// The nominal model is a mechanism.
    #[error("the model as given")]
    Mechanism(#[from] crate::modal::Mechanism),
    /// The model has nothing to calibrate.
    #[error(
        "the model identifies no joint parameter (no joint, or every parameter held fixed): there is nothing to calibrate"
    )]
    NoParameters,
    /// The per-mode settings given cannot serve the measured modes.
    #[error("per-mode corrections (--n, --m)")]
    PerMode(#[from] crate::identify::IdentifyError),
    /// Fewer modes than joint parameters.
    #[error(
        "{modes} measured mode(s) cannot calibrate {parameters} joint parameters: measure at least {parameters} modes"
    )]
    TooFewModes {
        /// Measured modes.
        modes: usize,
        /// Joint parameters.
        parameters: usize,
    },
}

/// Diagnoses `measured` against `model` (see the module docs for the steps).
pub fn diagnose(
    model: &Structure,
    measured: &MeasuredModes,
    settings: DiagnoseSettings,
) -> Result<Report, DiagnoseError> {
    diagnose_watched(model, measured, settings, Watch::silent())
}

/// As [`diagnose`], every step told to `watch` as it finishes ([`progress`]).
pub fn diagnose_watched(
    model: &Structure,
    measured: &MeasuredModes,
    settings: DiagnoseSettings,
    watch: Watch,
) -> Result<Report, DiagnoseError> {
    diagnose_solved(model, measured, settings, watch, None)
}

/// As [`diagnose_watched`], the nominal model's lowest pairs taken from `nominal` (a solve of
/// `model` as it is, with its factor: [`crate::model::from_path_solved`]) when it holds
/// [`nominal_count`] of them: the same pairs, not solved twice.
pub fn diagnose_solved(
    model: &Structure,
    measured: &MeasuredModes,
    settings: DiagnoseSettings,
    watch: Watch,
    nominal: Option<ModalSolution>,
) -> Result<Report, DiagnoseError> {
    settings.check()?;
    let (ctx, mut nominal) = calibrate::prepare(model, measured, &settings, nominal)?;
    let factor = nominal.take_factor();
    let reduced = if settings.full_model {
        Arc::clone(&ctx)
    } else {
        reduce::attach(
            Arc::clone(&ctx),
            &nominal,
            factor,
            measured,
            settings.extended,
        )?
    };
    drop(nominal);
    if Arc::ptr_eq(&reduced, &ctx) {
        return Ok(diagnose_on(&ctx, model, measured, settings, watch)?.0);
    }
    let (mut report, check) = diagnose_on(&reduced, model, measured, settings.clone(), watch)?;
    if check.as_ref().is_none_or(|c| c.verified) {
        report.reduction = check;
        return Ok(report);
    }
    // The reduced model missed the full one at the final parameters: the diagnosis again on
    // the full model, the failed check reported beside it.
    let (mut report, _) = diagnose_on(&ctx, model, measured, settings, watch)?;
    report.reduction = check;
    Ok(report)
}

/// The diagnosis on the effects' context `ctx` (its structure's reduced model when it carries
/// one), with the check of the final model against the full one when it does.
fn diagnose_on(
    ctx: &Arc<EffectContext>,
    model: &Structure,
    measured: &MeasuredModes,
    settings: DiagnoseSettings,
    watch: Watch,
) -> Result<(Report, Option<reduce::ReductionCheck>), DiagnoseError> {
    // The measurement error: the data's own standard errors where every mode carries them,
    // else the stated noise; each fit adds its own discrepancy to it.
    let calibration = Calibration {
        noise: settings.noise,
        discrepancy: Discrepancy::default(),
        pairing: settings.pairing.clone(),
        shape_floor: fit::SHAPE_FLOOR,
        measured_std: measured.has_std(),
    };
    let calibrated = calibrate::calibrate(ctx, measured, &calibration)?;
    // The reduced model as the calibration enriched it, for every fit after it.
    let ctx = &reduce::recentred(ctx, &calibrated.base);
    watch.tell(&Step::Calibrated {
        chi2: calibrated.base.chi2,
        iterations: calibrated.base.iterations,
    });
    let measured = &calibrated.measured;
    let library = candidate::library(ctx, settings.extended);
    let stage = Stage {
        ctx,
        measured,
        calibration: &calibration,
        base: &calibrated.base,
        watch,
    };
    let given = given_causes(&settings.causes, &library)?;
    let found = search::search(
        &library,
        &stage,
        candidate::hypotheses(&library, ctx),
        &given,
    );
    let (largest, fitted) = found.largest(&calibrated.base);
    let estimate = yardstick::of_model(largest, fitted, measured, &calibration);
    watch.tell(&Step::Noise(&estimate));
    let judge = Judge {
        estimate: &estimate,
        measured,
    };
    let base_explains = judge.of_model(&calibrated.base).explains(&estimate);
    let (path, hypotheses) = (found.path.clone(), found.hypotheses);
    let scored = score::score(found, &judge);
    let names: Vec<Verdict> = scored.iter().map(|s| s.verdict).collect();
    let explains = |i: usize| decide::Judgement::of(&scored[i].report).explains(&estimate);
    let before = ErrorSummary::of(&calibrated.base, measured, &estimate).chi2;
    let lowers = |i: usize| {
        scored[i]
            .model
            .as_ref()
            .is_some_and(|m| ErrorSummary::of(m, measured, &estimate).chi2 < before)
    };
    let decision = decide::decide(&path, explains, lowers, base_explains, &names);
    let after = decision.best.and_then(|b| scored[b].model.clone());
    let after = after.unwrap_or_else(|| calibrated.base.clone());
    let report = assemble::assemble(Findings {
        measured,
        stated: settings.noise,
        criterion: decide::criterion(&estimate, hypotheses, library.len()),
        hypotheses,
        estimate,
        initial: &calibrated.initial,
        base: &calibrated.base,
        scored,
        decision,
        per_mode: settings
            .per_mode
            .unwrap_or_else(|| report::default_settings(model, measured)),
        left_out: calibrated.left_out.clone(),
    });
    // The last step: the check frees the factor the reduced solves kept.
    let check = reduce::check(&after, measured)?;
    Ok((report, check))
}

/// The combinations of causes the settings ask for, as indices into `library`; refused when
/// one names a candidate the library does not hold for this model (another tier, or one that
/// does not apply to it).
fn given_causes(
    causes: &[Vec<String>],
    library: &[std::sync::Arc<dyn Candidate>],
) -> Result<Vec<Vec<usize>>, DiagnoseError> {
    causes
        .iter()
        .map(|combination| {
            combination
                .iter()
                .map(|name| {
                    library
                        .iter()
                        .position(|c| c.name() == name)
                        .ok_or_else(|| {
                            let tier = registry()
                                .iter()
                                .find(|c| c.name() == name)
                                .map(|c| c.tier());
                            let why = if tier == Some(Tier::Extended) {
                                format!(
                                    "{name} is a candidate of the extended tier: add --extended"
                                )
                            } else {
                                format!("{name} does not apply to this model")
                            };
                            DiagnoseError::Settings(crate::input::SettingError::new(
                                "causes",
                                combination.join("+"),
                                why,
                            ))
                        })
                })
                .collect()
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts_are_written_as_the_battery_reads_them() {
        let words: Vec<String> = [
            Verdict::None,
            Verdict::Effect,
            Verdict::Partial,
            Verdict::Ambiguous,
            Verdict::Unexplained,
            Verdict::FrequencyDependent,
        ]
        .iter()
        .map(|v| {
            serde_json::to_value(v)
                .unwrap()
                .as_str()
                .unwrap()
                .to_string()
        })
        .collect();
        assert_eq!(
            words,
            [
                "none",
                "effect",
                "partial",
                "ambiguous",
                "unexplained",
                "frequency_dependent"
            ]
        );
    }
}

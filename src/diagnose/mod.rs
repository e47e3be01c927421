//! Diagnosis of measured data: calibrate the invariant joint on every measured mode, estimate
//! the noise, try every candidate explanation of what the joint leaves, decide, and report
//! before and after.
//!
//! The pipeline ([`diagnose`]), one step per module, each returning plain data:
//! 1. [`calibrate`]: the model checked, the effects' context, the joint calibrated;
//! 2. [`noise`]: every candidate fitted under the stated noise, and the noise estimated from
//!    what the largest physical model that fits leaves (shape pseudo-residuals and levels;
//!    [`yardstick`]: the stated noise kept when no model fits);
//! 3. [`candidate`]: every candidate fitted again under the working noise (the registry of
//!    candidates: effects of the model library, the frequency-dependent joint, scans), but
//!    for the fits the noise check made under it already;
//! 4. [`score`]: each fit judged: likelihood-ratio p-value, goodness of fit, lack of fit of
//!    the frequencies, whiteness of the shape residuals ([`whiteness`]);
//! 5. [`decide`]: the rules: multiple testing, what explains the data, the selection by
//!    likelihood ratio and information criterion, the verdict;
//! 6. [`assemble`]: the [`report`] assembled: errors before and after, the paper's per-mode
//!    corrections, the misfit's pattern.
//!
//! Beside them: [`settings`] (checked where set), [`pairing`] (MAC pairing of measured and
//! model modes), [`sensitivity`] (eigenpair derivatives), [`fit`] (the weighted nonlinear
//! least squares of a model on the data, on the solver of [`crate::optim`]), [`along`]
//! (residuals in sensor order).
//!
//! The fits keep what of the plausible range is a linear inequality (non-negative masses and
//! springs, a rotary inertia within its mass's largest gyration:
//! `EffectParameter::non_negative`, `Effect::inequalities`); a candidate whose fitted size is
//! still not physically plausible (`Effect::plausible`, `Effect::admissible`) is excluded,
//! with the reason.
//!
//! Layer 6 (diagnosis and results; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`], [`crate::model`], [`crate::measured`], [`crate::extract`],
//! [`crate::identify`], [`crate::simulate`], [`crate::study`]) and, without a circle,
//! [`crate::report`], [`crate::cluster`].

pub mod along;
pub mod assemble;
pub mod calibrate;
pub mod candidate;
pub mod decide;
pub mod fit;
pub mod noise;
pub mod pairing;
pub mod progress;
pub mod report;
pub mod score;
pub mod sensitivity;
pub mod settings;
pub mod whiteness;
pub mod yardstick;

pub use candidate::{Candidate, Tier, catalogue, registry};
pub use decide::{ALPHA, AMBIGUITY_MARGIN, FIT_ALPHA, TREND_SIGMAS};
pub use fit::{Calibration, Estimate, FitError, Fitted, Noise, Residuals, residuals};
pub use noise::NoiseEstimate;
pub use pairing::PairingRule;
pub use progress::{Pass, Step, Watch};
pub use report::{CandidateReport, ErrorSummary, Report, ResidualPattern, Verdict};
pub use settings::DiagnoseSettings;
pub use whiteness::Whiteness;

use crate::measured::MeasuredModes;
use crate::modal::ModalError;
use crate::optim::Silent;
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
        "the calibration of the joint ended with chi^2 {after:.4e} above the model as given ({before:.4e}): refused (the pairing of modes changed on the way; check it with --pair)"
    )]
    ErrorGrew {
        /// chi^2 of the model as given.
        before: f64,
        /// chi^2 after the calibration.
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
    settings.check()?;
    let ctx = calibrate::prepare(model, measured, &settings)?;
    let library = candidate::library(&ctx, settings.extended);
    // Under the stated noise: the largest physical model gives the noise estimate.
    // Data with their own standard errors are weighed by them throughout; else by the
    // stated noise first.
    let stated = Calibration {
        noise: settings.noise,
        pairing: settings.pairing.clone(),
        shape_floor: fit::SHAPE_FLOOR,
        measured_std: measured.has_std(),
    };
    let first_base = fit::fit(&ctx, measured, &stated, &[], &mut Silent)?;
    watch.tell(&Step::Calibrated {
        chi2: first_base.chi2,
        iterations: first_base.iterations,
    });
    let first_stage = Stage {
        ctx: &ctx,
        measured,
        calibration: &stated,
        base: &first_base,
        estimate: None,
        watch,
    };
    let first = candidate::fit_all(&library, &first_stage, None, None);
    let (estimate, checked) = if stated.measured_std {
        let largest = yardstick::largest(&first, &first_base);
        let estimate = noise::from_data(largest.name, largest.fitted, measured, &stated);
        (estimate, None)
    } else {
        let chosen = yardstick::choose(&first, &first_stage);
        (chosen.estimate, chosen.checked)
    };
    // Under the working noise: the joint calibrated again, every candidate refitted (but for
    // the fits the noise check made under it), judged.
    let working = Calibration {
        noise: estimate.working,
        pairing: settings.pairing.clone(),
        shape_floor: estimate.working_floor,
        measured_std: stated.measured_std,
    };
    let watch = watch.during(Pass::Working);
    watch.tell(&Step::Noise(&estimate));
    // The noise check's fits under the working calibration are this pass's own.
    let (base_done, candidate_done) = match checked.filter(|c| c.calibration == working) {
        Some(c) => (Some(c.base), c.candidate),
        None => (None, None),
    };
    let calibrated = calibrate::calibrate(&ctx, measured, &working, &first_base, base_done)?;
    watch.tell(&Step::Calibrated {
        chi2: calibrated.base.chi2,
        iterations: calibrated.base.iterations,
    });
    let stage = Stage {
        calibration: &working,
        base: &calibrated.base,
        estimate: Some(&estimate),
        watch,
        ..first_stage
    };
    let done = candidate_done.as_ref().map(|(i, fit)| (*i, fit));
    let fits = candidate::fit_all(&library, &stage, Some(&first), done);
    let tried = candidate::hypotheses(&library, &ctx);
    let judge = Judge {
        estimate: &estimate,
        measured,
        tried,
    };
    let scored = score::score(fits, &judge);
    let reports: Vec<CandidateReport> = scored.iter().map(|s| s.report.clone()).collect();
    let names: Vec<Verdict> = scored.iter().map(|s| s.verdict).collect();
    let decision = decide::decide(
        &reports,
        &names,
        judge.of_model(&calibrated.base),
        &estimate,
    );
    Ok(assemble::assemble(Findings {
        measured,
        stated: settings.noise,
        criterion: decide::criterion(&estimate, tried, library.len()),
        hypotheses: tried,
        estimate,
        initial: &calibrated.initial,
        base: &calibrated.base,
        scored,
        decision,
        per_mode: settings
            .per_mode
            .unwrap_or_else(|| report::default_settings(model, measured)),
    }))
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn verdicts_are_written_as_the_battery_reads_them() {
        let words: Vec<String> = [
            Verdict::None,
            Verdict::Effect,
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
                "ambiguous",
                "unexplained",
                "frequency_dependent"
            ]
        );
    }
}

//! What a diagnosis reports (the last step of the pipeline, `super::assemble`, fills it):
//! error summaries of a model against the data (module `summary`), the
//! paper's per-mode joint corrections with their uncertainties (module `per_mode`), where a
//! misfit sits (module `pattern`), what no model explains (module `remains`), every
//! candidate, the verdict. Plain data, serialisable.

mod pattern;
mod per_mode;
mod reference;
mod remains;
mod summary;

use serde::Serialize;

pub use pattern::{ModeChi2, Region, ResidualPattern};
pub use per_mode::{
    Flatness, ModeCorrection, Source, default_settings, flatness, per_mode_corrections,
};
pub use reference::{Absorbed, Shift};
pub use remains::{Lacking, Misfit, Remaining, remains};
pub use summary::{ErrorSummary, ModeError};

use super::fit::{Discrepancy, Estimate, Noise};
use super::noise::NoiseEstimate;

/// The verdict of a diagnosis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// The calibrated model explains the data within the working noise (stated, or estimated
    /// from the data); no candidate is significant.
    None,
    /// A cause (or several together, `Report::causes`) is clearly the best explanation and
    /// brings the residual down to the measurement error.
    Effect,
    /// A cause is clearly the best explanation (several together, `Report::causes`, where the
    /// search added more), but a misfit beyond the measurement error remains
    /// ([`Report::remaining`] says which modes, how large and where, and the model's
    /// discrepancy).
    Partial,
    /// The best candidate explains the data, but another does nearly as well (within
    /// [`super::decide::AMBIGUITY_MARGIN`] of information criterion): the data cannot tell them apart.
    Ambiguous,
    /// No candidate is clearly better than the calibrated joint (none significant, or several
    /// partial explanations the data cannot tell apart), and the joint alone does not fit:
    /// an effect outside the library ([`Report::pattern`] says where the residual sits).
    Unexplained,
    /// The joint whose parameters scale as (f / f_ref)^alpha, each mode at its own frequency,
    /// explains the data, and no static candidate comes close: the paper's
    /// frequency-dependent joint (the candidate `frequency_dependence`, whose fit is `after`;
    /// [`Report::trend`] shows the per-mode corrections of the invariant joint).
    #[serde(rename = "frequency_dependent")]
    FrequencyDependent,
}

/// One candidate's fit, or why it failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CandidateReport {
    /// Candidate name (a combination of causes: their names joined by " + ").
    pub name: String,
    /// The model this one extends by its last cause (a combination), absent for a candidate
    /// alone (it extends the joint-only fit).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub extends: Option<String>,
    /// The effect's fitted parameters (joints are in `summary`).
    pub parameters: Vec<Estimate>,
    /// Fitted size in the unit of `jointid simulate --effect` (see `describe`).
    pub size: Option<f64>,
    /// Standard error of the size.
    pub size_se: Option<f64>,
    /// What the effect is and what its size means.
    pub describe: String,
    /// chi^2 with the candidate under the measurement error (the yardstick).
    pub chi2: Option<f64>,
    /// Degrees of freedom with the candidate.
    pub dof: Option<usize>,
    /// Deviance with the candidate under its own error model: measurement error and the
    /// discrepancy estimated with it (module `discrepancy`).
    pub deviance: Option<f64>,
    /// The discrepancy estimated with the candidate.
    pub discrepancy: Option<Discrepancy>,
    /// Likelihood-ratio statistic: the deviance of the model it extends (the joint-only fit
    /// for a candidate alone) less its own.
    pub lrt: Option<f64>,
    /// The criterion: the likelihood-ratio p-value (chi-square, or F where a discrepancy was
    /// estimated), Bonferroni-adjusted for the hypotheses tried up to its step (smaller is
    /// more significant).
    pub criterion: Option<f64>,
    /// Goodness of fit with the candidate under the measurement error.
    pub fit_p_value: Option<f64>,
    /// Lack of fit of the frequencies alone under the working noise, P(chi^2_dof > chi^2_f)
    /// (module `noise`).
    pub frequency_p_value: Option<f64>,
    /// Structure of the shape residuals along the structure, P(N(0, 1) > Z) (module
    /// `whiteness`): small when neighbouring residuals share their sign.
    pub whiteness_p_value: Option<f64>,
    /// The fit's summary with the candidate.
    #[serde(skip)]
    pub summary: Option<ErrorSummary>,
    /// Why the fit failed, if it did.
    pub error: Option<String>,
    /// Why the fitted size is not physically plausible (the candidate is then excluded from
    /// the selection), if it is not.
    pub excluded: Option<String>,
    /// A scan's chi^2 along its coordinate (scans only).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub profile: Option<Profile>,
}

impl CandidateReport {
    /// The report of a candidate whose fit failed with `error`.
    pub fn failed(name: &str, describe: &str, error: String) -> Self {
        Self {
            name: name.to_string(),
            extends: None,
            parameters: Vec::new(),
            size: None,
            size_se: None,
            describe: describe.to_string(),
            chi2: None,
            dof: None,
            deviance: None,
            discrepancy: None,
            lrt: None,
            criterion: None,
            fit_p_value: None,
            frequency_p_value: None,
            whiteness_p_value: None,
            summary: None,
            error: Some(error),
            excluded: None,
            profile: None,
        }
    }
}

/// What remains beyond the measurement error with the named model (`partial`).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Remainder {
    /// The share of the joint-only fit's misfit (its chi^2 under the measurement error) that
    /// the named model removes: 1 - chi^2(after) / chi^2(before), at least 0.
    pub removed: f64,
    /// chi^2 of the named model under the measurement error, and its degrees of freedom.
    pub chi2: f64,
    /// Its degrees of freedom.
    pub dof: usize,
    /// The modes whose frequency or shape still miss beyond the measurement error, how large
    /// (in % and in standard deviations of the measurement error), and what the library lacks
    /// for them where it can be said.
    pub modes: Vec<Remaining>,
    /// Where along the structure the remaining misfit sits.
    pub pattern: ResidualPattern,
}

/// A kind of quantity whose discrepancy the data cannot estimate: the model's unknowns leave
/// its residuals less than one degree of freedom (the discrepancy is then held at 0).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Undetermined {
    /// `frequency` or `shape`.
    pub kind: &'static str,
    /// Its measured values.
    pub values: usize,
    /// The residual degrees of freedom left (values less the kind's share of the unknowns).
    pub dof: f64,
}

/// A measured mode the diagnosis left out: no model mode resembled it, with the model as
/// given nor with the joint calibrated on the other modes.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct LeftOut {
    /// Measured mode r.
    pub mode: usize,
    /// Its frequency, Hz.
    pub frequency_hz: f64,
    /// Why: the pairing's message.
    pub reason: String,
}

/// A whole diagnosis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// none, effect, partial, ambiguous, unexplained or frequency-dependent.
    pub verdict: Verdict,
    /// The named model, when the verdict is `effect`, `partial` or `frequency_dependent` (when
    /// `ambiguous`: the best of the contenders), whose fit is `after`: a candidate's name, or
    /// the causes together joined by " + ".
    pub selected: Option<String>,
    /// The causes of `selected`, in the order the search added them.
    pub causes: Vec<String>,
    /// When `ambiguous` (or `unexplained` with several partial explanations): every candidate
    /// within the margin of the best, best first.
    pub contenders: Vec<String>,
    /// The discrepancy of the `after` model: what it misses beyond the measurement error, as
    /// standard deviations (module `discrepancy`).
    pub discrepancy: Discrepancy,
    /// The kinds of quantity of the `after` model whose discrepancy the data cannot estimate
    /// (held at 0; absent from the JSON when none).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub undetermined: Vec<Undetermined>,
    /// When `partial`: what remains beyond the measurement error with the named model.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub remaining: Option<Remainder>,
    /// Measured modes left out of the diagnosis: no model mode resembles them.
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub left_out: Vec<LeftOut>,
    /// When `unexplained`: where the misfit of the joint-only fit sits, under the working
    /// noise.
    pub pattern: Option<ResidualPattern>,
    /// When `unexplained`: what remains of each mode with every model, and what the library
    /// lacks for it (absent from the JSON when empty).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub remains: Vec<Remaining>,
    /// When `unexplained` or `frequency-dependent`: the per-mode corrections (before) that
    /// trend with frequency.
    pub trend: Vec<Flatness>,
    /// The statistical criterion, in words.
    pub criterion: String,
    /// The stated noise.
    pub noise: Noise,
    /// The noise estimated from the data, beside the stated; the selection used its working
    /// noise.
    pub noise_estimate: NoiseEstimate,
    /// Pairing remarks: modes paired with another model mode than their number.
    pub warnings: Vec<String>,
    /// The model as given (joints uncalibrated).
    pub initial: ErrorSummary,
    /// The invariant joint calibrated on every mode, no effect.
    pub before: ErrorSummary,
    /// With the selected effect (equal to `before` when none is selected).
    pub after: ErrorSummary,
    /// Every candidate.
    pub candidates: Vec<CandidateReport>,
    /// The paper's per-mode corrections on the `before` model.
    pub per_mode_before: Vec<ModeCorrection>,
    /// The same on the `after` model.
    pub per_mode_after: Vec<ModeCorrection>,
    /// Flatness of the per-mode corrections before.
    pub flatness_before: Vec<Flatness>,
    /// Flatness after.
    pub flatness_after: Vec<Flatness>,
    /// The per-mode identification settings (n, m, weighting).
    pub per_mode_settings: String,
    /// The shape-noise floor used in the weights.
    pub shape_floor: f64,
    /// On a model whose beams were calibrated on a reference test: the joint with the beams
    /// as typed beside this one (module `absorbed`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reference: Option<Absorbed>,
    /// Hypotheses the selection tested (the multiple-testing count: a scan counts each of its
    /// members; for the figures, not in the JSON).
    #[serde(skip)]
    pub hypotheses: usize,
    /// The reduced model against the full one at the final parameters, when the diagnosis
    /// ran on a reduced model (module `crate::diagnose::reduce`).
    #[serde(skip_serializing_if = "Option::is_none")]
    pub reduction: Option<super::reduce::ReductionCheck>,
}

/// chi^2 of a scan along its coordinate.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Profile {
    /// Name of the coordinate.
    pub coordinate: String,
    /// Its unit.
    pub unit: &'static str,
    /// Every member: (coordinate, chi^2 of its fit; None when it failed or is not physical).
    pub points: Vec<(f64, Option<f64>)>,
    /// The best member's coordinate.
    pub best: f64,
    /// The coordinates where chi^2 <= chi^2_min + 1: (lowest, highest).
    pub interval: (f64, f64),
}

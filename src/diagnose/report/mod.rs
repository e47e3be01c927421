//! What a diagnosis reports, and the last step of the pipeline that assembles it
//! ([`assemble`]): error summaries of a model against the data (module `summary`), the
//! paper's per-mode joint corrections with their uncertainties (module `per_mode`), where a
//! misfit sits (module `pattern`), every candidate, the verdict. Plain data, serialisable.

mod pattern;
mod per_mode;
mod summary;

use serde::Serialize;

pub use pattern::{ModeChi2, Region, ResidualPattern};
pub use per_mode::{Flatness, ModeCorrection, default_settings, flatness, per_mode_corrections};
pub use summary::{ErrorSummary, ModeError};

use super::candidate::Profile;
use super::decide::{Decision, TREND_SIGMAS};
use super::fit::{Estimate, Fitted, Noise, SHAPE_FLOOR};
use super::noise::NoiseEstimate;
use super::score::Scored;
use crate::identify::Settings;
use crate::measured::MeasuredModes;

/// The verdict of a diagnosis.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Verdict {
    /// The calibrated model explains the data within the working noise (stated, or estimated
    /// from the data); no candidate is significant.
    None,
    /// A candidate is significant and brings the residual down to the noise.
    Effect,
    /// The best candidate explains the data, but another does nearly as well (within
    /// [`super::decide::AMBIGUITY_MARGIN`] of information criterion): the data cannot tell them apart.
    Ambiguous,
    /// The residual stays above the noise with every candidate: an effect outside the library
    /// ([`Report::pattern`] says where the residual sits).
    Unexplained,
    /// The joint whose parameters scale as (f / f_ref)^alpha is the best explanation, and no
    /// static candidate comes close: the paper's frequency-dependent joint (the candidate
    /// `frequency_dependence`; [`Report::trend`] shows the per-mode corrections).
    #[serde(rename = "frequency_dependent")]
    FrequencyDependent,
}

/// One candidate's fit, or why it failed.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CandidateReport {
    /// Candidate name.
    pub name: String,
    /// The effect's fitted parameters (joints are in `summary`).
    pub parameters: Vec<Estimate>,
    /// Fitted size in the unit of `jointid simulate --effect` (see `describe`).
    pub size: Option<f64>,
    /// Standard error of the size.
    pub size_se: Option<f64>,
    /// What the effect is and what its size means.
    pub describe: String,
    /// chi^2 with the candidate.
    pub chi2: Option<f64>,
    /// Degrees of freedom with the candidate.
    pub dof: Option<usize>,
    /// Likelihood-ratio statistic chi^2(joint only) - chi^2(with candidate).
    pub lrt: Option<f64>,
    /// The criterion: the likelihood-ratio p-value P(chi^2_k > lrt), Bonferroni-adjusted for
    /// the number of candidates tried (smaller is more significant).
    pub criterion: Option<f64>,
    /// Goodness of fit with the candidate, P(chi^2_dof > chi^2).
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
            parameters: Vec::new(),
            size: None,
            size_se: None,
            describe: describe.to_string(),
            chi2: None,
            dof: None,
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

/// A whole diagnosis.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Report {
    /// none, effect, ambiguous, unexplained or frequency-dependent.
    pub verdict: Verdict,
    /// The selected candidate, when the verdict is `effect` (when `ambiguous`: the best of
    /// the contenders, whose fit is `after`).
    pub selected: Option<String>,
    /// When `ambiguous`: every candidate within the margin of the best, best first.
    pub contenders: Vec<String>,
    /// When `unexplained` or `frequency-dependent`: where the misfit of the joint-only fit
    /// sits, under the working noise.
    pub pattern: Option<ResidualPattern>,
    /// When `unexplained` or `frequency-dependent`: the per-mode corrections (before) that
    /// trend with frequency.
    pub trend: Vec<Flatness>,
    /// The statistical criterion, in words.
    pub criterion: String,
    /// The stated noise.
    pub noise: Noise,
    /// The noise estimated from the data, beside the stated; the selection used its working
    /// noise.
    pub noise_estimate: super::noise::NoiseEstimate,
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
    /// Hypotheses the selection tested (the multiple-testing count: a scan counts each of its
    /// members; for the figures, not in the JSON).
    #[serde(skip)]
    pub hypotheses: usize,
}

/// Everything the report is made of: the steps' results.
#[derive(Debug)]
pub struct Findings<'a> {
    /// The measured modes.
    pub measured: &'a MeasuredModes,
    /// The stated noise.
    pub stated: Noise,
    /// The noise estimate; its working noise was the selection's.
    pub estimate: NoiseEstimate,
    /// The model as given, its shape scales fitted.
    pub initial: &'a Fitted,
    /// The joint calibrated, no candidate.
    pub base: &'a Fitted,
    /// Every candidate tried, scored.
    pub scored: Vec<Scored>,
    /// The selection.
    pub decision: Decision,
    /// The rule of the selection, in words.
    pub criterion: String,
    /// Hypotheses the selection tested.
    pub hypotheses: usize,
    /// The per-mode identification settings.
    pub per_mode: Settings,
}

/// The report of a diagnosis from its findings: the verdict and the models before and after,
/// the per-mode corrections on both (under the stated noise when no model explains the data,
/// whose residual is then not noise alone), their trend and the misfit's pattern when the
/// verdict is `unexplained` or `frequency_dependent`, and the pairing remarks.
pub fn assemble(f: Findings) -> Report {
    let measured = f.measured;
    let noise = f.estimate.working;
    let decision = &f.decision;
    let best = decision.best.map(|b| &f.scored[b]);
    let after = best.and_then(|s| s.model.as_ref()).unwrap_or(f.base);
    let selected = best
        .filter(|_| decision.verdict != Verdict::FrequencyDependent)
        .map(|s| s.report.name.clone());
    let yardstick = if decision.verdict == Verdict::Unexplained {
        f.stated
    } else {
        noise
    };
    let per_mode_before = per_mode_corrections(f.base, measured, yardstick, f.per_mode);
    let per_mode_after = per_mode_corrections(after, measured, yardstick, f.per_mode);
    let flatness_before = flatness(&per_mode_before);
    let (mut trend, mut pattern) = (Vec::new(), None);
    if matches!(
        decision.verdict,
        Verdict::Unexplained | Verdict::FrequencyDependent
    ) {
        // The paper's view of the same question: the per-mode corrections that trend with
        // frequency (shown, not tested: the verdict stands on the candidates' tests).
        trend = flatness_before
            .iter()
            .filter(|f| f.slope_per_khz.abs() > TREND_SIGMAS * f.slope_se_per_khz)
            .cloned()
            .collect();
        pattern = Some(ResidualPattern::of(
            f.base,
            measured,
            noise,
            f.estimate.working_floor,
        ));
    }
    Report {
        verdict: decision.verdict,
        selected,
        contenders: decision
            .contenders
            .iter()
            .map(|&i| f.scored[i].report.name.clone())
            .collect(),
        pattern,
        trend,
        criterion: f.criterion,
        noise: f.stated,
        initial: ErrorSummary::of(f.initial, measured, &f.estimate),
        before: ErrorSummary::of(f.base, measured, &f.estimate),
        after: ErrorSummary::of(after, measured, &f.estimate),
        warnings: pairing_remarks(f.base, measured),
        noise_estimate: f.estimate,
        candidates: f.scored.into_iter().map(|s| s.report).collect(),
        flatness_before,
        flatness_after: flatness(&per_mode_after),
        per_mode_before,
        per_mode_after,
        per_mode_settings: format!(
            "n = {}, m = {}, weighting = {}",
            f.per_mode.n, f.per_mode.m, f.per_mode.weighting
        ),
        shape_floor: SHAPE_FLOOR,
        hypotheses: f.hypotheses,
    }
}

/// Modes of `fitted` paired with another model mode than their number.
fn pairing_remarks(fitted: &Fitted, measured: &MeasuredModes) -> Vec<String> {
    let rigid = fitted.configured.structure.rigid;
    fitted
        .pairing
        .model_index
        .iter()
        .zip(measured.modes())
        .filter(|(s, m)| **s != m.mode - 1 + rigid)
        .map(|(s, m)| format!("measured mode {} pairs with model mode {} (MAC): a swapped or missing mode; it is compared with that model mode", m.mode, s + 1 - rigid))
        .collect()
}

//! Diagnosis of measured data: calibrate the invariant joint on every measured mode, estimate
//! the noise from what the largest model leaves (module `noise`), try every candidate effect
//! of the library and the frequency-dependent joint (module `frequency_dependence`), select by
//! likelihood-ratio tests under the estimated scale, and report before and after.
//!
//! Selection, stated: with chi^2_0 the calibrated joint-only fit (dof_0) and chi^2_c the fit
//! with candidate c (k_c more unknowns), the likelihood-ratio statistic
//! D_c = chi^2_0 - chi^2_c; with the noise scale estimated on nu degrees of freedom, D_c / k_c
//! is F(k_c, nu) when c is absent. A candidate is significant when that p-value, times the
//! number of candidates tried (Bonferroni), is below [`ALPHA`]. A model explains the data when
//! P(F(dof, nu) > chi^2 / dof), its frequencies alone and the whiteness of its shape residuals
//! are all >= [`FIT_ALPHA`] and the estimated noise is within `noise::LARGEST_FACTOR` of the
//! stated. The fits keep what of the plausible range is a linear inequality (non-negative
//! masses and springs, a rotary inertia within its mass's largest gyration:
//! `EffectParameter::non_negative`, `Effect::inequalities`, module [`crate::optim::bounds`]); a candidate
//! whose fitted size is still not physically plausible (a joint or sensor mass above the
//! beams' mass, an inadmissible theta: `Effect::plausible`, `Effect::admissible`) is
//! excluded, with the reason.
//! - no significant candidate and the joint-only fit good: `none`;
//! - the significant candidate with the largest D_c, if its fit is good: `effect` (or
//!   `frequency_dependent` when it is the frequency-dependent joint) when every other
//!   significant candidate is at least [`AMBIGUITY_MARGIN`] behind it in Akaike's
//!   information criterion (AIC_c = chi^2_c + 2 k_c; Burnham & Anderson, "Model Selection
//!   and Multimodel Inference", sec. 2.6), else `ambiguous` naming those within it;
//! - otherwise `unexplained`, with where the misfit sits ([`report::ResidualPattern`]).
//!
//! - [`pairing`]: MAC pairing of measured and model modes;
//! - [`sensitivity`]: eigenpair derivatives;
//! - [`fit`]: the weighted nonlinear least squares (Levenberg-Marquardt);
//! - [`report`]: summaries, per-mode corrections, the report.

pub mod along;
pub mod fit;
pub mod frequency_dependence;
pub mod noise;
pub mod pairing;
pub mod report;
pub mod sensitivity;
pub mod whiteness;

use std::sync::Arc;

use rayon::prelude::*;

pub use fit::{Calibration, Estimate, FitError, Fitted, Noise, Residuals, residuals};
pub use noise::NoiseEstimate;
pub use pairing::PairingRule;
pub use report::{CandidateReport, ErrorSummary, Report, ResidualPattern, Verdict};
pub use whiteness::Whiteness;

use crate::identify::{Identifier, Settings, Weighting};
use crate::measured::MeasuredModes;
use crate::modal::{ModalError, ModalSolution};
use crate::model::effects::{Effect, EffectContext, candidates, extended};
use crate::structure::{Structure, check_elastic};

/// Family-wise false-alarm probability of the candidate search.
pub const ALPHA: f64 = 0.01;
/// Smallest goodness-of-fit probability of a model that explains the data.
pub const FIT_ALPHA: f64 = 0.001;
/// Smallest lead in AIC of the selected candidate over every other significant one.
pub const AMBIGUITY_MARGIN: f64 = 6.0;
/// A per-mode correction whose slope against frequency exceeds this many standard errors
/// is reported as a trend (`Report::trend`; shown, not the test).
pub const TREND_SIGMAS: f64 = 3.0;

/// Why a diagnosis cannot be made.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum DiagnoseError {
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
    Mechanism(#[from] crate::structure::Mechanism),
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

/// Settings of a diagnosis.
#[derive(Debug, Clone, PartialEq)]
pub struct DiagnoseSettings {
    /// The stated measurement noise.
    pub noise: Noise,
    /// How measured modes pair with model modes.
    pub pairing: PairingRule,
    /// The paper's per-mode identification (None: n = the fewest identified DOFs of a mode,
    /// at most N; m = min(n - 2, 6); inverse weighting).
    pub per_mode: Option<Settings>,
    /// Also search the richer candidates ([`crate::model::effects::extended`]).
    pub extended: bool,
}

/// Diagnoses `measured` against `model`.
pub fn diagnose(
    model: &Structure,
    measured: &MeasuredModes,
    settings: DiagnoseSettings,
) -> Result<Report, DiagnoseError> {
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
    let ctx = Arc::new(EffectContext::new(
        model.clone(),
        &measured.points(),
        nominal.frequency_hz(rigid),
    ));
    let stated = settings.noise;
    let stated_calibration = Calibration {
        noise: stated,
        pairing: settings.pairing.clone(),
        shape_floor: fit::SHAPE_FLOOR,
    };
    let library: Vec<Arc<dyn Effect>> = candidates()
        .into_iter()
        .chain(settings.extended.then(extended).into_iter().flatten())
        .filter(|c| c.applies(&ctx))
        .collect();
    // The largest model under the stated noise gives the noise estimate; the selection runs
    // under the working noise (module `noise`).
    let first_base = fit::fit(&ctx, measured, &stated_calibration, &[])?;
    let first = fit_all(&ctx, measured, &stated_calibration, &library);
    // The largest physical model: a fit outside its effect's plausible range absorbs misfit
    // no physical effect explains, and would pass it off as noise.
    let joint_count = first_base.estimates.len();
    let largest = first
        .iter()
        .filter_map(|(c, r)| r.as_ref().ok().map(|f| (c, f)))
        .filter(|(c, f)| implausible(c.as_ref(), &ctx, f, &effect_theta(f, joint_count)).is_none())
        .map(|(c, f)| (c.name(), f))
        .min_by(|a, b| a.1.chi2.total_cmp(&b.1.chi2))
        .filter(|(_, f)| f.chi2 < first_base.chi2)
        .unwrap_or(("joint only", &first_base));
    let estimate = noise::estimate(
        largest.1,
        measured,
        largest.1.estimates.len(),
        stated,
        fit::SHAPE_FLOOR,
        largest.0,
    );
    let noise = estimate.working;
    let calibration = Calibration {
        noise,
        pairing: settings.pairing.clone(),
        shape_floor: estimate.working_floor,
    };
    let initial = fit::as_given(&ctx, measured, &calibration)?;
    let base = fit::refit(&ctx, measured, &calibration, &[], &first_base)?;
    // Growth beyond round-off (relative, and absolute for data the model fits exactly).
    if base.chi2 > initial.chi2 * (1.0 + 1e-9) + 1e-9 * base.dof as f64 {
        return Err(DiagnoseError::ErrorGrew {
            before: initial.chi2,
            after: base.chi2,
        });
    }
    // The static candidates and the frequency-dependent joint.
    let tried = library.len() as f64 + 1.0;
    // The lack of fit a model's residuals show in what is trustworthy (module `noise`): P of
    // its frequencies alone and of the whiteness of its shape residuals.
    let lack_of_fit = |res: &Residuals, unknowns: usize| {
        (
            estimate.frequency_lack_of_fit(res, unknowns).2,
            whiteness::of_residuals(res, measured, noise, estimate.working_floor).p_value,
        )
    };
    let fits = refit_all(&ctx, measured, &calibration, &first);
    let mut candidates: Vec<(CandidateReport, Option<&Fitted>)> = fits
        .iter()
        .map(|(c, result)| match result {
            Ok(f) => {
                let k = f.estimates.len() - joint_count;
                let lrt = (base.chi2 - f.chi2).max(0.0);
                let parameters = f.estimates[joint_count..].to_vec();
                let theta = effect_theta(f, joint_count);
                let size = c.size_of_theta(&ctx, &theta);
                // Linear propagation of the parameters' standard errors to the size.
                let size_se = parameters
                    .iter()
                    .enumerate()
                    .map(|(i, e)| {
                        let h = 1e-6 * e.value.abs().max(e.se).max(f64::MIN_POSITIVE);
                        let mut t = theta.clone();
                        t[i] += h;
                        ((c.size_of_theta(&ctx, &t) - size) / h * e.se).powi(2)
                    })
                    .sum::<f64>()
                    .sqrt();
                let (frequency_p, white_p) =
                    lack_of_fit(&residuals(f, measured), f.estimates.len());
                let report = CandidateReport {
                    name: c.name().to_string(),
                    parameters,
                    size: Some(size),
                    size_se: Some(size_se),
                    describe: c.describe().to_string(),
                    chi2: Some(f.chi2),
                    dof: Some(f.dof),
                    lrt: Some(lrt),
                    criterion: Some((estimate.lrt_p_value(lrt, k) * tried).min(1.0)),
                    fit_p_value: Some(estimate.fit_p_value(f.chi2, f.dof)),
                    frequency_p_value: Some(frequency_p),
                    whiteness_p_value: Some(white_p),
                    summary: Some(ErrorSummary::of(f, measured, &estimate)),
                    error: None,
                    excluded: implausible(c.as_ref(), &ctx, f, &theta),
                };
                (report, Some(f))
            }
            Err(e) => (
                CandidateReport {
                    name: c.name().to_string(),
                    parameters: Vec::new(),
                    size: None,
                    size_se: None,
                    describe: c.describe().to_string(),
                    chi2: None,
                    dof: None,
                    lrt: None,
                    criterion: None,
                    fit_p_value: None,
                    frequency_p_value: None,
                    whiteness_p_value: None,
                    summary: None,
                    error: Some(e.to_string()),
                    excluded: None,
                },
                None,
            ),
        })
        .collect();
    let linearised = fit::linearise(&ctx, measured, &calibration, &base)?;
    let dependence = frequency_dependence::fit(&linearised, measured);
    if let Some(d) = &dependence {
        let dof = base.dof.saturating_sub(1).max(1);
        let (frequency_p, white_p) = lack_of_fit(
            &linearised.unweighted(&d.residual, measured),
            base.estimates.len() + 1,
        );
        candidates.push((
            CandidateReport {
                name: frequency_dependence::NAME.to_string(),
                parameters: vec![Estimate {
                    name: format!("{}.alpha", frequency_dependence::NAME),
                    unit: "1",
                    value: d.exponent,
                    se: d.exponent_se,
                }],
                size: Some(d.exponent),
                size_se: Some(d.exponent_se),
                describe: format!(
                    "every joint parameter scales as (f / {:.4e} Hz)^alpha (linearised at the calibrated joint: a score test)",
                    d.reference_hz
                ),
                chi2: Some(d.chi2),
                dof: Some(dof),
                lrt: Some(d.statistic),
                criterion: Some((estimate.lrt_p_value(d.statistic, 1) * tried).min(1.0)),
                fit_p_value: Some(estimate.fit_p_value(d.chi2, dof)),
                frequency_p_value: Some(frequency_p),
                whiteness_p_value: Some(white_p),
                summary: None,
                error: None,
                excluded: None,
            },
            None,
        ));
    }
    // A model explains the data when its whole fit and its frequencies alone pass under the
    // working noise, and that noise is within LARGEST_FACTOR of the stated.
    let plausible_noise = estimate.shape_factor <= noise::LARGEST_FACTOR;
    let base_p = estimate.fit_p_value(base.chi2, base.dof);
    let (base_frequency_p, base_white_p) =
        lack_of_fit(&residuals(&base, measured), base.estimates.len());
    let explains = |fit_p: Option<f64>, frequency_p: Option<f64>, white_p: Option<f64>| {
        plausible_noise
            && fit_p.is_some_and(|p| p >= FIT_ALPHA)
            && frequency_p.is_some_and(|p| p >= FIT_ALPHA)
            && white_p.is_some_and(|p| p >= FIT_ALPHA)
    };
    let reports: Vec<CandidateReport> = candidates.iter().map(|(c, _)| c.clone()).collect();
    let mut contenders = Vec::new();
    let (verdict, after, selected): (Verdict, &Fitted, Option<String>) = match select(&reports) {
        Some((b, close)) => match &candidates[b] {
            (c, fitted) if explains(c.fit_p_value, c.frequency_p_value, c.whiteness_p_value) => {
                // The frequency-dependent joint has no refit of its own: its "after" is the
                // calibrated invariant joint.
                let after = fitted.unwrap_or(&base);
                if !close.is_empty() {
                    contenders = std::iter::once(b)
                        .chain(close)
                        .map(|i| reports[i].name.clone())
                        .collect();
                    (Verdict::Ambiguous, after, Some(c.name.clone()))
                } else if c.name == frequency_dependence::NAME {
                    (Verdict::FrequencyDependent, after, None)
                } else {
                    (Verdict::Effect, after, Some(c.name.clone()))
                }
            }
            _ => (Verdict::Unexplained, &base, None),
        },
        None if explains(Some(base_p), Some(base_frequency_p), Some(base_white_p)) => {
            (Verdict::None, &base, None)
        }
        None => (Verdict::Unexplained, &base, None),
    };
    let per_mode = settings
        .per_mode
        .unwrap_or_else(|| default_per_mode(model, measured));
    // When no model explains the data, the residual of the largest model is not noise alone:
    // the stated noise stays the yardstick of the per-mode corrections.
    let yardstick = if verdict == Verdict::Unexplained {
        stated
    } else {
        noise
    };
    let per_mode_before = report::per_mode_corrections(&base, measured, yardstick, per_mode);
    let per_mode_after = report::per_mode_corrections(after, measured, yardstick, per_mode);
    let flatness_before = report::flatness(&per_mode_before);
    let mut trend = Vec::new();
    let mut pattern = None;
    if matches!(verdict, Verdict::Unexplained | Verdict::FrequencyDependent) {
        // The paper's view of the same question: the per-mode corrections that trend with
        // frequency (shown, not tested: the verdict stands on the score test above).
        trend = flatness_before
            .iter()
            .filter(|f| f.slope_per_khz.abs() > TREND_SIGMAS * f.slope_se_per_khz)
            .cloned()
            .collect();
        // Where the invariant joint misses.
        pattern = Some(report::ResidualPattern::of(
            &base,
            measured,
            noise,
            estimate.working_floor,
        ));
    }
    let warnings = base
        .pairing
        .model_index
        .iter()
        .zip(measured.modes())
        .filter(|(s, m)| **s != m.mode - 1 + rigid)
        .map(|(s, m)| format!("measured mode {} pairs with model mode {} (MAC): a swapped or missing mode; it is compared with that model mode", m.mode, s + 1 - rigid))
        .collect();
    Ok(Report {
        verdict,
        selected,
        contenders,
        pattern,
        trend,
        criterion: format!(
            "likelihood-ratio test under the noise estimated from the shape residuals of the largest model ({}, {:.0} degrees of freedom: F tests): a candidate is significant when its p-value times {tried} candidates is below {ALPHA}; a model explains the data when its chi^2, its frequencies alone and the whiteness of its shape residuals along the structure all pass at {FIT_ALPHA}; the best is named alone when every other significant candidate is {AMBIGUITY_MARGIN} or more behind it in AIC",
            estimate.from_model, estimate.dof
        ),
        noise: stated,
        initial: ErrorSummary::of(&initial, measured, &estimate),
        before: ErrorSummary::of(&base, measured, &estimate),
        after: ErrorSummary::of(after, measured, &estimate),
        noise_estimate: estimate,
        warnings,
        candidates: candidates.into_iter().map(|(c, _)| c).collect(),
        flatness_before,
        flatness_after: report::flatness(&per_mode_after),
        per_mode_before,
        per_mode_after,
        per_mode_settings: format!(
            "n = {}, m = {}, weighting = {}",
            per_mode.n, per_mode.m, per_mode.weighting
        ),
        shape_floor: fit::SHAPE_FLOOR,
    })
}

/// The selection among fitted candidates: among the significant ones (adjusted p-value below
/// [`ALPHA`]) whose size is plausible, the one with the largest likelihood-ratio statistic,
/// and every other of them less than [`AMBIGUITY_MARGIN`] behind it in AIC (indices into
/// `candidates`; `None` when no candidate is significant).
pub fn select(candidates: &[CandidateReport]) -> Option<(usize, Vec<usize>)> {
    let mut significant: Vec<usize> = (0..candidates.len())
        .filter(|&i| {
            let c = &candidates[i];
            c.error.is_none() && c.excluded.is_none() && c.criterion.is_some_and(|p| p < ALPHA)
        })
        .collect();
    significant.sort_by(|&a, &b| {
        let lrt = |i: usize| candidates[i].lrt.unwrap_or(0.0);
        lrt(b).total_cmp(&lrt(a))
    });
    let (&best, rest) = significant.split_first()?;
    let close = rest
        .iter()
        .copied()
        .filter(|&i| aic(&candidates[i]) - aic(&candidates[best]) < AMBIGUITY_MARGIN)
        .collect();
    Some((best, close))
}

/// Akaike's information criterion of a fitted candidate relative to the joint-only fit
/// (AIC = chi^2 + 2 k with k its effect parameters; the joints' 2 p are common to all).
fn aic(c: &CandidateReport) -> f64 {
    let k = c.parameters.len();
    c.chi2.unwrap_or(f64::INFINITY) + 2.0 * k as f64
}

/// The effect's fitted parameters theta of `fitted` (its estimates after the `joints` joint
/// parameters).
fn effect_theta(fitted: &Fitted, joints: usize) -> Vec<f64> {
    fitted.estimates[joints..].iter().map(|e| e.value).collect()
}

/// Why the fitted theta of `effect` is not a physical explanation, if it is not: a negative
/// value of a non-negative parameter, a theta the calibrated structure does not admit, a size
/// outside the effect's plausible range.
fn implausible(
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

/// A candidate with its fit (or why it failed).
type CandidateFit = (Arc<dyn Effect>, Result<Fitted, FitError>);

/// Every candidate of `library` fitted with the joints.
fn fit_all(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    library: &[Arc<dyn Effect>],
) -> Vec<CandidateFit> {
    library
        .par_iter()
        .map(|c| {
            let result = fit::fit(ctx, measured, calibration, std::slice::from_ref(c));
            (c.clone(), result)
        })
        .collect()
}

/// Every candidate fitted again under `calibration`, each from its fit in `first` (a
/// candidate whose first fit failed starts afresh).
fn refit_all(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    first: &[CandidateFit],
) -> Vec<CandidateFit> {
    first
        .par_iter()
        .map(|(c, earlier)| {
            let effects = std::slice::from_ref(c);
            let result = match earlier {
                Ok(from) => fit::refit(ctx, measured, calibration, effects, from),
                Err(_) => fit::fit(ctx, measured, calibration, effects),
            };
            (c.clone(), result)
        })
        .collect()
}

fn default_per_mode(model: &Structure, measured: &MeasuredModes) -> Settings {
    let fewest = measured
        .modes()
        .iter()
        .map(|m| m.points.len())
        .min()
        .unwrap_or(0);
    let rigid = model.rigid;
    let n = fewest.min(model.dof_count()).max(rigid + 2);
    Settings {
        n,
        m: (n - rigid).min(6),
        weighting: Weighting::Inverse,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::chi2_sf;

    /// A fitted candidate with `k` parameters, chi^2 `chi2` against the joint-only 100.
    fn fitted(name: &str, k: usize, chi2: f64) -> CandidateReport {
        let lrt = 100.0 - chi2;
        CandidateReport {
            name: name.to_string(),
            parameters: (0..k)
                .map(|i| Estimate {
                    name: format!("{name}.{i}"),
                    unit: "",
                    value: 1.0,
                    se: 0.1,
                })
                .collect(),
            size: Some(1.0),
            size_se: Some(0.1),
            describe: String::new(),
            chi2: Some(chi2),
            dof: Some(50),
            lrt: Some(lrt),
            criterion: Some((chi2_sf(lrt, k as f64) * 3.0).min(1.0)),
            fit_p_value: Some(0.5),
            frequency_p_value: Some(0.5),
            whiteness_p_value: Some(0.5),
            summary: None,
            error: None,
            excluded: None,
        }
    }

    #[test]
    fn the_best_is_selected_alone_only_with_a_lead_of_the_margin_in_aic() {
        // Leads of 6.5 and 5.5 in chi^2 at equal k: effect, then ambiguous.
        let clear = [
            fitted("a", 1, 80.0),
            fitted("b", 1, 50.0),
            fitted("c", 1, 56.5),
        ];
        assert_eq!(select(&clear), Some((1, Vec::new())));
        let close = [
            fitted("a", 1, 80.0),
            fitted("b", 1, 50.0),
            fitted("c", 1, 55.5),
        ];
        assert_eq!(select(&close), Some((1, vec![2])));
        // A lead of 9 in chi^2 with 2 more parameters is a lead of 5 in AIC: ambiguous, the
        // one with the larger statistic first.
        let penalised = [fitted("a", 3, 50.0), fitted("b", 1, 59.0)];
        assert_eq!(select(&penalised), Some((0, vec![1])));
        // A runner-up that is not significant does not contend: D = 5 < chi2_1 isf(0.01/2).
        let weak = [fitted("a", 1, 95.0), fitted("b", 1, 99.0)];
        assert_eq!(select(&weak), None);
    }

    #[test]
    fn an_implausible_or_failed_candidate_is_not_selected_nor_contends() {
        let mut heavy = fitted("heavy", 1, 40.0);
        heavy.excluded = Some("heavier than the beams".into());
        let mut failed = fitted("failed", 1, 41.0);
        failed.error = Some("did not converge".into());
        let candidates = [heavy, failed, fitted("light", 1, 50.0)];
        assert_eq!(select(&candidates), Some((2, Vec::new())));
    }

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

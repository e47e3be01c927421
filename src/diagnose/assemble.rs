//! The last step of a diagnosis: the report assembled from the steps' findings: the verdict
//! and the models before and after, the paper's per-mode corrections on both, their trend and
//! the misfit's pattern and what remains of each mode where no model explains the data, what
//! remains beyond the measurement error with a partial explanation, the modes left out, the
//! pairing remarks.

use super::candidate::{Tier, registry};
use super::decide::{Decision, FIT_ALPHA, TREND_SIGMAS};
use super::discrepancy;
use super::fit::{Fitted, Noise, SHAPE_FLOOR};
use super::noise::NoiseEstimate;
use super::report::{
    ErrorSummary, LeftOut, Remainder, Remaining, Report, ResidualPattern, Undetermined, Verdict,
    flatness, per_mode_corrections, remains,
};
use super::score::Scored;
use crate::identify::Settings;
use crate::measured::MeasuredModes;

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
    /// The measured modes left out (no model mode resembles them).
    pub left_out: Vec<LeftOut>,
}

/// The report of a diagnosis from its findings: the verdict and the models before and after,
/// the per-mode corrections on both (under the stated noise when no model explains the data,
/// whose residual is then not noise alone; the data's own errors when they carry them), their
/// trend and the misfit's pattern when the verdict is `unexplained` or `frequency_dependent`,
/// what remains when it is `partial`, and the pairing remarks.
pub fn assemble(f: Findings) -> Report {
    let measured = f.measured;
    let noise = f.estimate.working;
    let decision = &f.decision;
    let best = decision.best.map(|b| &f.scored[b]);
    let after = best.and_then(|s| s.model.as_ref()).unwrap_or(f.base);
    let selected = best.map(|s| s.report.name.clone());
    let misfit_remains = matches!(decision.verdict, Verdict::Unexplained | Verdict::Partial);
    let yardstick = if misfit_remains && !f.estimate.from_data {
        f.stated
    } else {
        noise
    };
    let per_mode_before = per_mode_corrections(f.base, measured, yardstick, f.per_mode);
    // No cause selected: the model after is the calibrated one, whose table is the same.
    let per_mode_after = if std::ptr::eq(after, f.base) {
        per_mode_before.clone()
    } else {
        per_mode_corrections(after, measured, yardstick, f.per_mode)
    };
    let flatness_before = flatness(&per_mode_before);
    let (mut trend, mut pattern, mut remaining) = (Vec::new(), None, Vec::new());
    if decision.verdict == Verdict::Unexplained {
        pattern = Some(ResidualPattern::of(
            f.base,
            measured,
            noise,
            f.estimate.working_floor,
        ));
        remaining = what_remains(&f);
    }
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
    }
    let before = ErrorSummary::of(f.base, measured, &f.estimate);
    let after_summary = ErrorSummary::of(after, measured, &f.estimate);
    let remainder = (decision.verdict == Verdict::Partial).then(|| {
        remainder(
            &f,
            selected.as_deref().unwrap_or_default(),
            after,
            before.chi2,
            &after_summary,
        )
    });
    Report {
        verdict: decision.verdict,
        causes: selected
            .as_deref()
            .map(|s| s.split(" + ").map(str::to_string).collect())
            .unwrap_or_default(),
        selected,
        contenders: decision
            .contenders
            .iter()
            .map(|&i| f.scored[i].report.name.clone())
            .collect(),
        discrepancy: after.discrepancy.clone(),
        undetermined: undetermined(after, measured),
        remaining: remainder,
        left_out: f.left_out.clone(),
        pattern,
        remains: remaining,
        trend,
        criterion: f.criterion.clone(),
        noise: f.stated,
        initial: ErrorSummary::of(f.initial, measured, &f.estimate),
        before,
        after: after_summary,
        warnings: pairing_remarks(f.base, measured),
        noise_estimate: f.estimate.clone(),
        candidates: f.scored.iter().map(|s| s.report.clone()).collect(),
        flatness_before,
        flatness_after: flatness(&per_mode_after),
        per_mode_before,
        per_mode_after,
        per_mode_settings: format!(
            "n = {}, m = {}, weighting = {}",
            f.per_mode.n, f.per_mode.m, f.per_mode.weighting
        ),
        shape_floor: SHAPE_FLOOR,
        reference: None,
        hypotheses: f.hypotheses,
        reduction: None,
    }
}

/// What remains beyond the measurement error with the named model `after` (`name`): the
/// share of the joint-only fit's chi^2 `before` it removes, the modes that still miss and
/// where.
fn remainder(
    f: &Findings,
    name: &str,
    after: &Fitted,
    before: f64,
    summary: &ErrorSummary,
) -> Remainder {
    Remainder {
        // A model fitted with its own discrepancy may trade one kind of misfit for another
        // and end above the joint-only fit's chi^2: it removes nothing of it then.
        removed: if before > 0.0 {
            (1.0 - summary.chi2 / before).clamp(0.0, 1.0)
        } else {
            0.0
        },
        chi2: summary.chi2,
        dof: summary.dof,
        modes: remains(
            &[(name, after)],
            f.measured,
            (&f.estimate, FIT_ALPHA),
            extended_tried(f),
        ),
        pattern: ResidualPattern::of(
            after,
            f.measured,
            f.estimate.working,
            f.estimate.working_floor,
        ),
    }
}

/// The kinds of quantity whose discrepancy `fitted` could not estimate.
fn undetermined(fitted: &Fitted, measured: &MeasuredModes) -> Vec<Undetermined> {
    let (f, s) = discrepancy::residual_dof(fitted, measured);
    let n_f = measured.modes().len();
    let n_s = measured.modes().iter().map(|m| m.points.len()).sum();
    [("frequency", n_f, f), ("shape", n_s, s)]
        .into_iter()
        .filter(|&(_, _, dof)| dof < discrepancy::LEAST_DOF)
        .map(|(kind, values, dof)| Undetermined { kind, values, dof })
        .collect()
}

/// Whether the extended library was searched.
fn extended_tried(f: &Findings) -> bool {
    let extended: Vec<&str> = registry()
        .iter()
        .filter(|c| c.tier() == Tier::Extended)
        .map(|c| c.name())
        .collect();
    f.scored
        .iter()
        .any(|s| extended.contains(&s.report.name.as_str()))
}

/// What remains of every mode with the joint-only fit and with every candidate that has a
/// physical model of its own.
fn what_remains(f: &Findings) -> Vec<Remaining> {
    let models: Vec<(&str, &Fitted)> = std::iter::once(("joint only", f.base))
        .chain(f.scored.iter().filter_map(|s| {
            let usable = s.report.error.is_none() && s.report.excluded.is_none();
            Some((s.report.name.as_str(), s.model.as_ref().filter(|_| usable)?))
        }))
        .collect();
    remains(
        &models,
        f.measured,
        (&f.estimate, FIT_ALPHA),
        extended_tried(f),
    )
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

//! Which noise judges the candidates of data without standard errors: the residual scale of a
//! model that fits, never that of one that does not.
//!
//! The largest physical model fitted under the stated noise (the smallest chi^2, when below
//! the joint-only fit's; else the joint-only fit) gives the noise estimate
//! ([`super::noise::estimate`] of its residuals) when it is *adequate*: when its residuals,
//! refitted under that estimate, pass the checks that do not stand on the noise level, each
//! at [`FIT_ALPHA`]:
//! - the whiteness of its shape residuals along the structure ([`whiteness`]: smooth
//!   residuals are misfit, whatever their size);
//! - its frequency residuals against the frequency noise its own shape residuals imply (the
//!   stated frequency noise times the factor by which the shape statement was off: one
//!   misstatement of the instrument's quality affects both alike);
//! - a residual scale within [`LARGEST_FACTOR`] of the stated.
//!
//! Its residual scale is the smallest any model reaches: a smaller model's, larger, would make
//! every model look better than the largest one does at its own scale. When the largest model
//! is not adequate, what every model leaves is not noise alone, and no residual scale may
//! become the yardstick: the stated noise is kept, the largest model's estimate is
//! reported as the check, and a candidate explains the data only when it fits under the
//! stated noise. The statement is taken as known to the precision the data could have
//! checked it: the tests stay F tests on the check's degrees of freedom. A misstated noise then costs, at worst, an `unexplained`
//! verdict where the effect lies outside the library; an effect of the library, which fits,
//! is judged under its own residual scale.

use super::candidate::{Stage, Tried};
use super::decide::FIT_ALPHA;
use super::fit::{self, Calibration, Noise, Residuals, SHAPE_FLOOR, residuals};
use super::noise::{LARGEST_FACTOR, NoiseEstimate, estimate};
use super::whiteness;

/// The name of the joint-only fit among the models.
const JOINT_ONLY: &str = "joint only";

/// What the choice needs of a fitted model: its residuals and its unknowns besides the
/// shape scales.
struct Leaves {
    residuals: Residuals,
    unknowns: usize,
}

/// The noise that judges the candidates (see the module docs): the estimate of the largest
/// model (the smallest chi^2, below the joint-only fit's, among the candidates of `first`
/// fitted on the stage `first_stage` under the stated noise, that have a model of their own
/// and a physical size; else the joint-only fit) when it is adequate; else the stated noise,
/// that estimate kept as the check.
pub fn choose(first: &[Tried], first_stage: &Stage) -> NoiseEstimate {
    let base = first_stage.base;
    let stated = first_stage.calibration.noise;
    let largest = first
        .iter()
        .enumerate()
        .filter_map(|(i, (_, outcome))| {
            let fit = outcome
                .as_ref()
                .ok()
                .filter(|f| f.excluded.is_none() && f.model.is_some())?;
            (fit.chi2 < base.chi2).then_some((i, fit))
        })
        .min_by(|a, b| a.1.chi2.total_cmp(&b.1.chi2));
    let (i, leaves) = match largest {
        Some((i, fit)) => (
            Some(i),
            Leaves {
                residuals: fit.residuals.clone(),
                unknowns: fit.unknowns,
            },
        ),
        None => (
            None,
            Leaves {
                residuals: residuals(base, first_stage.measured),
                unknowns: base.estimates.len(),
            },
        ),
    };
    let e = estimate(
        &leaves.residuals,
        first_stage.measured,
        leaves.unknowns,
        stated,
        SHAPE_FLOOR,
        i.map_or(JOINT_ONLY, |i| first[i].0.name()),
    );
    if refitted(first, first_stage, i, &e).is_some_and(|l| adequate(&e, &l, first_stage)) {
        e
    } else {
        stated_yardstick(e, stated)
    }
}

/// Candidate `i` of `first` (the joint-only fit for None) fitted again under the noise `e`
/// estimated from it, as the selection would fit it; None when a fit fails (the model is then
/// not adequate).
fn refitted(first: &[Tried], stage: &Stage, i: Option<usize>, e: &NoiseEstimate) -> Option<Leaves> {
    let calibration = Calibration {
        noise: e.working,
        pairing: stage.calibration.pairing.clone(),
        shape_floor: e.working_floor,
        measured_std: false,
    };
    let base = fit::refit(stage.ctx, stage.measured, &calibration, &[], stage.base).ok()?;
    let Some((candidate, Ok(earlier))) = i.and_then(|i| first.get(i)) else {
        return Some(Leaves {
            residuals: residuals(&base, stage.measured),
            unknowns: base.estimates.len(),
        });
    };
    let stage = Stage {
        calibration: &calibration,
        base: &base,
        ..*stage
    };
    let fit = candidate.fit(&stage, Some(earlier)).ok()?;
    Some(Leaves {
        residuals: fit.residuals,
        unknowns: fit.unknowns,
    })
}

/// Whether what a model leaves, refitted under the noise `e`, passes the checks that do not
/// stand on the noise level.
fn adequate(e: &NoiseEstimate, leaves: &Leaves, stage: &Stage) -> bool {
    let res = &leaves.residuals;
    let frequency = e.frequency_lack_of_fit(res, leaves.unknowns).2;
    let white = whiteness::of_residuals(res, stage.measured, e.working, e.working_floor).p_value;
    e.shape_factor <= LARGEST_FACTOR && frequency >= FIT_ALPHA && white >= FIT_ALPHA
}

/// The stated noise as the yardstick, `check` (the largest model's estimate) kept as the
/// check. The statement is taken as known to the precision the data could have checked it:
/// the tests stay F tests on the check's degrees of freedom. The scale is the stated; the
/// shape of the variance function (the floor relative to the relative part, b / a) is kept
/// from the check, whose misfit inflates a and b alike.
fn stated_yardstick(check: NoiseEstimate, stated: Noise) -> NoiseEstimate {
    NoiseEstimate {
        working: stated,
        frequency_estimated: false,
        stated_kept: true,
        ..check
    }
}

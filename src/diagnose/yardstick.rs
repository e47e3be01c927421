//! Which noise judges the candidates of data without standard errors: the residual scale of a
//! model that fits, never that of one that does not.
//!
//! The largest physical model fitted under the stated noise (the smallest chi^2, when below
//! the joint-only fit's by more than [`TIE`] of it; else the joint-only fit) gives the noise
//! estimate ([`super::noise::estimate`] of its residuals) when it is *adequate*: when its
//! residuals, refitted under that estimate, pass the checks that do not stand on the noise
//! level, each at [`FIT_ALPHA`]:
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

use super::candidate::{Fit, Stage, Tried, tell_fitted};
use super::decide::FIT_ALPHA;
use super::fit::{self, Calibration, Fitted, Noise, Residuals, SHAPE_FLOOR, residuals};
use super::noise::{LARGEST_FACTOR, NoiseEstimate, estimate};
use super::progress::{Pass, Step};
use super::report::Verdict;
use super::whiteness;
use crate::measured::MeasuredModes;
use crate::optim::Silent;

/// Relative chi^2 difference within which a candidate is the joint-only fit as far as the
/// fits can tell (a candidate at the bound where it is the joint-only model, such as a mass of
/// 0): two fits of one model end within the solver's decrement tolerance, 1e-8 of the cost,
/// and which of two such ends is lower is the solver's path, not the data.
pub const TIE: f64 = 1e-6;

/// The name of the joint-only fit among the models.
const JOINT_ONLY: &str = "joint only";

/// The noise that judges the candidates ([`choose`]), and the fits its check made under it.
pub struct Chosen {
    /// The estimate; its working noise judges the candidates.
    pub estimate: NoiseEstimate,
    /// The check's fits, when the estimate was adopted (the stated noise kept: None).
    pub checked: Option<Checked>,
}

/// What the noise check fitted under an estimate: the joint-only fit and the largest model,
/// each from the stage's optimum. Under that estimate as the working noise, these are the
/// working pass's own fits (the same model, calibration and start), which it need not make
/// again: on a solid of 2e5 DOFs the joint's calibration alone takes minutes.
pub struct Checked {
    /// The calibration they were fitted under.
    pub calibration: Calibration,
    /// The joint-only fit.
    pub base: Fitted,
    /// The largest model's fit when it is a candidate: its index in the stage's fits, the fit.
    pub candidate: Option<(usize, Fit)>,
}

impl Checked {
    /// What the largest model leaves: its residuals and its unknowns besides the shape scales.
    fn leaves(&self, measured: &MeasuredModes) -> (Residuals, usize) {
        match &self.candidate {
            Some((_, fit)) => (fit.residuals.clone(), fit.unknowns),
            None => (residuals(&self.base, measured), self.base.estimates.len()),
        }
    }
}

/// The largest physical model of a stage: the candidate with the smallest chi^2 among those
/// of `first` that have a static model of their own and a physical size, when below the
/// joint-only fit `base`'s by more than [`TIE`] of it; else `base`. Its residual scale is the smallest any model reaches.
/// The frequency-dependent joint is not one: its exponents act on every mode's frequency and
/// fit a smooth trend of the frequencies with the mode whatever its cause, so that its
/// residual scale would pass a static misfit as noise; it is judged under the yardstick of
/// the static models.
#[derive(Debug, Clone, Copy)]
pub struct Largest<'a> {
    /// Its index in `first`; None for the joint-only fit.
    pub index: Option<usize>,
    /// Its name (`joint only` for the joint-only fit).
    pub name: &'static str,
    /// The fitted model.
    pub fitted: &'a Fitted,
}

/// The largest physical model of `first` and `base` ([`Largest`]).
pub fn largest<'a>(first: &'a [Tried], base: &'a Fitted) -> Largest<'a> {
    first
        .iter()
        .enumerate()
        .filter(|(_, (candidate, _))| candidate.verdict() != Verdict::FrequencyDependent)
        .filter_map(|(i, (candidate, outcome))| {
            let fit = outcome.as_ref().ok().filter(|f| f.excluded.is_none())?;
            let fitted = fit
                .model
                .as_ref()
                .filter(|m| m.chi2 < base.chi2 * (1.0 - TIE))?;
            Some(Largest {
                index: Some(i),
                name: candidate.name(),
                fitted,
            })
        })
        .min_by(|a, b| a.fitted.chi2.total_cmp(&b.fitted.chi2))
        .unwrap_or(Largest {
            index: None,
            name: JOINT_ONLY,
            fitted: base,
        })
}

/// The noise that judges the candidates (see the module docs): the estimate of the
/// [`largest`] model of `first` (fitted on the stage `first_stage`, under the stated noise)
/// when it is adequate, with the check's fits; else the stated noise, that estimate kept as
/// the check.
pub fn choose(first: &[Tried], first_stage: &Stage) -> Chosen {
    let stated = first_stage.calibration.noise;
    let largest = largest(first, first_stage.base);
    let e = estimate(
        &residuals(largest.fitted, first_stage.measured),
        first_stage.measured,
        largest.fitted.estimates.len(),
        stated,
        SHAPE_FLOOR,
        largest.name,
    );
    let checked = refitted(first, first_stage, largest.index, &e);
    let adopted = checked.as_ref().is_some_and(|c| {
        let (residuals, unknowns) = c.leaves(first_stage.measured);
        adequate(&e, &residuals, unknowns, first_stage)
    });
    if adopted {
        Chosen {
            estimate: e,
            checked,
        }
    } else {
        Chosen {
            estimate: stated_yardstick(e, stated),
            checked: None,
        }
    }
}

/// Candidate `i` of `first` (the joint-only fit for None) fitted again under the noise `e`
/// estimated from it, as the selection would fit it, with the joint-only fit it extends;
/// None when a fit fails (the model is then not adequate).
fn refitted(
    first: &[Tried],
    stage: &Stage,
    i: Option<usize>,
    e: &NoiseEstimate,
) -> Option<Checked> {
    let calibration = Calibration {
        noise: e.working,
        pairing: stage.calibration.pairing.clone(),
        shape_floor: e.working_floor,
        measured_std: false,
    };
    let watch = stage.watch.during(Pass::NoiseCheck);
    let base = fit::refit(
        stage.ctx,
        stage.measured,
        &calibration,
        &[],
        stage.base,
        &mut Silent,
    )
    .ok()?;
    watch.tell(&Step::Calibrated {
        chi2: base.chi2,
        iterations: base.iterations,
    });
    let (index, candidate, earlier) = match i.and_then(|i| Some((i, first.get(i)?))) {
        Some((index, (candidate, Ok(earlier)))) => (index, candidate, earlier),
        _ => {
            return Some(Checked {
                calibration,
                base,
                candidate: None,
            });
        }
    };
    let refit_stage = Stage {
        calibration: &calibration,
        base: &base,
        estimate: Some(e),
        watch,
        ..*stage
    };
    let fit = candidate.fit(&refit_stage, Some(earlier));
    tell_fitted(&watch, candidate.as_ref(), &fit);
    let fit = fit.ok()?;
    Some(Checked {
        calibration,
        base,
        candidate: Some((index, fit)),
    })
}

/// Whether what a model leaves, refitted under the noise `e` (its residuals `res`, its
/// `unknowns` besides the shape scales), passes the checks that do not stand on the noise
/// level.
fn adequate(e: &NoiseEstimate, res: &Residuals, unknowns: usize, stage: &Stage) -> bool {
    let frequency = e.frequency_lack_of_fit(res, unknowns).2;
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

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::candidate::{fit_all, library, registry};
    use crate::diagnose::progress::Watch;

    /// Where the estimate is adopted, the check's fits are what the working pass would fit:
    /// the joint-only calibration and the largest model refitted under the working noise from
    /// the same starts give the same optima to the last bit, so the pass may take them as
    /// they are. The data (shear 0.5 in the model, so shear is the largest model) fit.
    #[test]
    fn the_checks_fits_are_the_working_passs_own() {
        let (measured, _, ctx, stated) = crate::diagnose::fit::tests::fixture();
        let base = fit::fit(&ctx, &measured, &stated, &[], &mut Silent).unwrap();
        let library = library(&ctx, false);
        let stage = Stage {
            ctx: &ctx,
            measured: &measured,
            calibration: &stated,
            base: &base,
            estimate: None,
            watch: Watch::silent(),
        };
        let first = fit_all(&library, &stage, None, None);
        let chosen = choose(&first, &stage);
        let checked = chosen
            .checked
            .expect("the largest model fits: the estimate is adopted");
        let (index, checked_fit) = checked.candidate.expect("a candidate is the largest model");
        assert_eq!(library[index].name(), "shear");
        let working = Calibration {
            noise: chosen.estimate.working,
            pairing: stated.pairing.clone(),
            shape_floor: chosen.estimate.working_floor,
            measured_std: false,
        };
        assert_eq!(checked.calibration, working);
        let again = fit::refit(&ctx, &measured, &working, &[], &base, &mut Silent).unwrap();
        assert_eq!(again.solution, checked.base.solution);
        assert_eq!(again.chi2.to_bits(), checked.base.chi2.to_bits());
        let stage = Stage {
            calibration: &working,
            base: &again,
            estimate: Some(&chosen.estimate),
            ..stage
        };
        let refitted = library[index]
            .fit(&stage, first[index].1.as_ref().ok())
            .unwrap();
        assert_eq!(refitted.chi2.to_bits(), checked_fit.chi2.to_bits());
        assert_eq!(
            refitted.model.unwrap().solution,
            checked_fit.model.unwrap().solution
        );
    }

    /// A candidate whose chi^2 is below the joint-only fit's by less than [`TIE`] of it (the
    /// same model to the solver's precision, as a mass at its bound 0) leaves the joint-only
    /// fit the largest model; one below by more is the largest.
    #[test]
    fn a_candidate_tied_with_the_joint_only_fit_is_not_the_largest() {
        let (measured, _, ctx, calibration) = crate::diagnose::fit::tests::fixture();
        let base = fit::fit(&ctx, &measured, &calibration, &[], &mut Silent).unwrap();
        let mass = registry()
            .into_iter()
            .find(|c| c.name() == "sensor_mass")
            .unwrap();
        let tried = |chi2: f64| -> Vec<Tried> {
            let mut model = base.clone();
            model.chi2 = chi2;
            let fit = Fit {
                parameters: Vec::new(),
                size: (0.0, 1.0),
                describe: String::new(),
                chi2,
                dof: model.dof - 1,
                lrt: base.chi2 - chi2,
                added: 1,
                unknowns: model.estimates.len() + 1,
                residuals: residuals(&model, &measured),
                model: Some(model),
                excluded: None,
                profile: None,
                members: Vec::new(),
            };
            vec![(mass.clone(), Ok(fit))]
        };
        let tied = tried(base.chi2 * (1.0 - 0.1 * TIE));
        assert_eq!(largest(&tied, &base).name, JOINT_ONLY);
        let lower = tried(base.chi2 * (1.0 - 10.0 * TIE));
        let chosen = largest(&lower, &base);
        assert_eq!((chosen.name, chosen.index), ("sensor_mass", Some(0)));
    }
}

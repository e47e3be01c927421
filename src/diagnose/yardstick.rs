//! The yardstick of adequacy: the measurement error every model is judged against when the
//! question is whether it fits (module `decide`), after the search has found which explains
//! best.
//!
//! Data with their own standard errors are judged by them ([`super::noise::from_data`]: the
//! residuals of the largest model are the check). Otherwise the largest physical model (the
//! search's: `super::search::Search::largest`) gives the noise estimate ([`super::noise::estimate`] of its residuals), which becomes the
//! yardstick when its residuals pass the checks that do not stand on the noise level, each at
//! [`FIT_ALPHA`]:
//! - the whiteness of its shape residuals along the structure ([`whiteness`]: smooth
//!   residuals are misfit, whatever their size);
//! - its frequency residuals against the frequency noise its own shape residuals imply (the
//!   stated frequency noise times the factor by which the shape statement was off: one
//!   misstatement of the instrument's quality affects both alike);
//! - a residual scale within [`LARGEST_FACTOR`] of the stated, its floor included
//!   ([`NoiseEstimate::plausible`]).
//!
//! Its residual scale is the smallest any model reaches: a smaller model's, larger, would make
//! every model look better than the largest one does at its own scale. When it does not pass,
//! what every model leaves is not noise alone and no residual scale may become the yardstick:
//! the stated noise is kept (taken as known to the precision the data could have checked it:
//! the tests stay F tests on the estimate's degrees of freedom), the estimate is reported as
//! the check. The frequency-dependent joint never gives the yardstick: its exponents fit any
//! smooth trend of the frequencies with the mode whatever its cause.
//!
//! Nothing is fitted here: the models' residuals are read as the search left them. The search
//! asks the same question of each model it would extend ([`adequate`]): causes are added only
//! while the model does not fit within the measurement error.

use super::decide::{FIT_ALPHA, Judgement};
use super::fit::{Calibration, Fitted, Noise, Residuals, SHAPE_FLOOR, chi2_of, residuals};
use super::noise::{LARGEST_FACTOR, NoiseEstimate, estimate, from_data};
use super::whiteness;
use crate::measured::MeasuredModes;

/// The yardstick the model `fitted` (named `name`) gives on `measured` (module docs),
/// `calibration` the measurement error (the stated noise or the data's standard errors).
pub fn of_model(
    name: &str,
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> NoiseEstimate {
    if calibration.measured_std {
        return from_data(name, fitted, measured, calibration);
    }
    let stated = calibration.noise;
    let res = residuals(fitted, measured);
    let e = estimate(
        &res,
        measured,
        fitted.estimates.len(),
        stated,
        SHAPE_FLOOR,
        name,
    );
    let frequency = e.frequency_lack_of_fit(&res, fitted.estimates.len()).2;
    let white = whiteness::of_residuals(&res, measured, e.working, e.working_floor).p_value;
    if e.plausible() && frequency >= FIT_ALPHA && white >= FIT_ALPHA {
        e
    } else {
        stated_yardstick(e, stated)
    }
}

/// The judgement under the yardstick `e` of residuals `res` of a model with `unknowns`
/// parameters besides the shape scales and `dof` degrees of freedom, with their chi^2 under it.
pub fn judgement(
    e: &NoiseEstimate,
    measured: &MeasuredModes,
    res: &Residuals,
    unknowns: usize,
    dof: usize,
) -> (f64, Judgement) {
    let chi2 = chi2_of(res, measured, &e.calibration());
    let judgement = Judgement {
        fit: Some(e.fit_p_value(chi2, dof)),
        frequency: Some(e.frequency_lack_of_fit(res, unknowns).2),
        whiteness: Some(whiteness::of_residuals(res, measured, e.working, e.working_floor).p_value),
    };
    (chi2, judgement)
}

/// Whether `fitted` explains `measured` within the measurement error, judged under the
/// yardstick it gives itself.
pub fn adequate(
    name: &str,
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> bool {
    let e = of_model(name, fitted, measured, calibration);
    let res = residuals(fitted, measured);
    judgement(&e, measured, &res, fitted.estimates.len(), fitted.dof)
        .1
        .explains(&e)
}

/// The stated noise as the yardstick, `check` (the largest model's estimate) kept as the
/// check. The statement is taken as known to the precision the data could have checked it:
/// the tests stay F tests on the check's degrees of freedom. The scale is the stated; the
/// shape of the variance function (the floor relative to the relative part, b / a) is kept
/// from the check, whose misfit inflates a and b alike, unless the check's level, floor
/// included, is beyond [`LARGEST_FACTOR`] of the stated: a floor that large is misfit the
/// variance function put into b (a at its smallest), and the stated floor is kept.
fn stated_yardstick(check: NoiseEstimate, stated: Noise) -> NoiseEstimate {
    let working_floor = if check.level_factor > LARGEST_FACTOR {
        SHAPE_FLOOR
    } else {
        check.working_floor
    };
    NoiseEstimate {
        working: stated,
        frequency_estimated: false,
        stated_kept: true,
        working_floor,
        ..check
    }
}

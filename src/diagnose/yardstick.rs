//! The yardstick of adequacy: the measurement error every model is judged against when the
//! question is whether it fits (module `decide`), after the search has found which explains
//! best.
//!
//! Data with their own standard errors are judged by them ([`super::noise::from_data`]: the
//! residuals of the largest model are the check). Otherwise the largest physical model (the
//! last model of the search's path when it is static, else the static candidate of least
//! deviance when below the joint-only fit's by more than [`TIE`] of it, else the joint-only fit)
//! gives the noise estimate ([`super::noise::estimate`] of its residuals), which becomes the
//! yardstick when its residuals pass the checks that do not stand on the noise level, each at
//! [`FIT_ALPHA`]:
//! - the whiteness of its shape residuals along the structure ([`whiteness`]: smooth
//!   residuals are misfit, whatever their size);
//! - its frequency residuals against the frequency noise its own shape residuals imply (the
//!   stated frequency noise times the factor by which the shape statement was off: one
//!   misstatement of the instrument's quality affects both alike);
//! - a residual scale within [`LARGEST_FACTOR`] of the stated.
//!
//! Its residual scale is the smallest any model reaches: a smaller model's, larger, would make
//! every model look better than the largest one does at its own scale. When it does not pass,
//! what every model leaves is not noise alone and no residual scale may become the yardstick:
//! the stated noise is kept (taken as known to the precision the data could have checked it:
//! the tests stay F tests on the estimate's degrees of freedom), the estimate is reported as
//! the check. The frequency-dependent joint never gives the yardstick: its exponents fit any
//! smooth trend of the frequencies with the mode whatever its cause.
//!
//! Nothing is fitted here: the models' residuals are read as the search left them.

use super::decide::FIT_ALPHA;
use super::fit::{Calibration, Fitted, Noise, SHAPE_FLOOR, residuals};
use super::noise::{LARGEST_FACTOR, NoiseEstimate, estimate, from_data};
use super::report::Verdict;
use super::search::Search;
use super::whiteness;
use crate::measured::MeasuredModes;

/// Relative deviance difference within which a candidate is the joint-only fit as far as the
/// fits can tell (a candidate at the bound where it is the joint-only model, such as a mass of
/// 0): two fits of one model end within the solver's decrement tolerance, 1e-8 of the cost,
/// and which of two such ends is lower is the solver's path, not the data.
pub const TIE: f64 = 1e-6;

/// The name of the joint-only fit among the models.
const JOINT_ONLY: &str = "joint only";

/// The largest physical model of a search (module docs): its name and fitted model.
pub fn largest<'a>(search: &'a Search, base: &'a Fitted) -> (&'a str, &'a Fitted) {
    let stands = |i: usize| search.models[i].verdict != Verdict::FrequencyDependent;
    let usable = |i: usize| {
        let m = &search.models[i];
        let fit = m.fit().filter(|f| f.excluded.is_none())?;
        Some((m.name.as_str(), fit.model.as_ref()?))
    };
    if let Some(found) = search
        .path
        .models
        .last()
        .filter(|&&i| stands(i))
        .and_then(|&i| usable(i))
    {
        return found;
    }
    (0..search.models.len())
        .filter(|&i| stands(i))
        .filter_map(usable)
        .filter(|(_, f)| f.deviance < base.deviance - TIE * base.deviance.abs())
        .min_by(|a, b| a.1.deviance.total_cmp(&b.1.deviance))
        .unwrap_or((JOINT_ONLY, base))
}

/// The yardstick of `search` on `measured` (module docs), `calibration` the measurement error
/// (the stated noise or the data's standard errors).
pub fn choose(
    search: &Search,
    base: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> NoiseEstimate {
    let (name, fitted) = largest(search, base);
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
    if e.shape_factor <= LARGEST_FACTOR && frequency >= FIT_ALPHA && white >= FIT_ALPHA {
        e
    } else {
        stated_yardstick(e, stated)
    }
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

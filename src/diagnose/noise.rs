//! The measurement noise estimated from the data: the residuals of the largest model fitted
//! (the candidate with the smallest chi^2 under the stated noise), so that the selection does
//! not stand on a noise level nobody knows well.
//!
//! Shapes (each mode scaled to a peak of 1, u_j the measured component, e_j the residual of
//! the fit): the variance function
//!
//! ```text
//!   Var e_j = a^2 u_j^2 + b^2      (a: relative part, b: additive floor)
//! ```
//!
//! is fitted to e_j^2 by iteratively reweighted least squares (weights 1 / v_j^2, since
//! Var e_j^2 = 2 v_j^2 for Gaussian errors: the quasi-likelihood of a gamma GLM with identity
//! link, McCullagh & Nelder, "Generalized Linear Models", ch. 8), a^2, b^2 >= 0, and scaled by
//! n / (n - p_s) for the unknowns the fit spent on the shapes (the shape scales c_r and a
//! share of the model's parameters proportional to the shape values).
//!
//! Frequencies: the relative residuals give s_f^2 = sum e_f^2 / (n_f - p_f) (p_f the
//! frequencies' share of the model's parameters). With 4-10 modes this has few degrees of
//! freedom, so it is a check, not the working value: the working frequency noise is the stated
//! one times the factor a / sigma_s by which the shape statement was off (one misstatement of
//! the instrument's quality affects both alike). Lack of fit then shows in the frequency
//! residuals against that scale, the trustworthy part of the data.

use serde::Serialize;

use super::fit::{Fitted, Noise, residuals};
use crate::measured::MeasuredModes;

/// Smallest relative shape noise the estimate returns, as a fraction of the stated (a fit
/// that interpolates the shapes must not make the noise vanish).
pub const SMALLEST_FACTOR: f64 = 0.25;

/// The noise estimated from the residuals of a fitted model, beside the stated noise.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct NoiseEstimate {
    /// The model whose residuals gave the estimate (`joint only` or a candidate's name).
    pub from_model: String,
    /// Relative part a of the shape noise (standard deviation per unit component).
    pub shape: f64,
    /// Additive floor b of the shape noise, as a fraction of the mode's peak.
    pub shape_floor_abs: f64,
    /// Relative frequency noise from the frequency residuals alone (the check).
    pub frequency_check: f64,
    /// The working noise of the selection: shape a with floor b / a, frequency the stated
    /// times a / sigma_s (stated).
    pub working: Noise,
    /// Working floor b / a, as a fraction of the peak (at least half the stated floor: a
    /// vanishing floor would let components at a node of the mode dominate).
    pub working_floor: f64,
    /// a / sigma_s (stated): how far the shape statement was off.
    pub shape_factor: f64,
    /// s_f / sigma_f (stated).
    pub frequency_factor: f64,
    /// Shape values and frequencies used.
    pub shape_values: usize,
    /// Frequencies used.
    pub frequency_values: usize,
}

/// Estimates the noise from `fitted` (with `unknowns` model parameters besides the shape
/// scales); `stated` with floor `stated_floor` (fraction of the peak) starts the iteration.
pub fn estimate(
    fitted: &Fitted,
    measured: &MeasuredModes,
    unknowns: usize,
    stated: Noise,
    stated_floor: f64,
    from_model: &str,
) -> NoiseEstimate {
    let res = residuals(fitted, measured);
    let n_s = res.shape.len() as f64;
    let n_f = res.frequency.len() as f64;
    let n = n_s + n_f;
    // The model's parameters are shared between frequencies and shapes by their counts; the
    // shape scales are the shapes' own.
    let p_s = measured.modes().len() as f64 + unknowns as f64 * n_s / n;
    let p_f = unknowns as f64 * n_f / n;
    let (a2, b2) = variance_function(
        &res.shape,
        stated.shape * stated.shape,
        (stated.shape * stated_floor).powi(2),
    );
    let dof_s = (n_s - p_s).max(1.0);
    let correction = n_s / dof_s;
    let a = (a2 * correction).sqrt().max(SMALLEST_FACTOR * stated.shape);
    let b = (b2 * correction).sqrt();
    let dof_f = (n_f - p_f).max(1.0);
    let frequency_check = (res.frequency.iter().map(|e| e * e).sum::<f64>() / dof_f).sqrt();
    let shape_factor = a / stated.shape;
    NoiseEstimate {
        from_model: from_model.to_string(),
        shape: a,
        shape_floor_abs: b,
        frequency_check,
        working: Noise {
            frequency: stated.frequency * shape_factor,
            shape: a,
        },
        working_floor: (b / a).max(0.5 * stated_floor),
        shape_factor,
        frequency_factor: frequency_check / stated.frequency,
        shape_values: res.shape.len(),
        frequency_values: res.frequency.len(),
    }
}

/// The variance function Var e = a^2 u^2 + b^2 fitted to the squared residuals e^2 of the
/// pairs (u, e) by iteratively reweighted least squares (weights 1 / v^2), a^2, b^2 >= 0,
/// from (a2, b2); no degrees-of-freedom correction. Returns (a^2, b^2).
pub fn variance_function(pairs: &[(f64, f64)], mut a2: f64, mut b2: f64) -> (f64, f64) {
    for _ in 0..50 {
        let (mut s11, mut s12, mut s22, mut t1, mut t2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for &(u, e) in pairs {
            let v = (a2 * u * u + b2).max(1e-300);
            let w = 1.0 / (v * v);
            let x1 = u * u;
            s11 += w * x1 * x1;
            s12 += w * x1;
            s22 += w;
            t1 += w * x1 * e * e;
            t2 += w * e * e;
        }
        let det = s11 * s22 - s12 * s12;
        let (mut na2, mut nb2) = if det > 1e-12 * s11 * s22 {
            ((t1 * s22 - t2 * s12) / det, (s11 * t2 - s12 * t1) / det)
        } else {
            (t1 / s11.max(1e-300), 0.0)
        };
        if na2 < 0.0 {
            na2 = 0.0;
            nb2 = t2 / s22.max(1e-300);
        } else if nb2 < 0.0 {
            nb2 = 0.0;
            na2 = t1 / s11.max(1e-300);
        }
        let converged = (na2 - a2).abs() <= 1e-10 * (na2 + nb2).max(1e-300)
            && (nb2 - b2).abs() <= 1e-10 * (na2 + nb2).max(1e-300);
        a2 = na2;
        b2 = nb2;
        if converged {
            break;
        }
    }
    (a2, b2)
}

/// Largest factor by which the stated shape noise may be off: an estimate beyond it means the
/// residual is not noise the user could have misjudged, and no model that leaves it explains
/// the data.
pub const LARGEST_FACTOR: f64 = 4.0;

/// The lack of fit of the frequencies of `fitted` (with `unknowns` model parameters) under
/// the working frequency noise: sum of ((f_s - f_m) / (sigma_f f_m))^2, its degrees of
/// freedom n_f - unknowns (at least 1: the joint parameters are fixed mostly by the
/// frequencies, the most precise data), and P(chi^2_dof > it).
pub fn frequency_lack_of_fit(
    fitted: &Fitted,
    measured: &MeasuredModes,
    unknowns: usize,
    working: Noise,
) -> (f64, usize, f64) {
    let res = residuals(fitted, measured);
    let chi2: f64 = res
        .frequency
        .iter()
        .map(|e| (e / working.frequency).powi(2))
        .sum();
    let dof = res.frequency.len().saturating_sub(unknowns).max(1);
    (chi2, dof, crate::stats::chi2_sf(chi2, dof as f64))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Pairs whose squared residuals lie exactly on a^2 u^2 + b^2: the fit returns a^2, b^2
    /// to rounding, from any start.
    #[test]
    fn exact_variance_function_is_recovered() {
        let (a, b) = (0.03, 0.004);
        let pairs: Vec<(f64, f64)> = (0..40)
            .map(|i| {
                let u = -1.0 + 2.0 * f64::from(i) / 39.0;
                (u, (a * a * u * u + b * b).sqrt())
            })
            .collect();
        for start in [(1e-4, 1e-8), (1e-2, 1e-2), (4e-4, 0.0)] {
            let (a2, b2) = variance_function(&pairs, start.0, start.1);
            assert!(
                (a2 - a * a).abs() <= 1e-12 * a * a,
                "a^2 {a2} from {start:?}"
            );
            assert!(
                (b2 - b * b).abs() <= 1e-10 * b * b,
                "b^2 {b2} from {start:?}"
            );
        }
    }

    /// Residuals of a pure relative noise (b = 0): the floor is clamped at zero, not negative.
    #[test]
    fn floor_stays_non_negative() {
        let pairs: Vec<(f64, f64)> = (1..30)
            .map(|i| {
                let u = f64::from(i) / 29.0;
                (u, 0.02 * u * if i % 2 == 0 { 0.9 } else { 1.1 })
            })
            .collect();
        let (a2, b2) = variance_function(&pairs, 4e-4, 1e-6);
        assert!(b2 >= 0.0 && a2 > 0.0, "a^2 {a2}, b^2 {b2}");
        assert!((a2.sqrt() / 0.02 - 1.0).abs() < 0.05, "a {}", a2.sqrt());
    }
}

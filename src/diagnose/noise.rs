//! The measurement noise estimated from the data: the residuals of the largest physical model
//! that fits (chosen by module `diagnose::yardstick`), so that the selection does not stand
//! on a noise level nobody knows well.
//!
//! Shapes (each mode scaled to a peak of 1, u_j the measured component, e_j the residual of
//! the fit): the variance function
//!
//! ```text
//!   Var e_j = a^2 u_j^2 + b^2      (a: relative part, b: additive floor)
//! ```
//!
//! is fitted by iteratively reweighted least squares (weights 1 / v^2, since Var e^2 = 2 v^2
//! for Gaussian errors: the quasi-likelihood of a gamma GLM with identity link, McCullagh &
//! Nelder, "Generalized Linear Models", ch. 8), a^2, b^2 >= 0, to
//! - the squared pseudo-residuals of neighbouring sensors ([`pseudo_residuals`]) where the
//!   sensors are dense along a mode ([`along::Sequence::dense`]): a wrong model's smooth
//!   difference of shapes cancels in them, so it does not pass as noise;
//! - the squared residuals themselves where they are sparse, scaled by n / (n - p) for the
//!   unknowns the fit spent on them (the shape scales c_r and a share of the model's
//!   parameters proportional to the shape values).
//!
//! The estimate's effective degrees of freedom nu ([`pseudo_dof`], plus n - p of the levels)
//! make the tests of module `diagnose` F tests.
//!
//! Frequencies: the relative residuals give s_f^2 = sum e_f^2 / (n_f - p_f) (p_f the
//! frequencies' share of the model's parameters). With 4-10 modes this has few degrees of
//! freedom, so it is a check, not the working value: the working frequency noise is the stated
//! one times the factor a / sigma_s by which the shape statement was off when that exceeds 1
//! (one misstatement of the instrument's quality affects both alike), never below the stated
//! (a handful of frequencies cannot tell a smaller noise from chance). Lack of fit then shows
//! in the frequency residuals against that scale, the trustworthy part of the data.

use serde::Serialize;

use super::along;
use super::fit::{Calibration, Fitted, Noise, Residuals, SHAPE_FLOOR, residuals, sigmas};
use crate::measured::MeasuredModes;
use crate::stats::{chi2_sf, f_sf, lr_sf};

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
    /// Effective degrees of freedom of the shape-noise estimate (nu of the F tests).
    pub dof: f64,
    /// The working noise of the selection: shape a with floor b / a; frequency the stated,
    /// times a / sigma_s (stated) when that exceeds 1.
    pub working: Noise,
    /// Whether the working frequency noise was scaled by the estimate (else it is the
    /// stated, known).
    pub frequency_estimated: bool,
    /// Working floor b / a, as a fraction of the peak, at least the stated floor: the data
    /// show a floor larger than stated (an additive error the statement left out), never a
    /// smaller one. The floor stands on the few components near the modes' nodes, whose
    /// squares cannot tell b = 0 from the stated b (the variance function's fit settles on
    /// the edge b = 0 wherever they are few), and a floor taken too small lets those
    /// components dominate chi^2: under twice the stated noise the true model's chi^2 was 3x
    /// its degrees of freedom with half the stated floor.
    pub working_floor: f64,
    /// a / sigma_s (stated): how far the shape statement was off.
    pub shape_factor: f64,
    /// The level of the estimated shape noise against the stated, floor included
    /// ([`level_factor`]); with the data's standard errors, `shape_factor`.
    pub level_factor: f64,
    /// s_f / sigma_f (stated).
    pub frequency_factor: f64,
    /// Pseudo-residuals of dense sensor sequences used ([`pseudo_residuals`]).
    pub from_differences: usize,
    /// Shape values of sparse sequences used at their levels.
    pub from_levels: usize,
    /// Frequencies used.
    pub frequency_values: usize,
    /// Whether the working noise is the data's own standard errors ([`from_data`]): the
    /// factors are then the check of the residuals against them, not a yardstick.
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub from_data: bool,
    /// Whether no model's residuals passed the checks that do not stand on the noise level,
    /// so that the stated noise is the working noise (known: chi^2 tests) and the estimate
    /// above, the largest model's, is a check only (module `diagnose::yardstick`).
    #[serde(skip_serializing_if = "std::ops::Not::not")]
    pub stated_kept: bool,
    /// With the data's standard errors: the relative standard deviation of each measured
    /// frequency (the working frequency noise is then their RMS, for the summaries).
    #[serde(skip)]
    pub frequency_sigmas: Option<Vec<f64>>,
}

/// The noise of data that carry their own standard errors: they are the working noise (known,
/// so the tests are chi^2 tests: infinite degrees of freedom), and the residuals of the
/// largest physical model `fitted` (named `name`; module `diagnose::yardstick`), fitted under
/// them, give the check:
/// `shape_factor` and `frequency_factor` are the RMS of the weighted shape and frequency
/// residuals, corrected for the unknowns spent on them (1 when the data's errors are right
/// and the model fits). The working noise's `shape` and `frequency` are the RMS relative
/// standard errors, for the summaries that need one number.
pub fn from_data(
    name: &str,
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> NoiseEstimate {
    let (sigma_f, sigma) = sigmas(measured, calibration);
    let res = residuals(fitted, measured);
    let mut shape_chi2 = 0.0;
    let mut relative = Vec::new();
    let mut at = 0;
    for (m, sigma) in measured.modes().iter().zip(&sigma) {
        let peak = m.peak().max(f64::MIN_POSITIVE);
        for s in sigma {
            let (u, e) = res.shape[at];
            shape_chi2 += (e * peak / s).powi(2);
            relative.push(s / (u.abs() * peak).max(SHAPE_FLOOR * peak));
            at += 1;
        }
    }
    let frequency_chi2: f64 = res
        .frequency
        .iter()
        .zip(&sigma_f)
        .map(|(e, s)| (e / s).powi(2))
        .sum();
    let (n_s, n_f) = (res.shape.len() as f64, res.frequency.len() as f64);
    let unknowns = fitted.estimates.len() as f64;
    let p_s = measured.modes().len() as f64 + unknowns * n_s / (n_s + n_f);
    let p_f = unknowns * n_f / (n_s + n_f);
    let shape_factor = (shape_chi2 / (n_s - p_s).max(1.0)).sqrt();
    let frequency_factor = (frequency_chi2 / (n_f - p_f).max(1.0)).sqrt();
    let rms = |v: &[f64]| (v.iter().map(|x| x * x).sum::<f64>() / v.len().max(1) as f64).sqrt();
    let working = Noise {
        frequency: rms(&sigma_f),
        shape: rms(&relative),
    };
    NoiseEstimate {
        from_model: name.to_string(),
        shape: working.shape * shape_factor,
        shape_floor_abs: 0.0,
        frequency_check: working.frequency * frequency_factor,
        dof: f64::INFINITY,
        working,
        frequency_estimated: false,
        working_floor: SHAPE_FLOOR,
        shape_factor,
        level_factor: shape_factor,
        frequency_factor,
        from_differences: 0,
        from_levels: res.shape.len(),
        frequency_values: res.frequency.len(),
        from_data: true,
        stated_kept: false,
        frequency_sigmas: Some(sigma_f),
    }
}

/// Estimates the noise from the residuals `res` of a model (with `unknowns` parameters
/// besides the shape scales); `stated` with floor `stated_floor` (fraction of the peak) starts
/// the iteration.
pub fn estimate(
    res: &Residuals,
    measured: &MeasuredModes,
    unknowns: usize,
    stated: Noise,
    stated_floor: f64,
    from_model: &str,
) -> NoiseEstimate {
    let n_s = res.shape.len() as f64;
    let n_f = res.frequency.len() as f64;
    let n = n_s + n_f;
    let start = (
        stated.shape * stated.shape,
        (stated.shape * stated_floor).powi(2),
    );
    // Dense sequences give pseudo-residuals (a smooth misfit cancels); sparse ones their
    // levels, corrected for the unknowns the fit spent on them: the model's parameters are
    // shared between frequencies and shapes by their counts, the shape scales are the
    // shapes' own.
    let (dense, sparse): (Vec<along::Sequence>, Vec<along::Sequence>) =
        along::of_residuals(res, measured)
            .into_iter()
            .partition(along::Sequence::dense);
    let mut rows = pseudo_residuals(&dense);
    let from_differences = rows.len();
    let from_levels: usize = sparse.iter().map(|s| s.e.len()).sum();
    let p_s = measured.modes().len() as f64 + unknowns as f64 * n_s / n;
    let spent = p_s * from_levels as f64 / n_s;
    let correction = from_levels as f64 / (from_levels as f64 - spent).max(1.0);
    rows.extend(
        sparse
            .iter()
            .flat_map(|s| level_rows(s.u.iter().copied().zip(s.e.iter().copied()), correction)),
    );
    let (a2, b2) = variance_function(&rows, start.0, start.1);
    let dof = (pseudo_dof(&dense, a2, b2) + (from_levels as f64 - spent) - 1.0).max(1.0);
    let a = a2.sqrt().max(SMALLEST_FACTOR * stated.shape);
    let b = b2.sqrt();
    let p_f = unknowns as f64 * n_f / n;
    let dof_f = (n_f - p_f).max(1.0);
    let frequency_check = (res.frequency.iter().map(|e| e * e).sum::<f64>() / dof_f).sqrt();
    let shape_factor = a / stated.shape;
    let level_factor = level_factor(&res.shape, (a, b), stated.shape, stated_floor);
    NoiseEstimate {
        from_model: from_model.to_string(),
        shape: a,
        shape_floor_abs: b,
        frequency_check,
        dof,
        working: Noise {
            frequency: stated.frequency * shape_factor.max(1.0),
            shape: a,
        },
        frequency_estimated: shape_factor > 1.0,
        working_floor: (b / a).max(stated_floor),
        shape_factor,
        level_factor,
        frequency_factor: frequency_check / stated.frequency,
        from_differences,
        from_levels,
        frequency_values: res.frequency.len(),
        from_data: false,
        stated_kept: false,
        frequency_sigmas: None,
    }
}

/// The root of the mean estimated shape variance over the mean stated one, at the shape
/// components `shape` ((u, e) as fractions of their mode's peak): the variance function
/// (a, b) estimated, a^2 u^2 + b^2, against the stated (sigma_s max(|u|, floor))^2.
/// `shape_factor` (a over sigma_s) alone misses a noise carried by the floor: on three
/// sensors the variance function may put a model's whole shape misfit into b (13% of the
/// peak on a solid lap with an end mass its model lacks, against a stated 1% noise), with a
/// at its smallest.
pub fn level_factor(shape: &[(f64, f64)], (a, b): (f64, f64), stated: f64, floor: f64) -> f64 {
    let (estimated, of_stated) = shape.iter().fold((0.0, 0.0), |(e, s), &(u, _)| {
        (
            e + a * a * u * u + b * b,
            s + (stated * u.abs().max(floor)).powi(2),
        )
    });
    if of_stated > 0.0 {
        (estimated / of_stated).sqrt()
    } else {
        a / stated
    }
}

/// One observation of the variance function: E(square) = a^2 relative + b^2 floor.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Row {
    /// Coefficient of a^2.
    pub relative: f64,
    /// Coefficient of b^2.
    pub floor: f64,
    /// The squared residual observed.
    pub square: f64,
}

/// The rows of residuals (u, e) taken at their levels, their squares scaled by `correction`.
fn level_rows(
    pairs: impl Iterator<Item = (f64, f64)>,
    correction: f64,
) -> impl Iterator<Item = Row> {
    pairs.map(move |(u, e)| Row {
        relative: u * u,
        floor: 1.0,
        square: e * e * correction,
    })
}

/// The pseudo-residuals of every interior sensor of each sequence (Gasser, Sroka &
/// Jennen-Steinmetz, "Residual variance and residual pattern in nonlinear regression",
/// Biometrika 73, 1986): with neighbours at x_{j-1} < x_j < x_{j+1},
///
/// ```text
///   r_j = alpha e_{j-1} + beta e_{j+1} - e_j,   alpha = (x_{j+1} - x_j) / (x_{j+1} - x_{j-1}),
///                                               beta = 1 - alpha,
/// ```
///
/// zero for any misfit linear in x over the three sensors, and under independent errors of
/// variance v_j = a^2 u_j^2 + b^2
///
/// ```text
///   E r_j^2 = a^2 (alpha^2 u_{j-1}^2 + beta^2 u_{j+1}^2 + u_j^2) + b^2 (alpha^2 + beta^2 + 1).
/// ```
///
/// A wrong model leaves a smooth difference of shapes, which the pseudo-residuals mostly
/// cancel: the noise estimate does not absorb it (the residuals' levels would). Neither do the
/// smooth components the fit itself removes (shape scales, joint and effect parameters), so
/// no degrees-of-freedom correction is applied.
pub fn pseudo_residuals(sequences: &[along::Sequence]) -> Vec<Row> {
    let mut rows = Vec::new();
    for s in sequences {
        for j in 1..s.x.len().saturating_sub(1) {
            let (alpha, beta) = stencil(&s.x, j);
            let r = alpha * s.e[j - 1] + beta * s.e[j + 1] - s.e[j];
            rows.push(Row {
                relative: alpha * alpha * s.u[j - 1].powi(2)
                    + beta * beta * s.u[j + 1].powi(2)
                    + s.u[j].powi(2),
                floor: alpha * alpha + beta * beta + 1.0,
                square: r * r,
            });
        }
    }
    rows
}

/// The weights (alpha, beta) of the neighbours of interior sensor j at positions `x`: the
/// line through the neighbours at x_j (equal halves for coincident neighbours).
fn stencil(x: &[f64], j: usize) -> (f64, f64) {
    let span = x[j + 1] - x[j - 1];
    let alpha = if span > 0.0 {
        (x[j + 1] - x[j]) / span
    } else {
        0.5
    };
    (alpha, 1.0 - alpha)
}

/// Effective degrees of freedom of the shape-noise scale estimated from the pseudo-residuals
/// under the variance function (a^2, b^2): neighbouring pseudo-residuals share errors, so
/// the normalised sum S = sum r_j^2 / V_j of M of them has E S = M and, for Gaussian errors,
/// Var S = 2 sum_jk rho_jk^2 (rho the correlation of r_j and r_k, nonzero for |j - k| <= 2):
/// nu = 2 (E S)^2 / Var S = M^2 / sum_jk rho_jk^2 (Satterthwaite).
/// Evenly spaced sensors under a constant variance give nu ~ 0.51 M.
pub fn pseudo_dof(sequences: &[along::Sequence], a2: f64, b2: f64) -> f64 {
    let (mut count, mut sum_rho2) = (0.0, 0.0);
    for s in sequences {
        let m = s.x.len();
        if m < 3 {
            continue;
        }
        let v: Vec<f64> = s.u.iter().map(|u| (a2 * u * u + b2).max(1e-300)).collect();
        let st: Vec<(f64, f64)> = (1..m - 1).map(|j| stencil(&s.x, j)).collect();
        let var: Vec<f64> = (1..m - 1)
            .map(|j| {
                let (a, b) = st[j - 1];
                a * a * v[j - 1] + v[j] + b * b * v[j + 1]
            })
            .collect();
        for i in 0..var.len() {
            count += 1.0;
            sum_rho2 += 1.0;
            // r_i and r_{i+1} share the errors at sensors i + 1 and i + 2; r_i and r_{i+2}
            // the error at sensor i + 2 (sensor index = pseudo-residual index + 1).
            if i + 1 < var.len() {
                let cov = -st[i + 1].0 * v[i + 1] - st[i].1 * v[i + 2];
                sum_rho2 += 2.0 * cov * cov / (var[i] * var[i + 1]);
            }
            if i + 2 < var.len() {
                let cov = st[i].1 * st[i + 2].0 * v[i + 2];
                sum_rho2 += 2.0 * cov * cov / (var[i] * var[i + 2]);
            }
        }
    }
    if sum_rho2 == 0.0 {
        return 0.0;
    }
    count * count / sum_rho2
}

/// The variance function E(square) = a^2 relative + b^2 floor fitted to `rows`, a^2, b^2 >= 0,
/// from (a2, b2); no degrees-of-freedom correction. Returns (a^2, b^2).
///
/// Iteratively reweighted least squares (weights 1 / v^2) finds the optimum of the Gaussian
/// likelihood of the rows, sum ln v + square / v, from the start; where few rows lie near the
/// modes' nodes that iteration can settle on the edge b^2 = 0 (the rows of small u then weigh
/// 1 / (a^2 u^2)^2 and hold it there). The likelihood profiled over the ratio
/// rho = b^2 / a^2 (a^2 in closed form for each rho) is searched as well, over a grid of
/// ln rho refined by golden sections, and the better of the two optima is returned.
pub fn variance_function(rows: &[Row], a2: f64, b2: f64) -> (f64, f64) {
    let irls = reweighted(rows, a2, b2);
    let profiled = profile(rows);
    if negative_log_likelihood(rows, profiled) < negative_log_likelihood(rows, irls) {
        profiled
    } else {
        irls
    }
}

/// sum ln v + square / v of the rows under (a^2, b^2) (infinite where some v vanishes).
fn negative_log_likelihood(rows: &[Row], (a2, b2): (f64, f64)) -> f64 {
    rows.iter()
        .map(|r| {
            let v = a2 * r.relative + b2 * r.floor;
            if v > 0.0 {
                v.ln() + r.square / v
            } else {
                f64::INFINITY
            }
        })
        .sum()
}

/// The likelihood's optimum over rho = b^2 / a^2 in [RHO_RANGE], a^2 = mean(square / (relative
/// + rho floor)) for each rho: a grid of ln rho, then golden sections around its best point.
fn profile(rows: &[Row]) -> (f64, f64) {
    let at = |ln_rho: f64| {
        let rho = ln_rho.exp();
        let a2 = rows
            .iter()
            .map(|r| r.square / (r.relative + rho * r.floor).max(1e-300))
            .sum::<f64>()
            / rows.len().max(1) as f64;
        let point = (a2, a2 * rho);
        (negative_log_likelihood(rows, point), point)
    };
    let (lo, hi) = (RHO_RANGE.0.ln(), RHO_RANGE.1.ln());
    const GRID: usize = 80;
    let step = (hi - lo) / GRID as f64;
    let best = (0..=GRID)
        .map(|i| lo + step * i as f64)
        .map(|ln_rho| (ln_rho, at(ln_rho).0))
        .min_by(|a, b| a.1.total_cmp(&b.1))
        .map_or(lo, |(ln_rho, _)| ln_rho);
    let (mut a, mut b) = ((best - step).max(lo), (best + step).min(hi));
    let phi = 0.5 * (5.0_f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (c, d) = (b - phi * (b - a), a + phi * (b - a));
        if at(c).0 < at(d).0 {
            b = d;
        } else {
            a = c;
        }
    }
    at(0.5 * (a + b)).1
}

/// Range of rho = b^2 / a^2 the profile searches: a floor from 1e-3 to 10 peaks times a.
const RHO_RANGE: (f64, f64) = (1e-6, 1e2);

/// Iteratively reweighted least squares of the variance function (weights 1 / v^2) from
/// (a2, b2).
fn reweighted(rows: &[Row], mut a2: f64, mut b2: f64) -> (f64, f64) {
    for _ in 0..50 {
        let (mut s11, mut s12, mut s22, mut t1, mut t2) = (0.0, 0.0, 0.0, 0.0, 0.0);
        for r in rows {
            let v = (a2 * r.relative + b2 * r.floor).max(1e-300);
            let w = 1.0 / (v * v);
            s11 += w * r.relative * r.relative;
            s12 += w * r.relative * r.floor;
            s22 += w * r.floor * r.floor;
            t1 += w * r.relative * r.square;
            t2 += w * r.floor * r.square;
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

impl NoiseEstimate {
    /// The measurement error this yardstick weighs residuals by: the working noise and floor,
    /// or the data's own standard errors; no discrepancy.
    pub fn calibration(&self) -> Calibration {
        Calibration {
            noise: self.working,
            discrepancy: Default::default(),
            pairing: Default::default(),
            shape_floor: self.working_floor,
            measured_std: self.from_data,
        }
    }

    /// Whether the residual scale is one a user could have misjudged the noise by: within
    /// [`LARGEST_FACTOR`] of the stated. With the stated kept as the yardstick it is the
    /// largest model's, the smallest residual any model reaches: beyond the factor, no model
    /// explains the data.
    pub fn plausible(&self) -> bool {
        self.shape_factor <= LARGEST_FACTOR && self.level_factor <= LARGEST_FACTOR
    }

    /// P(F(dof, nu) > chi^2 / dof): the goodness of fit of a chi^2 computed under the working
    /// noise, whose scale was estimated on nu degrees of freedom.
    pub fn fit_p_value(&self, chi2: f64, dof: usize) -> f64 {
        let dof = dof.max(1) as f64;
        if self.dof.is_infinite() {
            return chi2_sf(chi2, dof);
        }
        f_sf(chi2 / dof, dof, self.dof)
    }

    /// P(F(k, nu) > D / k): the likelihood-ratio statistic D of k more unknowns under the
    /// estimated scale (chi-square under a known one); `bounded` when every added unknown is
    /// held non-negative and zero in the model extended ([`crate::stats::lr_sf`]).
    pub fn lrt_p_value(&self, lrt: f64, k: usize, bounded: bool) -> f64 {
        lr_sf(lrt, k, self.dof, bounded)
    }

    /// The lack of fit of the frequency residuals `res` of a fit (with `unknowns` model parameters)
    /// under the working frequency noise: chi^2 = sum of ((f_s - f_m) / (sigma_f f_m))^2, its
    /// degrees of freedom n_f - unknowns (at least 1: the joint parameters are fixed mostly
    /// by the frequencies, the most precise data), and its p-value (F(dof, nu) when the
    /// working frequency noise was scaled by the estimate, chi^2 when it is the stated).
    pub fn frequency_lack_of_fit(&self, res: &Residuals, unknowns: usize) -> (f64, usize, f64) {
        let chi2: f64 = res
            .frequency
            .iter()
            .enumerate()
            .map(|(r, e)| {
                let sigma = match &self.frequency_sigmas {
                    Some(s) => s[r],
                    None => self.working.frequency,
                };
                (e / sigma).powi(2)
            })
            .sum();
        let dof = res.frequency.len().saturating_sub(unknowns).max(1);
        let p = if self.frequency_estimated {
            self.fit_p_value(chi2, dof)
        } else {
            chi2_sf(chi2, dof as f64)
        };
        (chi2, dof, p)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn sequence(x: &[f64], u: &[f64], e: &[f64]) -> along::Sequence {
        along::Sequence {
            mode: 1,
            x: x.to_vec(),
            u: u.to_vec(),
            e: e.to_vec(),
        }
    }

    /// A misfit linear in x leaves no pseudo-residual, on uneven spacing; the coefficients of
    /// a^2 and b^2 are those of the docs (x = 0, 1, 3: alpha = 2/3, beta = 1/3).
    #[test]
    fn pseudo_residuals_cancel_a_linear_misfit() {
        let x = [0.0, 1.0, 3.0, 3.5, 7.0];
        let e: Vec<f64> = x.iter().map(|x| 0.3 - 2.0 * x).collect();
        let rows = pseudo_residuals(&[sequence(&x, &[1.0, 2.0, 3.0, 0.5, 0.1], &e)]);
        assert_eq!(rows.len(), 3);
        assert!(rows.iter().all(|r| r.square < 1e-28), "{rows:?}");
        assert!(
            (rows[0].relative - 49.0 / 9.0).abs() < 1e-14,
            "{:?}",
            rows[0]
        );
        assert!((rows[0].floor - 14.0 / 9.0).abs() < 1e-14, "{:?}", rows[0]);
    }

    /// Evenly spaced, constant variance: rho = -2/3 for neighbours, 1/6 two apart, so
    /// nu = M^2 / (M + 8/9 (M - 1) + 1/18 (M - 2)).
    #[test]
    fn pseudo_dof_of_even_spacing() {
        let x: Vec<f64> = (0..20).map(f64::from).collect();
        let nu = pseudo_dof(&[sequence(&x, &[0.0; 20], &[0.0; 20])], 0.0, 1.0);
        let m = 18.0;
        let expected = m * m / (m + 8.0 / 9.0 * (m - 1.0) + (m - 2.0) / 18.0);
        assert!(
            (nu - expected).abs() < 1e-12 * expected,
            "{nu} vs {expected}"
        );
    }

    /// On uneven spacing and a variance changing along the sequence, S = sum r_j^2 / V_j of
    /// independent Gaussian errors has mean M and variance 2 M^2 / nu (Satterthwaite's nu
    /// matches the second moment): 20000 draws, within 4 standard errors of each.
    #[test]
    fn pseudo_dof_matches_the_variance_of_the_normalised_sum() {
        use crate::random::TrialRng;
        use rand_distr::{Distribution, StandardNormal};
        let x: Vec<f64> = (0..15)
            .map(|j| f64::from(j) + 0.4 * f64::from(j % 3))
            .collect();
        let u: Vec<f64> = x.iter().map(|x| (0.4 * x).sin()).collect();
        let (a2, b2) = (4e-4, 1e-6);
        let template = sequence(&x, &u, &[0.0; 15]);
        let nu = pseudo_dof(std::slice::from_ref(&template), a2, b2);
        let m = 13.0;
        let mut rng = TrialRng::new(11, 0, 0);
        let draws = 20_000;
        let sums: Vec<f64> = (0..draws)
            .map(|_| {
                let e: Vec<f64> = u
                    .iter()
                    .map(|u| {
                        let z: f64 = StandardNormal.sample(&mut rng);
                        z * (a2 * u * u + b2).sqrt()
                    })
                    .collect();
                pseudo_residuals(&[sequence(&x, &u, &e)])
                    .iter()
                    .map(|r| r.square / (a2 * r.relative + b2 * r.floor))
                    .sum()
            })
            .collect();
        let n = f64::from(draws);
        let mean = sums.iter().sum::<f64>() / n;
        let var = sums.iter().map(|s| (s - mean).powi(2)).sum::<f64>() / (n - 1.0);
        let expected = 2.0 * m * m / nu;
        // Standard errors: of the mean sqrt(var / n); of the variance about var sqrt(2 / n)
        // times sqrt(1 + 6 / nu) for a chi-square-like sum (its excess kurtosis 12 / nu).
        assert!(
            (mean - m).abs() < 4.0 * (expected / n).sqrt(),
            "mean {mean} vs {m}"
        );
        let se = expected * (2.0 / n * (1.0 + 6.0 / nu)).sqrt();
        assert!(
            (var - expected).abs() < 4.0 * se,
            "variance {var} vs {expected} (nu {nu})"
        );
    }

    fn levels(pairs: &[(f64, f64)]) -> Vec<Row> {
        level_rows(pairs.iter().copied(), 1.0).collect()
    }

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
            let (a2, b2) = variance_function(&levels(&pairs), start.0, start.1);
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

    /// The rows of a case of the independent battery (fixture 025-floor_x10-joint_mass-strong:
    /// six sensors, a true floor of 0.2 of the peak; 4 pseudo-residuals, 30 levels), rounded
    /// to 5 digits: reweighting from the stated start settles on b = 0, where the components
    /// near a node (u^2 ~ 1e-7 with squares ~ 5e-5) are impossible; the result is the
    /// likelihood's optimum over a fine grid of (a^2, b^2) from every start.
    #[test]
    fn the_likelihood_optimum_is_found_where_reweighting_settles_on_no_floor() {
        let rows: Vec<Row> = [
            (3.1557e-01, 1.5556e+00, 1.9549e-07),
            (1.6304e-01, 1.6250e+00, 6.0263e-05),
            (5.2399e-01, 1.5001e+00, 1.5910e-04),
            (3.1386e-01, 1.5213e+00, 2.3588e-04),
            (5.3527e-01, 1.0000e+00, 2.2128e-05),
            (5.2694e-03, 1.0000e+00, 5.4499e-05),
            (6.0004e-02, 1.0000e+00, 2.5536e-04),
            (1.0000e+00, 1.0000e+00, 9.6836e-04),
            (5.6471e-01, 1.0000e+00, 1.2170e-04),
            (1.3556e-01, 1.0000e+00, 1.5029e-06),
            (2.5657e-02, 1.0000e+00, 1.5473e-04),
            (1.1684e-03, 1.0000e+00, 2.6229e-05),
            (1.0213e-02, 1.0000e+00, 6.7337e-05),
            (2.1174e-04, 1.0000e+00, 1.4903e-05),
            (9.0069e-03, 1.0000e+00, 1.5784e-05),
            (1.0000e+00, 1.0000e+00, 1.9906e-04),
            (1.0000e+00, 1.0000e+00, 1.9756e-03),
            (5.7092e-02, 1.0000e+00, 6.7587e-05),
            (3.0188e-01, 1.0000e+00, 2.0375e-06),
            (1.3614e-01, 1.0000e+00, 6.0290e-05),
            (2.8620e-04, 1.0000e+00, 1.8623e-06),
            (9.8334e-04, 1.0000e+00, 4.7674e-07),
            (1.3847e-04, 1.0000e+00, 1.4338e-05),
            (2.8449e-07, 1.0000e+00, 4.7908e-05),
            (9.3046e-05, 1.0000e+00, 3.0440e-05),
            (4.1295e-05, 1.0000e+00, 6.5363e-08),
            (1.0000e+00, 1.0000e+00, 2.9446e-04),
            (1.1399e-04, 1.0000e+00, 1.9190e-11),
            (1.0000e+00, 1.0000e+00, 7.1489e-05),
            (4.4615e-01, 1.0000e+00, 1.6767e-04),
            (1.3606e-01, 1.0000e+00, 1.8427e-05),
            (4.9144e-03, 1.0000e+00, 8.8830e-06),
            (1.1321e-05, 1.0000e+00, 1.2682e-06),
            (2.7360e-05, 1.0000e+00, 7.7486e-05),
        ]
        .iter()
        .map(|&(relative, floor, square)| Row {
            relative,
            floor,
            square,
        })
        .collect();
        let edge = reweighted(&rows, 4e-4, 1.6e-7);
        assert_eq!(edge.1, 0.0, "{edge:?}");
        let ln =
            |lo: f64, hi: f64, i: u32| (lo.ln() + (hi.ln() - lo.ln()) * f64::from(i) / 400.0).exp();
        let mut grid_best = f64::INFINITY;
        for i in 0..=400 {
            for j in 0..=400 {
                let point = (ln(1e-6, 1e-2, i), ln(1e-9, 1e-3, j));
                grid_best = grid_best.min(negative_log_likelihood(&rows, point));
            }
        }
        for start in [(4e-4, 1.6e-7), (4e-4, 0.0), (1e-6, 1e-3)] {
            let found = variance_function(&rows, start.0, start.1);
            let l = negative_log_likelihood(&rows, found);
            assert!(found.1 > 0.0, "from {start:?}: {found:?}");
            assert!(
                l <= grid_best + 1e-6,
                "from {start:?}: {found:?}, {l} against {grid_best}"
            );
            assert!(l < negative_log_likelihood(&rows, edge) - 100.0);
        }
    }

    /// Residuals of a pure relative noise (b = 0): the floor is clamped at zero, not negative.
    #[test]
    fn the_level_factor_weighs_the_floor_with_the_relative_part() {
        let shape: Vec<(f64, f64)> = [1.0, -0.6, 0.3, 0.01, -0.9, 0.45]
            .iter()
            .map(|&u| (u, 0.0))
            .collect();
        let (stated, floor) = (0.01, 0.02);
        // The stated noise itself: 1, whatever the components.
        let own = level_factor(&shape, (stated, stated * floor), stated, floor);
        assert!((own - 1.0).abs() < 1e-2, "{own}");
        // Twice the stated relative part, no floor: about 2 (the floor's share is small).
        let twice = level_factor(&shape, (2.0 * stated, 0.0), stated, floor);
        assert!((twice - 2.0).abs() < 1e-3, "{twice}");
        // The relative part at its smallest and a floor of 13% of the peak: the shape factor
        // (0.25) says nothing; the level is 13 / 1 over the RMS component, about 20.
        let u2 = shape.iter().map(|(u, _)| u * u).sum::<f64>() / shape.len() as f64;
        let hidden = level_factor(&shape, (0.25 * stated, 0.13), stated, floor);
        let expect = ((0.0025f64.powi(2) * u2 + 0.13f64.powi(2)) / (stated * stated * u2)).sqrt();
        assert!(
            hidden > LARGEST_FACTOR && (hidden / expect - 1.0).abs() < 1e-3,
            "{hidden}"
        );
    }

    #[test]
    fn floor_stays_non_negative() {
        let pairs: Vec<(f64, f64)> = (1..30)
            .map(|i| {
                let u = f64::from(i) / 29.0;
                (u, 0.02 * u * if i % 2 == 0 { 0.9 } else { 1.1 })
            })
            .collect();
        let (a2, b2) = variance_function(&levels(&pairs), 4e-4, 1e-6);
        assert!(b2 >= 0.0 && a2 > 0.0, "a^2 {a2}, b^2 {b2}");
        assert!((a2.sqrt() / 0.02 - 1.0).abs() < 0.05, "a {}", a2.sqrt());
    }
}

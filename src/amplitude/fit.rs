//! Weighted least squares of one law ([`super::laws`]) to one mode's stiffness and damping
//! across levels, and the extra variance that the scatter asks for beyond the stated standard
//! errors.
//!
//! The residuals are (law - data) / sigma, sigma_i^2 = s_i^2 + tau^2 per series (stiffness,
//! damping): s_i the standard error the data state, tau an extra standard deviation common to
//! the series' levels, estimated by [`extra_sd`] (zero when the stated errors explain the
//! scatter). The fit runs on the amplitude divided by a reference amplitude, its largest value
//! (the parameters then have sizes near one), from several starts. Everything computed from
//! the fit is computed there too: chi^2, residuals, bands and the covariance (J^T J)^-1 of the
//! weighted Jacobian ([`crate::optim::lstsq::inverse_gram`]). Only the reported parameters
//! are mapped back to the natural amplitude, with their covariance by the map's Jacobian. The
//! laws on the natural amplitude overflow when its unit changes (A^b of A = 1e145 m), while
//! on the scaled amplitude the choice and the fit are the same in every unit, and the natural
//! parameters change by the unit conversion only.
//!
//! Imports: [`super::laws`], [`crate::optim`].

use faer::Mat;

use super::laws::{Evaluation, Law, Regime};
use crate::optim::{LevenbergMarquardt, Linearisation, Problem, lstsq};

/// Iteration limit of one fit.
const MAX_ITERATIONS: usize = 500;
/// Convergence: a Gauss-Newton step would lower the cost by less than this * max(cost, 1).
const DECREMENT_TOLERANCE: f64 = 1e-14;
/// Smallest sigma, relative to the series' largest |value| (data given without errors and
/// fitted exactly).
const SIGMA_FLOOR: f64 = 1e-13;

/// One mode's data across levels, the amplitude ascending or not.
#[derive(Debug, Clone, PartialEq)]
pub struct Series {
    /// Response amplitude A per level (m, > 0).
    pub amplitude: Vec<f64>,
    /// Modal stiffness lambda = (2 pi f)^2 per level ((rad/s)^2).
    pub stiffness: Vec<f64>,
    /// Its standard error (0 when not given).
    pub stiffness_std: Vec<f64>,
    /// Damping ratio per level.
    pub damping: Vec<f64>,
    /// Its standard error (0 when not given).
    pub damping_std: Vec<f64>,
}

impl Series {
    /// Number of levels.
    pub fn len(&self) -> usize {
        self.amplitude.len()
    }

    /// Whether there is no level.
    pub fn is_empty(&self) -> bool {
        self.amplitude.is_empty()
    }
}

/// The sigmas of the two series: the stated errors with the extra standard deviations.
#[derive(Debug, Clone, PartialEq)]
pub struct Weights {
    /// sigma of each stiffness.
    pub stiffness: Vec<f64>,
    /// sigma of each damping ratio.
    pub damping: Vec<f64>,
}

impl Weights {
    /// sigma_i = sqrt(s_i^2 + tau^2), not below [`SIGMA_FLOOR`] of the series' scale.
    pub fn new(data: &Series, tau_stiffness: f64, tau_damping: f64) -> Self {
        let combine = |s: &[f64], y: &[f64], tau: f64| {
            let floor = SIGMA_FLOOR * y.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
            s.iter()
                .map(|s| (s * s + tau * tau).sqrt().max(floor))
                .collect()
        };
        Self {
            stiffness: combine(&data.stiffness_std, &data.stiffness, tau_stiffness),
            damping: combine(&data.damping_std, &data.damping, tau_damping),
        }
    }
}

/// A law fitted with given weights.
#[derive(Debug, Clone, PartialEq)]
pub struct Fitted {
    /// The law.
    pub law: Law,
    /// Its regime (Iwan only; microslip for the others).
    pub regime: Regime,
    /// The natural parameters, in the order of [`Law::parameters`].
    pub parameters: Vec<f64>,
    /// Their covariance, when the data determine every one.
    pub covariance: Option<Vec<Vec<f64>>>,
    /// The reference amplitude the law was fitted on (the largest amplitude, > 0).
    pub reference: f64,
    /// The parameters on the amplitude divided by `reference` ([`Fitted::evaluate`]).
    pub scaled: Vec<f64>,
    /// Their covariance, when the data determine every one.
    pub scaled_covariance: Option<Vec<Vec<f64>>>,
    /// Weighted sum of squares of the stiffness residuals.
    pub chi2_stiffness: f64,
    /// Weighted sum of squares of the damping residuals.
    pub chi2_damping: f64,
    /// Whether the iteration ended at a minimum.
    pub converged: bool,
}

impl Fitted {
    /// chi^2 of both series.
    pub fn chi2(&self) -> f64 {
        self.chi2_stiffness + self.chi2_damping
    }

    /// The law at the natural amplitude `a` > 0, evaluated on `a / reference` with the scaled
    /// parameters; the gradients are in the scaled parameters (their covariance is
    /// `scaled_covariance`).
    pub fn evaluate(&self, a: f64) -> Evaluation {
        self.law
            .evaluate(self.regime, &self.scaled, a / self.reference)
    }
}

/// The weighted problem on amplitudes `x` (divided by the reference amplitude).
struct Weighted<'a> {
    law: Law,
    regime: Regime,
    x: Vec<f64>,
    data: &'a Series,
    weights: &'a Weights,
}

impl Weighted<'_> {
    fn residuals(&self, p: &[f64]) -> (Vec<f64>, Mat<f64>) {
        let n = self.x.len();
        let mut r = vec![0.0; 2 * n];
        let mut j = Mat::zeros(2 * n, p.len());
        for (i, &a) in self.x.iter().enumerate() {
            let e = self.law.evaluate(self.regime, p, a);
            let (sk, sz) = (self.weights.stiffness[i], self.weights.damping[i]);
            r[i] = (e.stiffness - self.data.stiffness[i]) / sk;
            r[n + i] = (e.damping - self.data.damping[i]) / sz;
            for c in 0..p.len() {
                j[(i, c)] = e.d_stiffness[c] / sk;
                j[(n + i, c)] = e.d_damping[c] / sz;
            }
        }
        (r, j)
    }
}

impl Problem for Weighted<'_> {
    type State = Vec<f64>;
    type Error = ();

    fn evaluate(&self, p: &[f64]) -> Result<Vec<f64>, ()> {
        if !self.law.admissible(self.regime, p, &self.x) {
            return Err(());
        }
        let r = self.residuals(p).0;
        if r.iter().all(|v| v.is_finite()) {
            Ok(r)
        } else {
            Err(())
        }
    }

    fn cost(&self, r: &Vec<f64>) -> f64 {
        r.iter().map(|v| v * v).sum()
    }

    fn linearise(&self, p: &[f64], _: &Vec<f64>) -> Linearisation {
        let (residual, jacobian) = self.residuals(p);
        Linearisation::Jacobian { residual, jacobian }
    }

    fn admissible(&self, p: &[f64]) -> bool {
        self.law.admissible(self.regime, p, &self.x)
    }
}

/// The natural parameters of parameters fitted on amplitudes divided by `scale`, and the
/// Jacobian d natural / d scaled of the map.
fn unscale(law: Law, regime: Regime, p: &[f64], scale: f64) -> (Vec<f64>, Vec<Vec<f64>>) {
    let mut q = p.to_vec();
    let mut jac: Vec<Vec<f64>> = (0..p.len())
        .map(|i| {
            (0..p.len())
                .map(|j| if i == j { 1.0 } else { 0.0 })
                .collect()
        })
        .collect();
    // A coefficient of (A / scale)^e: natural = scaled * scale^-e, d/d e = -natural ln(scale).
    let mut power = |q: &mut Vec<f64>, coefficient: usize, exponent: usize, e: f64| {
        let factor = scale.powf(-e);
        q[coefficient] = p[coefficient] * factor;
        jac[coefficient][coefficient] = factor;
        jac[coefficient][exponent] = -q[coefficient] * scale.ln();
    };
    match law {
        Law::Constant => {}
        Law::PowerLaw => {
            power(&mut q, 1, 2, p[2]);
            power(&mut q, 4, 5, p[5]);
        }
        Law::Iwan => {
            power(&mut q, 2, 1, p[1] + 1.0);
            if regime == Regime::Macroslip {
                q[4] = p[4] * scale;
                jac[4][4] = scale;
            }
        }
    }
    (q, jac)
}

/// J C J^T.
fn congruence(jac: &[Vec<f64>], c: &[Vec<f64>]) -> Vec<Vec<f64>> {
    let n = jac.len();
    (0..n)
        .map(|a| {
            (0..n)
                .map(|b| {
                    (0..n)
                        .flat_map(|i| (0..n).map(move |j| (i, j)))
                        .map(|(i, j)| jac[a][i] * c[i][j] * jac[b][j])
                        .sum()
                })
                .collect()
        })
        .collect()
}

/// Fits `law` in `regime` to `data` with `weights` from each of `starts` (parameters for the
/// amplitude scaled by its largest value); the best fit, or None when no start is admissible.
pub fn fit(
    law: Law,
    regime: Regime,
    data: &Series,
    weights: &Weights,
    starts: &[Vec<f64>],
) -> Option<Fitted> {
    let scale = data.amplitude.iter().fold(0.0_f64, |m, &a| m.max(a));
    let scaled = Weighted {
        law,
        regime,
        x: data.amplitude.iter().map(|a| a / scale).collect(),
        data,
        weights,
    };
    let solver = LevenbergMarquardt::new(MAX_ITERATIONS)
        .and_then(|s| s.with_decrement(DECREMENT_TOLERANCE))
        .expect("the solver's settings are within their ranges");
    let best = starts
        .iter()
        .filter_map(|start| solver.minimise(&scaled, start.clone()).ok())
        .min_by(|a, b| a.cost.total_cmp(&b.cost))?;
    let (r, j) = scaled.residuals(&best.x);
    let n = data.len();
    let sum = |r: &[f64]| r.iter().map(|v| v * v).sum::<f64>();
    let scaled_covariance: Option<Vec<Vec<f64>>> = lstsq::inverse_gram(j.as_ref()).map(|c| {
        (0..c.nrows())
            .map(|a| (0..c.ncols()).map(|b| c[(a, b)]).collect())
            .collect()
    });
    let (parameters, jac) = unscale(law, regime, &best.x, scale);
    Some(Fitted {
        law,
        regime,
        parameters,
        covariance: scaled_covariance.as_ref().map(|c| congruence(&jac, c)),
        reference: scale,
        scaled: best.x,
        scaled_covariance,
        chi2_stiffness: sum(&r[..n]),
        chi2_damping: sum(&r[n..]),
        converged: best.termination.converged(),
    })
}

/// The extra standard deviation tau of a series: the root of sum r_i^2 / (s_i^2 + tau^2) =
/// dof (the scatter-based estimate, as Birge's ratio or DerSimonian-Laird's between-study
/// variance), 0 when the stated errors s_i already explain the residuals r_i (or dof <= 0).
pub fn extra_sd(residuals: &[f64], s: &[f64], dof: f64) -> f64 {
    let chi2 = |tau: f64| -> f64 {
        residuals
            .iter()
            .zip(s)
            .map(|(r, s)| {
                let v = s * s + tau * tau;
                if v > 0.0 { r * r / v } else { f64::INFINITY }
            })
            .sum()
    };
    if dof <= 0.0 || chi2(0.0) <= dof {
        return 0.0;
    }
    let mut hi = residuals
        .iter()
        .fold(0.0_f64, |m, r| m.max(r.abs()))
        .max(1e-300);
    while chi2(hi) > dof {
        hi *= 2.0;
    }
    let mut lo = 0.0;
    for _ in 0..200 {
        let mid = 0.5 * (lo + hi);
        if chi2(mid) > dof {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    0.5 * (lo + hi)
}

/// The raw residuals (law - data) of both series at the natural parameters of `fitted`.
pub fn raw_residuals(fitted: &Fitted, data: &Series) -> (Vec<f64>, Vec<f64>) {
    data.amplitude
        .iter()
        .enumerate()
        .map(|(i, &a)| {
            let e = fitted.evaluate(a);
            (e.stiffness - data.stiffness[i], e.damping - data.damping[i])
        })
        .unzip()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn the_extra_sd_makes_chi2_equal_the_degrees_of_freedom() {
        let r = [1.0, -2.0, 0.5, 1.5];
        let s = [0.1, 0.1, 0.2, 0.1];
        let tau = extra_sd(&r, &s, 3.0);
        let chi2: f64 = r
            .iter()
            .zip(&s)
            .map(|(r, s)| r * r / (s * s + tau * tau))
            .sum();
        assert!((chi2 - 3.0).abs() < 1e-9, "{chi2}");
        assert_eq!(extra_sd(&[0.01, -0.01], &[0.1, 0.1], 1.0), 0.0);
    }

    #[test]
    fn a_constant_is_the_weighted_mean() {
        let data = Series {
            amplitude: vec![1e-5, 2e-5, 3e-5],
            stiffness: vec![100.0, 102.0, 104.0],
            stiffness_std: vec![1.0, 1.0, 2.0],
            damping: vec![0.01, 0.01, 0.01],
            damping_std: vec![0.001; 3],
        };
        let w = Weights::new(&data, 0.0, 0.0);
        let f = fit(
            Law::Constant,
            Regime::Microslip,
            &data,
            &w,
            &[vec![50.0, 0.02]],
        )
        .unwrap();
        let mean = (100.0 + 102.0 + 104.0 / 4.0) / 2.25;
        assert!((f.parameters[0] - mean).abs() < 1e-9 * mean);
        let var = f.covariance.unwrap()[0][0];
        assert!((var - 1.0 / 2.25).abs() < 1e-9);
    }
}

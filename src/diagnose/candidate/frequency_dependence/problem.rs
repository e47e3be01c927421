//! The frequency-dependent joint's weighted nonlinear least squares: its residuals, as the
//! calibration's (module `crate::diagnose::fit`), every mode read from its own self-consistent
//! solution (module `own`), and their analytic derivatives.
//!
//! Unknowns: x_j = ln(p_j0 / p_j,nominal) (every identified joint parameter), alpha_a (one
//! shared, or one per parameter), the shape scales c_r. For mode r, with
//! l_r = ln(f_r / f_ref), D_r = 1 - sum_j G_j alpha_j and e_j(theta) = d q_j / d theta at a
//! fixed frequency (1 for theta = x_j, l_r for the alpha that scales p_j), the implicit
//! dependence of the self-consistent frequency gives
//!
//! ```text
//!   d ln f_r / d theta = sum_j G_j e_j(theta) / D_r
//!   d q_j / d theta    = e_j(theta) + alpha_j d ln f_r / d theta
//!   d y_r / d theta    = sum_j (d y_s / d q_j) (d q_j / d theta)
//! ```
//!
//! d y_s / d q_j = p_j d y_s / d p_j by Nelson's method (`crate::diagnose::sensitivity`).

use std::sync::{Arc, Mutex, PoisonError};

use faer::Mat;

use super::own::{self, Law, Settled, Solved};
use crate::diagnose::fit::{self, Calibration, Discrepancy, FitError, chi2, model_sign};
use crate::diagnose::pairing::Pairing;
use crate::diagnose::sensitivity::ModeDerivatives;
use crate::measured::MeasuredModes;
use crate::model::effects::EffectContext;
use crate::optim;

/// Largest |alpha|: a joint stiffness proportional to f^2 across the band is beyond any
/// contact law, and the self-consistent frequency is no longer unique near there.
pub const ALPHA_MAX: f64 = 2.0;

/// The least squares of one variant (shared or per-parameter alpha), the pairing fixed.
pub struct Problem<'a> {
    pub(super) ctx: &'a Arc<EffectContext>,
    pub(super) measured: &'a MeasuredModes,
    pub(super) pairing: &'a Pairing,
    /// ln p_j,nominal.
    log_nominal: Vec<f64>,
    /// For every joint parameter, the alpha that scales it.
    pub(super) group: Vec<usize>,
    /// Number of alphas.
    pub(super) alphas: usize,
    /// ln f_ref.
    pub(super) log_ref: f64,
    sigma_f: Vec<f64>,
    sigma: Vec<Vec<f64>>,
    /// The interval of every x_j = ln(p_j0 / p_j nominal) ([`fit::ranges`]).
    ranges: Vec<(f64, f64)>,
    /// The discrepancy in the weights.
    pub discrepancy: Discrepancy,
    /// Eigenpairs computed per solve.
    count: usize,
    /// Per measured mode, where it settled at the last evaluation: its next start.
    settled: Mutex<Vec<Option<Settled>>>,
}

/// An evaluated point: every mode's solution and the weighted residuals.
pub struct State {
    /// Per measured mode.
    pub modes: Vec<Solved>,
    /// Per measured mode its frequency, then its shape values.
    pub residual: Vec<f64>,
}

impl<'a> Problem<'a> {
    /// The deviance of weighted residuals whose squares sum to `chi2` ([`fit::deviance`]).
    pub fn deviance(&self, chi2: f64) -> f64 {
        fit::deviance(chi2, self.measured, &self.sigma_f, &self.sigma)
    }

    /// The problem of `measured` on `ctx` under `calibration`, modes paired as `pairing`, with
    /// one alpha shared by every joint parameter or one each (`per_parameter`).
    pub fn new(
        ctx: &'a Arc<EffectContext>,
        measured: &'a MeasuredModes,
        calibration: &Calibration,
        pairing: &'a Pairing,
        per_parameter: bool,
    ) -> Self {
        let (sigma_f, sigma) = fit::sigmas(measured, calibration);
        let ranges = fit::ranges(&ctx.structure);
        let log_nominal: Vec<f64> = ctx
            .structure
            .identified()
            .iter()
            .map(|p| p.value.ln())
            .collect();
        let joints = log_nominal.len();
        let group: Vec<usize> = (0..joints)
            .map(|j| if per_parameter { j } else { 0 })
            .collect();
        let modes = measured.modes();
        let log_ref =
            modes.iter().map(|m| m.frequency_hz.ln()).sum::<f64>() / modes.len().max(1) as f64;
        let count = ctx.structure.rigid + modes.len() + 2;
        Problem {
            ctx,
            measured,
            pairing,
            log_nominal,
            alphas: if per_parameter { joints } else { 1 },
            group,
            log_ref,
            sigma_f,
            sigma,
            ranges,
            discrepancy: calibration.discrepancy.clone(),
            count,
            settled: Mutex::new(vec![None; modes.len()]),
        }
    }

    /// Eigenpairs computed per solve.
    pub fn count(&self) -> usize {
        self.count
    }

    /// Joint parameters.
    pub fn joints(&self) -> usize {
        self.log_nominal.len()
    }

    /// Unknowns: joints, alphas, shape scales.
    pub fn unknowns(&self) -> usize {
        self.joints() + self.alphas + self.measured.modes().len()
    }

    /// q_j0 = ln p_j0 and alpha_j of every joint parameter at x.
    pub fn law(&self, x: &[f64]) -> (Vec<f64>, Vec<f64>) {
        let j = self.joints();
        let q0 = self.log_nominal.iter().zip(x).map(|(n, x)| n + x).collect();
        let alpha = self.group.iter().map(|&a| x[j + a]).collect();
        (q0, alpha)
    }

    /// Every mode solved at its own frequency and the residuals at x.
    pub fn evaluate(&self, x: &[f64]) -> Result<State, FitError> {
        use rayon::prelude::*;
        let (q0, alpha) = self.law(x);
        let law = Law {
            q0: &q0,
            alpha: &alpha,
            log_ref: self.log_ref,
        };
        let modes = self.measured.modes();
        let mut settled = self.settled.lock().unwrap_or_else(PoisonError::into_inner);
        let solved: Vec<Solved> = modes
            .par_iter()
            .zip(settled.par_iter())
            .enumerate()
            .map(|(r, (m, last))| {
                let s = self.pairing.model_index[r];
                let start = last
                    .as_ref()
                    .and_then(|last| law.predict(last))
                    .unwrap_or(m.frequency_hz.ln());
                // All `count` pairs, though the residuals and sensitivities read pair s only:
                // with s + 2 the 24k lap's diagnose was slower (docs/benchmarks.md).
                own::solve(&self.ctx.structure, law, s, self.count, start, m.mode)
            })
            .collect::<Result<_, _>>()?;
        *settled = solved
            .iter()
            .map(|sv| Some(Settled::new(law, sv)))
            .collect();
        drop(settled);
        let at = self.joints() + self.alphas;
        let mut residual = Vec::new();
        for (r, (m, sv)) in modes.iter().zip(&solved).enumerate() {
            let s = self.pairing.model_index[r];
            let f = sv.modal.frequency_hz(s);
            residual.push((f - m.frequency_hz) / (self.sigma_f[r] * m.frequency_hz));
            let sign = model_sign(&sv.modal, s, m);
            let y = sv.modal.vectors();
            for ((p, &v), &sigma) in m.points.iter().zip(&m.values).zip(&self.sigma[r]) {
                residual.push((x[at + r] * sign * p.read_column(y, s) - v) / sigma);
            }
        }
        Ok(State {
            modes: solved,
            residual,
        })
    }

    /// d residual / dx at x of state `state` (module docs).
    pub fn jacobian(&self, x: &[f64], state: &State) -> Mat<f64> {
        let (joints, alphas) = (self.joints(), self.alphas);
        let at = joints + alphas;
        let (_, alpha) = self.law(x);
        let mut jac = Mat::zeros(state.residual.len(), x.len());
        let mut row = 0;
        // One factor for every mode: their models differ in the joint only.
        let mut shared = None;
        for (r, (m, sv)) in self.measured.modes().iter().zip(&state.modes).enumerate() {
            let s = self.pairing.model_index[r];
            let sign = model_sign(&sv.modal, s, m);
            let f = sv.modal.frequency_hz(s);
            let level = sv.log_frequency - self.log_ref;
            // d y_s / d q_j at the measured points.
            let params = sv.structure.identified();
            let pairs: Vec<_> = params.iter().map(|p| (&p.stiffness, &p.mass)).collect();
            let mats = ModeDerivatives::needs_matrices(&sv.modal).then(|| sv.structure.assemble());
            let derivatives = ModeDerivatives::sharing(mats.as_ref(), &sv.modal, shared.take());
            let dy: Vec<Vec<f64>> = derivatives
                .of(&[s], &pairs)
                .remove(0)
                .iter()
                .zip(&params)
                .map(|((_, d), p)| m.points.iter().map(|o| p.value * o.read(d)).collect())
                .collect();
            shared = derivatives.factor();
            let g = &sv.sensitivity;
            let denominator = 1.0 - own::slope(g, &alpha);
            for col in 0..at {
                // d q_j / d theta at a fixed frequency.
                let fixed: Vec<f64> = (0..joints)
                    .map(|j| match col {
                        c if c < joints => f64::from(u8::from(c == j)),
                        c => f64::from(u8::from(self.group[j] == c - joints)) * level,
                    })
                    .collect();
                let d_log_f = g.iter().zip(&fixed).map(|(g, e)| g * e).sum::<f64>() / denominator;
                jac[(row, col)] = f * d_log_f / (self.sigma_f[r] * m.frequency_hz);
                let dq: Vec<f64> = (0..joints).map(|j| fixed[j] + alpha[j] * d_log_f).collect();
                for (k, &sigma) in self.sigma[r].iter().enumerate() {
                    let d: f64 = (0..joints).map(|j| dy[j][k] * dq[j]).sum();
                    jac[(row + 1 + k, col)] = x[at + r] * sign * d / sigma;
                }
            }
            for (k, (p, &sigma)) in m.points.iter().zip(&self.sigma[r]).enumerate() {
                jac[(row + 1 + k, at + r)] = sign * p.read_column(sv.modal.vectors(), s) / sigma;
            }
            row += 1 + m.points.len();
        }
        jac
    }

    /// Whether x keeps every alpha within [`ALPHA_MAX`] and every p_j0 within its range
    /// between free and rigid ([`fit::ranges`]).
    pub fn admissible(&self, x: &[f64]) -> bool {
        let j = self.joints();
        x[..j]
            .iter()
            .zip(&self.ranges)
            .all(|(v, (lo, hi))| (lo..=hi).contains(&v))
            && x[j..j + self.alphas].iter().all(|a| a.abs() <= ALPHA_MAX)
    }
}

impl optim::Problem for Problem<'_> {
    type State = State;
    type Error = FitError;

    fn evaluate(&self, x: &[f64]) -> Result<State, FitError> {
        Problem::evaluate(self, x)
    }

    fn cost(&self, state: &State) -> f64 {
        chi2(&state.residual)
    }

    fn linearise(&self, x: &[f64], state: &State) -> optim::Linearisation {
        optim::Linearisation::Jacobian {
            residual: state.residual.clone(),
            jacobian: self.jacobian(x, state),
        }
    }

    fn admissible(&self, x: &[f64]) -> bool {
        Problem::admissible(self, x)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::pairing::pair;

    /// The residual Jacobian (the self-consistent frequency's implicit derivative included)
    /// against central differences of the residuals, for both variants, at a point with
    /// alpha away from zero. Every point is evaluated by a problem of its own: an evaluation
    /// starts from the last one's solutions, which moves the residuals within the
    /// self-consistency's round-off (the next test), and the differences compare the
    /// residuals as a function of x alone.
    #[test]
    fn residual_jacobian_matches_central_differences() {
        let (measured, nominal, ctx, calibration) = crate::diagnose::fit::tests::fixture();
        let pairing = pair(&nominal, &measured, 2, &calibration.pairing).unwrap();
        for per_parameter in [false, true] {
            let fresh = || Problem::new(&ctx, &measured, &calibration, &pairing, per_parameter);
            let mut x = vec![0.2, -0.3, 0.4];
            if per_parameter {
                x.push(-0.3);
            }
            x.extend([1.0, 0.9, 1.1, 1.05]);
            let problem = fresh();
            let state = problem.evaluate(&x).unwrap();
            let jac = problem.jacobian(&x, &state);
            for col in 0..x.len() {
                // Eigenvalues carry round-off of about eps lambda_max: a step long enough to rise
                // above it (as the calibration's own test).
                let h = 1e-3;
                let at = |sign: f64| {
                    let mut t = x.clone();
                    t[col] += sign * h;
                    fresh().evaluate(&t).unwrap().residual
                };
                let (plus, minus) = (at(1.0), at(-1.0));
                let scale = (0..plus.len())
                    .map(|r| jac[(r, col)].abs())
                    .fold(0.0, f64::max);
                assert!(scale > 0.0, "column {col} is zero");
                for r in 0..plus.len() {
                    let fd = (plus[r] - minus[r]) / (2.0 * h);
                    assert!(
                        (fd - jac[(r, col)]).abs() < 1e-5 * scale,
                        "per parameter {per_parameter}, column {col}, row {r}: {fd} vs {}",
                        jac[(r, col)]
                    );
                }
            }
        }
    }

    /// An evaluation started from another's solutions (a trial step away) gives the residuals
    /// of a fresh one to within 1e-5 of a standard deviation: the start moves only where
    /// within its round-off a mode settles (its ln f here to about 1e-9).
    #[test]
    fn the_start_from_the_last_evaluation_moves_no_residual_beyond_round_off() {
        let (measured, nominal, ctx, calibration) = crate::diagnose::fit::tests::fixture();
        let pairing = pair(&nominal, &measured, 2, &calibration.pairing).unwrap();
        let x = [0.2, -0.3, 0.4, 1.0, 0.9, 1.1, 1.05];
        let fresh = Problem::new(&ctx, &measured, &calibration, &pairing, false);
        let alone = fresh.evaluate(&x).unwrap().residual;
        let warm = Problem::new(&ctx, &measured, &calibration, &pairing, false);
        warm.evaluate(&[0.25, -0.32, 0.38, 1.0, 0.9, 1.1, 1.05])
            .unwrap();
        let after = warm.evaluate(&x).unwrap().residual;
        for (r, (a, b)) in alone.iter().zip(&after).enumerate() {
            assert!(
                (a - b).abs() < 1e-5,
                "row {r}: {a} alone, {b} after another point"
            );
        }
    }
}

//! One mode of the frequency-dependent joint, solved with the joint evaluated at the mode's
//! own frequency.
//!
//! The joint parameters of mode s at frequency f are
//!
//! ```text
//!   p_j(f) = p_j0 (f / f_ref)^alpha_j,   q_j(u) = ln p_j = q_j0 + alpha_j (u - ln f_ref),
//! ```
//!
//! with u = ln f. The mode's frequency F(u) (of pair s of K(p(u)), M(p(u))) is
//! self-consistent when F(u) = e^u: h(u) = ln F(u) - u = 0. Newton's iteration on h, with
//! h'(u) = sum_j G_j alpha_j - 1 and G_j = d ln F / d q_j =
//! p_j y_s^T (dK_j - lambda dM_j) y_s / (2 lambda) (the eigenvalue's first-order
//! sensitivity, no solve), each step at most [`MAX_STEP`] in u:
//!
//! ```text
//!   u <- u + delta,   delta = h(u) / (1 - sum_j G_j alpha_j).
//! ```
//!
//! What has to be consistent is the joint: the step would move q_j by alpha_j delta. Converged
//! when max_j |alpha_j delta| <= [`TOLERANCE`] (the joint solved is the self-consistent one to
//! that relative precision; with every alpha 0 at once, any u), or when |h| <= [`ROUND_OFF`]
//! and the last step did not halve it (the eigenvalue's round-off is reached); the solution's
//! frequency is then u + delta. Not converged after [`MAX_ITERATIONS`]: an error naming the
//! mode, never a result. With sum_j G_j <= 1/2 (the joints carry part of the strain energy)
//! the plain fixed point u <- ln F(u) already contracts for |alpha| < 2; Newton's converges
//! quadratically.
//!
//! The start: the measured frequency, or, where the mode settled under a nearby law (the
//! fit's last evaluation), that solution moved to first order. With the joint changed by
//! dq0_j and dalpha_j, the self-consistent u* moves by
//!
//! ```text
//!   du* = sum_j G_j (dq0_j + dalpha_j (u* - ln f_ref)) / (1 - sum_j G_j alpha_j),
//! ```
//!
//! an error of second order in the change: late in a fit the first solve is often the last.

use crate::diagnose::fit::FitError;
use crate::identify::frequency_only::sensitivities;
use crate::modal::{ModalSolution, reduced};
use crate::structure::Structure;

/// Self-consistency reached: the joint at most this far (relative) from its self-consistent
/// values, max_j |alpha_j delta|.
pub const TOLERANCE: f64 = 1e-12;
/// Self-consistency reached at the eigenvalue's round-off: |ln F(u) - u| at most this and no
/// longer halving.
pub const ROUND_OFF: f64 = 1e-8;
/// Largest number of Newton steps.
pub const MAX_ITERATIONS: usize = 40;
/// Largest Newton step in ln f.
pub const MAX_STEP: f64 = 0.5;

/// What the joint of one mode depends on.
#[derive(Debug, Clone, Copy)]
pub struct Law<'a> {
    /// q_j0 = ln p_j0, every identified parameter.
    pub q0: &'a [f64],
    /// alpha_j, every identified parameter.
    pub alpha: &'a [f64],
    /// ln f_ref.
    pub log_ref: f64,
}

impl Law<'_> {
    /// The parameter values at u = ln f.
    pub fn values(&self, u: f64) -> Vec<f64> {
        self.q0
            .iter()
            .zip(self.alpha)
            .map(|(q, a)| (q + a * (u - self.log_ref)).exp())
            .collect()
    }

    /// The self-consistent ln f under this law predicted from `settled`, the mode's solution
    /// under another (module docs), the move at most [`MAX_STEP`]; none where it is not a
    /// number.
    pub fn predict(&self, settled: &Settled) -> Option<f64> {
        let level = settled.log_frequency - self.log_ref;
        let moved: f64 = (0..self.q0.len())
            .map(|j| {
                let dq = self.q0[j] - settled.q0[j] + (self.alpha[j] - settled.alpha[j]) * level;
                settled.sensitivity[j] * dq
            })
            .sum();
        let du = moved / (1.0 - slope(&settled.sensitivity, self.alpha));
        du.is_finite()
            .then(|| settled.log_frequency + du.clamp(-MAX_STEP, MAX_STEP))
    }
}

/// sum_j G_j alpha_j, h'(u) + 1, for sensitivities `g` and exponents `alpha`.
pub fn slope(g: &[f64], alpha: &[f64]) -> f64 {
    g.iter().zip(alpha).map(|(g, a)| g * a).sum()
}

/// Where a mode settled: the law (its q0 and alpha) it was solved under, its self-consistent
/// ln f and G_j there; the start of its next solve ([`Law::predict`]).
#[derive(Debug, Clone)]
pub struct Settled {
    q0: Vec<f64>,
    alpha: Vec<f64>,
    log_frequency: f64,
    sensitivity: Vec<f64>,
}

impl Settled {
    /// Mode `solved` under `law`.
    pub fn new(law: Law, solved: &Solved) -> Self {
        Self {
            q0: law.q0.to_vec(),
            alpha: law.alpha.to_vec(),
            log_frequency: solved.log_frequency,
            sensitivity: solved.sensitivity.clone(),
        }
    }
}

/// A mode solved at its own frequency.
#[derive(Debug, Clone)]
pub struct Solved {
    /// The structure with the joint at u (its matrices are assembled again where needed:
    /// one mode's at a time, not every mode's kept).
    pub structure: Structure,
    /// Its eigensolution.
    pub modal: ModalSolution,
    /// The self-consistent ln f, u + delta (the joint is evaluated at u, within the
    /// convergence test of it: module docs).
    pub log_frequency: f64,
    /// G_j = d ln F / d ln p_j at the solution.
    pub sensitivity: Vec<f64>,
}

/// G_j = d ln f_s / d ln p_j of pair `s` of `modal`, solution of `structure`: half the
/// eigenvalue's logarithmic sensitivity.
pub fn log_sensitivity(structure: &Structure, modal: &ModalSolution, s: usize) -> Vec<f64> {
    sensitivities(structure, modal, s)
        .into_iter()
        .map(|g| 0.5 * g)
        .collect()
}

/// Pair `s` (of at least `count` computed) of `nominal` with the joint of `law`, at its own
/// frequency, starting from u = `start` (ln f); `mode` names the measured mode in the error.
pub fn solve(
    nominal: &Structure,
    law: Law,
    s: usize,
    count: usize,
    start: f64,
    mode: usize,
) -> Result<Solved, FitError> {
    let mut u = start;
    let mut last = f64::INFINITY;
    let largest = law.alpha.iter().fold(0.0, |m: f64, a| m.max(a.abs()));
    // The reduced model as this mode's solves enrich it (module `crate::modal::reduced`).
    let mut enriched = None;
    for _ in 0..MAX_ITERATIONS {
        let mut structure = nominal.with_values(&law.values(u));
        if let Some(reduced) = &enriched {
            structure.reduced = Some(std::sync::Arc::clone(reduced));
        }
        let (modal, next) =
            reduced::lowest_checking(&structure, &[], count.max(s + 1), Some(s..s + 1))?;
        if let Some(next) = next {
            structure.reduced = Some(std::sync::Arc::clone(&next));
            enriched = Some(next);
        }
        if s >= modal.len() || modal.values()[s] <= 0.0 {
            break;
        }
        let h = modal.frequency_hz(s).ln() - u;
        let sensitivity = log_sensitivity(&structure, &modal, s);
        let step = h / (1.0 - slope(&sensitivity, law.alpha));
        if !step.is_finite() {
            break;
        }
        if largest * step.abs() <= TOLERANCE || (h.abs() <= ROUND_OFF && h.abs() > 0.5 * last) {
            return Ok(Solved {
                structure,
                modal,
                log_frequency: u + step,
                sensitivity,
            });
        }
        last = h.abs();
        u += step.clamp(-MAX_STEP, MAX_STEP);
    }
    Err(FitError::NotSelfConsistent {
        mode,
        iterations: MAX_ITERATIONS,
        change: last,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    /// The solved mode's frequency is the one its joint is evaluated at, and with alpha = 0
    /// it is the invariant joint's.
    #[test]
    fn the_solved_frequency_is_the_one_the_joint_is_evaluated_at() {
        let model = paper_model(1e7, 1e4);
        let q0: Vec<f64> = model.identified().iter().map(|p| p.value.ln()).collect();
        let fixed = ModalSolution::solve(&model.assemble()).unwrap();
        let still = Law {
            q0: &q0,
            alpha: &[0.0, 0.0],
            log_ref: 500f64.ln(),
        };
        let s = 4;
        let a = solve(&model, still, s, 6, 1000f64.ln(), 3).unwrap();
        assert!((a.modal.frequency_hz(s) / fixed.frequency_hz(s) - 1.0).abs() < 1e-12);
        // Started 1000 Hz away from it, the joint does not move: its own frequency.
        assert!((a.log_frequency - fixed.frequency_hz(s).ln()).abs() < 1e-12);
        let law = Law {
            alpha: &[0.5, 0.8],
            ..still
        };
        let b = solve(&model, law, s, 6, 1000f64.ln(), 3).unwrap();
        let f = b.modal.frequency_hz(s);
        assert!((f.ln() - b.log_frequency).abs() <= ROUND_OFF, "{f}");
        // The joint stiffer above f_ref = 500 Hz: the mode rises.
        assert!(f > fixed.frequency_hz(s), "{f}");
        let values = law.values(f.ln());
        for (p, v) in b.structure.identified().iter().zip(&values) {
            assert!((p.value / v - 1.0).abs() < 1e-7);
        }
    }

    /// The start predicted from a solution under a nearby law is off by the second order of
    /// the change: a tenth of the change, a hundredth of the error.
    #[test]
    fn the_predicted_start_is_second_order_accurate() {
        let model = paper_model(1e7, 1e4);
        let q: Vec<f64> = model.identified().iter().map(|p| p.value.ln()).collect();
        let (s, log_ref) = (4, 500f64.ln());
        let from = Law {
            q0: &q,
            alpha: &[0.5, 0.8],
            log_ref,
        };
        let solved = solve(&model, from, s, 6, 1000f64.ln(), 3).unwrap();
        let settled = Settled::new(from, &solved);
        let error = |e: f64| {
            let q0 = [q[0] + 0.3 * e, q[1] - 0.5 * e];
            let alpha = [0.5 - 0.4 * e, 0.8 + 0.2 * e];
            let law = Law {
                q0: &q0,
                alpha: &alpha,
                log_ref,
            };
            let exact = solve(&model, law, s, 6, 1000f64.ln(), 3).unwrap();
            let predicted = law.predict(&settled).unwrap();
            let moved = (exact.log_frequency - solved.log_frequency).abs();
            let off = (predicted - exact.log_frequency).abs();
            // The prediction removes all but a small part of the move.
            assert!(
                off < 0.05 * moved,
                "{e}: moved {moved}, predicted off by {off}"
            );
            off
        };
        let (coarse, fine) = (error(0.05), error(0.005));
        assert!(coarse / fine > 50.0, "{coarse} then {fine}");
    }
}

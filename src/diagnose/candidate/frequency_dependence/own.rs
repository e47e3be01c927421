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
//! self-consistent when F(u) = e^u: h(u) = ln F(u) - u = 0. Newton's iteration on h from the
//! measured frequency, with h'(u) = sum_j G_j alpha_j - 1 and G_j = d ln F / d q_j =
//! p_j y_s^T (dK_j - lambda dM_j) y_s / (2 lambda) (the eigenvalue's first-order
//! sensitivity, no solve), each step at most [`MAX_STEP`] in u:
//!
//! ```text
//!   u <- u + h(u) / (1 - sum_j G_j alpha_j)
//! ```
//!
//! Converged when |h| <= [`TOLERANCE`], or when |h| <= [`ROUND_OFF`] and the last step did not
//! halve it (the eigenvalue's round-off is reached). Not converged after [`MAX_ITERATIONS`]:
//! an error naming the mode, never a result. With sum_j G_j <= 1/2 (the joints carry part of
//! the strain energy) the plain fixed point u <- ln F(u) already contracts for |alpha| < 2;
//! Newton's converges quadratically.

use crate::diagnose::fit::FitError;
use crate::identify::frequency_only::sensitivities;
use crate::modal::ModalSolution;
use crate::structure::Structure;

/// Self-consistency reached: |ln F(u) - u| at most this.
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
}

/// A mode solved at its own frequency.
#[derive(Debug, Clone)]
pub struct Solved {
    /// The structure with the joint at u (its matrices are assembled again where needed:
    /// one mode's at a time, not every mode's kept).
    pub structure: Structure,
    /// Its eigensolution.
    pub modal: ModalSolution,
    /// u = ln f at which the joint is evaluated.
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
/// frequency, starting from `start_hz`; `mode` names the measured mode in the error.
pub fn solve(
    nominal: &Structure,
    law: Law,
    s: usize,
    count: usize,
    start_hz: f64,
    mode: usize,
) -> Result<Solved, FitError> {
    let mut u = start_hz.ln();
    let mut last = f64::INFINITY;
    // The last step's joint and solution: with every alpha 0 the joint does not move with u,
    // and the step that confirms the solution would solve the same model again.
    let mut previous: Option<(Vec<f64>, Structure, ModalSolution)> = None;
    for _ in 0..MAX_ITERATIONS {
        let values = law.values(u);
        let (structure, modal) = match previous.take() {
            Some((at, structure, modal)) if at == values => (structure, modal),
            _ => {
                let structure = nominal.with_values(&values);
                let modal = ModalSolution::lowest_of(&structure.assemble(), count.max(s + 1))?;
                (structure, modal)
            }
        };
        if s >= modal.len() || modal.values()[s] <= 0.0 {
            break;
        }
        let h = modal.frequency_hz(s).ln() - u;
        let sensitivity = log_sensitivity(&structure, &modal, s);
        if h.abs() <= TOLERANCE || (h.abs() <= ROUND_OFF && h.abs() > 0.5 * last) {
            return Ok(Solved {
                structure,
                modal,
                log_frequency: u,
                sensitivity,
            });
        }
        last = h.abs();
        let slope: f64 = sensitivity.iter().zip(law.alpha).map(|(g, a)| g * a).sum();
        let step = h / (1.0 - slope);
        if !step.is_finite() {
            break;
        }
        previous = Some((values, structure, modal));
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
        let a = solve(&model, still, s, 6, 1000.0, 3).unwrap();
        assert!((a.modal.frequency_hz(s) / fixed.frequency_hz(s) - 1.0).abs() < 1e-12);
        let law = Law {
            alpha: &[0.5, 0.8],
            ..still
        };
        let b = solve(&model, law, s, 6, 1000.0, 3).unwrap();
        let f = b.modal.frequency_hz(s);
        assert!((f.ln() - b.log_frequency).abs() <= ROUND_OFF, "{f}");
        // The joint stiffer above f_ref = 500 Hz: the mode rises.
        assert!(f > fixed.frequency_hz(s), "{f}");
        let values = law.values(f.ln());
        for (p, v) in b.structure.identified().iter().zip(&values) {
            assert!((p.value / v - 1.0).abs() < 1e-7);
        }
    }
}

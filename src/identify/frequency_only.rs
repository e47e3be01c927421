//! Per-mode identification from a frequency alone: one joint parameter per mode.
//!
//! The paper's projection (eq. (14)-(15)) needs at least as many measured shape components as
//! basis vectors, and its system (eq. (10)-(13)) one equation per parameter: with three sensors
//! on a free-free beam neither holds, and the question the paper asks, does the joint's
//! stiffness change with the mode's frequency, would go unanswered. A mode's frequency alone
//! determines one parameter: the value p of parameter i at which the model's mode t has the
//! measured eigenvalue, the other parameters held,
//!
//! ```text
//!   lambda_t(p) = lambda_meas = (2 pi f_meas)^2.
//! ```
//!
//! Solved exactly (not linearised): u = ln(p / p_0) on [ln 1e-4, ln 1e4] by Newton steps kept
//! inside a bracket that bisection shrinks ([`super::root`]; for a stiffening parameter the
//! ends of the reach are solved only when the search needs them), the eigenproblem re-solved
//! at every step, with the derivative of an M-normalised pair
//!
//! ```text
//!   d ln lambda / d ln p = p y^T (dK/dp - lambda dM/dp) y / lambda   (= s, the sensitivity).
//! ```
//!
//! For a stiffness parameter (dK/dp positive semi-definite, no mass) lambda_t(p) is
//! non-decreasing (Courant-Fischer), so the root is unique. A measured frequency outside what
//! p from 1e-4 to 1e4 times its value reaches is refused with that range: the mode disagrees
//! with the model in more than this parameter. The standard deviation is first order:
//! sigma(ln p) = 2 sigma_f / (f |s|), and sigma(p / p_0 - 1) = (p / p_0) sigma(ln p).
//!
//! The parameter is the one the mode is most sensitive to at the start (largest |s|) or the
//! one the caller names.
//!
//! Layer 4 (identification): imports the structure and the modal solution.

use super::reach::Ends;
use super::root::{Named, Order, Probe, Search, quadratic};
use crate::modal::{ModalSolution, hz_to_lambda, reduced};
use crate::structure::Structure;

/// What a per-mode correction of one parameter comes from.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Source {
    /// The paper's system on the mode's shape and frequency (eq. (10)-(13)); a rank-deficient
    /// system leaves the correction empty.
    Shape,
    /// The mode's frequency alone ([`identify`]).
    Frequency,
    /// Held at its value on this mode.
    Held,
}

/// Why a mode was identified from its frequency alone.
#[derive(Debug, Clone)]
pub enum Fallback {
    /// The user asked for it.
    Asked,
    /// The paper's system of the mode is rank deficient (its outcome).
    RankDeficient(super::ModeOutcome),
}

pub use super::frequency_error::FrequencyError;
pub use super::reach::REACH;

/// Which parameter a mode's frequency identifies.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Choice {
    /// The identified parameter the mode is most sensitive to (largest |d ln lambda / d ln p|).
    MostSensitive,
    /// This one: an index into [`Structure::identified`].
    Named(usize),
}

/// One mode's parameter identified from its frequency.
#[derive(Debug, Clone, PartialEq)]
pub struct FrequencyOutcome {
    /// Measured mode r.
    pub mode: usize,
    /// Index of the parameter in [`Structure::identified`].
    pub param: usize,
    /// p / p_0 - 1: the relative correction.
    pub relative: f64,
    /// Its standard deviation, when the frequency's is known.
    pub std: Option<f64>,
    /// d ln lambda / d ln p at the solution.
    pub sensitivity: f64,
    /// The paired model mode's frequency at p_0, Hz.
    pub frequency_model_hz: f64,
}

/// d ln lambda_t / d ln p_i of model mode `t` (0-based, rigid-body modes counted) for every
/// identified parameter of `structure`, from its modal solution `modal`.
pub fn sensitivities(structure: &Structure, modal: &ModalSolution, t: usize) -> Vec<f64> {
    let lambda = modal.values()[t];
    let y: Vec<f64> = modal.vectors().col(t).iter().copied().collect();
    structure
        .identified()
        .iter()
        .map(|p| p.value * (quadratic(&p.stiffness, &y) - lambda * quadratic(&p.mass, &y)) / lambda)
        .collect()
}

/// Identifies one parameter of `structure` from measured mode `mode`'s frequency `f_hz`
/// (relative standard deviation `f_rel_std` when known), the mode paired with model mode `t`
/// (0-based, rigid-body modes counted); see the module docs.
pub fn identify(
    structure: &Structure,
    t: usize,
    mode: usize,
    f_hz: f64,
    f_rel_std: Option<f64>,
    choice: Choice,
) -> Result<FrequencyOutcome, FrequencyError> {
    identify_within(structure, t, mode, f_hz, f_rel_std, choice, None)
}

/// As [`identify`], the ends of the parameter's reach taken from `ends` (solved once for
/// every mode, [`super::reach`]) when given and `structure` carries a reduced model, and
/// solved only when the search needs them ([`Order::NewtonFirst`]).
pub fn identify_within(
    structure: &Structure,
    t: usize,
    mode: usize,
    f_hz: f64,
    f_rel_std: Option<f64>,
    choice: Choice,
    ends: Option<&Ends>,
) -> Result<FrequencyOutcome, FrequencyError> {
    let order = Order::NewtonFirst;
    identify_ordered(structure, t, mode, (f_hz, f_rel_std), choice, ends, order).map(|o| o.0)
}

/// As [`identify_within`], the ends of the reach solved in `order`; whether they were.
pub(super) fn identify_ordered(
    structure: &Structure,
    t: usize,
    mode: usize,
    (f_hz, f_rel_std): (f64, Option<f64>),
    choice: Choice,
    ends: Option<&Ends>,
    order: Order,
) -> Result<(FrequencyOutcome, bool), FrequencyError> {
    let identified = structure.identified();
    let at_all = structure.identified_indices();
    if identified.is_empty() {
        return Err(FrequencyError::NoParameter);
    }
    let start = reduced::lowest(structure, &[], t + 1)?;
    let frequency_model_hz = start.frequency_hz(t);
    let param = match choice {
        Choice::Named(i) => i,
        Choice::MostSensitive => {
            let s = sensitivities(structure, &start, t);
            (0..s.len())
                .max_by(|&a, &b| s[a].abs().total_cmp(&s[b].abs()))
                .unwrap_or(0)
        }
    };
    let probe = Probe {
        structure: structure.clone(),
        at: at_all[param],
        param: &identified[param],
        t,
    };
    let named = Named {
        mode,
        param: identified[param].name.clone(),
        model_mode: t + 1 - structure.rigid,
        measured_hz: f_hz,
    };
    let shared = ends.filter(|_| reduced::usable(structure).is_some());
    let target = hz_to_lambda(f_hz).ln();
    let root = Search::new(probe, shared, param, target, named).run(order)?;
    let s = root.s;
    if s.abs() < 1e-12 {
        return Err(FrequencyError::Insensitive {
            mode,
            param: identified[param].name.clone(),
            sensitivity: s,
        });
    }
    let ratio = root.u.exp();
    let outcome = FrequencyOutcome {
        mode,
        param,
        relative: ratio - 1.0,
        std: f_rel_std.map(|sf| ratio * 2.0 * sf / s.abs()),
        sensitivity: s,
        frequency_model_hz,
    };
    Ok((outcome, root.ends_solved))
}

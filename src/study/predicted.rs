//! First-order predicted standard deviation of every correction of a study cell: the noise
//! model propagated linearly through g, S and b at the noise-free point
//! ([`crate::identify::propagation`]).

use super::plan::{CellPlan, ModePlan};
use crate::identify::propagation::{jacobian, propagated_std};
use crate::random::NoiseKind;

pub use crate::identify::propagation::Jacobian;

/// Predicted standard deviation of every Delta p_i of `mode` (at its noise levels); `None` when the
/// noise-free system is rank deficient.
pub fn predicted_std(plan: &CellPlan, mode: &ModePlan, noise: NoiseKind) -> Option<Vec<f64>> {
    let jac = jacobian(
        &plan.projector,
        &mode.system,
        &mode.truth_shape,
        mode.truth_lambda,
    )?;
    let freq_var = mode.frequency_noise * mode.frequency_noise;
    Some(propagated_std(
        &jac,
        &mode.truth_shape,
        mode.truth_lambda,
        &plan.values,
        noise.shape_variance(mode.shape_noise),
        freq_var,
    ))
}

/// The Jacobian of Z at the noise-free point of `mode`; `None` when rank deficient.
pub fn noise_free_jacobian(plan: &CellPlan, mode: &ModePlan) -> Option<Jacobian> {
    jacobian(
        &plan.projector,
        &mode.system,
        &mode.truth_shape,
        mode.truth_lambda,
    )
}

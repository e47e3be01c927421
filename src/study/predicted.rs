//! First-order predicted standard deviation of every correction of a study cell: the noise
//! model propagated linearly through g, S and b at the noise-free point
//! ([`crate::identify::propagation`]).

use super::plan::{Cell, CellPlan, ModePlan};
use crate::identify::propagation::{jacobian, propagated_std};
use crate::random::NoiseKind;

pub use crate::identify::propagation::Jacobian;

/// Predicted standard deviation of every Delta p_i of `mode` in `cell`; `None` when the
/// noise-free system is rank deficient.
pub fn predicted_std(
    plan: &CellPlan,
    mode: &ModePlan,
    cell: &Cell,
    noise: NoiseKind,
) -> Option<Vec<f64>> {
    let jac = jacobian(
        &plan.projector,
        &mode.system,
        &mode.truth_shape,
        mode.truth_lambda,
    )?;
    let freq_var = cell.frequency_noise * cell.frequency_noise;
    Some(propagated_std(
        &jac,
        &mode.truth_shape,
        mode.truth_lambda,
        &plan.values,
        noise.shape_variance(cell.shape_noise),
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

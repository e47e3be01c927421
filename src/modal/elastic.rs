//! Whether a modal solution is that of an elastic structure: the first deformable eigenvalue
//! must stand above the solver's zero, else the structure is a mechanism (it moves without
//! deforming more ways than its rigid-body count says).

use super::{DENSE_MAX_DOFS, ModalSolution};
use crate::structure::Matrices;

/// A structure whose first deformable eigenvalue is zero to round-off: it moves without
/// deforming more ways than its rigid-body count says.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error(
    "deformable mode {mode} has frequency {frequency_hz:.3e} Hz, at the round-off level of zero: the structure is a mechanism (a joint or support stiffness too small for the rest of the model, or all stiffness removed somewhere)"
)]
pub struct Mechanism {
    /// The deformable mode (1-based).
    pub mode: usize,
    /// Its computed frequency, Hz.
    pub frequency_hz: f64,
}

/// How far above the computed rigid-body eigenvalues (the sparse solver's zero) the first
/// deformable one must stand.
const RIGID_MARGIN: f64 = 1e2;

/// Checks that the first deformable eigenvalue of `modal` (the solution of `matrices`, with
/// `rigid` rigid-body modes first) stands above the solver's zero: for the dense solve of a
/// small model, the round-off level [`Matrices::zero_eigenvalue_level`]; for the sparse
/// solver of a large one, whose low eigenvalues are accurate relative to themselves,
/// `RIGID_MARGIN` times the largest computed rigid-body eigenvalue. Never at or below 0.
pub fn check_elastic(
    matrices: &Matrices,
    modal: &ModalSolution,
    rigid: usize,
) -> Result<(), Mechanism> {
    let zero = if matrices.size() <= DENSE_MAX_DOFS {
        matrices.zero_eigenvalue_level()
    } else {
        RIGID_MARGIN
            * modal.values()[..rigid.min(modal.len())]
                .iter()
                .fold(0.0, |a: f64, l| a.max(l.abs()))
    };
    match modal.values().get(rigid) {
        Some(&lambda) if lambda <= zero => Err(Mechanism {
            mode: 1,
            frequency_hz: modal.frequency_hz(rigid),
        }),
        _ => Ok(()),
    }
}

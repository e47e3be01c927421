//! Simulated measurements: the exact eigensolution of a model (the paper's "simulated
//! identified model"), over chosen DOFs, in the measured-modes form.

use crate::measured::{MeasuredMode, MeasuredModes};
use crate::modal::ModalSolution;
use crate::model::RIGID_BODY_MODES;

/// Deformable modes `modes` (1 = first elastic) of `modal`, exact, over the DOFs `dofs`.
/// The caller guarantees every mode exists (`mode + rigid-body modes <= N`).
pub fn exact_modes(modal: &ModalSolution, modes: &[usize], dofs: &[usize]) -> MeasuredModes {
    let y = modal.vectors();
    MeasuredModes::new(
        modes
            .iter()
            .map(|&r| {
                let s = r - 1 + RIGID_BODY_MODES;
                MeasuredMode {
                    mode: r,
                    frequency_hz: modal.frequency_hz(s),
                    dofs: dofs.to_vec(),
                    values: dofs.iter().map(|&d| y[(d, s)]).collect(),
                }
            })
            .collect(),
    )
}

//! Models shared by the integration tests.
#![allow(dead_code)]

use jointid::model::Model;

#[allow(unused_imports)]
pub use jointid::model::fixtures::{paper_model, steel_bar};

/// Every DOF of a model.
pub fn all_dofs(model: &Model) -> Vec<usize> {
    (0..model.dof_count()).collect()
}

/// The translations only (rotations unmeasured).
pub fn translations(model: &Model) -> Vec<usize> {
    (0..model.dof_count()).step_by(2).collect()
}

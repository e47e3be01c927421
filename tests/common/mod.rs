//! Models shared by the integration tests.
#![allow(dead_code)]

use jointid::model::{Beam, Joint, Model};

/// A steel bar 60 mm wide and 40 mm high (the shipped paper models' section).
pub fn steel_bar(length: f64, elements: usize) -> Beam {
    Beam {
        length,
        elements,
        youngs_modulus: 2.1e11,
        density: 7850.0,
        area: 2.4e-3,
        second_moment: 3.2e-7,
    }
}

/// The paper's system: 0.20 m / 7 elements and 0.30 m / 10 elements, one joint; 38 DOF.
pub fn paper_model(k1: f64, k2: f64) -> Model {
    Model::new(
        vec![steel_bar(0.2, 7), steel_bar(0.3, 10)],
        vec![Joint { k1, k2 }],
    )
}

/// Every DOF of a model.
pub fn all_dofs(model: &Model) -> Vec<usize> {
    (0..model.dof_count()).collect()
}

/// The translations only (rotations unmeasured).
pub fn translations(model: &Model) -> Vec<usize> {
    (0..model.dof_count()).step_by(2).collect()
}

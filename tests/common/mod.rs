//! Models shared by the integration tests.
#![allow(dead_code)]

use jointid::structure::{Observation, Structure};

#[allow(unused_imports)]
pub use jointid::model::fixtures::{paper_chain, paper_model, steel_bar};

/// Every DOF of a model, as measured points.
pub fn all_dofs(model: &Structure) -> Vec<Observation> {
    (0..model.dof_count())
        .map(|d| Observation::dof(&model.dofs, d))
        .collect()
}

/// The translations only (rotations unmeasured).
pub fn translations(model: &Structure) -> Vec<Observation> {
    all_dofs(model)
        .into_iter()
        .filter(|p| !p.direction.is_rotation())
        .collect()
}

/// A fresh scratch directory for one test.
pub fn scratch(prefix: &str, name: &str) -> std::path::PathBuf {
    let dir = std::env::temp_dir().join(format!("jointid-{prefix}-{name}-{}", std::process::id()));
    let _ = std::fs::remove_dir_all(&dir);
    std::fs::create_dir_all(&dir).unwrap();
    dir
}

/// Runs the binary.
pub fn jointid(args: &[&str]) -> std::process::Output {
    std::process::Command::new(env!("CARGO_BIN_EXE_jointid"))
        .args(args)
        .output()
        .unwrap()
}

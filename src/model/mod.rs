//! Builders of the [`Structure`] every command works on, and the effects a model may lack.
//!
//! - [`chain`]: beam chains as tests are set up (the paper's Fig. 1 and real set-ups:
//!   supports, stepped beams, point masses, sensors anywhere);
//! - [`matrices`]: external finite-element models (Matrix Market K, M, dK/dp, a DOF table),
//!   and the export of any structure as one;
//! - [`matrix_market`]: the Matrix Market reader and writer;
//! - [`solid`]: a 3D brick model of a bolted lap specimen, written as an external model
//!   (independent of the chain: test data for external models);
//! - [`effects`]: physical effects a model may lack, for `diagnose` and `simulate`.
//!
//! A model file is TOML; `kind` says which builder reads it: `"chain"` (the default) or
//! `"matrices"`.
//!
//! Layer 3 (models and measurements; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`]) and, without a circle, [`crate::measured`], [`crate::extract`].

pub mod chain;
pub mod effects;
pub mod matrices;
pub mod matrix_market;
pub mod solid;

use std::path::Path;

use crate::input::{InputError, parse_toml, read_file};
use crate::structure::Structure;

pub use chain::{Beam, Chain, Joint};

/// Reads and validates a model file into its structure.
pub fn from_path(path: &Path) -> Result<Structure, InputError> {
    from_toml(&read_file(path)?, path)
}

/// [`from_path`], and for an external model the lowest pairs that its check of the rigid-body
/// modes computed, at least `elastic` of the structure (as read, before the check) beyond
/// them where the model declares its rigid-body count
/// ([`matrices::build::MatricesData::build_solved`]), with the factor that solve made: a
/// command that solves the model as read for that many modes takes them instead of solving
/// it again. A beam chain has no such solution (`None`).
pub fn from_path_solved(
    path: &Path,
    elastic: matrices::build::Elastic,
) -> Result<(Structure, Option<crate::modal::ModalSolution>), InputError> {
    let text = read_file(path)?;
    match kind(&text, path)?.as_deref() {
        Some("matrices") => matrices::from_toml_solved(&text, path, elastic)
            .map(|(s, modal)| (s, Some(modal)))
            .map_err(|e| e.into_input(path)),
        _ => Ok((from_toml(&text, path)?, None)),
    }
}

/// Parses and validates model TOML text; `file` names it in errors.
pub fn from_toml(text: &str, file: &Path) -> Result<Structure, InputError> {
    match kind(text, file)?.as_deref() {
        Some("matrices") => matrices::from_toml(text, file).map_err(|e| e.into_input(file)),
        None | Some("chain") => Ok(chain_from_toml(text, file)?.build()),
        Some(other) => Err(crate::input::FieldCheck { file }.invalid(
            "kind",
            format!("\"{other}\""),
            "it must be \"chain\" (the default) or \"matrices\"",
        )),
    }
}

/// The `kind` of a model file, if it names one.
fn kind(text: &str, file: &Path) -> Result<Option<String>, InputError> {
    #[derive(serde::Deserialize)]
    struct Kind {
        kind: Option<String>,
    }
    Ok(parse_toml::<Kind>(text, file)?.kind)
}

/// Parses and validates a beam-chain model file.
pub fn chain_from_toml(text: &str, file: &Path) -> Result<Chain, InputError> {
    let raw: chain::config::RawChain = parse_toml(text, file)?;
    raw.validate(file, text)
}

/// The paper's system on the shipped geometry (`models/paper-case-*.toml`), built in code for
/// tests and benchmarks.
pub mod fixtures {
    use super::{Beam, Chain, Joint};
    use crate::structure::{Section, SparseSym, Structure};

    /// A steel bar 60 mm wide and 40 mm high.
    pub fn steel_bar(length: f64, elements: usize) -> Beam {
        Beam::uniform(
            length,
            elements,
            Section {
                youngs_modulus: 2.1e11,
                density: 7850.0,
                area: 2.4e-3,
                second_moment: 3.2e-7,
                shear: None,
            },
        )
    }

    /// The paper's chain on the shipped geometry: 0.20 m / 7 and 0.30 m / 10 elements.
    pub fn paper_chain(k1: f64, k2: f64) -> Chain {
        Chain::free(
            vec![steel_bar(0.2, 7), steel_bar(0.3, 10)],
            vec![Joint::identified(k1, k2)],
        )
    }

    /// The structure of [`paper_chain`].
    pub fn paper_model(k1: f64, k2: f64) -> Structure {
        paper_chain(k1, k2).build()
    }

    /// Two free steel bars of 0.2 and 0.3 m, `elements` elements each, joined by the paper's
    /// joint (k1 = 1e7, k2 = 1e4 identified): the test model of the eigenpair derivatives.
    pub fn free_two_bars(elements: usize) -> Structure {
        Chain::free(
            vec![steel_bar(0.2, elements), steel_bar(0.3, elements)],
            vec![Joint::identified(1e7, 1e4)],
        )
        .build()
    }

    /// Of a model of [`free_two_bars`]: dK/dk2 of its joint, and dM of a point mass on the
    /// joint's first w DOF (the DOF before k2's first).
    pub fn k2_and_point_mass(structure: &Structure) -> (SparseSym, SparseSym) {
        let k2 = structure.identified()[1].clone();
        let joint_w = (0..structure.dof_count())
            .find(|&i| k2.stiffness.entries().iter().any(|e| e.0 == i))
            .expect("k2 couples DOFs")
            - 1;
        let mut point_mass = SparseSym::zero();
        point_mass.add(joint_w, joint_w, 1.0);
        (k2.stiffness, point_mass)
    }
}

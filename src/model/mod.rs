//! The jointed-beam model: a free-free chain of uniform Euler-Bernoulli beams, joint i
//! connecting the last node of beam i to the first node of beam i+1 (the paper's Fig. 1 with
//! two beams and one joint).
//!
//! - [`beam`]: element matrices;
//! - [`joint`]: the joint stiffness matrix of eq. (17) and its parameters;
//! - [`assembly`]: global K, M and the parameter derivatives dK/dp, dM/dp of eq. (8);
//! - [`config`]: the TOML model file, parsed and validated.

pub mod assembly;
pub mod beam;
pub mod config;
pub mod effects;
pub mod joint;
pub mod sparse;

pub use assembly::{Matrices, Parameter};
pub use beam::Beam;
pub use joint::Joint;
pub use sparse::SparseSym;

use std::fmt;

/// The two DOFs of a node, in their order within the node.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Dof {
    /// Transverse displacement, m.
    W,
    /// Rotation, rad.
    Theta,
}

impl Dof {
    /// Number of DOFs per node.
    pub const PER_NODE: usize = 2;

    /// Offset of this DOF within its node.
    pub fn offset(self) -> usize {
        match self {
            Dof::W => 0,
            Dof::Theta => 1,
        }
    }

    /// The name used in files: `w` or `theta`.
    pub fn name(self) -> &'static str {
        match self {
            Dof::W => "w",
            Dof::Theta => "theta",
        }
    }

    /// Parses `w` or `theta`.
    pub fn parse(s: &str) -> Option<Dof> {
        match s {
            "w" => Some(Dof::W),
            "theta" => Some(Dof::Theta),
            _ => None,
        }
    }
}

impl fmt::Display for Dof {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

/// Global index of DOF `dof` of node `node`.
pub fn dof_index(node: usize, dof: Dof) -> usize {
    Dof::PER_NODE * node + dof.offset()
}

/// The node and DOF kind of a global DOF index.
pub fn dof_of_index(index: usize) -> (usize, Dof) {
    let dof = if index.is_multiple_of(Dof::PER_NODE) {
        Dof::W
    } else {
        Dof::Theta
    };
    (index / Dof::PER_NODE, dof)
}

/// Number of rigid-body modes of a free-free planar beam chain (heave and pitch).
pub const RIGID_BODY_MODES: usize = 2;

/// A validated model: at least one beam and exactly `beams - 1` joints.
#[derive(Debug, Clone, PartialEq)]
pub struct Model {
    beams: Vec<Beam>,
    joints: Vec<Joint>,
}

impl Model {
    /// Builds a model; the caller guarantees `joints.len() + 1 == beams.len()` and valid
    /// values (see [`config`] for the checked path from a file).
    pub fn new(beams: Vec<Beam>, joints: Vec<Joint>) -> Self {
        assert!(!beams.is_empty() && joints.len() + 1 == beams.len());
        Self { beams, joints }
    }

    /// The beams in chain order.
    pub fn beams(&self) -> &[Beam] {
        &self.beams
    }

    /// The joints; joint `i` connects beam `i` to beam `i + 1`.
    pub fn joints(&self) -> &[Joint] {
        &self.joints
    }

    /// Number of nodes: every beam has `elements + 1` nodes of its own.
    pub fn node_count(&self) -> usize {
        self.beams.iter().map(|b| b.elements + 1).sum()
    }

    /// Number of DOFs N.
    pub fn dof_count(&self) -> usize {
        Dof::PER_NODE * self.node_count()
    }

    /// First node of beam `b`.
    pub fn first_node(&self, b: usize) -> usize {
        self.beams[..b].iter().map(|b| b.elements + 1).sum()
    }

    /// Last node of beam `b`.
    pub fn last_node(&self, b: usize) -> usize {
        self.first_node(b) + self.beams[b].elements
    }

    /// The two nodes joint `j` connects: last of beam `j`, first of beam `j + 1`.
    pub fn joint_nodes(&self, j: usize) -> (usize, usize) {
        (self.last_node(j), self.first_node(j + 1))
    }

    /// Abscissa of every node along the chain, m (the joint has no length: its two nodes
    /// share one abscissa).
    pub fn node_positions(&self) -> Vec<f64> {
        let mut x = Vec::with_capacity(self.node_count());
        let mut start = 0.0;
        for beam in &self.beams {
            let l = beam.element_length();
            x.extend((0..=beam.elements).map(|e| start + l * e as f64));
            start += beam.length;
        }
        x
    }

    /// Total mass, kg.
    pub fn mass(&self) -> f64 {
        self.beams.iter().map(Beam::mass).sum()
    }

    /// The same model with the joint parameters shifted by `delta`, in the order of
    /// [`Model::joint_parameters`] (k1, k2 of joint 1, then of joint 2, ...).
    pub fn with_joint_delta(&self, delta: &[f64]) -> Model {
        assert_eq!(delta.len(), joint::PARAMETERS_PER_JOINT * self.joints.len());
        let joints = self
            .joints
            .iter()
            .zip(delta.chunks(joint::PARAMETERS_PER_JOINT))
            .map(|(j, d)| Joint {
                k1: j.k1 + d[0],
                k2: j.k2 + d[1],
            })
            .collect();
        Model {
            beams: self.beams.clone(),
            joints,
        }
    }
}

/// The paper's system on the shipped geometry (`models/paper-case-*.toml`), built in code for
/// tests and benchmarks.
pub mod fixtures {
    use super::{Beam, Joint, Model};

    /// A steel bar 60 mm wide and 40 mm high.
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

    /// The paper's system on the shipped geometry: 0.20 m / 7 and 0.30 m / 10 elements.
    pub fn paper_model(k1: f64, k2: f64) -> Model {
        Model::new(
            vec![steel_bar(0.2, 7), steel_bar(0.3, 10)],
            vec![Joint { k1, k2 }],
        )
    }
}

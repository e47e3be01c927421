//! The beam chain, as tests are set up: uniform or stepped Euler-Bernoulli beams joined end to
//! end by joints of transversal stiffness k1 and rotational stiffness k2 (eq. (17)), free-free
//! by default or held by supports, with point masses and sensors anywhere along it. The paper's
//! Fig. 1 is the chain of two beams and one joint, free-free.
//!
//! - [`beam`]: element matrices, sections and stepped segments;
//! - [`calibration`]: the record of beams calibrated on a reference test;
//! - [`joint`]: the joint of eq. (17) and the names of its parameters;
//! - [`lap`], [`layered`], [`interface`]: a joint's overlap, and the layered lap that replaces
//!   the point joint over it (two layers, a distributed interface, its element matrices);
//! - [`support`]: the kinds of support, their table in the model file, the count of
//!   rigid-body modes;
//! - [`setup`]: point masses, sensors;
//! - [`mesh`]: nodes where things happen, elements between them;
//! - [`assembly`]: the [`crate::structure::Structure`] of a chain;
//! - [`config`]: the TOML model file, parsed and validated.

pub mod assembly;
pub mod beam;
pub mod calibration;
pub mod config;
pub mod interface;
pub mod joint;
pub mod lap;
pub mod layered;
pub mod mesh;
pub mod notch;
pub mod setup;
pub mod support;

pub use beam::{Beam, Section, Segment};
pub use calibration::{BeamCalibration, Factor};
pub use joint::Joint;
pub use lap::{Lap, Layer};
pub use mesh::Mesh;
pub use setup::{PointMass, Sensor};
pub use support::{Support, SupportKind};

/// A validated chain: at least one beam and exactly `beams - 1` joints; joint i connects the
/// last node of beam i to the first node of beam i + 1. Abscissae run from the first end.
#[derive(Debug, Clone, PartialEq)]
pub struct Chain {
    /// The beams in chain order.
    pub beams: Vec<Beam>,
    /// The joints.
    pub joints: Vec<Joint>,
    /// Supports (none: free-free).
    pub supports: Vec<Support>,
    /// Point masses.
    pub masses: Vec<PointMass>,
    /// Declared sensors.
    pub sensors: Vec<Sensor>,
    /// Extra node positions, m.
    pub nodes_at: Vec<f64>,
    /// The beams calibrated on a reference test (module [`calibration`]).
    pub calibration: Vec<BeamCalibration>,
}

impl Chain {
    /// A free-free chain of `beams` and `joints`, nothing attached. The caller guarantees
    /// `joints.len() + 1 == beams.len()` and valid values (see [`config`] for the checked path
    /// from a file).
    pub fn free(beams: Vec<Beam>, joints: Vec<Joint>) -> Self {
        assert!(!beams.is_empty() && joints.len() + 1 == beams.len());
        Self {
            beams,
            joints,
            supports: Vec::new(),
            masses: Vec::new(),
            sensors: Vec::new(),
            nodes_at: Vec::new(),
            calibration: Vec::new(),
        }
    }

    /// Length of the chain, m.
    pub fn length(&self) -> f64 {
        self.beams.iter().map(|b| b.length).sum()
    }

    /// Abscissa of the start of beam `b`, m.
    pub fn beam_start(&self, b: usize) -> f64 {
        self.beams[..b].iter().map(|b| b.length).sum()
    }

    /// Mass of all beams, kg.
    pub fn beam_mass(&self) -> f64 {
        self.beams.iter().map(Beam::mass).sum()
    }

    /// Abscissae where a node must be: rigid supports, masses hanging on springs, requested
    /// nodes, the ends of the joints' overlaps (the sensors, the rigidly attached masses and
    /// the supports of springs are nodes where they can be: [`Chain::point_positions`], module
    /// `mesh`).
    pub fn feature_positions(&self) -> Vec<f64> {
        self.supports
            .iter()
            .filter(|s| s.kind.holds_a_motion())
            .map(|s| s.x)
            .chain(
                self.masses
                    .iter()
                    .filter(|m| m.spring.is_some())
                    .map(|m| m.x),
            )
            .chain(self.nodes_at.iter().copied())
            .chain(self.overlaps().into_iter().flat_map(|(_, a, b)| [a, b]))
            .collect()
    }

    /// Abscissae of what the model can read or carry between nodes, by the elements'
    /// interpolation: the sensors, the rigidly attached masses and the supports of springs
    /// (module `mesh`).
    pub fn point_positions(&self) -> Vec<f64> {
        self.sensors
            .iter()
            .map(|s| s.x)
            .chain(
                self.supports
                    .iter()
                    .filter(|s| !s.kind.holds_a_motion())
                    .map(|s| s.x),
            )
            .chain(
                self.masses
                    .iter()
                    .filter(|m| m.spring.is_none())
                    .map(|m| m.x),
            )
            .collect()
    }

    /// Every joint's overlap that the model file gives: (joint, start, end), m.
    pub fn overlaps(&self) -> Vec<(usize, f64, f64)> {
        self.joints
            .iter()
            .enumerate()
            .filter_map(|(j, joint)| {
                let (a, b) = joint.lap?.span(self.beam_start(j + 1));
                Some((j, a, b))
            })
            .collect()
    }

    /// The same chain with every joint whose overlap is given made its layered lap.
    pub fn with_laps(&self) -> Chain {
        let mut chain = self.clone();
        for joint in &mut chain.joints {
            if let Some(lap) = &mut joint.lap {
                lap.active = true;
                joint.roles = lap.roles;
            }
        }
        chain
    }
}

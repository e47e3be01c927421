//! The joint of eq. (17): transversal stiffness k1 between the two `w`, rotational stiffness
//! k2 between the two `theta`, no transversal-rotational coupling.
//!
//! ```text
//!          [  k1   0   -k1   0  ]   w_a
//!   K^j =  [  0    k2   0   -k2 ]   theta_a
//!          [ -k1   0    k1   0  ]   w_b
//!          [  0   -k2   0    k2 ]   theta_b
//! ```

/// Number of identified parameters per joint (q = 2 per joint in the paper).
pub const PARAMETERS_PER_JOINT: usize = 2;

use super::lap::Lap;
use crate::structure::Role;

/// Stiffness parameters of one joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Joint {
    /// Transversal stiffness k1, N/m (unused when the joint is a layered lap).
    pub k1: f64,
    /// Rotational stiffness k2, N m/rad (unused when the joint is a layered lap).
    pub k2: f64,
    /// Whether k1, k2 are identified or held fixed.
    pub roles: [Role; 2],
    /// The joint's overlap, when the model file gives it: the joint itself when it is
    /// [`Lap::active`], else the layered lap a diagnosis tries in place of k1, k2.
    pub lap: Option<Lap>,
}

impl Joint {
    /// A joint whose k1 and k2 are both identified.
    pub fn identified(k1: f64, k2: f64) -> Self {
        Self {
            k1,
            k2,
            roles: [Role::Identified; 2],
            lap: None,
        }
    }

    /// The layered lap this joint is, if it is one.
    pub fn active_lap(&self) -> Option<&Lap> {
        self.lap.as_ref().filter(|l| l.active)
    }
}

/// Which stiffness of a joint a parameter is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum JointStiffness {
    /// k1, couples the two transverse displacements.
    Transversal,
    /// k2, couples the two rotations.
    Rotational,
}

impl JointStiffness {
    /// Both, in parameter order.
    pub const ALL: [JointStiffness; PARAMETERS_PER_JOINT] =
        [JointStiffness::Transversal, JointStiffness::Rotational];

    /// `k1` or `k2`.
    pub fn short_name(self) -> &'static str {
        match self {
            JointStiffness::Transversal => "k1",
            JointStiffness::Rotational => "k2",
        }
    }

    /// Unit of the parameter.
    pub fn unit(self) -> &'static str {
        match self {
            JointStiffness::Transversal => "N/m",
            JointStiffness::Rotational => "N m/rad",
        }
    }

    /// The value of this stiffness in `joint`.
    pub fn of(self, joint: &Joint) -> f64 {
        match self {
            JointStiffness::Transversal => joint.k1,
            JointStiffness::Rotational => joint.k2,
        }
    }
}

/// Name of a joint parameter in output files: `k1`/`k2` with one joint, `joint2.k1` with several.
pub fn parameter_name(joint: usize, joint_count: usize, kind: JointStiffness) -> String {
    if joint_count == 1 {
        kind.short_name().to_string()
    } else {
        format!("joint{}.{}", joint + 1, kind.short_name())
    }
}

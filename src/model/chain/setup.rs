//! What is attached to a beam chain in a test: point masses (with rotary inertia, rigidly
//! attached or hanging on a spring) and sensors. How it is held: [`super::support`].

use crate::structure::Direction;

/// A point mass at abscissa `x` (a stinger, an accelerometer, a bolt head).
#[derive(Debug, Clone, PartialEq)]
pub struct PointMass {
    /// Abscissa, m.
    pub x: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Rotary inertia about the bending axis, kg m^2 (rigidly attached masses only).
    pub rotary_inertia: f64,
    /// `Some(k)`: the mass hangs on a translational spring of stiffness k (N/m) and moves on
    /// its own DOF; `None`: rigidly attached.
    pub spring: Option<f64>,
    /// Whether the mass is an identified parameter (its rotary inertia scales with it).
    pub identify: bool,
}

/// A sensor declared in the model: a node is placed at it, `simulate` can read it, and its
/// mass, if given, is part of the model.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensor {
    /// Abscissa, m.
    pub x: f64,
    /// What it measures: w or theta.
    pub direction: Direction,
    /// Label in measured files, if any.
    pub label: Option<String>,
    /// Mass, kg (0: not modelled).
    pub mass: f64,
}

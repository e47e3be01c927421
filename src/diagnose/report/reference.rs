//! The joint with and without the reference test (computed by module `diagnose::absorbed`).

use crate::model::chain::BeamCalibration;

/// One joint parameter with the beams calibrated and as typed.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Shift {
    /// The parameter (`k1`, `joint2.k_n`, ...).
    pub name: String,
    /// Its value with the beams calibrated (the diagnosis's `before`).
    pub calibrated: f64,
    /// Its standard error there.
    pub se: f64,
    /// Its value with the beams as typed.
    pub typed: f64,
    /// typed / calibrated.
    pub ratio: f64,
    /// (typed - calibrated) / se: the shift in standard errors.
    pub sigmas: f64,
}

/// The joint with and without the reference test.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Absorbed {
    /// The beams' calibration, from the model file.
    pub beams: Vec<BeamCalibration>,
    /// Every joint parameter.
    pub parameters: Vec<Shift>,
    /// RMS of the relative frequency errors of the joint calibrated on the typed beams, %
    /// (the diagnosis's `before` is that on the calibrated beams).
    pub typed_frequency_rms_pct: f64,
}

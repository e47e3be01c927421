//! What the joint would have absorbed without the reference test: on a model whose beams were
//! calibrated (`jointid calibrate`, the record `[beam.calibrated]`), the joint calibrated on
//! the beams as typed beside the joint of the diagnosis (calibrated on the calibrated beams,
//! the same modes, the same error model: module `calibrate`). A joint that moves by many of its
//! standard errors between the two would have carried the material's error as its own.

use std::sync::Arc;

use super::DiagnoseError;
use super::calibrate::{calibrate, prepare};
use super::fit::{self, Calibration, Discrepancy};
use super::report::{Absorbed, Report, Shift};
use super::settings::DiagnoseSettings;
use crate::measured::MeasuredModes;
use crate::model::chain::BeamCalibration;
use crate::structure::Structure;

/// The joint of `report` (a diagnosis of `measured` on the calibrated model) beside the joint
/// calibrated on `typed`, the same model with its beams as typed; `beams` the calibration.
pub fn absorbed(
    typed: &Structure,
    beams: &[BeamCalibration],
    measured: &MeasuredModes,
    settings: &DiagnoseSettings,
    report: &Report,
) -> Result<Absorbed, DiagnoseError> {
    let (ctx, _) = prepare(typed, measured, settings, None)?;
    let calibration = Calibration {
        noise: settings.noise,
        discrepancy: Discrepancy::default(),
        pairing: settings.pairing.clone(),
        shape_floor: fit::SHAPE_FLOOR,
        measured_std: measured.has_std(),
    };
    let fitted = calibrate(&Arc::clone(&ctx), measured, &calibration)?;
    let rms = {
        let e = fit::residuals(&fitted.base, &fitted.measured).frequency;
        100.0 * (e.iter().map(|x| x * x).sum::<f64>() / e.len().max(1) as f64).sqrt()
    };
    let parameters = report
        .before
        .parameters
        .iter()
        .zip(&fitted.base.estimates)
        .map(|(with, without)| Shift {
            name: with.name.clone(),
            calibrated: with.value,
            se: with.se,
            typed: without.value,
            ratio: without.value / with.value,
            sigmas: (without.value - with.value) / with.se,
        })
        .collect();
    Ok(Absorbed {
        beams: beams.to_vec(),
        parameters,
        typed_frequency_rms_pct: rms,
    })
}

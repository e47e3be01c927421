//! How a fitted model compares with the data: frequency errors, MACs, the shape misfit, chi^2
//! and its goodness of fit, mode by mode and in all.

use serde::Serialize;

use crate::diagnose::fit::{Discrepancy, Estimate, Fitted, chi2_of, residuals};
use crate::diagnose::noise::NoiseEstimate;
use crate::diagnose::pairing::mac;
use crate::measured::MeasuredModes;

/// How one measured mode compares with its paired model mode.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeError {
    /// Measured mode r.
    pub mode: usize,
    /// Paired model mode (deformable numbering, 1 = first elastic).
    pub model_mode: usize,
    /// Measured frequency, Hz.
    pub frequency_measured_hz: f64,
    /// Model frequency, Hz.
    pub frequency_model_hz: f64,
    /// (model - measured) / measured, %.
    pub frequency_error_pct: f64,
    /// MAC over the measured DOFs.
    pub mac: f64,
    /// RMS of (c y_model - y_measured) over the measured DOFs, % of the largest measured
    /// component.
    pub shape_rms_pct: f64,
    /// The model shape at the measured DOFs, scaled and signed to the measured one (for
    /// plots; not in the JSON).
    #[serde(skip)]
    pub model_shape: Vec<f64>,
}

/// How a model compares with all the data.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ErrorSummary {
    /// RMS of the relative frequency errors, %.
    pub frequency_rms_pct: f64,
    /// Smallest MAC.
    pub min_mac: f64,
    /// Mean MAC.
    pub mean_mac: f64,
    /// chi^2 of the residuals under the measurement error (the yardstick: module
    /// `diagnose::yardstick`).
    pub chi2: f64,
    /// Its degrees of freedom (data minus fitted unknowns).
    pub dof: usize,
    /// chi^2 / dof (about 1 at the noise level; below 1 where the shape floor dominates).
    pub chi2_per_dof: f64,
    /// P(chi^2_dof > chi^2): the goodness of fit.
    pub p_value: f64,
    /// The model's discrepancy: what it misses beyond the measurement error (for the model as
    /// given, that of its residuals).
    pub discrepancy: Discrepancy,
    /// The fitted parameters (joints, then effect), with standard errors.
    pub parameters: Vec<Estimate>,
    /// Mode by mode.
    pub modes: Vec<ModeError>,
}

impl ErrorSummary {
    /// The summary of a fitted (or as-given) model; its chi^2 and goodness of fit under the
    /// measurement error `noise` (the yardstick).
    pub fn of(fitted: &Fitted, measured: &MeasuredModes, noise: &NoiseEstimate) -> Self {
        let chi2 = chi2_of(&residuals(fitted, measured), measured, &noise.calibration());
        let modes: Vec<ModeError> = measured
            .modes()
            .iter()
            .enumerate()
            .map(|(r, m)| {
                let s = fitted.pairing.model_index[r];
                let modal = fitted.modal_of(r);
                let y = modal.vectors();
                let model: Vec<f64> = m.points.iter().map(|p| p.read_column(y, s)).collect();
                let sign = if model.iter().zip(&m.values).map(|(a, b)| a * b).sum::<f64>() < 0.0 {
                    -1.0
                } else {
                    1.0
                };
                let peak = m.peak();
                let ss: f64 = model
                    .iter()
                    .zip(&m.values)
                    .map(|(a, b)| (fitted.scales[r] * sign * a - b).powi(2))
                    .sum();
                let f = modal.frequency_hz(s);
                ModeError {
                    mode: m.mode,
                    model_mode: s + 1 - fitted.configured.structure.rigid,
                    frequency_measured_hz: m.frequency_hz,
                    frequency_model_hz: f,
                    frequency_error_pct: 100.0 * (f - m.frequency_hz) / m.frequency_hz,
                    mac: mac(&model, &m.values),
                    shape_rms_pct: 100.0 * (ss / m.values.len() as f64).sqrt() / peak,
                    model_shape: model.iter().map(|a| fitted.scales[r] * sign * a).collect(),
                }
            })
            .collect();
        let count = modes.len() as f64;
        ErrorSummary {
            frequency_rms_pct: (modes
                .iter()
                .map(|e| e.frequency_error_pct.powi(2))
                .sum::<f64>()
                / count)
                .sqrt(),
            min_mac: modes.iter().map(|e| e.mac).fold(f64::INFINITY, f64::min),
            mean_mac: modes.iter().map(|e| e.mac).sum::<f64>() / count,
            chi2,
            dof: fitted.dof,
            chi2_per_dof: chi2 / fitted.dof as f64,
            p_value: noise.fit_p_value(chi2, fitted.dof),
            discrepancy: fitted.discrepancy.clone(),
            parameters: fitted.estimates.clone(),
            modes,
        }
    }
}

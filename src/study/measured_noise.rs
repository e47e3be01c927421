//! The noise of a study taken from a measured-modes file that carries standard errors
//! (`[monte_carlo] noise = "measured"`, `measured = "modes.csv"`): every identified mode gets
//! the relative errors of the same mode of the file, and the grid's `shape_noise` and
//! `frequency_noise` become factors on them (1 = as measured).
//!
//! A study perturbs every shape component relatively, y_i (1 + e_i). The file's errors are
//! absolute, sigma_i on a component v_i, at the file's points, which need not be the DOFs a
//! cell identifies. Each mode's file errors are therefore summarised as one relative standard
//! deviation of equal energy,
//!
//!   a_r = sqrt( sum_i sigma_i^2 / sum_i v_i^2 ),
//!
//! over the components with a positive error (the peak that normalises an extracted mode is
//! exact by construction: its error is spread over the others, and it is left out of both
//! sums). With errors proportional to the components, as the coherence gives them
//! (sigma_i = a |v_i|), a_r is that a exactly. The frequency's relative standard deviation is
//! frequency_std / frequency_hz. The errors are drawn normal.

use std::path::{Path, PathBuf};

use crate::input::{FieldCheck, InputError, Number};
use crate::measured::{MeasuredMode, MeasuredModes};
use crate::structure::Structure;

/// The relative standard deviations of one mode of a measured file.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ModeNoise {
    /// Deformable mode number r.
    pub mode: usize,
    /// Relative standard deviation of every shape component, a_r (module docs).
    pub shape: f64,
    /// Relative standard deviation of the frequency.
    pub frequency: f64,
}

/// A study's noise taken from a measured file.
#[derive(Debug, Clone, PartialEq)]
pub struct MeasuredNoise {
    /// The measured-modes file, resolved.
    pub file: PathBuf,
    /// One entry per mode of the study, in the study's mode order.
    pub modes: Vec<ModeNoise>,
}

impl MeasuredNoise {
    /// Reads `file` against `model` and takes the relative errors of every mode in `modes`;
    /// `check` and `field` (the study's `monte_carlo.measured`) name the study file's field
    /// in errors.
    pub fn read(
        file: &Path,
        model: &Structure,
        modes: &[usize],
        check: &FieldCheck,
        field: &str,
    ) -> Result<Self, InputError> {
        let value = format!("\"{}\"", file.display());
        let measured = MeasuredModes::from_path(file, model)
            .map_err(|e| check.invalid(field, &value, format!("the file cannot be used: {e}")))?;
        let modes = modes
            .iter()
            .map(|&r| {
                let mode = measured.get(r).ok_or_else(|| {
                    check.invalid(
                        field,
                        &value,
                        format!("the file has no mode {r}, which the grid identifies"),
                    )
                })?;
                mode_noise(mode).map_err(|why| {
                    check.invalid(field, &value, format!("mode {r} of the file {why}"))
                })
            })
            .collect::<Result<Vec<_>, _>>()?;
        Ok(Self {
            file: file.to_path_buf(),
            modes,
        })
    }

    /// The relative errors of mode r (one of the study's modes).
    pub fn of(&self, r: usize) -> Option<&ModeNoise> {
        self.modes.iter().find(|m| m.mode == r)
    }
}

/// The relative errors of one measured mode, or why it has none to give.
pub fn mode_noise(mode: &MeasuredMode) -> Result<ModeNoise, String> {
    let (Some(frequency_std), Some(value_std)) = (mode.frequency_std, mode.value_std.as_ref())
    else {
        return Err(
            "carries no standard errors: a measured noise needs the columns frequency_std and \
             value_std (written by `jointid extract`)"
                .to_string(),
        );
    };
    let (noise, signal) = mode
        .values
        .iter()
        .zip(value_std)
        .filter(|(_, s)| **s > 0.0)
        .fold((0.0, 0.0), |(n, s), (v, e)| (n + e * e, s + v * v));
    if signal <= 0.0 {
        return Err(
            "has no shape component with a positive standard error and a nonzero value".to_string(),
        );
    }
    let shape = (noise / signal).sqrt();
    let frequency = frequency_std / mode.frequency_hz;
    if !(shape.is_finite() && frequency.is_finite() && frequency > 0.0) {
        return Err(format!(
            "gives relative errors that are not finite and positive (shape {}, frequency {})",
            Number(shape),
            Number(frequency)
        ));
    }
    Ok(ModeNoise {
        mode: mode.mode,
        shape,
        frequency,
    })
}

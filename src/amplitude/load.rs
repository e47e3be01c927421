//! The data of an amplitude fit from a validated levels file ([`super::levels`]): per level
//! and mode the frequency and damping ratio (with their standard errors) of the measured-modes
//! file, and the response amplitude.
//!
//! The amplitude A is the displacement amplitude at the reference sensor, A = a / omega_r^2,
//! a the acceleration amplitude: given, or the excitation times the magnitude of the
//! reference's FRF at the mode's frequency (the steady response to a harmonic drive of the
//! level's size at resonance). Under a flat random excitation of RMS `excitation` over
//! `random_band_hz` = B, a is the RMS of the mode's response instead: the integral of the
//! resonance's |H|^2 (a Lorentzian of half-width zeta f_r) is |H_peak|^2 pi zeta f_r, so
//! a = excitation |H_peak| sqrt(pi zeta_r f_r / B). The FRF's magnitude is its largest within f_r (1 +- 2 zeta_r),
//! refined by a parabola through that line and its neighbours; a velocity or displacement FRF
//! is turned into acceleration by omega or omega^2.
//!
//! Every amplitude is checked to be finite and at least the smallest normal double: a dead
//! channel (an FRF whose peak is 0) is refused naming the FRF file, an amplitude that
//! overflows or underflows naming the field of the levels file it comes from (the level's
//! excitation, or its given acceleration).
//!
//! Imports: [`super::levels`], [`super::fit`], [`crate::input`], [`crate::structure`],
//! [`crate::model`], [`crate::measured`],
//! [`crate::uff`].

use std::f64::consts::PI;
use std::path::Path;

use super::AmplitudeError;
use super::fit::Series;
use super::levels::{Level, Levels, Source};
use crate::input::{InputError, Number};
use crate::measured::{MeasuredMode, MeasuredModes};
use crate::structure::{Observation, Structure};
use crate::uff::{Function, FunctionType, Record};

/// One level's row of one mode, as read.
#[derive(Debug, Clone, PartialEq)]
pub struct Row {
    /// Excitation level.
    pub excitation: f64,
    /// Mode number.
    pub mode: usize,
    /// Acceleration amplitude (RMS under random excitation) at the reference (m/s^2).
    pub acceleration: f64,
    /// Displacement amplitude (RMS under random excitation) at the reference (m).
    pub amplitude: f64,
    /// Frequency (Hz).
    pub frequency_hz: f64,
    /// Its standard error (0 when not given).
    pub frequency_std: f64,
    /// Damping ratio.
    pub damping: f64,
    /// Its standard error (0 when not given).
    pub damping_std: f64,
}

/// One mode's rows across levels.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeData {
    /// Mode number.
    pub mode: usize,
    /// The reference sensor's point in the first level's modes file, when the levels file
    /// names it (`reference_x`).
    pub reference: Option<Observation>,
    /// One row per level, in the levels file's order.
    pub rows: Vec<Row>,
}

impl ModeData {
    /// The series the fit works on: lambda = (2 pi f)^2 with se 2 lambda s_f / f.
    pub fn series(&self) -> Series {
        let lambda = |f: f64| (2.0 * PI * f).powi(2);
        Series {
            amplitude: self.rows.iter().map(|r| r.amplitude).collect(),
            stiffness: self.rows.iter().map(|r| lambda(r.frequency_hz)).collect(),
            stiffness_std: self
                .rows
                .iter()
                .map(|r| 2.0 * lambda(r.frequency_hz) * r.frequency_std / r.frequency_hz)
                .collect(),
            damping: self.rows.iter().map(|r| r.damping).collect(),
            damping_std: self.rows.iter().map(|r| r.damping_std).collect(),
        }
    }
}

fn data_error(file: &Path, message: String) -> AmplitudeError {
    AmplitudeError::Data {
        file: file.to_path_buf(),
        message,
    }
}

/// The FRF of `node` among the records of `file`, with the power p of omega that turns it
/// into an accelerance (2 displacement, 1 velocity, 0 acceleration).
fn reference_frf<'r>(
    records: &'r [Record],
    node: u64,
    file: &Path,
) -> Result<(&'r Function, i32), AmplitudeError> {
    let f = records
        .iter()
        .find_map(|r| match r {
            Record::Function(f) if f.function_type == FunctionType::Frf && f.response.node == node => {
                Some(f)
            }
            _ => None,
        })
        .ok_or_else(|| data_error(file, format!("no FRF (dataset 58, type 4) of response node {node} (`reference` of the levels file)")))?;
    let power = match f.ordinate_axis.data_type {
        12 => 0,
        11 => 1,
        8 => 2,
        other => {
            return Err(data_error(
                file,
                format!(
                    "the FRF of node {node} has ordinate data type {other}: it must be 12 \
                     (acceleration), 11 (velocity) or 8 (displacement)"
                ),
            ));
        }
    };
    Ok((f, power))
}

/// The acceleration magnitude of `frf` at the mode (module docs), None when the mode's band
/// lies outside the FRF's lines.
fn peak(frf: &Function, power: i32, mode: &MeasuredMode) -> Option<f64> {
    let f = frf.abscissa_values();
    let h = frf.ordinate.to_complex();
    let fr = mode.frequency_hz;
    let half = 2.0 * mode.damping_ratio? * fr;
    let inside: Vec<usize> = (0..f.len())
        .filter(|&i| (f[i] - fr).abs() <= half.max(f64::EPSILON))
        .collect();
    let nearest = (0..f.len()).min_by(|&a, &b| (f[a] - fr).abs().total_cmp(&(f[b] - fr).abs()))?;
    let candidates = if inside.is_empty() {
        vec![nearest]
    } else {
        inside
    };
    let k = *candidates
        .iter()
        .max_by(|&&a, &&b| h[a].norm().total_cmp(&h[b].norm()))?;
    if k == 0 || k + 1 >= f.len() || (f[k] - fr).abs() > 2.0 * (half + (f[1] - f[0]).abs()) {
        return None;
    }
    let accel = |i: usize| h[i].norm() * (2.0 * PI * f[i]).powi(power);
    let (y0, y1, y2) = (accel(k - 1), accel(k), accel(k + 1));
    let curvature = y0 - 2.0 * y1 + y2;
    let top = if curvature < 0.0 {
        let t = 0.5 * (y0 - y2) / curvature;
        y1 - 0.25 * (y0 - y2) * t
    } else {
        y1
    };
    Some(top)
}

/// The range an amplitude must lie in, as messages say it.
const RANGE: &str = "outside a double's range (2.2e-308 to 1.8e308)";

/// Whether an amplitude is finite and at least the smallest normal double: zero (a dead
/// channel), an underflow or an overflow would make the fit's logarithms, ratios and
/// chi^2 infinite or NaN.
fn in_range(v: f64) -> bool {
    v.is_finite() && v >= f64::MIN_POSITIVE
}

/// A level's amplitudes: given, or from its FRFs.
enum Amplitudes<'a> {
    /// Acceleration amplitudes per mode.
    Given(&'a [f64]),
    /// The FRF file and its records.
    Frf(&'a Path, Vec<Record>),
}

/// The acceleration amplitude of mode `m` (the `k`-th of its file) at `level` (module docs).
fn acceleration(
    source: &Amplitudes,
    k: usize,
    m: &MeasuredMode,
    damping: f64,
    level: &Level,
    levels: &Levels,
) -> Result<f64, AmplitudeError> {
    let (path, records) = match source {
        Amplitudes::Given(values) => return Ok(values[k]),
        Amplitudes::Frf(path, records) => (path, records),
    };
    let node = levels.reference.unwrap_or_default();
    let (f, power) = reference_frf(records, node, path)?;
    let top = peak(f, power, m).ok_or_else(|| {
        data_error(
            path,
            format!(
                "mode {} at {} Hz lies outside the lines of the FRF of node {node}",
                m.mode, m.frequency_hz
            ),
        )
    })?;
    if !in_range(top) {
        return Err(data_error(
            path,
            format!(
                "the FRF of node {node} peaks at {} near mode {} ({} Hz): a dead channel gives \
                 no amplitude; check it or the `reference`",
                Number(top),
                m.mode,
                Number(m.frequency_hz)
            ),
        ));
    }
    // A random excitation of RMS `excitation` spread flat over B Hz: the mode's RMS response
    // is |H_peak| excitation sqrt(pi zeta f_r / B).
    let share = levels
        .random_band_hz
        .map_or(1.0, |b| (PI * damping * m.frequency_hz / b).sqrt());
    Ok(top * level.excitation * share)
}

/// The rows of level `i`: one per mode of its modes file.
fn level_rows(
    i: usize,
    level: &Level,
    levels: &Levels,
    model: &Structure,
) -> Result<Vec<Row>, AmplitudeError> {
    let modes = MeasuredModes::from_path(&level.modes, model)?;
    let source = match &level.source {
        Source::Acceleration(values) if values.len() != modes.modes().len() => {
            return Err(AmplitudeError::Input(InputError::Invalid {
                file: levels.file.clone(),
                path: format!("level[{i}].acceleration"),
                value: format!("{} value(s)", values.len()),
                allowed: format!(
                    "one per mode of {} ({} modes)",
                    level.modes.display(),
                    modes.modes().len()
                ),
            }));
        }
        Source::Acceleration(values) => Amplitudes::Given(values),
        Source::Frf(path) => Amplitudes::Frf(path, crate::uff::read_path(path)?),
    };
    let mut rows = Vec::with_capacity(modes.modes().len());
    for (k, m) in modes.modes().iter().enumerate() {
        let damping = match m.damping_ratio {
            Some(z) if z > 0.0 => z,
            _ => {
                return Err(data_error(
                    &level.modes,
                    format!(
                        "mode {} has no positive damping_ratio: the amplitude fit needs the \
                         damping of every mode (jointid extract writes it)",
                        m.mode
                    ),
                ));
            }
        };
        let acceleration = acceleration(&source, k, m, damping, level, levels)?;
        let omega = 2.0 * PI * m.frequency_hz;
        let amplitude = acceleration / (omega * omega);
        if !(in_range(acceleration) && in_range(amplitude)) {
            let (field, value) = match &source {
                Amplitudes::Given(values) => (format!("level[{i}].acceleration[{k}]"), values[k]),
                Amplitudes::Frf(..) => (format!("level[{i}].excitation"), level.excitation),
            };
            return Err(AmplitudeError::Input(InputError::Invalid {
                file: levels.file.clone(),
                path: field,
                value: Number(value).to_string(),
                allowed: if in_range(acceleration) {
                    format!("mode {}: a / omega^2 = {amplitude:.3e} m, {RANGE}", m.mode)
                } else {
                    format!("mode {}: a = {acceleration:.3e} m/s^2, {RANGE}", m.mode)
                },
            }));
        }
        rows.push(Row {
            excitation: level.excitation,
            mode: m.mode,
            acceleration,
            amplitude,
            frequency_hz: m.frequency_hz,
            frequency_std: m.frequency_std.unwrap_or(0.0),
            damping,
            damping_std: m.damping_std.unwrap_or(0.0),
        });
    }
    Ok(rows)
}

/// Reads every level's modes and amplitudes (module docs) against `model`: one [`ModeData`]
/// per mode of the first level, each with a row per level.
pub fn load(levels: &Levels, model: &Structure) -> Result<Vec<ModeData>, AmplitudeError> {
    let per_level: Vec<Vec<Row>> = levels
        .levels
        .iter()
        .enumerate()
        .map(|(i, level)| level_rows(i, level, levels, model))
        .collect::<Result<_, _>>()?;
    let first: Vec<usize> = per_level[0].iter().map(|r| r.mode).collect();
    let mut out: Vec<ModeData> = first
        .iter()
        .map(|&mode| ModeData {
            mode,
            reference: None,
            rows: Vec::new(),
        })
        .collect();
    if let Some(point) = &levels.reference_point {
        find_references(levels, point, model, &mut out)?;
    }
    for (level, rows) in levels.levels.iter().zip(&per_level) {
        for data in &mut out {
            let row = rows.iter().find(|r| r.mode == data.mode).ok_or_else(|| {
                let list: Vec<String> = first.iter().map(|m| m.to_string()).collect();
                data_error(
                    &level.modes,
                    format!(
                        "mode {} is missing: every level must hold the modes of the first \
                         level ({})",
                        data.mode,
                        list.join(", ")
                    ),
                )
            })?;
            data.rows.push(row.clone());
        }
    }
    Ok(out)
}

/// Each mode's reference point `(x, dof)` (`reference_x`, `reference_dof`) among its points
/// in the first level's modes file.
fn find_references(
    levels: &Levels,
    (x, dof): &(f64, String),
    model: &Structure,
    out: &mut [ModeData],
) -> Result<(), AmplitudeError> {
    let first = &levels.levels[0].modes;
    let modes = MeasuredModes::from_path(first, model)?;
    for data in out {
        let Some(m) = modes.modes().iter().find(|m| m.mode == data.mode) else {
            continue;
        };
        let found = m.points.iter().find(|p| {
            (p.x - x).abs() <= 1e-9 * x.abs().max(1.0) && p.direction.to_string() == *dof
        });
        data.reference = Some(found.cloned().ok_or_else(|| {
            let list: Vec<String> = m.points.iter().map(|p| p.label.clone()).collect();
            data_error(
                first,
                format!(
                    "mode {} has no point at x = {x}, {dof} (`reference_x`, `reference_dof` of {}); its points: {}",
                    m.mode,
                    levels.file.display(),
                    list.join(", ")
                ),
            )
        })?);
    }
    Ok(())
}

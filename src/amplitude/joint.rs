//! The joint's own stiffness and damping against amplitude (`jointid amplitude --joint P`): per
//! level and mode, the joint parameter p that the model needs for that level's frequency
//! (`crate::identify::frequency_only`, the mode paired with the model's deformable mode of its
//! number), and the joint's damping ratio zeta_j = zeta / s, s = d ln lambda / d ln p the share
//! of the mode's strain energy that the joint stores (the modal damping all the joint's: what
//! a dissipative joint element of loss factor 2 zeta_j gives the mode to first order). The three
//! laws are then fitted on (A, p, zeta_j) as on the modal series. A is the joint's own
//! deformation amplitude when the levels file names the reference sensor (`reference_x`):
//! A_j = A sqrt(y^T (dK/dp) y) / |y_ref|, y the model's mode at the level's p (for a spring
//! parameter the relative displacement or rotation across the joint, m or rad); else the
//! reference sensor's amplitude, as for the modal series.
//!
//! Before and after, per level: the frequencies of the model with the constant law's joint (one
//! stiffness for every level) and with the chosen law's joint at the level's amplitude, against
//! the measured ones.
//!
//! Imports: [`super::load`](mod@super::load), [`super::select`], [`super::laws`],
//! [`crate::identify`], [`crate::modal`], [`crate::structure`].

use super::AmplitudeError;
use super::fit::Series;
use super::laws::Law;
use super::load::ModeData;
use super::select::ModeFit;
use crate::identify::frequency_only::{self, Choice};
use crate::modal::ModalSolution;
use crate::structure::{Observation, Structure};

/// One mode's joint parameter and damping per level.
#[derive(Debug, Clone, PartialEq)]
pub struct JointData {
    /// The parameter's name in the model.
    pub name: String,
    /// Its unit.
    pub unit: &'static str,
    /// Its value per level.
    pub value: Vec<f64>,
    /// Its standard error per level, from the frequency's (0 when not given).
    pub std: Vec<f64>,
    /// d ln lambda / d ln p at each level's value.
    pub sensitivity: Vec<f64>,
    /// The amplitude the laws are fitted against, per level: the joint's deformation (m or
    /// rad), or the reference sensor's displacement when no reference point is named.
    pub amplitude: Vec<f64>,
    /// Whether `amplitude` is the joint's deformation.
    pub at_joint: bool,
    /// The joint's damping ratio zeta / s per level.
    pub damping: Vec<f64>,
    /// Its standard error.
    pub damping_std: Vec<f64>,
}

impl JointData {
    /// The series the laws are fitted on.
    pub fn series(&self) -> Series {
        Series {
            amplitude: self.amplitude.clone(),
            stiffness: self.value.clone(),
            stiffness_std: self.std.clone(),
            damping: self.damping.clone(),
            damping_std: self.damping_std.clone(),
        }
    }
}

/// Per level: the measured frequency and the model's with the constant and the chosen joint.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct LevelError {
    /// The level's excitation.
    pub excitation: f64,
    /// The amplitude of the joint's laws ([`JointData::amplitude`]).
    pub amplitude: f64,
    /// Measured frequency (Hz).
    pub measured_hz: f64,
    /// The model's with the constant law's joint (Hz).
    pub constant_hz: f64,
    /// The model's with the chosen law's joint at this amplitude (Hz).
    pub selected_hz: f64,
}

/// The joint data of one mode (module docs); `param` indexes [`Structure::identified`].
pub fn joint_data(
    model: &Structure,
    param: usize,
    data: &ModeData,
) -> Result<JointData, AmplitudeError> {
    let p0 = model.identified()[param].value;
    let t = model
        .model_mode(data.mode)
        .map_err(|e| AmplitudeError::Joint(e.to_string()))?;
    let mut out = JointData {
        name: model.identified()[param].name.clone(),
        unit: model.identified()[param].unit,
        value: Vec::new(),
        std: Vec::new(),
        sensitivity: Vec::new(),
        amplitude: Vec::new(),
        at_joint: data.reference.is_some(),
        damping: Vec::new(),
        damping_std: Vec::new(),
    };
    for r in &data.rows {
        let rel_std = (r.frequency_std > 0.0).then(|| r.frequency_std / r.frequency_hz);
        let o = frequency_only::identify(
            model,
            t,
            data.mode,
            r.frequency_hz,
            rel_std,
            Choice::Named(param),
        )
        .map_err(|e| AmplitudeError::Joint(format!("level {}: {e}", r.excitation)))?;
        let s = o.sensitivity;
        let p = p0 * (1.0 + o.relative);
        out.amplitude.push(match &data.reference {
            Some(reference) => r.amplitude * deformation(model, param, t, p, reference)?,
            None => r.amplitude,
        });
        out.value.push(p);
        out.std.push(p0 * o.std.unwrap_or(0.0));
        out.sensitivity.push(s);
        out.damping.push(r.damping / s.abs());
        out.damping_std.push(r.damping_std / s.abs());
    }
    Ok(out)
}

/// The joint's deformation per unit displacement at `reference` in model mode `t` with the
/// parameter at `p`: sqrt(y^T (dK/dp) y) / |y_ref|.
fn deformation(
    model: &Structure,
    param: usize,
    t: usize,
    p: f64,
    reference: &Observation,
) -> Result<f64, AmplitudeError> {
    let mut s = model.clone();
    s.parameters[model.identified_indices()[param]].value = p;
    let modal = ModalSolution::lowest_of(&s.assemble(), t + 1)
        .map_err(|e| AmplitudeError::Joint(format!("the model at p = {p:e}: {e}")))?;
    let y: Vec<f64> = modal.vectors().col(t).iter().copied().collect();
    let mut ky = vec![0.0; y.len()];
    model.identified()[param].stiffness.apply(&y, &mut ky);
    let across: f64 = y.iter().zip(&ky).map(|(a, b)| a * b).sum();
    let at = reference.read_column(modal.vectors(), t).abs();
    if at == 0.0 || !at.is_finite() {
        return Err(AmplitudeError::Joint(format!(
            "model mode {} does not move the reference point {}: name another",
            t + 1 - model.rigid,
            reference.label
        )));
    }
    Ok(across.abs().sqrt() / at)
}

/// The frequency (Hz) of measured mode `mode`'s model mode with the joint parameter at `p`.
fn frequency_at(
    model: &Structure,
    param: usize,
    mode: usize,
    p: f64,
) -> Result<f64, AmplitudeError> {
    let mut s = model.clone();
    s.parameters[model.identified_indices()[param]].value = p;
    let t = model
        .model_mode(mode)
        .map_err(|e| AmplitudeError::Joint(e.to_string()))?;
    let modal = ModalSolution::lowest_of(&s.assemble(), t + 1).map_err(|e| {
        AmplitudeError::Joint(format!(
            "the model at {} = {p:e}: {e}",
            model.identified()[param].name
        ))
    })?;
    Ok(modal.frequency_hz(t))
}

/// Before (the constant law's joint) and after (the chosen law's) per level of one mode.
pub fn level_errors(
    model: &Structure,
    param: usize,
    data: &ModeData,
    joint: &JointData,
    fit: &ModeFit,
) -> Result<Vec<LevelError>, AmplitudeError> {
    let law_value = |law: Law, a: f64| {
        fit.laws
            .iter()
            .find(|j| j.fitted.law == law)
            .map(|j| j.fitted.evaluate(a).stiffness)
    };
    data.rows
        .iter()
        .zip(&joint.amplitude)
        .map(|(r, &a)| {
            let at = |law: Law| match law_value(law, a) {
                Some(p) => frequency_at(model, param, data.mode, p),
                None => Ok(f64::NAN),
            };
            Ok(LevelError {
                excitation: r.excitation,
                amplitude: a,
                measured_hz: r.frequency_hz,
                constant_hz: at(Law::Constant)?,
                selected_hz: at(fit.selected)?,
            })
        })
        .collect()
}

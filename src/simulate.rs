//! Simulated measurements: the exact eigensolution of a model (the paper's "simulated
//! identified model"), over chosen DOFs, in the measured-modes form, optionally with
//! measurement errors.
//!
//! Layer 5 (simulation and studies; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`], [`crate::model`], [`crate::measured`], [`crate::extract`],
//! [`crate::identify`]) and, without a circle, [`crate::study`].

use std::sync::Arc;

use crate::input::{Number, SettingError};
use crate::measured::{MeasuredMode, MeasuredModes};
use crate::modal::{ModalSolution, check_elastic};
use crate::model::effects::{Configured, EffectContext, by_name, registry};
use crate::random::{NoiseKind, TrialRng};
use crate::structure::{Observation, Structure};

/// Deformable modes `modes` (1 = first elastic) of `modal`, whose first `rigid` pairs are
/// rigid-body modes, exact, read at `points`. The caller guarantees every mode exists
/// (`mode + rigid <= modal.len()`).
pub fn exact_modes(
    modal: &ModalSolution,
    rigid: usize,
    modes: &[usize],
    points: &[Observation],
) -> MeasuredModes {
    let y = modal.vectors();
    MeasuredModes::new(
        modes
            .iter()
            .map(|&r| {
                let s = r - 1 + rigid;
                MeasuredMode::new(
                    r,
                    modal.frequency_hz(s),
                    points.to_vec(),
                    points.iter().map(|p| p.read_column(y, s)).collect(),
                )
            })
            .collect(),
    )
}

/// Measurement errors of a simulated test campaign.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Errors {
    /// Relative error level of every shape element (std, or maximum for uniform noise).
    pub shape: f64,
    /// Relative standard deviation of every frequency.
    pub frequency: f64,
    /// Distribution of the errors.
    pub kind: NoiseKind,
    /// Seed: mode r draws from the stream (seed, 0, r) of [`TrialRng`].
    pub seed: u64,
}

impl Errors {
    /// The errors of these levels, checked ([`Errors::check`]).
    pub fn new(
        shape: f64,
        frequency: f64,
        kind: NoiseKind,
        seed: u64,
    ) -> Result<Errors, SettingError> {
        let errors = Errors {
            shape,
            frequency,
            kind,
            seed,
        };
        errors.check()?;
        Ok(errors)
    }

    /// Checks that each level (settings `shape_noise`, `frequency_noise`) is a finite
    /// relative level from 0 to below 1.
    pub fn check(&self) -> Result<(), SettingError> {
        for (setting, level) in [
            ("shape_noise", self.shape),
            ("frequency_noise", self.frequency),
        ] {
            if !(level.is_finite() && (0.0..1.0).contains(&level)) {
                return Err(SettingError::new(
                    setting,
                    crate::input::Number(level),
                    "it must be a relative level from 0 to below 1",
                ));
            }
        }
        Ok(())
    }
}

/// The first `count` deformable modes of `structure`, 1 to `count` (setting `modes`: from 1
/// to its deformable modes).
pub fn first_modes(structure: &Structure, count: usize) -> Result<Vec<usize>, SettingError> {
    let deformable = structure.dof_count() - structure.rigid;
    if count == 0 || count > deformable {
        return Err(SettingError::new(
            "modes",
            count,
            format!("the model has deformable modes 1 to {deformable}"),
        ));
    }
    Ok((1..=count).collect())
}

/// Exact modes as [`exact_modes`], each shape scaled to a largest component of +1 (left as it
/// is when every measured component is zero), then every shape element multiplied by (1 + e)
/// and every frequency by (1 + eps).
pub fn measured_modes(
    modal: &ModalSolution,
    rigid: usize,
    modes: &[usize],
    points: &[Observation],
    errors: Errors,
) -> MeasuredModes {
    let exact = exact_modes(modal, rigid, modes, points);
    MeasuredModes::new(
        exact
            .into_modes()
            .into_iter()
            .map(|mut m| {
                let mut rng = TrialRng::new(errors.seed, 0, m.mode as u64);
                let peak = m
                    .values
                    .iter()
                    .copied()
                    .fold(0.0_f64, |a, b| if b.abs() > a.abs() { b } else { a });
                let peak = if peak == 0.0 { 1.0 } else { peak };
                for v in &mut m.values {
                    *v = *v / peak * (1.0 + rng.shape_error(errors.kind, errors.shape));
                }
                m.frequency_hz *= 1.0 + rng.frequency_error(errors.kind, errors.frequency);
                m
            })
            .collect(),
    )
}

/// Name of the per-mode joint trend `jointid simulate` accepts beside the effects.
pub const RISING_JOINT: &str = "rising_joint";

/// The names `jointid simulate --effect` accepts beside the registered effects, with what
/// their size means.
pub const NOT_EFFECTS: [(&str, &str); 1] = [(
    RISING_JOINT,
    "joint stiffnesses that rise with the mode (outside the candidate library): mode r is simulated with every k1, k2 times (1 + size (r - 1))",
)];

/// An effect `simulate` does not know.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum SimulateError {
    /// No effect of that name.
    #[error("unknown effect `{name}`: the effects are {known}")]
    UnknownEffect {
        /// The name given.
        name: String,
        /// The names accepted.
        known: String,
    },
    /// A size that makes the model unphysical.
    #[error("{name} = {size} is invalid: {reason}", size = Number(*.size))]
    Inadmissible {
        /// The effect.
        name: String,
        /// Its size.
        size: f64,
        /// Why.
        reason: String,
    },
    /// A requested mode beyond the model's deformable modes.
    #[error("mode {mode} is invalid: the model has deformable modes 1 to {deformable}")]
    NoSuchMode {
        /// The highest mode asked for.
        mode: usize,
        /// Deformable modes of the model.
        deformable: usize,
    },
    /// The simulated structure is a mechanism.
    #[error("the simulated structure")]
    Mechanism(#[from] crate::modal::Mechanism),
    /// The simulated model has no eigensolution.
    #[error("the simulated model has no eigensolution")]
    Modal(#[from] crate::modal::ModalError),
    /// The errors' levels are out of range ([`Errors::check`]).
    #[error(transparent)]
    Setting(#[from] SettingError),
}

/// Every name `--effect` accepts, with what its size means.
pub fn effect_catalogue() -> Vec<(String, String)> {
    registry()
        .iter()
        .map(|e| (e.name(), e.describe()))
        .chain(NOT_EFFECTS)
        .map(|(name, describe)| (name.to_string(), describe.to_string()))
        .collect()
}

/// Which DOFs a simulated test measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Measure {
    /// Translations only (the usual accelerometer test).
    W,
    /// Rotations only.
    Theta,
    /// Every DOF.
    All,
    /// The sensors the model declares (`[[sensor]]`).
    Sensors,
}

/// The points a test measuring `measure` reads on `structure`; None for `Sensors` on a model
/// that declares none.
pub fn measured_points(structure: &Structure, measure: Measure) -> Option<Vec<Observation>> {
    if measure == Measure::Sensors {
        return (!structure.sensors.is_empty()).then(|| structure.sensors.clone());
    }
    let points = (0..structure.dof_count())
        .filter(|&d| {
            let rotation = structure.dofs.get(d).direction.is_rotation();
            match measure {
                Measure::W => !rotation,
                Measure::Theta => rotation,
                Measure::All | Measure::Sensors => true,
            }
        })
        .map(|d| Observation::dof(&structure.dofs, d))
        .collect();
    Some(points)
}

/// Measured modes of `structure` with `effects` (name, size) added, measured at `points`.
/// Sensor masses sit at the measured translations.
pub fn simulate(
    structure: &Structure,
    effects: &[(String, f64)],
    modes: &[usize],
    points: &[Observation],
    errors: Errors,
) -> Result<MeasuredModes, SimulateError> {
    simulate_from(structure, None, effects, modes, points, errors)
}

/// [`simulate`] with the lowest pairs of `structure` as given, when the caller has them
/// (the check of an external model's rigid-body modes computed them,
/// [`crate::model::from_path_solved`]): used when they reach the highest mode asked for,
/// instead of a solve of the same matrices. Without effects and a rising joint the truth is
/// the structure itself, and its pairs are these too.
pub fn simulate_from(
    structure: &Structure,
    nominal: Option<ModalSolution>,
    effects: &[(String, f64)],
    modes: &[usize],
    points: &[Observation],
    errors: Errors,
) -> Result<MeasuredModes, SimulateError> {
    errors.check()?;
    let rigid = structure.rigid;
    let highest = modes.iter().copied().max().unwrap_or(1) + rigid;
    let nominal = match nominal {
        Some(given) if given.len() >= highest && given.dof_count() == structure.dof_count() => {
            given
        }
        _ => ModalSolution::lowest_of(&structure.assemble(), highest)?,
    };
    if highest > nominal.len() {
        return Err(SimulateError::NoSuchMode {
            mode: highest - rigid,
            deformable: nominal.len() - rigid,
        });
    }
    let ctx = Arc::new(EffectContext::new(
        structure.clone(),
        points,
        nominal.frequency_hz(rigid),
    ));
    let mut rising = 0.0;
    let mut applied = Vec::new();
    for (name, size) in effects {
        if name == RISING_JOINT {
            rising += size;
            continue;
        }
        let effect = by_name(name).ok_or_else(|| SimulateError::UnknownEffect {
            name: name.clone(),
            known: effect_catalogue()
                .into_iter()
                .map(|(n, _)| n)
                .collect::<Vec<_>>()
                .join(", "),
        })?;
        let theta = effect.theta_of_size(&ctx, *size);
        if theta.is_empty() {
            return Err(SimulateError::Inadmissible {
                name: name.clone(),
                size: *size,
                reason: "this structure has no site for it".into(),
            });
        }
        let parameters = effect.parameters(&ctx);
        if let Some(p) = parameters
            .iter()
            .zip(&theta)
            .find(|(p, t)| p.non_negative && **t < 0.0)
        {
            return Err(SimulateError::Inadmissible {
                name: name.clone(),
                size: *size,
                reason: format!("{} = {} {} must be >= 0", p.0.name, Number(*p.1), p.0.unit),
            });
        }
        effect
            .admissible(&ctx, structure, &theta)
            .map_err(|reason| SimulateError::Inadmissible {
                name: name.clone(),
                size: *size,
                reason,
            })?;
        applied.push((effect, theta));
    }
    let mut out = Vec::with_capacity(modes.len());
    // The modes of one joint stiffness factor share one solution (all of them when the
    // joint does not rise): solved once, not once per mode. Factor 1 without effects is the
    // structure as given, whose pairs are the nominal ones (checked below like any other).
    let mut solved: Option<(f64, ModalSolution)> = None;
    let mut nominal = applied.is_empty().then_some(nominal);
    for &r in modes {
        let factor = 1.0 + rising * (r as f64 - 1.0);
        if factor <= 0.0 {
            return Err(SimulateError::Inadmissible {
                name: RISING_JOINT.into(),
                size: rising,
                reason: format!("mode {r} would have a joint stiffness factor {factor} <= 0"),
            });
        }
        if solved
            .as_ref()
            .is_none_or(|(f, _)| f.to_bits() != factor.to_bits())
        {
            let mut rising_structure = structure.clone();
            for p in &mut rising_structure.parameters {
                p.value *= factor;
            }
            let truth = Configured {
                ctx: ctx.clone(),
                structure: rising_structure,
                effects: applied.clone(),
            };
            let matrices = truth.assemble();
            let modal = match nominal.take_if(|_| factor == 1.0) {
                Some(nominal) => nominal,
                None => ModalSolution::lowest_of(&matrices, highest)?,
            };
            check_elastic(&matrices, &modal, rigid)?;
            solved = Some((factor, modal));
        }
        let (_, modal) = solved.as_ref().expect("solved just above");
        out.extend(measured_modes(modal, rigid, &[r], points, errors).into_modes());
    }
    Ok(MeasuredModes::new(out))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    #[test]
    fn errors_and_modes_are_checked_where_they_are_set() {
        let uniform = NoiseKind::Uniform;
        assert!(Errors::new(0.0, 0.999, uniform, 1).is_ok());
        for (shape, frequency, setting) in [
            (1.0, 0.0, "shape_noise"),
            (-0.1, 0.0, "shape_noise"),
            (0.0, f64::NAN, "frequency_noise"),
        ] {
            let e = Errors::new(shape, frequency, uniform, 1).unwrap_err();
            assert_eq!(e.setting, setting);
            assert!(
                e.to_string()
                    .ends_with("is invalid: it must be a relative level from 0 to below 1"),
                "{e}"
            );
        }
        let model = paper_model(1e7, 1e4);
        assert_eq!(first_modes(&model, 3).unwrap(), vec![1, 2, 3]);
        for count in [0, 37] {
            assert_eq!(
                first_modes(&model, count).unwrap_err().to_string(),
                format!("modes = {count} is invalid: the model has deformable modes 1 to 36")
            );
        }
        let points = [Observation::dof(&model.dofs, 0)];
        let bad = Errors {
            shape: 1.5,
            ..Errors::new(0.0, 0.0, uniform, 1).unwrap()
        };
        assert!(matches!(
            simulate(&model, &[], &[1], &points, bad),
            Err(SimulateError::Setting(_))
        ));
    }

    #[test]
    fn noise_free_measurement_is_the_scaled_exact_mode_and_noise_is_seeded() {
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let dofs: Vec<Observation> = (0..38)
            .step_by(2)
            .map(|d| Observation::dof(&model.dofs, d))
            .collect();
        let clean = Errors {
            shape: 0.0,
            frequency: 0.0,
            kind: NoiseKind::Gaussian,
            seed: 1,
        };
        let m = measured_modes(&modal, 2, &[1, 3], &dofs, clean);
        let exact = exact_modes(&modal, 2, &[1, 3], &dofs);
        for (a, b) in m.modes().iter().zip(exact.modes()) {
            assert_eq!(a.frequency_hz, b.frequency_hz);
            assert_eq!(a.values.iter().cloned().fold(f64::MIN, f64::max), 1.0);
            let ratio = a.values[3] / b.values[3];
            assert!(
                a.values
                    .iter()
                    .zip(&b.values)
                    .all(|(x, y)| (x - ratio * y).abs() < 1e-14)
            );
        }
        let noisy = |seed| {
            measured_modes(
                &modal,
                2,
                &[1, 3],
                &dofs,
                Errors {
                    shape: 0.02,
                    frequency: 0.001,
                    seed,
                    ..clean
                },
            )
        };
        assert_eq!(noisy(4), noisy(4));
        assert_ne!(noisy(4), noisy(5));
        assert_ne!(
            noisy(4).modes()[0].frequency_hz,
            exact.modes()[0].frequency_hz
        );
    }
}

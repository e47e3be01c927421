//! Physical effects the beam-and-joint model of eq. (1)-(17) may lack, each one or two
//! parameters theta with their contribution to K and M and the derivatives dK/dtheta,
//! dM/dtheta.
//!
//! The library is open: an effect is one small type implementing [`Effect`], listed once in
//! [`candidates`] (the library `jointid diagnose` searches) or [`outside_library`] (effects
//! `jointid simulate` can put into data to test the diagnosis, that the diagnosis does not
//! know). Every effect is zero at theta = 0: the nominal model is nested in every candidate.

mod element_damage;
mod joint_coupling;
mod joint_mass;
mod sensor_mass;
mod shear;
mod suspension;

pub use element_damage::ElementDamage;
pub use joint_coupling::JointCoupling;
pub use joint_mass::JointMass;
pub use sensor_mass::SensorMass;
pub use shear::Shear;
pub use suspension::Suspension;

use std::sync::Arc;

use super::{Matrices, Model, Parameter, SparseSym};

/// What an effect may depend on besides its parameters.
#[derive(Debug, Clone)]
pub struct EffectContext {
    /// The nominal model (its joint stiffnesses included).
    pub model: Model,
    /// Nodes carrying a sensor (where a translation is measured).
    pub sensor_nodes: Vec<usize>,
    /// First elastic frequency of the nominal model, Hz (a scale for the suspension).
    pub first_elastic_hz: f64,
}

/// One parameter of an effect.
#[derive(Debug, Clone, PartialEq)]
pub struct EffectParameter {
    /// Name in reports, e.g. `joint_mass.m` or `joint_mass.joint2.m`.
    pub name: String,
    /// Unit.
    pub unit: &'static str,
    /// A typical magnitude: the fit works in theta / scale.
    pub scale: f64,
    /// Whether theta must stay >= 0 (a mass, a spring).
    pub non_negative: bool,
}

/// A physical effect: see the module docs.
pub trait Effect: Send + Sync + std::fmt::Debug {
    /// Name on the command line and in reports.
    fn name(&self) -> &'static str;

    /// What the effect is and what `size` means in `jointid simulate --effect name=size`.
    fn describe(&self) -> &'static str;

    /// The parameters theta.
    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter>;

    /// K(theta) - K(0) and M(theta) - M(0).
    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym);

    /// dK/dtheta_i and dM/dtheta_i at theta.
    fn derivatives(&self, ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)>;

    /// theta for a simulate size (see [`Effect::describe`]).
    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64>;

    /// The size of theta, in the unit of [`Effect::describe`] (the inverse of
    /// [`Effect::theta_of_size`]; several parameters are summarised by their mean size).
    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64;

    /// Whether theta keeps `model` (with its current joints) physical; the reason when not.
    fn admissible(&self, _model: &Model, _theta: &[f64]) -> Result<(), String> {
        Ok(())
    }
}

/// The candidate library searched by `jointid diagnose`, in report order.
pub fn candidates() -> Vec<Arc<dyn Effect>> {
    vec![
        Arc::new(JointCoupling),
        Arc::new(JointMass),
        Arc::new(SensorMass),
        Arc::new(Suspension),
        Arc::new(Shear),
    ]
}

/// Effects outside the library: for simulated data that no candidate explains.
pub fn outside_library() -> Vec<Arc<dyn Effect>> {
    vec![Arc::new(ElementDamage)]
}

/// The effect named `name`, candidate or outside the library.
pub fn by_name(name: &str) -> Option<Arc<dyn Effect>> {
    candidates()
        .into_iter()
        .chain(outside_library())
        .find(|e| e.name() == name)
}

/// A model with effects at given parameter values.
#[derive(Debug, Clone)]
pub struct Configured {
    /// Context of the effects (nominal model, sensors).
    pub ctx: EffectContext,
    /// The model whose joints are used (calibrated values).
    pub model: Model,
    /// The effects and their theta.
    pub effects: Vec<(Arc<dyn Effect>, Vec<f64>)>,
}

impl Configured {
    /// K and M of the model plus every effect.
    pub fn assemble(&self) -> Matrices {
        let mut mats = self.model.assemble();
        for (effect, theta) in &self.effects {
            let (dk, dm) = effect.contribution(&self.ctx, theta);
            dk.add_to(&mut mats.k, 1.0);
            dm.add_to(&mut mats.m, 1.0);
        }
        mats
    }

    /// The effects' parameters with their derivatives at the current theta, in effect order.
    pub fn effect_parameters(&self) -> Vec<Parameter> {
        let mut out = Vec::new();
        for (effect, theta) in &self.effects {
            let specs = effect.parameters(&self.ctx);
            for ((spec, (dk, dm)), &value) in specs
                .into_iter()
                .zip(effect.derivatives(&self.ctx, theta))
                .zip(theta)
            {
                out.push(Parameter {
                    name: spec.name,
                    unit: spec.unit,
                    value,
                    stiffness: dk,
                    mass: dm,
                });
            }
        }
        out
    }
}

/// K(theta) - K(0), M(theta) - M(0) of an effect linear in its parameters, whose
/// dK/dtheta_i, dM/dtheta_i are `patterns[i]`.
pub(crate) fn linear_contribution(
    patterns: &[(SparseSym, SparseSym)],
    theta: &[f64],
) -> (SparseSym, SparseSym) {
    let (mut k, mut m) = (SparseSym::zero(), SparseSym::zero());
    for ((dk, dm), &t) in patterns.iter().zip(theta) {
        if t != 0.0 {
            k.extend_scaled(dk, t);
            m.extend_scaled(dm, t);
        }
    }
    (k, m)
}

/// `name` or `name.jointK.suffix` for an effect with one parameter per joint.
pub(crate) fn per_joint_name(effect: &str, joint: usize, joints: usize, suffix: &str) -> String {
    if joints == 1 {
        format!("{effect}.{suffix}")
    } else {
        format!("{effect}.joint{}.{suffix}", joint + 1)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::fixtures::paper_model;

    pub(crate) fn context() -> EffectContext {
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        EffectContext {
            sensor_nodes: (0..model.node_count()).collect(),
            first_elastic_hz: modal.frequency_hz(2),
            model,
        }
    }

    /// Every effect's dK/dtheta and dM/dtheta against central differences of its
    /// contribution, at theta away from zero.
    #[test]
    fn every_effect_derivative_matches_central_differences() {
        let ctx = context();
        for effect in candidates().into_iter().chain(outside_library()) {
            let theta = effect.theta_of_size(&ctx, 0.3);
            let derivs = effect.derivatives(&ctx, &theta);
            assert_eq!(derivs.len(), theta.len());
            for (i, (dk, dm)) in derivs.iter().enumerate() {
                let h = 1e-6 * theta[i].abs().max(effect.parameters(&ctx)[i].scale);
                let at = |sign: f64| {
                    let mut t = theta.clone();
                    t[i] += sign * h;
                    let (k, m) = effect.contribution(&ctx, &t);
                    let (mut kd, mut md) = (faer::Mat::zeros(38, 38), faer::Mat::zeros(38, 38));
                    k.add_to(&mut kd, 1.0);
                    m.add_to(&mut md, 1.0);
                    (kd, md)
                };
                let ((kp, mp), (km, mm)) = (at(1.0), at(-1.0));
                let (mut ka, mut ma) = (faer::Mat::zeros(38, 38), faer::Mat::zeros(38, 38));
                dk.add_to(&mut ka, 1.0);
                dm.add_to(&mut ma, 1.0);
                let fd_k = (&kp - &km) * faer::Scale(1.0 / (2.0 * h));
                let fd_m = (&mp - &mm) * faer::Scale(1.0 / (2.0 * h));
                let (sk, sm) = (ka.norm_max().max(1e-300), ma.norm_max().max(1e-300));
                assert!(
                    (&fd_k - &ka).norm_max() <= 1e-6 * sk,
                    "{}: dK/dtheta{i}",
                    effect.name()
                );
                assert!(
                    (&fd_m - &ma).norm_max() <= 1e-6 * sm,
                    "{}: dM/dtheta{i}",
                    effect.name()
                );
                assert!(
                    ka.norm_max() > 0.0 || ma.norm_max() > 0.0,
                    "{}: zero derivative",
                    effect.name()
                );
            }
        }
    }

    #[test]
    fn every_effect_vanishes_at_zero_and_round_trips_its_size() {
        let ctx = context();
        for effect in candidates().into_iter().chain(outside_library()) {
            let zero = vec![0.0; effect.parameters(&ctx).len()];
            let (k, m) = effect.contribution(&ctx, &zero);
            let (mut kd, mut md) = (
                faer::Mat::<f64>::zeros(38, 38),
                faer::Mat::<f64>::zeros(38, 38),
            );
            k.add_to(&mut kd, 1.0);
            m.add_to(&mut md, 1.0);
            assert_eq!(kd.norm_max(), 0.0, "{}", effect.name());
            assert_eq!(md.norm_max(), 0.0, "{}", effect.name());
            let size = 0.07;
            let back = effect.size_of_theta(&ctx, &effect.theta_of_size(&ctx, size));
            assert!((back - size).abs() < 1e-12, "{}: {back}", effect.name());
            assert!(by_name(effect.name()).is_some());
        }
    }
}

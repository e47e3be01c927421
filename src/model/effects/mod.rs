//! Physical effects a model may lack, each one or a few parameters theta with their
//! contribution to K and M and the derivatives dK/dtheta, dM/dtheta.
//!
//! The library is open: an effect is one small type implementing [`Effect`] in its own file,
//! which declares there its name, its [`Tier`] and its description, and is listed once in
//! [`registry`]. The tier says what the diagnosis does with it: [`Tier::Default`] effects are
//! the candidates every `jointid diagnose` searches, [`Tier::Extended`] ones are searched with
//! `--extended`, and [`Tier::Outside`] ones only `jointid simulate` puts into data, to test the
//! diagnosis on what it does not know. Every list of effects (the CLI's help, simulate's
//! catalogue, the table of docs/diagnosis.md, the tests' lists) reads the registry. Every effect is zero
//! at theta = 0: the nominal model is nested in every candidate. Effects act on the sites of a
//! structure ([`crate::structure::Sites`]: joints, beam elements, free ends, rigid supports)
//! and on its measured points; an effect with no site to act on does not apply to that
//! structure.
//!
//! Layer: a model module; imports `crate::structure` and the chain builder's element matrices
//! (`crate::model::chain`), nothing above the model.

mod beam_stiffness;
mod element_damage;
mod end_mass;
mod joint_coupling;
mod joint_inertia;
mod joint_mass;
mod joint_region;
mod lap;
mod local_stiffness;
mod sensor_mass;
mod shear;
mod support_flexibility;
mod suspension;

pub use beam_stiffness::BeamStiffness;
pub use element_damage::ElementDamage;
pub use end_mass::EndMass;
pub use joint_coupling::JointCoupling;
pub use joint_inertia::JointInertia;
pub use joint_mass::JointMass;
pub use joint_region::{JointRegion, lengths as region_lengths};
pub use lap::Lap;
pub use local_stiffness::{LocalStiffness, scan};
pub use sensor_mass::SensorMass;
pub use shear::Shear;
pub use support_flexibility::SupportFlexibility;
pub use suspension::Suspension;

use std::sync::Arc;

use crate::modal::reduced;
use crate::modal::{ModalError, ModalSolution};
use crate::structure::reduced::Reduced;
use crate::structure::{Matrices, Observation, Parameter, Role, SparseSym, Structure};

/// What an effect may depend on besides its parameters.
#[derive(Debug, Clone)]
pub struct EffectContext {
    /// The nominal structure (its parameters at their nominal values).
    pub structure: Structure,
    /// The measured translations (where sensors sit).
    pub sensors: Vec<Observation>,
    /// First elastic frequency of the nominal model, Hz (a scale for the suspension).
    pub first_elastic_hz: f64,
}

impl EffectContext {
    /// The context of `structure` measured at `points` (only translations carry a sensor mass).
    pub fn new(structure: Structure, points: &[Observation], first_elastic_hz: f64) -> Self {
        Self {
            sensors: points
                .iter()
                .filter(|p| !p.direction.is_rotation())
                .cloned()
                .collect(),
            structure,
            first_elastic_hz,
        }
    }
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

/// What the diagnosis does with an effect (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum Tier {
    /// A candidate of every diagnosis.
    Default,
    /// A candidate of `jointid diagnose --extended`.
    Extended,
    /// Never a candidate: `jointid simulate` puts it into data the diagnosis does not know.
    Outside,
}

/// A physical effect: see the module docs.
pub trait Effect: Send + Sync + std::fmt::Debug {
    /// Name on the command line and in reports.
    fn name(&self) -> &'static str;

    /// What the diagnosis does with the effect.
    fn tier(&self) -> Tier;

    /// What the effect is and what `size` means in `jointid simulate --effect name=size`.
    fn describe(&self) -> &'static str;

    /// The parameters theta (none when the structure has no site for the effect).
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

    /// Whether theta keeps `current` (the structure with its current parameter values)
    /// physical; the reason when not.
    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &Structure,
        _theta: &[f64],
    ) -> Result<(), String> {
        Ok(())
    }

    /// Linear inequalities sum_i c_i theta_i >= 0, as (index, c_i) pairs, that a fit keeps
    /// besides the non-negative bounds: the part of the plausible range
    /// ([`Effect::plausible`]) a fit can hold to, so that a size on its edge is fitted there
    /// instead of overstepping it.
    fn inequalities(&self, _ctx: &EffectContext) -> Vec<Vec<(usize, f64)>> {
        Vec::new()
    }

    /// Whether a fitted theta is a physically plausible size (beyond the bounds the fit keeps:
    /// [`EffectParameter::non_negative`] and [`Effect::admissible`]); the reason when not. A
    /// fitted size outside it is not an explanation of the data.
    fn plausible(&self, _ctx: &EffectContext, _theta: &[f64]) -> Result<(), String> {
        Ok(())
    }

    /// Whether the effect can act on this structure and data.
    fn applies(&self, ctx: &EffectContext) -> bool {
        let params = self.parameters(ctx);
        if params.is_empty() {
            return false;
        }
        let theta: Vec<f64> = params.iter().map(|p| p.scale).collect();
        self.derivatives(ctx, &theta)
            .iter()
            .any(|(k, m)| !k.is_zero() || !m.is_zero())
    }
}

/// Every effect that can be named, in report order: the registry (see the module docs). An
/// effect is registered by one line here.
pub fn registry() -> Vec<Arc<dyn Effect>> {
    vec![
        Arc::new(JointCoupling),
        Arc::new(JointMass),
        Arc::new(SensorMass),
        Arc::new(Suspension),
        Arc::new(SupportFlexibility),
        Arc::new(Shear),
        Arc::new(BeamStiffness),
        Arc::new(Lap),
        Arc::new(JointInertia),
        Arc::new(EndMass),
        Arc::new(ElementDamage),
    ]
}

/// The registered effects of `tier`, in report order.
pub fn of_tier(tier: Tier) -> Vec<Arc<dyn Effect>> {
    registry()
        .into_iter()
        .filter(|e| e.tier() == tier)
        .collect()
}

/// The registered effect named `name`.
pub fn by_name(name: &str) -> Option<Arc<dyn Effect>> {
    registry().into_iter().find(|e| e.name() == name)
}

/// A structure with effects at given parameter values.
#[derive(Debug, Clone)]
pub struct Configured {
    /// Context of the effects (nominal structure, sensors).
    pub ctx: Arc<EffectContext>,
    /// The structure whose parameters are used (calibrated values).
    pub structure: Structure,
    /// The effects and their theta.
    pub effects: Vec<(Arc<dyn Effect>, Vec<f64>)>,
}

impl Configured {
    /// K and M of the structure plus every effect.
    pub fn assemble(&self) -> Matrices {
        let mats = self.structure.assemble();
        let contributions = self.contributions();
        if contributions.is_empty() {
            return mats;
        }
        mats.plus(&terms(&contributions))
    }

    /// Every effect's K(theta) - K(0) and M(theta) - M(0), in effect order.
    pub fn contributions(&self) -> Vec<(SparseSym, SparseSym)> {
        self.effects
            .iter()
            .map(|(effect, theta)| effect.contribution(&self.ctx, theta))
            .collect()
    }

    /// The lowest `count` pairs of the structure plus every effect: on the structure's
    /// reduced model when it carries one, else in full ([`reduced::lowest`]).
    pub fn lowest(&self, count: usize) -> Result<ModalSolution, ModalError> {
        reduced::lowest(&self.structure, &terms(&self.contributions()), count)
    }

    /// The lowest pairs up to `f_max_hz` and at least `count`, the first `checked` of them
    /// checked ([`reduced::covering`]), with the reduction when the solve enriched it.
    pub fn covering(
        &self,
        count: usize,
        f_max_hz: f64,
        checked: usize,
    ) -> Result<(ModalSolution, Option<Arc<Reduced>>), ModalError> {
        reduced::covering(
            &self.structure,
            &terms(&self.contributions()),
            count,
            f_max_hz,
            checked,
        )
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
                    role: Role::Identified,
                });
            }
        }
        out
    }

    /// Whether every effect keeps the structure physical.
    pub fn admissible(&self) -> bool {
        self.effects
            .iter()
            .all(|(e, t)| e.admissible(&self.ctx, &self.structure, t).is_ok())
    }
}

/// Contributions as the extra terms of [`Matrices::plus`], each at scale 1.
fn terms(contributions: &[(SparseSym, SparseSym)]) -> Vec<(&SparseSym, &SparseSym, f64)> {
    contributions.iter().map(|(k, m)| (k, m, 1.0)).collect()
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

/// Largest radius of gyration of a body attached to a beam (a sensor, joint hardware) about
/// the beam's axis, in section heights.
pub(crate) const LARGEST_GYRATION_HEIGHTS: f64 = 2.0;

/// The square of [`LARGEST_GYRATION_HEIGHTS`] section heights of a rectangle whose I/A is
/// `r2` (its height^2 is 12 I/A).
pub(crate) fn largest_gyration_squared(r2: f64) -> f64 {
    LARGEST_GYRATION_HEIGHTS.powi(2) * 12.0 * r2
}

/// Whether `value` exceeds `bound` beyond the round-off of a fit held on that bound.
pub(crate) fn beyond(value: f64, bound: f64) -> bool {
    value > bound * (1.0 + 1e-9)
}

/// `effect.suffix`, or `effect.siteK.suffix` (K 1-based) for an effect with one parameter per
/// site of a kind (`joint`, `end`) when there are several.
pub(crate) fn per_site_name(
    effect: &str,
    site: &str,
    index: usize,
    count: usize,
    suffix: &str,
) -> String {
    if count == 1 {
        format!("{effect}.{suffix}")
    } else {
        format!("{effect}.{site}{}.{suffix}", index + 1)
    }
}

/// [`per_site_name`] of joint `joint` of `joints`.
pub(crate) fn per_joint_name(effect: &str, joint: usize, joints: usize, suffix: &str) -> String {
    per_site_name(effect, "joint", joint, joints, suffix)
}

/// Adds `value` at (a, b) and its mirror, skipping removed DOFs.
pub(crate) fn add_pair(s: &mut SparseSym, a: Option<usize>, b: Option<usize>, value: f64) {
    if let (Some(a), Some(b)) = (a, b) {
        s.add(a, b, value);
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use faer::Mat;

    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::fixtures::paper_model;

    pub(crate) fn context() -> EffectContext {
        context_of(paper_model(1e7, 1e4))
    }

    /// The context of `structure` measured at every DOF.
    pub(crate) fn context_of(structure: Structure) -> EffectContext {
        let modal = ModalSolution::solve(&structure.assemble()).unwrap();
        let points: Vec<Observation> = (0..structure.dof_count())
            .map(|d| Observation::dof(&structure.dofs, d))
            .collect();
        let first_elastic = modal.frequency_hz(structure.rigid);
        EffectContext::new(structure, &points, first_elastic)
    }

    /// u^T K u for the displacement of a uniform curvature `kappa` about `x0` on the nodes of
    /// `elements` (w = kappa (x - x0)^2 / 2, theta = kappa (x - x0); 0 elsewhere and on
    /// removed DOFs): EI kappa^2 times the elements' length for their bending stiffness.
    pub(crate) fn curvature_energy(
        elements: &[&crate::structure::ElementSite],
        x0: f64,
        kappa: f64,
        k: &Mat<f64>,
    ) -> f64 {
        let n = k.nrows();
        let mut u = vec![0.0; n];
        for e in elements {
            for (node, &x) in e.line.x.iter().enumerate() {
                let s = x - x0;
                if let Some(d) = e.line.dofs[2 * node] {
                    u[d] = 0.5 * kappa * s * s;
                }
                if let Some(d) = e.line.dofs[2 * node + 1] {
                    u[d] = kappa * s;
                }
            }
        }
        (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| u[i] * k[(i, j)] * u[j])
            .sum()
    }

    /// K and M of a contribution or derivative as dense n x n matrices.
    pub(crate) fn dense(n: usize, (k, m): &(SparseSym, SparseSym)) -> (Mat<f64>, Mat<f64>) {
        let (mut kd, mut md) = (Mat::zeros(n, n), Mat::zeros(n, n));
        k.add_to(&mut kd, 1.0);
        m.add_to(&mut md, 1.0);
        (kd, md)
    }

    /// Asserts that dK/dtheta_i and dM/dtheta_i of `effect` at `theta` match central
    /// differences of its contribution with step `h` to 1e-6 of their largest entries; returns
    /// the analytic derivative.
    pub(crate) fn assert_central_differences(
        effect: &dyn Effect,
        ctx: &EffectContext,
        theta: &[f64],
        i: usize,
        h: f64,
    ) -> (Mat<f64>, Mat<f64>) {
        let n = ctx.structure.dof_count();
        let (ka, ma) = dense(n, &effect.derivatives(ctx, theta)[i]);
        let at = |sign: f64| {
            let mut t = theta.to_vec();
            t[i] += sign * h;
            dense(n, &effect.contribution(ctx, &t))
        };
        let ((kp, mp), (km, mm)) = (at(1.0), at(-1.0));
        let fd_k = (&kp - &km) * faer::Scale(1.0 / (2.0 * h));
        let fd_m = (&mp - &mm) * faer::Scale(1.0 / (2.0 * h));
        let (sk, sm) = (ka.norm_max().max(1e-300), ma.norm_max().max(1e-300));
        let name = effect.name();
        assert!(
            (&fd_k - &ka).norm_max() <= 1e-6 * sk,
            "{name}: dK/dtheta{i} at {theta:?}"
        );
        assert!(
            (&fd_m - &ma).norm_max() <= 1e-6 * sm,
            "{name}: dM/dtheta{i} at {theta:?}"
        );
        (ka, ma)
    }

    /// Every registered effect's dK/dtheta and dM/dtheta against central differences of its
    /// contribution, at theta away from zero (the free-free context: `support_flexibility`
    /// has its own tests on supported chains; a new effect is checked here with no test code
    /// of its own).
    #[test]
    fn every_effect_derivative_matches_central_differences() {
        let ctx = context();
        for effect in registry().into_iter().filter(|e| e.applies(&ctx)) {
            let theta = effect.theta_of_size(&ctx, 0.3);
            assert_eq!(effect.derivatives(&ctx, &theta).len(), theta.len());
            for i in 0..theta.len() {
                let h = 1e-6 * theta[i].abs().max(effect.parameters(&ctx)[i].scale);
                let (ka, ma) = assert_central_differences(effect.as_ref(), &ctx, &theta, i, h);
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
        for effect in registry().into_iter().filter(|e| e.applies(&ctx)) {
            let zero = vec![0.0; effect.parameters(&ctx).len()];
            let (kd, md) = dense(38, &effect.contribution(&ctx, &zero));
            assert_eq!(kd.norm_max(), 0.0, "{}", effect.name());
            assert_eq!(md.norm_max(), 0.0, "{}", effect.name());
            let size = 0.07;
            let back = effect.size_of_theta(&ctx, &effect.theta_of_size(&ctx, size));
            assert!((back - size).abs() < 1e-12, "{}: {back}", effect.name());
            assert!(by_name(effect.name()).is_some());
        }
    }

    #[test]
    fn masses_up_to_the_beams_mass_are_plausible_and_beyond_are_not() {
        let ctx = context();
        for effect in [
            by_name("joint_mass").unwrap(),
            by_name("sensor_mass").unwrap(),
        ] {
            // Sizes are mass / mass of all beams (joint_mass: per joint; the context has one).
            let light = effect.theta_of_size(&ctx, 0.99);
            assert!(effect.plausible(&ctx, &light).is_ok(), "{}", effect.name());
            let heavy = effect.theta_of_size(&ctx, 1.0);
            let reason = effect.plausible(&ctx, &heavy).unwrap_err();
            assert!(reason.contains("mass of all beams"), "{reason}");
        }
        // The default: every other effect has no range beyond the fit's bounds.
        let shear = by_name("shear").unwrap();
        assert!(
            shear
                .plausible(&ctx, &shear.theta_of_size(&ctx, 50.0))
                .is_ok()
        );
    }
}

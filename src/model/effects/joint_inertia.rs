//! `joint_inertia`: the rotary inertia of the joint hardware as its own parameter. A joint's
//! splice plates or bolt-and-washer sets sit away from the neutral axis, and their radius of
//! gyration is several times the beam section's: `joint_mass` frees it beside the hardware's
//! mass, within a plausible radius of gyration (a rotary inertia needs a mass); this candidate
//! is the rotary inertia J of every joint alone, half on each joint node's rotation:
//!
//! ```text
//!   M(J) - M(0) = sum_j J_j / 2 (e_theta_a e_theta_a^T + e_theta_b e_theta_b^T)
//! ```
//!
//! Translation-free: it changes only the rotational inertia, so it separates from
//! `joint_mass` by the modes' joint rotations against their joint displacements.
//!
//! Size (in `jointid simulate --effect joint_inertia=size`): J / (M_beams I/A), the rotary
//! inertia of every joint over that of all beams' mass at the beam's radius of gyration (the
//! first joint's left section).

use super::{
    Effect, EffectContext, EffectParameter, Tier, add_pair, linear_contribution, per_joint_name,
};
use crate::structure::{JointSite, SparseSym};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct JointInertia;

/// dM/dJ of a joint.
fn pattern(site: &JointSite) -> SparseSym {
    let mut s = SparseSym::zero();
    for side in 0..2 {
        add_pair(&mut s, site.theta[side], site.theta[side], 0.5);
    }
    s
}

/// dM/dJ of every joint.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    ctx.structure
        .sites
        .joints
        .iter()
        .map(|site| (SparseSym::zero(), pattern(site)))
        .collect()
}

/// M_beams I/A, kg m^2: the unit of the size.
fn unit_inertia(ctx: &EffectContext) -> f64 {
    let sites = &ctx.structure.sites;
    sites
        .joints
        .first()
        .map_or(0.0, |j| j.sections[0].gyration_squared())
        * sites.beam_mass
}

impl Effect for JointInertia {
    fn name(&self) -> &'static str {
        "joint_inertia"
    }

    fn tier(&self) -> Tier {
        Tier::Extended
    }

    fn describe(&self) -> &'static str {
        "rotary inertia J of every joint, half on each joint node's rotation (no translational mass); size = J / (mass of all beams x I/A of the beam)"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = ctx.structure.sites.joints.len();
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "J"),
                unit: "kg m^2",
                scale: 0.01 * unit_inertia(ctx),
                non_negative: true,
            })
            .collect()
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size * unit_inertia(ctx); ctx.structure.sites.joints.len()]
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len() as f64 / unit_inertia(ctx)
    }
}

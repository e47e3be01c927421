//! `joint_mass`: the mass of the joint hardware (bolts, flanges, washers) that the beam model
//! does not carry: mass m per joint, half lumped at each of its two nodes, with the rotary
//! inertia (m/2) r^2 of a body of the adjacent beam's radius of gyration r^2 = I/A. It keeps
//! this coupled inertia (one parameter per joint); hardware whose rotary inertia is its own is
//! the separate candidate `joint_inertia` (rotary inertia only, no translational mass).

use super::{
    Effect, EffectContext, EffectParameter, add_pair, linear_contribution, per_joint_name,
};
use crate::structure::{JointSite, SparseSym};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct JointMass;

/// dM/dm of a joint.
fn pattern(site: &JointSite) -> SparseSym {
    let mut s = SparseSym::zero();
    for side in 0..2 {
        add_pair(&mut s, site.w[side], site.w[side], 0.5);
        let gyration = site.sections[side].gyration_squared();
        add_pair(&mut s, site.theta[side], site.theta[side], 0.5 * gyration);
    }
    s
}

/// dM/dm of every joint.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    ctx.structure
        .sites
        .joints
        .iter()
        .map(|site| (SparseSym::zero(), pattern(site)))
        .collect()
}

impl Effect for JointMass {
    fn name(&self) -> &'static str {
        "joint_mass"
    }

    fn describe(&self) -> &'static str {
        "lumped mass (and rotary inertia) of every joint, half on each joint node; size = joint mass / mass of all beams"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = ctx.structure.sites.joints.len();
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "m"),
                unit: "kg",
                scale: 0.01 * ctx.structure.sites.beam_mass,
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
        vec![size * ctx.structure.sites.beam_mass; ctx.structure.sites.joints.len()]
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len() as f64 / ctx.structure.sites.beam_mass
    }

    /// The joints' hardware together is lighter than the beams it joins.
    fn plausible(&self, ctx: &EffectContext, theta: &[f64]) -> Result<(), String> {
        let total: f64 = theta.iter().sum();
        let beams = ctx.structure.sites.beam_mass;
        if total >= beams {
            return Err(format!(
                "the joint masses add up to {total:.4e} kg, not less than the mass of all beams {beams:.4e} kg"
            ));
        }
        Ok(())
    }
}

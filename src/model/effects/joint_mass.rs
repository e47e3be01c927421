//! `joint_mass`: the mass of the joint hardware (bolts, flanges, washers) that the beam model
//! does not carry: mass m per joint, half lumped at each of its two nodes, with the rotary
//! inertia (m/2) r^2 of a body of the adjacent beam's radius of gyration r^2 = I/A.

use super::{Effect, EffectContext, EffectParameter, linear_contribution, per_joint_name};
use crate::model::{Dof, Model, SparseSym, dof_index};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct JointMass;

/// dM/dm of joint `joint`.
fn pattern(model: &Model, joint: usize) -> SparseSym {
    let (a, b) = model.joint_nodes(joint);
    let mut s = SparseSym::zero();
    for (node, beam) in [(a, &model.beams()[joint]), (b, &model.beams()[joint + 1])] {
        s.add(dof_index(node, Dof::W), dof_index(node, Dof::W), 0.5);
        s.add(
            dof_index(node, Dof::Theta),
            dof_index(node, Dof::Theta),
            0.5 * beam.second_moment / beam.area,
        );
    }
    s
}

/// dM/dm of every joint.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    (0..ctx.model.joints().len())
        .map(|j| (SparseSym::zero(), pattern(&ctx.model, j)))
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
        let joints = ctx.model.joints().len();
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "m"),
                unit: "kg",
                scale: 0.01 * ctx.model.mass(),
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
        vec![size * ctx.model.mass(); ctx.model.joints().len()]
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len() as f64 / ctx.model.mass()
    }
}

//! `joint_coupling`: the transversal-rotational coupling stiffness k12 of every joint, which
//! eq. (17) assumes absent. The joint energy becomes
//! 1/2 [k1 dw^2 + 2 k12 dw dtheta + k2 dtheta^2] with dw = w_a - w_b, dtheta = theta_a - theta_b,
//! positive semidefinite while k12^2 <= k1 k2.

use super::{Effect, EffectContext, EffectParameter, linear_contribution, per_joint_name};
use crate::model::{Dof, Model, SparseSym, dof_index};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct JointCoupling;

fn pattern(model: &Model, joint: usize) -> SparseSym {
    let (a, b) = model.joint_nodes(joint);
    let (wa, ta, wb, tb) = (
        dof_index(a, Dof::W),
        dof_index(a, Dof::Theta),
        dof_index(b, Dof::W),
        dof_index(b, Dof::Theta),
    );
    let mut s = SparseSym::zero();
    s.add(wa, ta, 1.0);
    s.add(wa, tb, -1.0);
    s.add(wb, ta, -1.0);
    s.add(wb, tb, 1.0);
    s
}

fn geometric_mean(model: &Model, joint: usize) -> f64 {
    let j = model.joints()[joint];
    (j.k1 * j.k2).sqrt()
}

/// dK/dk12 of every joint.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    (0..ctx.model.joints().len())
        .map(|j| (pattern(&ctx.model, j), SparseSym::zero()))
        .collect()
}

impl Effect for JointCoupling {
    fn name(&self) -> &'static str {
        "joint_coupling"
    }

    fn describe(&self) -> &'static str {
        "coupling stiffness k12 between the transversal and rotational motion of every joint; size = k12 / sqrt(k1 k2), from -1 to 1"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = ctx.model.joints().len();
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "k12"),
                unit: "N/rad",
                scale: geometric_mean(&ctx.model, j),
                non_negative: false,
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
        (0..ctx.model.joints().len())
            .map(|j| size * geometric_mean(&ctx.model, j))
            .collect()
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta
            .iter()
            .enumerate()
            .map(|(j, t)| t / geometric_mean(&ctx.model, j))
            .sum::<f64>()
            / theta.len() as f64
    }

    fn admissible(&self, model: &Model, theta: &[f64]) -> Result<(), String> {
        for (j, t) in theta.iter().enumerate() {
            let limit = geometric_mean(model, j);
            if t.abs() >= limit {
                return Err(format!(
                    "|k12| = {:.4e} reaches sqrt(k1 k2) = {limit:.4e} of joint {}: the joint matrix would not be positive semidefinite",
                    t.abs(),
                    j + 1
                ));
            }
        }
        Ok(())
    }
}

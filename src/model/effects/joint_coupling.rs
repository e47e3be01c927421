//! `joint_coupling`: the transversal-rotational coupling stiffness k12 of every joint, which
//! eq. (17) assumes absent. The joint energy becomes
//! 1/2 [k1 dw^2 + 2 k12 dw dtheta + k2 dtheta^2] with dw = w_a - w_b, dtheta = theta_a - theta_b,
//! positive semidefinite while k12^2 <= k1 k2.

use super::{
    Effect, EffectContext, EffectParameter, Tier, add_pair, linear_contribution, per_joint_name,
};
use crate::structure::{JointSite, SparseSym, Structure};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct JointCoupling;

/// dK/dk12 of a joint.
fn pattern(site: &JointSite) -> SparseSym {
    let ([wa, wb], [ta, tb]) = (site.w, site.theta);
    let mut s = SparseSym::zero();
    add_pair(&mut s, wa, ta, 1.0);
    add_pair(&mut s, wa, tb, -1.0);
    add_pair(&mut s, wb, ta, -1.0);
    add_pair(&mut s, wb, tb, 1.0);
    s
}

/// sqrt(k1 k2) of joint `joint` in `structure`.
fn geometric_mean(structure: &Structure, joint: usize) -> f64 {
    let [k1, k2] = structure.sites.joints[joint].parameters;
    (structure.parameters[k1].value * structure.parameters[k2].value).sqrt()
}

/// dK/dk12 of every joint.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    ctx.structure
        .sites
        .joints
        .iter()
        .map(|site| (pattern(site), SparseSym::zero()))
        .collect()
}

impl Effect for JointCoupling {
    fn name(&self) -> &'static str {
        "joint_coupling"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "coupling stiffness k12 between the transversal and rotational motion of every joint; size = k12 / sqrt(k1 k2), from -1 to 1"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = ctx.structure.sites.joints.len();
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "k12"),
                unit: "N/rad",
                scale: geometric_mean(&ctx.structure, j),
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
        (0..ctx.structure.sites.joints.len())
            .map(|j| size * geometric_mean(&ctx.structure, j))
            .collect()
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta
            .iter()
            .enumerate()
            .map(|(j, t)| t / geometric_mean(&ctx.structure, j))
            .sum::<f64>()
            / theta.len() as f64
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        current: &Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        for (j, t) in theta.iter().enumerate() {
            let limit = geometric_mean(current, j);
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

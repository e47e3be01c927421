//! `joint_mass`: the mass of the joint hardware (bolts, flanges, washers, splice plates) that
//! the beam model does not carry. Per joint: mass m, half lumped at each of its two nodes with
//! the rotary inertia (m/2) r^2 of a body of the adjacent beam's radius of gyration
//! r^2 = I/A, and the hardware's own rotary inertia J beyond that, half on each node's
//! rotation (plates and bolt heads sit away from the neutral axis: their radius of gyration is
//! several times r):
//!
//! ```text
//!   M(m, J) - M(0) = sum_j sum_sides m_j / 2 (e_w e_w^T + r_side^2 e_theta e_theta^T)
//!                                  + J_j / 2 e_theta e_theta^T
//! ```
//!
//! Plausible hardware has m >= 0, J >= 0 and a radius of gyration within
//! LARGEST_GYRATION_HEIGHTS section heights h (h^2 = 12 r^2 for a rectangle):
//! m r^2 + J <= m (2 h)^2, i.e. J <= 47 m r^2; the fit keeps this cone (a rotary inertia with
//! no mass is no hardware). A rotary inertia alone is the separate candidate `joint_inertia`.

use super::{
    Effect, EffectContext, EffectParameter, LARGEST_GYRATION_HEIGHTS, Tier, add_pair, beyond,
    largest_gyration_squared, linear_contribution, per_joint_name,
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

/// dM/dJ of a joint.
fn inertia_pattern(site: &JointSite) -> SparseSym {
    let mut s = SparseSym::zero();
    for side in 0..2 {
        add_pair(&mut s, site.theta[side], site.theta[side], 0.5);
    }
    s
}

/// Mean r^2 = I/A of a joint's two sections.
fn gyration_squared(site: &JointSite) -> f64 {
    0.5 * (site.sections[0].gyration_squared() + site.sections[1].gyration_squared())
}

/// Whether the joint's nodes have rotations for a rotary inertia to load.
fn has_rotation(site: &JointSite) -> bool {
    site.theta.iter().any(Option::is_some)
}

/// The joints with a rotary inertia parameter.
fn rotating(ctx: &EffectContext) -> Vec<&JointSite> {
    ctx.structure
        .sites
        .joints
        .iter()
        .filter(|s| has_rotation(s))
        .collect()
}

/// dM/dm of every joint, then dM/dJ of every joint with rotations.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    let joints = &ctx.structure.sites.joints;
    joints
        .iter()
        .map(|site| (SparseSym::zero(), pattern(site)))
        .chain(
            rotating(ctx)
                .into_iter()
                .map(|site| (SparseSym::zero(), inertia_pattern(site))),
        )
        .collect()
}

/// (2 h)^2 - r^2 with h^2 = 12 r^2: the largest J / m beyond the coupled inertia.
fn extra_gyration_squared(site: &JointSite) -> f64 {
    (largest_gyration_squared(1.0) - 1.0) * gyration_squared(site)
}

impl Effect for JointMass {
    fn name(&self) -> &'static str {
        "joint_mass"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "lumped mass m and rotary inertia J (beyond m I/A) of every joint, half on each joint node; size = joint mass / mass of all beams (J = 0 in simulate)"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let sites = &ctx.structure.sites;
        let joints = sites.joints.len();
        let scale = 0.01 * sites.beam_mass;
        let masses = (0..joints).map(|j| EffectParameter {
            name: per_joint_name(self.name(), j, joints, "m"),
            unit: "kg",
            scale,
            non_negative: true,
        });
        let inertias = sites
            .joints
            .iter()
            .enumerate()
            .filter(|(_, s)| has_rotation(s))
            .map(|(j, site)| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "J"),
                unit: "kg m^2",
                scale: scale * gyration_squared(site),
                non_negative: true,
            });
        masses.chain(inertias).collect()
    }

    /// J_j <= m_j ((2 h)^2 - r^2) = 47 m_j r^2 (module docs).
    fn inequalities(&self, ctx: &EffectContext) -> Vec<Vec<(usize, f64)>> {
        let joints = &ctx.structure.sites.joints;
        let mut at = joints.len();
        let mut out = Vec::new();
        for (j, site) in joints.iter().enumerate() {
            if has_rotation(site) {
                out.push(vec![(j, extra_gyration_squared(site)), (at, -1.0)]);
                at += 1;
            }
        }
        out
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        let joints = ctx.structure.sites.joints.len();
        let mut theta = vec![size * ctx.structure.sites.beam_mass; joints];
        theta.resize(joints + rotating(ctx).len(), 0.0);
        theta
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        let joints = ctx.structure.sites.joints.len();
        theta[..joints].iter().sum::<f64>() / joints as f64 / ctx.structure.sites.beam_mass
    }

    /// The joints' hardware together is lighter than the beams it joins, and each joint's
    /// radius of gyration is within LARGEST_GYRATION_HEIGHTS section heights.
    fn plausible(&self, ctx: &EffectContext, theta: &[f64]) -> Result<(), String> {
        let joints = &ctx.structure.sites.joints;
        let total: f64 = theta[..joints.len()].iter().sum();
        let beams = ctx.structure.sites.beam_mass;
        if total >= beams {
            return Err(format!(
                "the joint masses add up to {total:.4e} kg, not less than the mass of all beams {beams:.4e} kg"
            ));
        }
        for (row, (j, site)) in self
            .inequalities(ctx)
            .iter()
            .zip(joints.iter().enumerate().filter(|(_, s)| has_rotation(s)))
        {
            let (m, inertia) = (theta[row[0].0], theta[row[1].0]);
            let largest = m * extra_gyration_squared(site);
            if beyond(inertia, largest) {
                return Err(format!(
                    "joint {}: a rotary inertia {inertia:.4e} kg m^2 beyond its mass's {m:.4e} kg puts the hardware's radius of gyration beyond {LARGEST_GYRATION_HEIGHTS} section heights",
                    j + 1
                ));
            }
        }
        Ok(())
    }
}

//! `joint_region`: a joint is a region, not a point, and its stiffness may be lower or higher
//! than the beams'. Over the `n` beam elements on each side of joint j (a bolted or bonded
//! overlap, a clamped or a loosened stretch), the bending stiffness is EI (1 + d_j):
//!
//! ```text
//!   K(d) - K(0) = sum_j d_j sum_{e in region j} k_e,   dK/dd_j = sum_{e in region j} k_e
//! ```
//!
//! with k_e the nominal element's Euler-Bernoulli stiffness; d_j > -1 (EI stays positive), of
//! either sign, one per joint. The region's length is a member of a scan: the diagnosis fits
//! the region at every length of [`lengths`] and keeps the best, with the profile of chi^2
//! along the length (`crate::diagnose::candidate::Scan`). [`super::Lap`] is the special case
//! of one element and a stiffening tied to the plates' added mass.
//!
//! Size (in the scan's report): d, the mean over the joints.

use super::{Effect, EffectContext, EffectParameter, Tier, linear_contribution, per_joint_name};
use crate::model::chain::beam::element_stiffness;
use crate::structure::{ElementSite, SparseSym, Structure};

/// See the module docs: a region of `elements` beam elements on each side of every joint.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct JointRegion {
    /// Elements on each side of the joint, >= 1.
    pub elements: usize,
}

/// The `n` elements of beam `joint` nearest the joint and the `n` elements of beam
/// `joint + 1` nearest it, nearest first on each side (fewer where a beam has fewer).
pub(crate) fn region(ctx: &EffectContext, joint: usize, n: usize) -> Vec<&ElementSite> {
    let elements = &ctx.structure.sites.elements;
    let mut left: Vec<&ElementSite> = elements.iter().filter(|e| e.beam == joint).collect();
    left.sort_by(|a, b| b.line.x[1].total_cmp(&a.line.x[1]));
    let mut right: Vec<&ElementSite> = elements.iter().filter(|e| e.beam == joint + 1).collect();
    right.sort_by(|a, b| a.line.x[0].total_cmp(&b.line.x[0]));
    left.into_iter()
        .take(n)
        .chain(right.into_iter().take(n))
        .collect()
}

/// The most elements a region may take on each side of every joint: half of each beam next to
/// a joint (0 when some joint has a beam without elements: the effect then does not apply).
fn longest(ctx: &EffectContext) -> usize {
    let sites = &ctx.structure.sites;
    let count = |beam: usize| sites.elements.iter().filter(|e| e.beam == beam).count();
    (0..sites.joints.len())
        .flat_map(|j| [count(j), count(j + 1)])
        .map(|c| c / 2)
        .min()
        .unwrap_or(0)
}

/// The region lengths a scan fits on this structure, in elements per side: 1, 2, 3, 4, 6, 8,
/// 11, 16, ... (steps of about sqrt 2) up to half of the shortest beam next to a joint.
pub fn lengths(ctx: &EffectContext) -> Vec<JointRegion> {
    let longest = longest(ctx);
    let mut out = Vec::new();
    let mut n = 1;
    while n <= longest {
        out.push(JointRegion { elements: n });
        n = (n + 1).max((n as f64 * std::f64::consts::SQRT_2).round() as usize);
    }
    out
}

impl JointRegion {
    /// sum k_e over the region of every joint (none when the structure cannot hold it).
    fn patterns(&self, ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
        if self.elements == 0 || self.elements > longest(ctx) {
            return Vec::new();
        }
        (0..ctx.structure.sites.joints.len())
            .map(|j| {
                let mut k = SparseSym::zero();
                for e in region(ctx, j, self.elements) {
                    k.add_element(
                        &e.line.dofs,
                        &element_stiffness(&e.section, e.length()),
                        1.0,
                    );
                }
                (k, SparseSym::zero())
            })
            .collect()
    }

    /// Length of the region of joint 1, both sides together (m).
    pub fn length(&self, ctx: &EffectContext) -> f64 {
        region(ctx, 0, self.elements)
            .iter()
            .map(|e| e.length())
            .sum()
    }
}

impl Effect for JointRegion {
    fn name(&self) -> &'static str {
        "joint_region"
    }

    fn tier(&self) -> Tier {
        Tier::Extended
    }

    fn describe(&self) -> &'static str {
        "bending stiffness EI (1 + d) over the given number of elements on each side of every joint, d > -1 per joint; size = d, the mean over the joints"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = self.patterns(ctx).len();
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "d"),
                unit: "-",
                scale: 0.1,
                non_negative: false,
            })
            .collect()
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&self.patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        self.patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size; self.patterns(ctx).len()]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len().max(1) as f64
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        match theta.iter().enumerate().find(|(_, d)| **d <= -1.0) {
            Some((j, d)) => Err(format!(
                "the region of joint {} would have EI times 1 + d = {}: it must stay above 0",
                j + 1,
                1.0 + d
            )),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::tests::{
        assert_central_differences, context, curvature_energy, dense,
    };

    /// The paper's chain (two beams of 9 elements each): lengths 1, 2, 3, 4 elements per side
    /// (half of 9 is 4), each region touching the joint and contiguous on both sides.
    #[test]
    fn lengths_run_up_to_half_the_shortest_beam_and_regions_touch_the_joint() {
        let ctx = context();
        let counts: Vec<usize> = (0..2)
            .map(|b| {
                let sites = &ctx.structure.sites.elements;
                sites.iter().filter(|e| e.beam == b).count()
            })
            .collect();
        let longest = counts.iter().min().unwrap() / 2;
        let found: Vec<usize> = lengths(&ctx).iter().map(|r| r.elements).collect();
        let expected: Vec<usize> = [1, 2, 3, 4, 6, 8, 11, 16]
            .into_iter()
            .filter(|&n| n <= longest)
            .collect();
        assert_eq!(found, expected);
        let x_joint = ctx.structure.sites.joints[0].x;
        for r in lengths(&ctx) {
            let elements = region(&ctx, 0, r.elements);
            assert_eq!(elements.len(), 2 * r.elements);
            let (left, right) = elements.split_at(r.elements);
            let mut edge = x_joint;
            for e in left {
                assert!((e.line.x[1] - edge).abs() < 1e-12);
                edge = e.line.x[0];
            }
            edge = x_joint;
            for e in right {
                assert!((e.line.x[0] - edge).abs() < 1e-12);
                edge = e.line.x[1];
            }
            let expected: f64 = elements.iter().map(|e| e.length()).sum();
            assert!((r.length(&ctx) - expected).abs() < 1e-15);
        }
        assert!(
            JointRegion {
                elements: longest + 1
            }
            .parameters(&ctx)
            .is_empty()
        );
    }

    /// A uniform curvature kappa over the region stores d EI kappa^2 L in the added stiffness
    /// (L the region's length), for a softening and a stiffening; linear in d (central
    /// differences), zero at d = 0, inadmissible at d = -1.
    #[test]
    fn the_region_carries_its_bending_energy_of_either_sign() {
        let ctx = context();
        let n = ctx.structure.dof_count();
        let x_joint = ctx.structure.sites.joints[0].x;
        for r in lengths(&ctx) {
            assert!(r.applies(&ctx));
            let zero = dense(n, &r.contribution(&ctx, &[0.0]));
            assert_eq!(zero.0.norm_max(), 0.0);
            assert_central_differences(&r, &ctx, &[-0.3], 0, 1e-3);
            let kappa = 0.4;
            let elements = region(&ctx, 0, r.elements);
            for d in [-0.6, 0.8] {
                let (k, _) = dense(n, &r.contribution(&ctx, &[d]));
                let energy = curvature_energy(&elements, x_joint, kappa, &k);
                let ei = ctx.structure.sites.elements[0].section.bending_stiffness();
                let expected = d * ei * kappa * kappa * r.length(&ctx);
                assert!(
                    (energy - expected).abs() < 1e-10 * expected.abs(),
                    "{} elements, d {d}: {energy} vs {expected}",
                    r.elements
                );
            }
            assert!(r.admissible(&ctx, &ctx.structure, &[-1.0]).is_err());
            assert!(r.admissible(&ctx, &ctx.structure, &[-0.99]).is_ok());
            assert_eq!(r.size_of_theta(&ctx, &r.theta_of_size(&ctx, -0.25)), -0.25);
        }
    }
}

//! `lap`: a joint is not a point. A lap or a spliced joint covers a finite length of the beams
//! on either side of the joint section, and over that length the section is stiffer (bonded or
//! bolted splice plates, the overlap of the two beams). The point joint of eq. (17) (the
//! springs k1, k2) cannot carry that: the finite region bends with the mode, and its effect on
//! a mode grows with the curvature the mode puts there, which is why the per-mode joint
//! stiffness of a real lap joint rises with the mode number.
//!
//! The lap region of joint j is the beam element on each side of the joint (the element of
//! beam j ending at the joint and the element of beam j + 1 starting there): the shortest
//! region the mesh resolves. Its bending stiffness is EI (1 + a_j) and its mass per length
//! rho A (1 + b_j), so
//!
//! ```text
//!   K - K0 = sum_j a_j (k_e(left of j) + k_e(right of j)),   dK/da_j = k_e(left) + k_e(right)
//!   M - M0 = sum_j b_j (m_e(left of j) + m_e(right of j)),   dM/db_j = m_e(left) + m_e(right)
//! ```
//!
//! with k_e, m_e the Euler-Bernoulli element stiffness and consistent mass of the nominal
//! section. Two parameters a_j, b_j >= 0 per joint, in that order. Both are needed: where the
//! joint springs are soft, stiffening the elements beside them changes little and the lap's
//! added mass is what the modes see (the independent battery's lap joints, k2 of a few
//! thousand N m/rad, showed it); where the joint is stiff, the stiffening dominates.
//!
//! Size (in `jointid simulate --effect lap=size`): the thickness t of splice plates bonded on
//! both faces over the lap region, as a fraction s = t / h of the section height h: EI times
//! (1 + 2 s)^3 (a solid rectangle of height h + 2t), rho A times 1 + 2 s, i.e.
//! a = (1 + 2 s)^3 - 1, b = 2 s. The size of fitted parameters is the mean over joints of
//! the two sizes they imply, ((1 + a)^(1/3) - 1) / 2 and b / 2.

use super::{Effect, EffectContext, EffectParameter, linear_contribution, per_joint_name};
use crate::model::chain::beam::{element_mass, element_stiffness};
use crate::structure::{ElementSite, SparseSym, Structure};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct Lap;

/// The element of beam `joint` ending at the joint and the element of beam `joint + 1`
/// starting there (absent when the structure's sites do not list them).
fn region(ctx: &EffectContext, joint: usize) -> Vec<&ElementSite> {
    let elements = &ctx.structure.sites.elements;
    let left = elements
        .iter()
        .filter(|e| e.beam == joint)
        .max_by(|a, b| a.line.x[1].total_cmp(&b.line.x[1]));
    let right = elements
        .iter()
        .filter(|e| e.beam == joint + 1)
        .min_by(|a, b| a.line.x[0].total_cmp(&b.line.x[0]));
    left.into_iter().chain(right).collect()
}

/// dK/da_j and dM/db_j of every joint with a lap region, in parameter order.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    let mut out = Vec::new();
    for j in 0..joints_with_region(ctx) {
        let (mut k, mut m) = (SparseSym::zero(), SparseSym::zero());
        for element in region(ctx, j) {
            let (section, l) = (&element.section, element.length());
            k.add_element(&element.line.dofs, &element_stiffness(section, l), 1.0);
            m.add_element(&element.line.dofs, &element_mass(section, l), 1.0);
        }
        out.push((k, SparseSym::zero()));
        out.push((SparseSym::zero(), m));
    }
    out
}

/// The number of joints, or 0 when some joint has no element beside it (a structure whose
/// sites do not list its elements): the effect then does not apply.
fn joints_with_region(ctx: &EffectContext) -> usize {
    let joints = ctx.structure.sites.joints.len();
    if (0..joints).all(|j| region(ctx, j).len() == 2) {
        joints
    } else {
        0
    }
}

/// a of splice plates of relative thickness `s` = t / h.
fn fraction_of_size(s: f64) -> f64 {
    (1.0 + 2.0 * s).powi(3) - 1.0
}

/// The inverse of [`fraction_of_size`].
fn size_of_fraction(a: f64) -> f64 {
    ((1.0 + a).cbrt() - 1.0) / 2.0
}

impl Effect for Lap {
    fn name(&self) -> &'static str {
        "lap"
    }

    fn describe(&self) -> &'static str {
        "finite-length lap at every joint: the element on each side of the joint stiffened to EI (1 + a); size = splice plate thickness t / section height h, a = (1 + 2 t/h)^3 - 1"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = joints_with_region(ctx);
        (0..joints)
            .flat_map(|j| {
                ["EI_fraction", "mass_fraction"].map(|suffix| EffectParameter {
                    name: per_joint_name(self.name(), j, joints, suffix),
                    unit: "-",
                    scale: 1.0,
                    non_negative: true,
                })
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
        [fraction_of_size(size), 2.0 * size].repeat(joints_with_region(ctx))
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        let sizes: f64 = theta
            .chunks(2)
            .map(|ab| size_of_fraction(ab[0]) + ab[1] / 2.0)
            .sum();
        sizes / theta.len() as f64
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        match theta.iter().enumerate().find(|(_, a)| **a <= -1.0) {
            Some((i, a)) => Err(format!(
                "the lap of joint {} has its {} times 1 + {a}: the factor must stay above 0",
                i / 2 + 1,
                if i % 2 == 0 { "EI" } else { "mass per length" }
            )),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::tests::context;

    /// The region is the two elements touching the joint, and dK/da is their stiffness: the
    /// lap's contribution to the strain energy of a rigid rotation about the joint is zero,
    /// and that of a uniform curvature kappa over the region is a EI kappa^2 (l_left + l_right).
    #[test]
    fn lap_region_touches_the_joint_and_carries_bending_energy() {
        let ctx = context();
        let joint = &ctx.structure.sites.joints[0];
        let elements = region(&ctx, 0);
        assert_eq!(elements.len(), 2);
        assert!((elements[0].line.x[1] - joint.x).abs() < 1e-12);
        assert!((elements[1].line.x[0] - joint.x).abs() < 1e-12);
        let (k, _) = Lap.contribution(&ctx, &[0.5, 0.0]);
        let n = ctx.structure.dof_count();
        let mut kd = faer::Mat::zeros(n, n);
        k.add_to(&mut kd, 1.0);
        // w = kappa (x - x_j)^2 / 2, theta = kappa (x - x_j) on each region element's nodes.
        let kappa = 0.3;
        let mut u = vec![0.0; n];
        for e in &elements {
            for (node, &x) in e.line.x.iter().enumerate() {
                let s = x - joint.x;
                if let Some(d) = e.line.dofs[2 * node] {
                    u[d] = 0.5 * kappa * s * s;
                }
                if let Some(d) = e.line.dofs[2 * node + 1] {
                    u[d] = kappa * s;
                }
            }
        }
        // The joint's two nodes move together: both carry w = theta = 0 at s = 0.
        let energy: f64 = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| u[i] * kd[(i, j)] * u[j])
            .sum();
        let ei = elements[0].section.bending_stiffness();
        let length: f64 = elements.iter().map(|e| e.length()).sum();
        let expected = 0.5 * ei * kappa * kappa * length;
        assert!(
            (energy - expected).abs() < 1e-10 * expected,
            "{energy} vs {expected}"
        );
    }

    /// dM/db is the region's consistent mass: a rigid translation w = 1 of the region carries
    /// its mass rho A (l_left + l_right) times b.
    #[test]
    fn lap_mass_is_the_region_mass() {
        let ctx = context();
        let elements = region(&ctx, 0);
        let (_, m) = Lap.contribution(&ctx, &[0.0, 0.25]);
        let n = ctx.structure.dof_count();
        let mut md = faer::Mat::zeros(n, n);
        m.add_to(&mut md, 1.0);
        let mut u = vec![0.0; n];
        for e in &elements {
            for node in 0..2 {
                if let Some(d) = e.line.dofs[2 * node] {
                    u[d] = 1.0;
                }
            }
        }
        let mass: f64 = (0..n)
            .flat_map(|i| (0..n).map(move |j| (i, j)))
            .map(|(i, j)| u[i] * md[(i, j)] * u[j])
            .sum();
        let expected: f64 = elements
            .iter()
            .map(|e| 0.25 * e.section.mass_per_length() * e.length())
            .sum();
        assert!(
            (mass - expected).abs() < 1e-12 * expected,
            "{mass} vs {expected}"
        );
    }

    #[test]
    fn size_is_the_splice_plate_thickness() {
        assert!((fraction_of_size(0.5) - 7.0).abs() < 1e-15);
        assert!((size_of_fraction(7.0) - 0.5).abs() < 1e-15);
    }
}

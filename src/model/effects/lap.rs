//! `lap`: a joint is not a point. A lap or a spliced joint covers a finite length of the beams
//! on either side of the joint section, and over that length the section is stiffer (bonded or
//! bolted splice plates, the overlap of the two beams). The point joint of eq. (17) (the
//! springs k1, k2) cannot carry that: the finite region bends with the mode, and its effect on
//! a mode grows with the curvature the mode puts there, which is why the per-mode joint
//! stiffness of a real lap joint rises with the mode number.
//!
//! The lap region of joint j is the beam element on each side of the joint (the element of
//! beam j ending at the joint and the element of beam j + 1 starting there): the shortest
//! region the mesh resolves. Over it, splice plates of thickness t on both faces of a section
//! of height h (or the overlap of the two beams) multiply the bending stiffness by
//! (1 + 2 s)^3 (a solid rectangle of height h + 2t) and the mass per length by 1 + 2 s, with
//! s = t / h the one parameter per joint:
//!
//! ```text
//!   K(s) - K(0) = ((1 + 2 s_j)^3 - 1) sum k_e,   dK/ds_j = 6 (1 + 2 s_j)^2 sum k_e
//!   M(s) - M(0) = 2 s_j sum m_e,                 dM/ds_j = 2 sum m_e
//! ```
//!
//! summed over the two region elements of joint j, k_e, m_e the Euler-Bernoulli element
//! stiffness and consistent mass of the nominal section. Stiffness and mass are tied by the
//! plates' geometry on purpose: where the joint springs are soft (k2 of a few thousand
//! N m/rad in the independent battery) stiffening the elements beside them changes little and
//! the lap's added mass is what the modes see, and a free mass parameter then makes the lap a
//! copy of `joint_mass` with more freedom (it took a strong joint mass from `joint_mass` on
//! that battery); tied, the lap has as many parameters as `joint_mass` and its own signature.
//! s >= 0 (a lap stiffens).
//!
//! Size (in `jointid simulate --effect lap=size`): s = t / h, the same at every joint.

use super::{Effect, EffectContext, EffectParameter, Tier, per_joint_name};
use crate::model::chain::beam::{element_mass, element_stiffness};
use crate::structure::{ElementSite, SparseSym, Structure};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct Lap;

/// The element of beam `joint` ending at the joint and the element of beam `joint + 1`
/// starting there (absent when the structure's sites do not list them).
fn region(ctx: &EffectContext, joint: usize) -> Vec<&ElementSite> {
    super::joint_region::region(ctx, joint, 1)
}

/// sum k_e and sum m_e over the lap region of every joint.
fn regions(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    (0..joints_with_region(ctx))
        .map(|j| {
            let (mut k, mut m) = (SparseSym::zero(), SparseSym::zero());
            for element in region(ctx, j) {
                let (section, l) = (&element.section, element.length());
                k.add_element(&element.line.dofs, &element_stiffness(section, l), 1.0);
                m.add_element(&element.line.dofs, &element_mass(section, l), 1.0);
            }
            (k, m)
        })
        .collect()
}

/// (K, M) of every joint's region scaled by (f(s_j), g(s_j)).
fn scaled(
    ctx: &EffectContext,
    theta: &[f64],
    f: impl Fn(f64) -> f64,
    g: impl Fn(f64) -> f64,
) -> Vec<(SparseSym, SparseSym)> {
    regions(ctx)
        .into_iter()
        .zip(theta)
        .map(|((k, m), &s)| {
            let (mut ks, mut ms) = (SparseSym::zero(), SparseSym::zero());
            ks.extend_scaled(&k, f(s));
            ms.extend_scaled(&m, g(s));
            (ks, ms)
        })
        .collect()
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

impl Effect for Lap {
    fn name(&self) -> &'static str {
        "lap"
    }

    fn tier(&self) -> Tier {
        Tier::Extended
    }

    fn describe(&self) -> &'static str {
        "finite-length lap at every joint: the element on each side of the joint stiffened to EI (1 + a); size = splice plate thickness t / section height h, a = (1 + 2 t/h)^3 - 1"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let joints = joints_with_region(ctx);
        (0..joints)
            .map(|j| EffectParameter {
                name: per_joint_name(self.name(), j, joints, "t_over_h"),
                unit: "-",
                scale: 0.1,
                non_negative: true,
            })
            .collect()
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        let mut k = SparseSym::zero();
        let mut m = SparseSym::zero();
        for (kj, mj) in scaled(ctx, theta, fraction_of_size, |s| 2.0 * s) {
            k.extend_scaled(&kj, 1.0);
            m.extend_scaled(&mj, 1.0);
        }
        (k, m)
    }

    fn derivatives(&self, ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        scaled(ctx, theta, |s| 6.0 * (1.0 + 2.0 * s).powi(2), |_| 2.0)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size; joints_with_region(ctx)]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len() as f64
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        match theta.iter().enumerate().find(|(_, s)| **s <= -0.5) {
            Some((j, s)) => Err(format!(
                "the lap of joint {} has t / h = {s}: the section height h + 2t must stay above 0",
                j + 1
            )),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::tests::{context, curvature_energy, dense};

    /// The region is the two elements touching the joint, and K(s) - K(0) is (1 + 2 s)^3 - 1 times their stiffness: the
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
        let (k, _) = dense(ctx.structure.dof_count(), &Lap.contribution(&ctx, &[0.5]));
        // The joint's two nodes move together: both carry w = theta = 0 at x_j.
        let kappa = 0.3;
        let energy = curvature_energy(&elements, joint.x, kappa, &k);
        let ei = elements[0].section.bending_stiffness();
        let length: f64 = elements.iter().map(|e| e.length()).sum();
        // s = 0.5: EI times (1 + 2 s)^3 = 8, an added 7 EI.
        let expected = 7.0 * ei * kappa * kappa * length;
        assert!(
            (energy - expected).abs() < 1e-10 * expected,
            "{energy} vs {expected}"
        );
    }

    /// dM/db is the region's consistent mass: a rigid translation w = 1 of the region carries
    /// its mass rho A (l_left + l_right) times 2 s.
    #[test]
    fn lap_mass_is_the_region_mass() {
        let ctx = context();
        let elements = region(&ctx, 0);
        // s = 0.125: rho A times 1 + 2 s = 1.25.
        let (_, m) = Lap.contribution(&ctx, &[0.125]);
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
    }
}

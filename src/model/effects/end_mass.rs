//! `end_mass`: a point mass at each free end of the chain (an end cap, a lifting eye, the
//! attachment of a suspension cord or of a shaker at the tip). One lumped translational mass
//! m_e per free end, each its own parameter:
//!
//! ```text
//!   M(m) - M(0) = sum_e m_e e_w(e) e_w(e)^T
//! ```
//!
//! Rotary inertia of the attachment is left out (a small body at the end of a beam loads its
//! translation far more than its rotation). The effect applies to structures with free ends.
//!
//! Size (in `jointid simulate --effect end_mass=size`): the mass at every free end as a
//! fraction of the mass of all beams.

use super::{Effect, EffectContext, EffectParameter, Tier, linear_contribution, per_site_name};
use crate::structure::SparseSym;

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct EndMass;

/// dM/dm_e of every free end.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    ctx.structure
        .sites
        .free_ends
        .iter()
        .map(|end| {
            let mut m = SparseSym::zero();
            m.add(end.w, end.w, 1.0);
            (SparseSym::zero(), m)
        })
        .collect()
}

impl Effect for EndMass {
    fn name(&self) -> &'static str {
        "end_mass"
    }

    fn tier(&self) -> Tier {
        Tier::Extended
    }

    fn describe(&self) -> &'static str {
        "a lumped mass at every free end, each its own parameter; size = mass at each end / mass of all beams"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let ends = ctx.structure.sites.free_ends.len();
        (0..ends)
            .map(|e| EffectParameter {
                name: per_site_name(self.name(), "end", e, ends, "m"),
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
        let sites = &ctx.structure.sites;
        vec![size * sites.beam_mass; sites.free_ends.len()]
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len() as f64 / ctx.structure.sites.beam_mass
    }
}

//! `suspension`: a free-free test is never perfectly free. Grounded translational springs of
//! stiffness k_s at the free ends of the chain. It applies to structures with rigid-body modes
//! (a suspended test), whose free ends are known.

use super::{Effect, EffectContext, EffectParameter, Tier, linear_contribution};
use crate::structure::SparseSym;

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct Suspension;

fn pattern(ctx: &EffectContext) -> SparseSym {
    let mut s = SparseSym::zero();
    for end in &ctx.structure.sites.free_ends {
        s.add(end.w, end.w, 1.0);
    }
    s
}

/// k_s putting the rigid bounce frequency sqrt(2 k_s / M) at `fraction` of the first elastic
/// frequency.
fn stiffness_of_bounce(ctx: &EffectContext, fraction: f64) -> f64 {
    let w = 2.0 * std::f64::consts::PI * fraction * ctx.first_elastic_hz;
    w * w * ctx.structure.sites.beam_mass / 2.0
}

/// dK/dk_s.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    vec![(pattern(ctx), SparseSym::zero())]
}

impl Effect for Suspension {
    fn name(&self) -> &'static str {
        "suspension"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "grounded translational springs at the two free ends; size = rigid bounce frequency sqrt(2 k_s / M) / first elastic frequency of the nominal model"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        if ctx.structure.rigid == 0 || ctx.structure.sites.free_ends.is_empty() {
            return Vec::new();
        }
        vec![EffectParameter {
            name: "suspension.k".into(),
            unit: "N/m",
            scale: stiffness_of_bounce(ctx, 0.1),
            non_negative: true,
        }]
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![stiffness_of_bounce(ctx, size.abs()).copysign(size)]
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        (theta[0].abs() / stiffness_of_bounce(ctx, 1.0))
            .sqrt()
            .copysign(theta[0])
    }
}

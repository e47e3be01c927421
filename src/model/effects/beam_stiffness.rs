//! `beam_stiffness` (extended tier): a beam stiffer or softer than the model says, one factor
//! per beam: E (and G with it) of each of its elements times (1 + theta_b), as a handbook E, a
//! nominal section or a heat treatment typed wrong would make it. It is the reference test's
//! unknown (`jointid calibrate`) offered to a diagnosis that has no reference test: a joint
//! calibrated on beams of the wrong stiffness carries their error.
//!
//! dK/dtheta_b is the beam's element stiffness (Euler-Bernoulli or Timoshenko: both linear in
//! E when G follows it), the layers of a layered lap left out (they are not element sites).
//! Plausible: every factor 1 + theta_b within [`PLAUSIBLE`] (a material or section value off
//! by more is a model typed wrong, not an effect); admissible while every factor stays
//! positive.

use super::{Effect, EffectContext, EffectParameter, Tier, linear_contribution, per_site_name};
use crate::model::chain::beam::element_stiffness;
use crate::structure::SparseSym;

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct BeamStiffness;

/// The plausible range of theta_b.
pub const PLAUSIBLE: (f64, f64) = (-0.25, 0.33);

/// The beams that have elements (0-based), in chain order.
fn beams(ctx: &EffectContext) -> Vec<usize> {
    let mut out: Vec<usize> = ctx
        .structure
        .sites
        .elements
        .iter()
        .map(|e| e.beam)
        .collect();
    out.dedup();
    out
}

/// dK/dtheta_b of every beam with elements.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    beams(ctx)
        .into_iter()
        .map(|b| {
            let mut k = SparseSym::zero();
            for e in ctx.structure.sites.elements.iter().filter(|e| e.beam == b) {
                let ke = element_stiffness(&e.section, e.length());
                k.add_element(&e.line.dofs, &ke, 1.0);
            }
            (k, SparseSym::zero())
        })
        .collect()
}

impl Effect for BeamStiffness {
    fn name(&self) -> &'static str {
        "beam_stiffness"
    }

    fn tier(&self) -> Tier {
        Tier::Extended
    }

    fn describe(&self) -> &'static str {
        "each beam's stiffness off: E (and G) of its elements times (1 + theta_b), one factor per beam (a lap's layers left out); size = theta of every beam"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let beams = beams(ctx);
        beams
            .iter()
            .map(|&b| EffectParameter {
                name: per_site_name("beam_stiffness", "beam", b, beams.len(), "change"),
                unit: "-",
                scale: 0.01,
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
        vec![size; beams(ctx).len()]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().sum::<f64>() / theta.len().max(1) as f64
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &crate::structure::Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        match theta.iter().find(|t| **t <= -1.0) {
            Some(t) => Err(format!("a beam's stiffness factor 1 + {t} is not positive")),
            None => Ok(()),
        }
    }

    fn plausible(&self, _ctx: &EffectContext, theta: &[f64]) -> Result<(), String> {
        let (lo, hi) = PLAUSIBLE;
        match theta.iter().find(|t| !(lo..=hi).contains(*t)) {
            Some(t) => Err(format!(
                "a beam's stiffness changed by {:+.0}%: beyond {:+.0}% to {:+.0}%, a model typed wrong",
                100.0 * t,
                100.0 * lo,
                100.0 * hi
            )),
            None => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::chain::calibration::scale_beam;
    use crate::model::effects::tests::{assert_central_differences, context_of};
    use crate::model::fixtures::paper_chain;

    #[test]
    fn a_change_of_each_beam_is_that_beam_built_with_its_e_scaled() {
        let chain = paper_chain(1e7, 1e4);
        let ctx = context_of(chain.build());
        let theta = [0.03, -0.02];
        let (dk, dm) = BeamStiffness.contribution(&ctx, &theta);
        assert!(dm.is_zero());
        let mut scaled = chain.clone();
        scale_beam(&mut scaled.beams[0], 1.03, 1.0);
        scale_beam(&mut scaled.beams[1], 0.98, 1.0);
        let built = scaled.build();
        let k = ctx.structure.base.k.plus(&[(&dk, 1.0)]);
        let largest = built
            .base
            .k
            .entries()
            .iter()
            .fold(0.0f64, |a, e| a.max(e.2.abs()));
        for (a, b) in k.entries().iter().zip(built.base.k.entries()) {
            assert!((a.2 - b.2).abs() <= 1e-12 * largest, "{a:?} vs {b:?}");
        }
        for i in 0..2 {
            assert_central_differences(&BeamStiffness, &ctx, &theta, i, 1e-6);
        }
        assert_eq!(
            BeamStiffness.parameters(&ctx)[1].name,
            "beam_stiffness.beam2.change"
        );
        assert!(BeamStiffness.plausible(&ctx, &[0.4, 0.0]).is_err());
        assert!(BeamStiffness.plausible(&ctx, &[0.1, -0.1]).is_ok());
    }
}

//! `element_damage` (outside the candidate library): the element at the middle of the last
//! beam loses a fraction of its bending stiffness, as a crack or a weld defect would. No
//! candidate models it; simulated data with it must come out `unexplained`.

use super::{Effect, EffectContext, EffectParameter, Tier, linear_contribution};
use crate::model::chain::beam::element_stiffness;
use crate::structure::{ElementSite, SparseSym};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct ElementDamage;

/// The element at the middle of the last beam.
fn damaged(ctx: &EffectContext) -> Option<&ElementSite> {
    let sites = &ctx.structure.sites;
    let last: Vec<&ElementSite> = sites
        .elements
        .iter()
        .filter(|e| e.beam + 1 == sites.beams)
        .collect();
    last.get(last.len() / 2).copied()
}

/// -k_e of the damaged element.
fn pattern(element: &ElementSite) -> SparseSym {
    let mut s = SparseSym::zero();
    let ke = element_stiffness(&element.section, element.length());
    s.add_element(&element.line.dofs, &ke, -1.0);
    s
}

/// dK/dfraction.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    damaged(ctx)
        .map(|e| (pattern(e), SparseSym::zero()))
        .into_iter()
        .collect()
}

impl Effect for ElementDamage {
    fn name(&self) -> &'static str {
        "element_damage"
    }

    fn tier(&self) -> Tier {
        Tier::Outside
    }

    fn describe(&self) -> &'static str {
        "loss of bending stiffness of the middle element of the last beam (outside the candidate library); size = lost fraction of EI"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        if damaged(ctx).is_none() {
            return Vec::new();
        }
        vec![EffectParameter {
            name: "element_damage.fraction".into(),
            unit: "-",
            scale: 0.1,
            non_negative: true,
        }]
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        patterns(ctx)
    }

    fn theta_of_size(&self, _ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta[0]
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &crate::structure::Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        match theta.first() {
            Some(&f) if !(0.0..1.0).contains(&f) => Err(format!(
                "the lost fraction of EI is {f}; it must be from 0 to below 1"
            )),
            _ => Ok(()),
        }
    }
}

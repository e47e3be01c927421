//! `element_damage` (outside the candidate library): the element at the middle of the last
//! beam loses a fraction of its bending stiffness, as a crack or a weld defect would. No
//! candidate models it; simulated data with it must come out `unexplained`.

use super::{Effect, EffectContext, EffectParameter, linear_contribution};
use crate::model::{Dof, Model, SparseSym, dof_index};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct ElementDamage;

/// -k_e of the damaged element.
fn pattern(model: &Model) -> SparseSym {
    let b = model.beams().len() - 1;
    let beam = &model.beams()[b];
    let base = dof_index(model.first_node(b) + beam.elements / 2, Dof::W);
    let mut s = SparseSym::zero();
    s.add_block(base, &beam.element_stiffness(), -1.0);
    s
}

/// dK/dfraction.
fn patterns(ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
    vec![(pattern(&ctx.model), SparseSym::zero())]
}

impl Effect for ElementDamage {
    fn name(&self) -> &'static str {
        "element_damage"
    }

    fn describe(&self) -> &'static str {
        "loss of bending stiffness of the middle element of the last beam (outside the candidate library); size = lost fraction of EI"
    }

    fn parameters(&self, _ctx: &EffectContext) -> Vec<EffectParameter> {
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
}

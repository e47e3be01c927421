//! `local_stiffness`: a change of bending stiffness EI (1 + d) of one beam element (a crack, a
//! weld, a machined or corroded stretch), the building block of the stiffness scan of issue 9:
//! the diagnosis fits it at every element of [`scan`] and keeps the best.
//!
//! ```text
//!   K(d) - K(0) = d k_e,   dK/dd = k_e
//! ```
//!
//! with k_e the nominal element's Euler-Bernoulli stiffness; d > -1 (EI stays positive), of
//! either sign. Not in [`super::candidates`] yet: a scan picks its position from the data, so
//! its test must account for the extra freedom (the largest of N likelihood-ratio statistics,
//! e.g. a Bonferroni factor N over the positions), which is the selection's business
//! (`crate::diagnose`). Size: d.

use super::{Effect, EffectContext, EffectParameter, Tier, linear_contribution};
use crate::model::chain::beam::element_stiffness;
use crate::structure::{SparseSym, Structure};

/// See the module docs: the element at index `element` of the structure's sites.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct LocalStiffness {
    /// Index into `Sites::elements`.
    pub element: usize,
}

/// One [`LocalStiffness`] per beam element of the structure, in chain order: the positions a
/// stiffness scan fits.
pub fn scan(ctx: &EffectContext) -> Vec<LocalStiffness> {
    (0..ctx.structure.sites.elements.len())
        .map(|element| LocalStiffness { element })
        .collect()
}

impl LocalStiffness {
    /// dK/dd (none when the structure has no such element).
    fn patterns(&self, ctx: &EffectContext) -> Vec<(SparseSym, SparseSym)> {
        ctx.structure
            .sites
            .elements
            .get(self.element)
            .map(|e| {
                let mut k = SparseSym::zero();
                k.add_element(
                    &e.line.dofs,
                    &element_stiffness(&e.section, e.length()),
                    1.0,
                );
                (k, SparseSym::zero())
            })
            .into_iter()
            .collect()
    }
}

impl Effect for LocalStiffness {
    fn name(&self) -> &'static str {
        "local_stiffness"
    }

    fn tier(&self) -> Tier {
        Tier::Extended
    }

    fn describe(&self) -> &'static str {
        "bending stiffness of one beam element times 1 + d; size = d"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let Some(e) = ctx.structure.sites.elements.get(self.element) else {
            return Vec::new();
        };
        vec![EffectParameter {
            name: format!(
                "local_stiffness.beam{}.x{:.4}.d",
                e.beam + 1,
                0.5 * (e.line.x[0] + e.line.x[1])
            ),
            unit: "-",
            scale: 0.1,
            non_negative: false,
        }]
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        linear_contribution(&self.patterns(ctx), theta)
    }

    fn derivatives(&self, ctx: &EffectContext, _theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        self.patterns(ctx)
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        self.patterns(ctx).iter().map(|_| size).collect()
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta[0]
    }

    fn admissible(
        &self,
        _ctx: &EffectContext,
        _current: &Structure,
        theta: &[f64],
    ) -> Result<(), String> {
        match theta.first() {
            Some(&d) if d <= -1.0 => Err(format!(
                "element {} would have EI times 1 + d = {}: it must stay above 0",
                self.element + 1,
                1.0 + d
            )),
            _ => Ok(()),
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::tests::{context, curvature_energy};

    /// Every scan position: zero at d = 0, dK/dd equal to the contribution's central
    /// difference (exact: linear), and a uniform curvature kappa over the element stores
    /// u^T dK u = EI kappa^2 l.
    #[test]
    fn every_scan_position_is_linear_and_carries_its_bending_energy() {
        let ctx = context();
        let n = ctx.structure.dof_count();
        let positions = scan(&ctx);
        assert_eq!(positions.len(), ctx.structure.sites.elements.len());
        assert!(!positions.is_empty());
        let dense = |s: &SparseSym| {
            let mut d = faer::Mat::zeros(n, n);
            s.add_to(&mut d, 1.0);
            d
        };
        for p in positions {
            assert!(p.applies(&ctx));
            assert_eq!(dense(&p.contribution(&ctx, &[0.0]).0).norm_max(), 0.0);
            let h = 1e-3;
            let fd = (dense(&p.contribution(&ctx, &[0.2 + h]).0)
                - dense(&p.contribution(&ctx, &[0.2 - h]).0))
                * faer::Scale(0.5 / h);
            let dk = dense(&p.derivatives(&ctx, &[0.2])[0].0);
            assert!((&fd - &dk).norm_max() <= 1e-9 * dk.norm_max());
            let e = &ctx.structure.sites.elements[p.element];
            let kappa = 0.7;
            let energy = curvature_energy(&[e], e.line.x[0], kappa, &dk);
            let expected = e.section.bending_stiffness() * kappa * kappa * e.length();
            // A clamped node (a removed DOF) carries u = 0 there: only compare free elements.
            if e.line.dofs.iter().all(Option::is_some) {
                assert!(
                    (energy - expected).abs() < 1e-10 * expected,
                    "element {}: {energy} vs {expected}",
                    p.element
                );
            }
            assert!(p.admissible(&ctx, &ctx.structure, &[-1.0]).is_err());
            assert_eq!(p.size_of_theta(&ctx, &p.theta_of_size(&ctx, -0.3)), -0.3);
        }
    }
}

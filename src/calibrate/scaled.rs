//! The unknowns of a calibration as an effect of the fit of module `diagnose::fit`: parts of
//! K and M that scale together, each by exp(theta_i) (theta_i = ln of its factor, 0 for the
//! values typed):
//!
//! ```text
//!   K(theta) - K(0) = sum_i (exp(theta_i) - 1) K_i,    dK/dtheta_i = exp(theta_i) K_i
//! ```
//!
//! and the same for M. A part is what the property of a group of beams contributes: K_i =
//! K(the group's E doubled) - K(as typed), exactly (the stiffness of a beam is linear in E
//! with G following it, its mass linear in rho), so that every piece of the beams (elements,
//! segments, a lap's layers) scales and nothing else does (joints, springs, masses).

use super::CalibrateError;
use super::specimen::{Specimen, specimen_chain};
use crate::model::chain::Chain;
use crate::model::chain::calibration::scale_beam;
use crate::model::effects::{Effect, EffectContext, EffectParameter, Tier};
use crate::structure::{SparseSym, SymMatrix};

/// What a factor scales.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Property {
    /// E of the beams (and G with it).
    YoungsModulus,
    /// rho of the beams.
    Density,
}

impl Property {
    /// Its name in the model file.
    pub fn name(self) -> &'static str {
        match self {
            Property::YoungsModulus => "youngs_modulus",
            Property::Density => "density",
        }
    }
}

/// One unknown factor: a property of a group of beams.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Unknown {
    /// What it scales.
    pub property: Property,
    /// The beams it scales (0-based).
    pub beams: Vec<usize>,
    /// Its name in reports: `youngs_modulus`, or `youngs_modulus.beam2` for one beam of
    /// several.
    pub name: String,
}

/// The unknowns as parts of K and M (module docs).
#[derive(Debug, Clone)]
pub struct Scaled {
    names: Vec<String>,
    parts: Vec<(SparseSym, SparseSym)>,
}

/// `a - b` of two matrices of the same pattern, exact zeros left out.
fn difference(a: &SymMatrix, b: &SymMatrix) -> SparseSym {
    let mut out = SparseSym::zero();
    for (x, y) in a.entries().into_iter().zip(b.entries()) {
        debug_assert_eq!((x.0, x.1), (y.0, y.1));
        if x.2 != y.2 {
            out.push(x.0, x.1, x.2 - y.2);
        }
    }
    out
}

impl Scaled {
    /// The parts of `unknowns` on the specimen `specimen` of `chain`.
    pub fn of(
        chain: &Chain,
        specimen: Specimen,
        unknowns: &[Unknown],
    ) -> Result<Self, CalibrateError> {
        let typed = specimen_chain(chain, specimen)?.build();
        let mut parts = Vec::with_capacity(unknowns.len());
        for u in unknowns {
            let mut doubled = chain.clone();
            for &b in &u.beams {
                let (stiffness, density) = match u.property {
                    Property::YoungsModulus => (2.0, 1.0),
                    Property::Density => (1.0, 2.0),
                };
                scale_beam(&mut doubled.beams[b], stiffness, density);
            }
            let doubled = specimen_chain(&doubled, specimen)?.build();
            parts.push((
                difference(&doubled.base.k, &typed.base.k),
                difference(&doubled.base.m, &typed.base.m),
            ));
        }
        Ok(Scaled {
            names: unknowns.iter().map(|u| u.name.clone()).collect(),
            parts,
        })
    }

    /// Whether scaling every part of K and of M by one factor each changes nothing in the
    /// specimen's modes but their scale: the parts make all of its K and all of its M (no
    /// spring, no mass, no joint besides the beams), so that E and rho are told apart by
    /// nothing but their ratio.
    pub fn only_ratio(&self, specimen: &crate::structure::Structure) -> bool {
        let whole = |matrix: &SymMatrix, mass: bool| {
            let mut rest = SparseSym::zero();
            for (k, m) in &self.parts {
                rest.extend_scaled(if mass { m } else { k }, -1.0);
            }
            let rest = matrix.plus(&[(&rest, 1.0)]);
            let size = |e: Vec<(usize, usize, f64)>| e.iter().map(|x| x.2 * x.2).sum::<f64>();
            size(rest.entries()) <= 1e-20 * size(matrix.entries())
        };
        whole(&specimen.base.k, false) && whole(&specimen.base.m, true)
    }
}

impl Effect for Scaled {
    fn name(&self) -> &'static str {
        "reference"
    }

    fn tier(&self) -> Tier {
        Tier::Outside
    }

    fn describe(&self) -> &'static str {
        "the beams' material scaled: E (and G) or rho of groups of beams times exp(theta)"
    }

    fn parameters(&self, _ctx: &EffectContext) -> Vec<EffectParameter> {
        self.names
            .iter()
            .map(|name| EffectParameter {
                name: name.clone(),
                unit: "-",
                scale: 1.0,
                non_negative: false,
            })
            .collect()
    }

    fn contribution(&self, _ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        let (mut k, mut m) = (SparseSym::zero(), SparseSym::zero());
        for ((dk, dm), t) in self.parts.iter().zip(theta) {
            if *t != 0.0 {
                k.extend_scaled(dk, t.exp_m1());
                m.extend_scaled(dm, t.exp_m1());
            }
        }
        (k, m)
    }

    fn derivatives(&self, _ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        self.parts
            .iter()
            .zip(theta)
            .map(|((dk, dm), t)| {
                let (mut k, mut m) = (SparseSym::zero(), SparseSym::zero());
                k.extend_scaled(dk, t.exp());
                m.extend_scaled(dm, t.exp());
                (k, m)
            })
            .collect()
    }

    fn theta_of_size(&self, _ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size.ln_1p(); self.parts.len()]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta.iter().map(|t| t.exp_m1()).sum::<f64>() / theta.len().max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::tests::{assert_central_differences, context_of};
    use crate::model::fixtures::paper_chain;

    fn unknowns(property: Property) -> Vec<Unknown> {
        (0..2)
            .map(|b| Unknown {
                property,
                beams: vec![b],
                name: format!("{}.beam{}", property.name(), b + 1),
            })
            .collect()
    }

    /// E and rho of each beam of `chain`'s monolithic specimen, and that specimen.
    fn e_and_rho_per_beam(chain: &Chain) -> (Scaled, crate::structure::Structure) {
        let both = [
            unknowns(Property::YoungsModulus),
            unknowns(Property::Density),
        ]
        .concat();
        let scaled = Scaled::of(chain, Specimen::Monolithic, &both).unwrap();
        let specimen = specimen_chain(chain, Specimen::Monolithic).unwrap().build();
        (scaled, specimen)
    }

    #[test]
    fn a_part_at_its_factor_is_the_specimen_built_with_that_factor() {
        let chain = paper_chain(1e7, 1e4);
        let (scaled, specimen) = e_and_rho_per_beam(&chain);
        let ctx = context_of(specimen.clone());
        let theta = [1.03f64, 0.98, 1.05, 1.01].map(f64::ln);
        let (dk, dm) = scaled.contribution(&ctx, &theta);
        let mut built = chain.clone();
        scale_beam(&mut built.beams[0], 1.03, 1.05);
        scale_beam(&mut built.beams[1], 0.98, 1.01);
        let built = specimen_chain(&built, Specimen::Monolithic)
            .unwrap()
            .build();
        let k = specimen.base.k.plus(&[(&dk, 1.0)]);
        let m = specimen.base.m.plus(&[(&dm, 1.0)]);
        for (a, b) in [(k, &built.base.k), (m, &built.base.m)] {
            let largest = b.entries().iter().fold(0.0f64, |x, e| x.max(e.2.abs()));
            for (x, y) in a.entries().iter().zip(b.entries()) {
                assert!((x.2 - y.2).abs() <= 1e-12 * largest, "{x:?} vs {y:?}");
            }
        }
        assert!(scaled.only_ratio(&specimen));
        for i in 0..4 {
            assert_central_differences(&scaled, &ctx, &theta, i, 1e-6);
        }
    }

    #[test]
    fn a_point_mass_tells_density_from_stiffness() {
        let mut chain = paper_chain(1e7, 1e4);
        chain.masses.push(crate::model::chain::PointMass {
            x: 0.1,
            mass: 0.05,
            rotary_inertia: 0.0,
            spring: None,
            identify: true,
        });
        let (scaled, specimen) = e_and_rho_per_beam(&chain);
        assert!(!scaled.only_ratio(&specimen));
    }
}

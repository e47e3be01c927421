//! `shear`: a thick beam shears, or shears more than the model says. One parameter theta >= 0
//! (0: the model as declared), element by element:
//! - a beam declared Euler-Bernoulli gets theta times the Timoshenko shear flexibility and
//!   rotary inertia of a rectangular section (shear coefficient kappa = 5/6, Poisson's ratio
//!   0.3): phi = theta 12 E I / (kappa G A l^2), and the stiffness
//!
//!   ```text
//!     k(phi) = EI / ((1 + phi) l^3) [A0 + phi A1],   A1 = l^2 [[0,0,0,0],[0,1,0,-1],[0,0,0,0],[0,-1,0,1]]
//!   ```
//!
//!   (Przemieniecki, *Theory of Matrix Structural Analysis*, sec. 5.6; A0 the Euler-Bernoulli
//!   pattern), the mass the Euler-Bernoulli consistent mass plus theta times the rotary-inertia
//!   matrix rho I / (30 l) [[36, 3l, -36, 3l], [3l, 4l^2, -3l, -l^2], [-36, -3l, 36, -3l],
//!   [3l, -l^2, -3l, 4l^2]]; the change of the translational mass with phi is left out;
//! - a beam declared Timoshenko (`shear_factor` in the model file) keeps its rotary inertia and
//!   gets exp(theta) times its declared shear flexibility: its element matrices
//!   (`chain::beam`, stiffness and consistent mass) at phi = exp(theta) phi_declared, less
//!   the declared ones. A shear factor or modulus too high or too low in the model is what it
//!   corrects: theta is free in sign where every beam is declared Timoshenko, and its size is
//!   the relative change of the shear flexibility, exp(theta) - 1.
//!
//! dK/dtheta and dM/dtheta follow from d/dphi of those matrices (`timoshenko_stiffness`,
//! `timoshenko_mass`) times dphi/dtheta.

use super::{Effect, EffectContext, EffectParameter, Tier};
use crate::model::chain::beam::{
    ElementMatrix, element_mass, shear_ratio, timoshenko_mass, timoshenko_stiffness,
};
use crate::structure::{ElementSite, Section, SparseSym};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct Shear;

/// Shear coefficient of a rectangular section.
const KAPPA: f64 = 5.0 / 6.0;
/// Poisson's ratio: G = E / (2 (1 + nu)).
const POISSON: f64 = 0.3;

/// phi of one element of length `l` at theta = 1.
fn phi_1(section: &Section, l: f64) -> f64 {
    let g = section.youngs_modulus / (2.0 * (1.0 + POISSON));
    12.0 * section.bending_stiffness() / (KAPPA * g * section.area * l * l)
}

fn rotary(element: &ElementSite) -> ElementMatrix {
    let (section, l) = (&element.section, element.length());
    let c = section.density * section.second_moment / (30.0 * l);
    [
        [36.0, 3.0 * l, -36.0, 3.0 * l],
        [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
        [-36.0, -3.0 * l, 36.0, -3.0 * l],
        [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
    ]
    .map(|row| row.map(|x| c * x))
}

/// One element's change of (K, M) at `t` from the model as declared, or with `slope` its
/// derivative in theta.
fn change(element: &ElementSite, t: f64, slope: bool) -> (ElementMatrix, ElementMatrix) {
    let (section, l) = (&element.section, element.length());
    let declared = shear_ratio(section, l);
    let (step, at) = if section.shear.is_some() {
        let at = declared * t.exp();
        (at, at)
    } else {
        let p1 = phi_1(section, l);
        (p1, t * p1)
    };
    let (k, dk) = timoshenko_stiffness(section, l, at);
    if slope {
        let m = if section.shear.is_some() {
            timoshenko_mass(section, l, at)
                .1
                .map(|r| r.map(|x| x * step))
        } else {
            rotary(element)
        };
        return (dk.map(|r| r.map(|x| x * step)), m);
    }
    let k0 = timoshenko_stiffness(section, l, declared).0;
    let m = if section.shear.is_some() {
        let (m, m0) = (timoshenko_mass(section, l, at).0, element_mass(section, l));
        std::array::from_fn(|i| std::array::from_fn(|j| m[i][j] - m0[i][j]))
    } else {
        rotary(element).map(|r| r.map(|x| x * t))
    };
    (
        std::array::from_fn(|i| std::array::from_fn(|j| k[i][j] - k0[i][j])),
        m,
    )
}

/// Whether every beam element is declared Timoshenko.
fn every_timoshenko(ctx: &EffectContext) -> bool {
    let elements = &ctx.structure.sites.elements;
    elements.iter().all(|e| e.section.shear.is_some())
}

/// Every beam element's change (or its derivative, `slope`) assembled.
fn assembled(ctx: &EffectContext, t: f64, slope: bool) -> (SparseSym, SparseSym) {
    let (mut k, mut m) = (SparseSym::zero(), SparseSym::zero());
    for element in &ctx.structure.sites.elements {
        let (dk, dm) = change(element, t, slope);
        k.add_element(&element.line.dofs, &dk, 1.0);
        m.add_element(&element.line.dofs, &dm, 1.0);
    }
    (k, m)
}

impl Effect for Shear {
    fn name(&self) -> &'static str {
        "shear"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "shear flexibility: on beams declared Euler-Bernoulli theta times a rectangle's Timoshenko shear and rotary inertia (kappa = 5/6, nu = 0.3; size = theta), on beams declared Timoshenko exp(theta) times their own (size = exp(theta) - 1); 0 for the model as declared"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        if ctx.structure.sites.elements.is_empty() {
            return Vec::new();
        }
        vec![EffectParameter {
            name: "shear.scale".into(),
            unit: "-",
            scale: 1.0,
            non_negative: !every_timoshenko(ctx),
        }]
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        if theta[0] == 0.0 {
            return (SparseSym::zero(), SparseSym::zero());
        }
        assembled(ctx, theta[0], false)
    }

    fn derivatives(&self, ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        vec![assembled(ctx, theta[0], true)]
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        if every_timoshenko(ctx) {
            vec![size.ln_1p()]
        } else {
            vec![size]
        }
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        if every_timoshenko(ctx) {
            theta[0].exp_m1()
        } else {
            theta[0]
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::tests::{assert_central_differences, context_of};
    use crate::model::{Beam, Chain, Joint};
    use crate::structure::{Shear as Declared, Structure};

    /// Two stubby steel bars (40 mm deep, 0.2 m long) and a joint, Timoshenko with shear
    /// factor `factor` where given.
    fn thick(factor: Option<f64>) -> Structure {
        let section = Section {
            youngs_modulus: 2.1e11,
            density: 7850.0,
            area: 0.03 * 0.04,
            second_moment: 0.03 * 0.04f64.powi(3) / 12.0,
            shear: factor.map(|factor| Declared {
                factor,
                modulus: 8.1e10,
            }),
        };
        let beams = vec![
            Beam::uniform(0.2, 8, section),
            Beam::uniform(0.2, 8, section),
        ];
        Chain::free(beams, vec![Joint::identified(1e8, 1e6)]).build()
    }

    #[test]
    fn the_derivatives_on_declared_timoshenko_beams_match_central_differences() {
        let ctx = context_of(thick(Some(0.85)));
        for t in [-0.5, 0.0, 0.3, 2.0] {
            assert_central_differences(&Shear, &ctx, &[t], 0, 1e-6);
        }
    }

    #[test]
    fn on_declared_timoshenko_beams_the_size_is_the_change_of_shear_flexibility() {
        // exp(theta) times the shear flexibility 1 / (kappa G A): size 1 (theta = ln 2) is
        // the model declared with half the shear factor, entry by entry.
        let declared = thick(Some(0.85));
        let ctx = context_of(declared.clone());
        assert!(!Shear.parameters(&ctx)[0].non_negative);
        let theta = Shear.theta_of_size(&ctx, 1.0);
        assert!((Shear.size_of_theta(&ctx, &theta) - 1.0).abs() < 1e-15);
        let (dk, dm) = Shear.contribution(&ctx, &theta);
        let changed = declared.assemble().plus(&[(&dk, &dm, 1.0)]);
        let halved = thick(Some(0.425)).assemble();
        for (a, b) in [(&changed.k, &halved.k), (&changed.m, &halved.m)] {
            let (a, b) = (a.to_dense(), b.to_dense());
            let scale = b.norm_max();
            assert!(
                (&a - &b).norm_max() < 1e-12 * scale,
                "{}",
                (&a - &b).norm_max() / scale
            );
        }
    }
}

//! `shear`: a thick beam shears. Timoshenko shear flexibility and rotary inertia of every beam
//! element the model declares Euler-Bernoulli, scaled by one parameter theta (0:
//! Euler-Bernoulli, 1: Timoshenko with a rectangular section's shear coefficient kappa = 5/6
//! and Poisson's ratio 0.3). Elements declared Timoshenko (`shear_factor` in the model file)
//! already have both and are left as they are; a model whose every beam is Timoshenko offers
//! the effect nothing to act on.
//!
//! Element stiffness (Przemieniecki, *Theory of Matrix Structural Analysis*, sec. 5.6), with
//! phi = theta 12 E I / (kappa G A l^2):
//!
//! ```text
//!   k(phi) = EI / ((1 + phi) l^3) [A0 + phi A1],   A1 = l^2 [[0,0,0,0],[0,1,0,-1],[0,0,0,0],[0,-1,0,1]]
//!   dk/dtheta = phi_1 EI / l^3 (A1 - A0) / (1 + theta phi_1)^2,   phi_1 = phi / theta
//! ```
//! A0 is the Euler-Bernoulli pattern. Mass: the Euler-Bernoulli consistent mass plus theta
//! times the rotary-inertia matrix rho I / (30 l) [[36, 3l, -36, 3l], [3l, 4l^2, -3l, -l^2],
//! [-36, -3l, 36, -3l], [3l, -l^2, -3l, 4l^2]]; the change of the translational mass with phi
//! is left out.

use super::{Effect, EffectContext, EffectParameter, Tier};
use crate::model::chain::beam::{ElementMatrix, element_stiffness};
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

fn a1(l: f64) -> ElementMatrix {
    let l2 = l * l;
    [
        [0.0, 0.0, 0.0, 0.0],
        [0.0, l2, 0.0, -l2],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, -l2, 0.0, l2],
    ]
}

fn a0(section: &Section, l: f64) -> ElementMatrix {
    let c = section.bending_stiffness() / (l * l * l);
    element_stiffness(section, l).map(|row| row.map(|x| x / c))
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

/// The beam elements declared Euler-Bernoulli.
fn euler_bernoulli(ctx: &EffectContext) -> impl Iterator<Item = &ElementSite> {
    let elements = &ctx.structure.sites.elements;
    elements.iter().filter(|e| e.section.shear.is_none())
}

/// Adds `f(element)` on every beam element declared Euler-Bernoulli.
fn every_element(ctx: &EffectContext, f: impl Fn(&ElementSite) -> ElementMatrix) -> SparseSym {
    let mut s = SparseSym::zero();
    for element in euler_bernoulli(ctx) {
        s.add_element(&element.line.dofs, &f(element), 1.0);
    }
    s
}

impl Effect for Shear {
    fn name(&self) -> &'static str {
        "shear"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "Timoshenko shear flexibility and rotary inertia of the beams declared Euler-Bernoulli; size = theta, 0 for Euler-Bernoulli, 1 for kappa = 5/6 and nu = 0.3"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        if euler_bernoulli(ctx).next().is_none() {
            return Vec::new();
        }
        vec![EffectParameter {
            name: "shear.scale".into(),
            unit: "-",
            scale: 1.0,
            non_negative: true,
        }]
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        let t = theta[0];
        if t == 0.0 {
            return (SparseSym::zero(), SparseSym::zero());
        }
        let k = every_element(ctx, |element| {
            let (section, l) = (&element.section, element.length());
            let c = section.bending_stiffness() / (l * l * l);
            let phi = t * phi_1(section, l);
            let (base, extra) = (a0(section, l), a1(l));
            // k(phi) - k(0) = c [(A0 + phi A1) / (1 + phi) - A0] = c phi (A1 - A0) / (1 + phi)
            std::array::from_fn(|i| {
                std::array::from_fn(|j| c * phi * (extra[i][j] - base[i][j]) / (1.0 + phi))
            })
        });
        let mut m = SparseSym::zero();
        m.extend_scaled(&every_element(ctx, rotary), t);
        (k, m)
    }

    fn derivatives(&self, ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        let t = theta[0];
        let dk = every_element(ctx, |element| {
            let (section, l) = (&element.section, element.length());
            let c = section.bending_stiffness() / (l * l * l);
            let p1 = phi_1(section, l);
            let (base, extra) = (a0(section, l), a1(l));
            let d = (1.0 + t * p1) * (1.0 + t * p1);
            std::array::from_fn(|i| {
                std::array::from_fn(|j| c * p1 * (extra[i][j] - base[i][j]) / d)
            })
        });
        vec![(dk, every_element(ctx, rotary))]
    }

    fn theta_of_size(&self, _ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta[0]
    }
}

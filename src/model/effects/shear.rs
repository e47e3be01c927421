//! `shear`: a thick beam shears. Timoshenko shear flexibility and rotary inertia of every beam
//! element, scaled by one parameter theta (0: Euler-Bernoulli, 1: Timoshenko with a
//! rectangular section's shear coefficient kappa = 5/6 and Poisson's ratio 0.3).
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

use super::{Effect, EffectContext, EffectParameter};
use crate::model::beam::ElementMatrix;
use crate::model::{Beam, Dof, Model, SparseSym, dof_index};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct Shear;

/// Shear coefficient of a rectangular section.
const KAPPA: f64 = 5.0 / 6.0;
/// Poisson's ratio: G = E / (2 (1 + nu)).
const POISSON: f64 = 0.3;

/// phi of one element at theta = 1.
fn phi_1(beam: &Beam) -> f64 {
    let l = beam.element_length();
    let g = beam.youngs_modulus / (2.0 * (1.0 + POISSON));
    12.0 * beam.bending_stiffness() / (KAPPA * g * beam.area * l * l)
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

fn a0(beam: &Beam) -> ElementMatrix {
    let l = beam.element_length();
    let c = beam.bending_stiffness() / (l * l * l);
    let k = beam.element_stiffness();
    k.map(|row| row.map(|x| x / c))
}

fn rotary(beam: &Beam) -> ElementMatrix {
    let l = beam.element_length();
    let c = beam.density * beam.second_moment / (30.0 * l);
    [
        [36.0, 3.0 * l, -36.0, 3.0 * l],
        [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
        [-36.0, -3.0 * l, 36.0, -3.0 * l],
        [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
    ]
    .map(|row| row.map(|x| c * x))
}

/// Adds `f(beam)` on every element of every beam.
fn every_element(model: &Model, mut f: impl FnMut(&Beam) -> ElementMatrix) -> SparseSym {
    let mut s = SparseSym::zero();
    for (b, beam) in model.beams().iter().enumerate() {
        let e_matrix = f(beam);
        for e in 0..beam.elements {
            s.add_block(dof_index(model.first_node(b) + e, Dof::W), &e_matrix, 1.0);
        }
    }
    s
}

impl Effect for Shear {
    fn name(&self) -> &'static str {
        "shear"
    }

    fn describe(&self) -> &'static str {
        "Timoshenko shear flexibility and rotary inertia of the beams; size = theta, 0 for Euler-Bernoulli, 1 for kappa = 5/6 and nu = 0.3"
    }

    fn parameters(&self, _ctx: &EffectContext) -> Vec<EffectParameter> {
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
        let k = every_element(&ctx.model, |beam| {
            let l = beam.element_length();
            let c = beam.bending_stiffness() / (l * l * l);
            let phi = t * phi_1(beam);
            let (base, extra) = (a0(beam), a1(l));
            // k(phi) - k(0) = c [(A0 + phi A1) / (1 + phi) - A0] = c phi (A1 - A0) / (1 + phi)
            std::array::from_fn(|i| {
                std::array::from_fn(|j| c * phi * (extra[i][j] - base[i][j]) / (1.0 + phi))
            })
        });
        let mut m = SparseSym::zero();
        m.extend_scaled(&every_element(&ctx.model, rotary), t);
        (k, m)
    }

    fn derivatives(&self, ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        let t = theta[0];
        let dk = every_element(&ctx.model, |beam| {
            let l = beam.element_length();
            let c = beam.bending_stiffness() / (l * l * l);
            let p1 = phi_1(beam);
            let (base, extra) = (a0(beam), a1(l));
            let d = (1.0 + t * p1) * (1.0 + t * p1);
            std::array::from_fn(|i| {
                std::array::from_fn(|j| c * p1 * (extra[i][j] - base[i][j]) / d)
            })
        });
        vec![(dk, every_element(&ctx.model, rotary))]
    }

    fn theta_of_size(&self, _ctx: &EffectContext, size: f64) -> Vec<f64> {
        vec![size]
    }

    fn size_of_theta(&self, _ctx: &EffectContext, theta: &[f64]) -> f64 {
        theta[0]
    }
}

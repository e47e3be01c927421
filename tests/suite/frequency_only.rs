//! One joint parameter per mode from its frequency alone (`identify::frequency_only`), against
//! the continuous Euler-Bernoulli solution of a jointed beam.
//!
//! Independence: the reference frequencies are not from jointid's elements. Two equal free-free
//! beams of length a joined at the middle by a rotational spring k2 (the transversal spring
//! stiff): in a mode symmetric about the joint the rotations on either side are opposite, so
//! each half is a beam free at x = a and, at the joint (x = 0), without shear (w''' = 0) and
//! restrained by EI w''(0) = 2 k2 w'(0) (the spring's energy 1/2 k2 (2 w'(0))^2 shared by the
//! halves). With w = A cos bx + B sin bx + C cosh bx + D sinh bx, the four conditions give a
//! 4 x 4 determinant in b whose roots this test finds by bisection; k2 -> infinity gives the
//! monoblock's symmetric modes (bL = 4.7300, 10.9956 for L = 2a), k2 -> 0 the free halves.
//! Symmetric modes are the elastic modes 1 and 3; mode 2 (antisymmetric) does not see k2.

use crate::common::steel_bar;
use jointid::identify::frequency_only::{Choice, FrequencyError, identify};
use jointid::model::{Chain, Joint};
use jointid::structure::Structure;

pub const HALF: f64 = 0.25;

/// det of the half-beam's boundary conditions at b (1/m), spring 2 k2 at x = 0.
fn det(b: f64, k2: f64) -> f64 {
    let bar = steel_bar(HALF, 1);
    let ei = bar.bending_stiffness();
    let a = HALF;
    let (c, s, ch, sh) = ((b * a).cos(), (b * a).sin(), (b * a).cosh(), (b * a).sinh());
    // rows: w''(a) = 0, w'''(a) = 0, w'''(0) = 0, EI w''(0) - 2 k2 w'(0) = 0 (divided by b^2)
    let m = [
        [-c, -s, ch, sh],
        [s, -c, sh, ch],
        [0.0, -1.0, 0.0, 1.0],
        [-ei * b, -2.0 * k2, ei * b, -2.0 * k2],
    ];
    let minor = |r: [usize; 3], cidx: [usize; 3]| -> f64 {
        let g = |i: usize, j: usize| m[r[i]][cidx[j]];
        g(0, 0) * (g(1, 1) * g(2, 2) - g(1, 2) * g(2, 1))
            - g(0, 1) * (g(1, 0) * g(2, 2) - g(1, 2) * g(2, 0))
            + g(0, 2) * (g(1, 0) * g(2, 1) - g(1, 1) * g(2, 0))
    };
    (0..4)
        .map(|j| {
            let cols: Vec<usize> = (0..4).filter(|&c| c != j).collect();
            let sign = if j % 2 == 0 { 1.0 } else { -1.0 };
            sign * m[0][j] * minor([1, 2, 3], [cols[0], cols[1], cols[2]])
        })
        .sum()
}

/// The lowest `count` symmetric frequencies (Hz) with spring k2, by scanning and bisection.
pub fn symmetric_hz(k2: f64, count: usize) -> Vec<f64> {
    let bar = steel_bar(HALF, 1);
    let c = (bar.bending_stiffness() / bar.mass_per_length()).sqrt();
    let mut roots = Vec::new();
    let (mut lo, step) = (1e-3, 1e-2);
    while roots.len() < count {
        let hi = lo + step;
        if det(lo, k2).signum() != det(hi, k2).signum() {
            let (mut a, mut b) = (lo, hi);
            for _ in 0..200 {
                let mid = 0.5 * (a + b);
                if det(a, k2).signum() == det(mid, k2).signum() {
                    a = mid;
                } else {
                    b = mid;
                }
            }
            roots.push(0.5 * (a + b));
        }
        lo = hi;
    }
    roots
        .iter()
        .map(|b| b * b * c / (2.0 * std::f64::consts::PI))
        .collect()
}

fn model(k2: f64, elements: usize) -> Structure {
    Chain::free(
        vec![steel_bar(HALF, elements), steel_bar(HALF, elements)],
        vec![Joint::identified(1e13, k2)],
    )
    .build()
}

#[test]
fn the_analytic_limits_hold() {
    // k2 -> infinity: the monoblock's symmetric roots bL = 4.7300407, 10.9956078 (L = 2a)
    let stiff = symmetric_hz(1e12, 2);
    let bar = steel_bar(2.0 * HALF, 1);
    let c = (bar.bending_stiffness() / bar.mass_per_length()).sqrt();
    for (f, bl) in stiff.iter().zip([4.7300407, 10.9956078]) {
        let want = (bl / (2.0 * HALF)).powi(2) * c / (2.0 * std::f64::consts::PI);
        assert!((f / want - 1.0).abs() < 1e-6, "{f} vs {want}");
    }
}

#[test]
fn the_spring_is_recovered_from_each_symmetric_frequency() {
    let k2_true = 2.0e4;
    let measured = symmetric_hz(k2_true, 2);
    let start = model(1.0e5, 60);
    for (f, t) in measured.iter().zip([2usize, 4]) {
        let out = identify(&start, t, t - 1, *f, Some(1e-3), Choice::Named(1)).unwrap();
        let k2 = 1.0e5 * (1.0 + out.relative);
        // the FE discretisation (60 elements per half) is the only difference: 2.3e-6 at mode 3
        assert!(
            (k2 / k2_true - 1.0).abs() < 1e-5,
            "mode {t}: k2 {k2} vs {k2_true}"
        );
        assert!(out.sensitivity > 0.0, "a stiffness raises the frequency");
    }
}

#[test]
fn the_most_sensitive_parameter_of_a_symmetric_mode_is_the_spring() {
    let f = symmetric_hz(2.0e4, 1)[0];
    let out = identify(&model(1.0e5, 30), 2, 1, f, None, Choice::MostSensitive).unwrap();
    assert_eq!(out.param, 1, "k2 is the parameter mode 1 sees");
    assert!(out.std.is_none());
}

#[test]
fn the_standard_deviation_is_the_derivative_of_the_solution() {
    // sigma(p / p0 - 1) = (p / p0) 2 sigma_f / |s|: check d ln p / d ln f = 2 / s by central
    // differences of the exact solution
    let f = symmetric_hz(2.0e4, 1)[0];
    let start = model(1.0e5, 30);
    let at = |g: f64| identify(&start, 2, 1, g, Some(1e-3), Choice::Named(1)).unwrap();
    let centre = at(f);
    let h = 1e-5;
    let (up, down) = (at(f * (1.0 + h)), at(f * (1.0 - h)));
    let dlnp_dlnf = ((1.0 + up.relative).ln() - (1.0 + down.relative).ln()) / (2.0 * h);
    let predicted = centre.std.unwrap() / (1.0 + centre.relative) / 1e-3;
    assert!(
        // the root is solved to 1e-12 in ln lambda: over a step of 1e-5, 1e-7 at worst
        (dlnp_dlnf / predicted - 1.0).abs() < 1e-6,
        "{dlnp_dlnf} vs {predicted}"
    );
}

#[test]
fn a_mode_that_does_not_see_the_parameter_or_lies_beyond_its_reach_is_refused() {
    let start = model(1.0e5, 30);
    // mode 2 is antisymmetric: k2 does not move it
    match identify(&start, 3, 2, 500.0, None, Choice::Named(1)) {
        Err(FrequencyError::Insensitive { mode: 2, .. }) => {}
        other => panic!("{other:?}"),
    }
    // above the monoblock's first symmetric frequency no k2 reaches
    let monoblock = symmetric_hz(1e12, 1)[0];
    match identify(&start, 2, 1, 1.2 * monoblock, None, Choice::Named(1)) {
        Err(e @ FrequencyError::OutOfReach { .. }) => {
            assert!(e.to_string().contains("beyond the reach of k2"), "{e}");
        }
        other => panic!("{other:?}"),
    }
}

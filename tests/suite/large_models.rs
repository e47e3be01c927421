//! Lowest modes of large beam models against analytic Euler-Bernoulli frequencies, through
//! `ModalSolution::lowest_of` (the sparse shift-invert path above `DENSE_MAX_DOFS`).
//!
//! The reference values come from the continuum, not from any finite element: the roots of
//! the frequency equations (cos bL cosh bL = -1 for a clamped-free beam; the 8 x 8 boundary
//! and joint conditions of two free-free beams joined by a translational and a rotational
//! spring), found by bisection of a determinant computed here by Gaussian elimination. At
//! 2000 elements per beam the discretisation error of the modes checked is below 1e-10
//! relative, so what is left is round-off (the module docs of `jointid::modal::refine`):
//! measured 8.8e-9 relative on the chain's first elastic frequency at N = 8004 (5e-10 at
//! N = 2004: it grows like N^2) and 2.7e-9 on the cantilever's first at N = 8000. The
//! tolerances are these, rounded up once.

use jointid::modal::{DENSE_MAX_DOFS, ModalSolution, hz_to_lambda};
use jointid::model::chain::{Chain, Joint, Support, SupportKind};
use jointid::model::fixtures::steel_bar;

const E: f64 = 2.1e11;
const RHO: f64 = 7850.0;
const AREA: f64 = 2.4e-3;
const I2: f64 = 3.2e-7;

/// b of a frequency: b^4 = omega^2 rho A / (E I).
fn beta_of(f_hz: f64) -> f64 {
    (hz_to_lambda(f_hz) * RHO * AREA / (E * I2)).powf(0.25)
}

fn hz_of(beta: f64) -> f64 {
    let omega = (beta.powi(4) * E * I2 / (RHO * AREA)).sqrt();
    omega / (2.0 * std::f64::consts::PI)
}

/// Determinant by Gaussian elimination with partial pivoting.
fn determinant(mut a: Vec<Vec<f64>>) -> f64 {
    let n = a.len();
    let mut det = 1.0;
    for c in 0..n {
        let p = (c..n)
            .max_by(|&i, &j| a[i][c].abs().total_cmp(&a[j][c].abs()))
            .unwrap();
        if p != c {
            a.swap(p, c);
            det = -det;
        }
        let pivot = a[c][c];
        if pivot == 0.0 {
            return 0.0;
        }
        det *= pivot;
        let (top, below) = a.split_at_mut(c + 1);
        for row in below {
            let f = row[c] / pivot;
            for (x, y) in row[c..].iter_mut().zip(&top[c][c..]) {
                *x -= f * y;
            }
        }
    }
    det
}

/// Derivatives 0..=3 of cosh, sinh, cos, sin (b x) with respect to x, each divided by b^d.
fn shapes(b: f64, x: f64) -> [[f64; 4]; 4] {
    let (ch, sh, c, s) = ((b * x).cosh(), (b * x).sinh(), (b * x).cos(), (b * x).sin());
    [
        [ch, sh, c, s],
        [sh, ch, -s, c],
        [ch, sh, -c, -s],
        [sh, ch, s, -c],
    ]
}

/// The joined free-free beams a (length la) and b (lb): w = A cosh + B sinh + C cos + D sin
/// on each; free ends; at the joint EI w_a'' + k2 (w_a' - w_b') = 0,
/// -EI w_a''' + k1 (w_a - w_b) = 0, EI w_b'' + k2 (w_a' - w_b') = 0,
/// EI w_b''' - k1 (w_a - w_b) = 0 (from the variation of the strain energy).
fn chain_determinant(b: f64, la: f64, lb: f64, k1: f64, k2: f64) -> f64 {
    let ei = E * I2;
    let (a0, al, b0, bl) = (shapes(b, 0.0), shapes(b, la), shapes(b, 0.0), shapes(b, lb));
    let mut rows = vec![vec![0.0; 8]; 8];
    for k in 0..4 {
        rows[0][k] = a0[2][k];
        rows[1][k] = a0[3][k];
        rows[2][4 + k] = bl[2][k];
        rows[3][4 + k] = bl[3][k];
        // Joint (w' = b shape[1], w'' = b^2 shape[2], w''' = b^3 shape[3]).
        rows[4][k] = ei * b * b * al[2][k] + k2 * b * al[1][k];
        rows[4][4 + k] = -k2 * b * b0[1][k];
        rows[5][k] = -ei * b.powi(3) * al[3][k] + k1 * al[0][k];
        rows[5][4 + k] = -k1 * b0[0][k];
        rows[6][k] = k2 * b * al[1][k];
        rows[6][4 + k] = ei * b * b * b0[2][k] - k2 * b * b0[1][k];
        rows[7][k] = -k1 * al[0][k];
        rows[7][4 + k] = ei * b.powi(3) * b0[3][k] + k1 * b0[0][k];
    }
    // Row scaling only (the sign changes are what matters).
    for row in &mut rows {
        let s = row.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        row.iter_mut().for_each(|v| *v /= s);
    }
    determinant(rows)
}

/// The first `count` roots of `g` above `from`, by a scan of step `step` and bisection.
fn roots(g: impl Fn(f64) -> f64, from: f64, step: f64, count: usize) -> Vec<f64> {
    let mut out = Vec::new();
    let (mut x, mut gx) = (from, g(from));
    while out.len() < count {
        let (y, gy) = (x + step, g(x + step));
        if gx * gy < 0.0 {
            let (mut lo, mut hi, mut glo) = (x, y, gx);
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                let gm = g(mid);
                if gm * glo <= 0.0 {
                    hi = mid;
                } else {
                    lo = mid;
                    glo = gm;
                }
            }
            out.push(0.5 * (lo + hi));
        }
        (x, gx) = (y, gy);
    }
    out
}

#[test]
fn free_free_chain_of_2_x_2000_elements_matches_the_continuum() {
    let (la, lb, k1, k2) = (0.2, 0.3, 1e7, 1e4);
    let chain = Chain::free(
        vec![steel_bar(la, 2000), steel_bar(lb, 2000)],
        vec![Joint::identified(k1, k2)],
    );
    let structure = chain.build();
    assert!(structure.dof_count() > DENSE_MAX_DOFS);
    let modes = ModalSolution::lowest_of(&structure.assemble(), 7).unwrap();
    assert_eq!(modes.len(), 7);
    let analytic: Vec<f64> = roots(
        |b| chain_determinant(b, la, lb, k1, k2),
        beta_of(1.0),
        beta_of(1.0) * 0.01,
        5,
    )
    .into_iter()
    .map(hz_of)
    .collect();
    // The reference for the first: 150.05 Hz.
    assert!((analytic[0] - 150.05).abs() < 0.01, "{analytic:?}");
    for (i, f) in analytic.iter().enumerate() {
        let fe = modes.frequency_hz(2 + i);
        assert!(
            (fe - f).abs() < 1e-8 * f,
            "elastic mode {}: {fe} Hz, analytic {f} Hz",
            i + 1
        );
    }
    // Rigid-body pair: zero to round-off of the stiffness scale.
    assert!(modes.frequency_hz(1) < 1e-2);
}

#[test]
fn clamped_free_beam_of_4000_elements_matches_the_continuum() {
    let length = 0.5;
    let mut chain = Chain::free(vec![steel_bar(length, 4000)], vec![]);
    chain.supports.push(Support {
        x: 0.0,
        kind: SupportKind::Clamped,
        identify: [false, false],
    });
    let structure = chain.build();
    assert_eq!(structure.rigid, 0);
    let modes = ModalSolution::lowest_of(&structure.assemble(), 5).unwrap();
    let bl = roots(|x| x.cos() * x.cosh() + 1.0, 0.5, 0.01, 5);
    assert!((bl[0] - 1.875_104_07).abs() < 1e-8, "{bl:?}");
    for (i, b) in bl.iter().enumerate() {
        let f = hz_of(b / length);
        let fe = modes.frequency_hz(i);
        assert!(
            (fe - f).abs() < 5e-9 * f,
            "mode {}: {fe} Hz, analytic {f} Hz",
            i + 1
        );
    }
}

/// The paper's per-mode systems on a fine mesh: the chain of 2 x 2000 elements, every
/// translation measured (4002 rows), modes 1-6 of the joint modified by (+20%, +20%), noise
/// free (jointid's own eigenpairs: this checks the conditioning of eq. (10)-(13), not the
/// model). The relative parametrisation keeps cond(W S) of the order of the coarse model's
/// (1.7-31 with the CLI at n = 10-100 and every weighting), and the 20% change comes back
/// within 2.5e-3 at n = 10 and 3.2e-4 at n = 40 (the truncated basis).
#[test]
fn per_mode_systems_of_a_fine_mesh_stay_well_conditioned() {
    use crate::common::translations;
    use jointid::identify::{Identifier, Settings, Weighting};
    use jointid::simulate::exact_modes;
    let nominal = Chain::free(
        vec![steel_bar(0.2, 2000), steel_bar(0.3, 2000)],
        vec![Joint::identified(1e7, 1e4)],
    )
    .build();
    let delta = [2e6, 2e3];
    let truth = nominal.with_delta(&delta);
    let dofs = translations(&nominal);
    let measured = exact_modes(
        &ModalSolution::lowest_of(&truth.assemble(), 8).unwrap(),
        2,
        &[1, 2, 3, 4, 5, 6],
        &dofs,
    );
    for (n, bound) in [(10, 5e-3), (40, 1e-3)] {
        let modal = ModalSolution::lowest_of(&nominal.assemble(), n + 2).unwrap();
        let settings = Settings {
            n,
            m: 6,
            weighting: Weighting::Inverse,
        };
        let id = Identifier::for_structure(&nominal, &modal, settings).unwrap();
        for mode in measured.modes() {
            let o = id.identify(mode).unwrap();
            assert!(
                o.condition < 100.0,
                "n {n} mode {}: cond {}",
                mode.mode,
                o.condition
            );
            let z = o.relative.unwrap();
            for (i, p) in id.parameters().iter().enumerate() {
                let relative_error = (p.value * z[i] - delta[i]).abs() / delta[i];
                assert!(
                    relative_error < bound,
                    "n {n} mode {} {}: {relative_error}",
                    mode.mode,
                    p.name
                );
            }
        }
    }
}

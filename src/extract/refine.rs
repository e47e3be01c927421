//! Refinement of the chosen poles by nonlinear least squares of the modal model of
//! [`super::lsfd`] to the FRFs, the residues and residual terms eliminated (variable
//! projection: Golub and Pereyra, "The differentiation of pseudo-inverses and nonlinear least
//! squares problems whose variables separate", SIAM J. Numer. Anal. 10, 1973; the Jacobian of
//! Kaufman, "A variable projection method for solving separable nonlinear least squares
//! problems", BIT 15, 1975).
//!
//! The LSCF poles come from a linearised equation error that weighs each line by |D(z)|^2 and
//! carries the bias of a linearised estimator on noisy data; here the output error itself is
//! minimised:
//!   phi(theta) = sum_o || W (H_o - A(theta) x_o) ||^2 at the best x_o, = || P_perp(theta) B ||^2,
//! theta = (Re lambda_r, Im lambda_r) for every chosen pole, A the design matrix of the LSFD
//! (columns of the poles and the residual terms), P_perp the projector off its range. With
//! T_j = dA/dtheta_j X the Gauss-Newton Jacobian is -P_perp T (the full Gauss-Newton step on
//! (theta, x) with x eliminated), and grad phi = -2 T^T P_perp B exactly. The Jacobian rows of
//! every response are compressed into one triangle by QR (the normal equations are never
//! formed), which the Levenberg-Marquardt solver of [`crate::optim::lm`] takes as it is: no
//! bounds, a trial accepted when its cost is strictly lower, stopped when an accepted step
//! gains less than [`COST_TOLERANCE`] of the cost, when no step lowers it, or after
//! [`MAX_ITERATIONS`].

use std::convert::Infallible;

use faer::{Mat, c64};

use super::lsfd::{Basis, data, design, pole_jacobian};
use crate::optim::{self, LevenbergMarquardt, Termination, lstsq};

/// Most Levenberg-Marquardt iterations.
pub const MAX_ITERATIONS: usize = 50;
/// Stop when an accepted step lowers the cost by less than this fraction.
pub const COST_TOLERANCE: f64 = 1e-12;

/// The outcome of the refinement.
#[derive(Debug, Clone)]
pub struct Refined {
    /// The refined poles (same order as given).
    pub poles: Vec<c64>,
    /// The cost before.
    pub cost_start: f64,
    /// The cost after.
    pub cost_end: f64,
    /// Accepted iterations.
    pub iterations: usize,
    /// Why the iteration stopped.
    pub termination: Termination,
}

/// The cost at theta, the compressed Jacobian [R g; 0 rho] (2K + 1 square) and the gradient.
pub(crate) struct Linearised {
    pub cost: f64,
    pub triangle: Mat<f64>,
    /// grad phi (checked against finite differences in the tests).
    #[cfg_attr(not(test), allow(dead_code))]
    pub gradient: Vec<f64>,
}

pub(crate) fn linearise(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    basis: Basis,
    responses: &[Vec<c64>],
) -> Linearised {
    let nf = omega.len();
    let n = 2 * poles.len();
    let a = design(omega, weights, poles, basis);
    let m = a.ncols();
    let b = data(weights, responses);
    let ls = lstsq::solve(a.as_ref(), b.as_ref());
    let mut acc = Mat::<f64>::zeros(0, n + 1);
    let mut cost = 0.0;
    let mut gradient = vec![0.0; n];
    for o in 0..responses.len() {
        // [T_o | b_o], T_o column 2r + c = dA/dtheta_(2r+c) x_o (c = 0: Re lambda, 1: Im lambda).
        let t = pole_jacobian(omega, weights, poles, basis.power, ls.x.col(o));
        let mut tb = Mat::<f64>::from_fn(
            2 * nf,
            n + 1,
            |i, j| {
                if j < n { t[(i, j)] } else { b[(i, o)] }
            },
        );
        lstsq::apply_qt(&ls.qr, tb.as_mut());
        let lower = tb.as_ref().subrows(m, 2 * nf - m);
        for i in 0..lower.nrows() {
            let e = lower[(i, n)];
            cost += e * e;
            for (j, g) in gradient.iter_mut().enumerate() {
                *g -= 2.0 * lower[(i, j)] * e;
            }
        }
        // Compress: triangle of [acc; lower].
        let mut stacked = Mat::<f64>::zeros(acc.nrows() + lower.nrows(), n + 1);
        for i in 0..acc.nrows() {
            for j in 0..=n {
                stacked[(i, j)] = acc[(i, j)];
            }
        }
        for i in 0..lower.nrows() {
            for j in 0..=n {
                stacked[(acc.nrows() + i, j)] = lower[(i, j)];
            }
        }
        acc = lstsq::triangle(stacked.as_ref());
    }
    Linearised {
        cost,
        triangle: acc,
        gradient,
    }
}

/// The refinement as the solver sees it: x = (Re lambda_1, Im lambda_1, Re lambda_2, ...).
struct Poles<'a> {
    omega: &'a [f64],
    weights: &'a [f64],
    basis: Basis,
    responses: &'a [Vec<c64>],
}

fn poles_of(x: &[f64]) -> Vec<c64> {
    x.chunks(2).map(|p| c64::new(p[0], p[1])).collect()
}

impl optim::Problem for Poles<'_> {
    type State = Linearised;
    type Error = Infallible;

    fn evaluate(&self, x: &[f64]) -> Result<Linearised, Infallible> {
        Ok(linearise(
            self.omega,
            self.weights,
            &poles_of(x),
            self.basis,
            self.responses,
        ))
    }

    fn cost(&self, state: &Linearised) -> f64 {
        state.cost
    }

    fn linearise(&self, _x: &[f64], state: &Linearised) -> optim::Linearisation {
        optim::Linearisation::Triangle(state.triangle.clone())
    }
}

/// Refines `poles` (see the module docs). The caller checks that the result is physical.
pub fn refine(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    basis: Basis,
    responses: &[Vec<c64>],
) -> Refined {
    let problem = Poles {
        omega,
        weights,
        basis,
        responses,
    };
    let solver = LevenbergMarquardt::new(MAX_ITERATIONS)
        .and_then(|s| s.with_gain(COST_TOLERANCE))
        .expect("the refinement's settings are within the solver's ranges");
    let start = poles.iter().flat_map(|p| [p.re, p.im]).collect();
    let Ok(solution) = solver.minimise(&problem, start);
    Refined {
        poles: poles_of(&solution.x),
        cost_start: solution.start_cost,
        cost_end: solution.cost,
        iterations: solution.accepted,
        termination: solution.termination,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The FRFs (quantity power `p`) of modes `poles` with residues `residues[mode][response]`,
    /// summed directly: the test data of the refinement and of the standard errors.
    pub(crate) fn model<const R: usize>(
        omega: &[f64],
        poles: &[c64],
        residues: &[[c64; R]],
        p: i32,
    ) -> Vec<Vec<c64>> {
        (0..R)
            .map(|o| {
                omega
                    .iter()
                    .map(|&w| {
                        let iw = c64::new(0.0, w);
                        let q = iw.powi(p);
                        poles
                            .iter()
                            .zip(residues)
                            .map(|(l, r)| q * (r[o] / (iw - l) + r[o].conj() / (iw - l.conj())))
                            .sum::<c64>()
                    })
                    .collect()
            })
            .collect()
    }

    /// grad phi = -2 T^T P_perp B against central differences of phi in every pole parameter.
    #[test]
    fn gradient_matches_central_differences() {
        let omega: Vec<f64> = (1..300).map(|k| k as f64 * 10.0).collect();
        let weights = vec![1.0; omega.len()];
        let truth = [c64::new(-8.0, 900.0), c64::new(-20.0, 2000.0)];
        let residues = [
            [c64::new(0.1, -2.0), c64::new(-0.3, 1.0)],
            [c64::new(0.0, 1.5), c64::new(0.2, 0.7)],
        ];
        let data = model(&omega, &truth, &residues, 1);
        let at = [c64::new(-9.0, 905.0), c64::new(-18.0, 1990.0)];
        let basis = Basis { power: 1, terms: 2 };
        let lin = linearise(&omega, &weights, &at, basis, &data);
        for j in 0..4 {
            let h = 1e-5 * at[j / 2].norm();
            let dir = if j % 2 == 0 {
                c64::new(h, 0.0)
            } else {
                c64::new(0.0, h)
            };
            let (mut plus, mut minus) = (at, at);
            plus[j / 2] += dir;
            minus[j / 2] -= dir;
            let fp = linearise(&omega, &weights, &plus, basis, &data).cost;
            let fm = linearise(&omega, &weights, &minus, basis, &data).cost;
            let fd = (fp - fm) / (2.0 * h);
            assert!(
                (fd - lin.gradient[j]).abs() < 1e-5 * lin.gradient[j].abs(),
                "{j}: fd {fd} analytic {}",
                lin.gradient[j]
            );
        }
    }

    /// Noise-free data of two modes: from poles off by 0.5% in frequency and 10% in damping
    /// the refinement returns the true poles.
    #[test]
    fn converges_to_the_true_poles() {
        let omega: Vec<f64> = (1..400).map(|k| k as f64 * 7.0).collect();
        let weights = vec![1.0; omega.len()];
        let truth = [c64::new(-6.0, 800.0), c64::new(-25.0, 2100.0)];
        let residues = [
            [c64::new(0.0, -2.0), c64::new(0.0, 1.0)],
            [c64::new(0.1, 1.5), c64::new(0.0, 0.7)],
        ];
        for p in 0..3 {
            let data = model(&omega, &truth, &residues, p);
            let start = [c64::new(-6.6, 804.0), c64::new(-22.5, 2090.0)];
            let refined = refine(
                &omega,
                &weights,
                &start,
                Basis { power: p, terms: 2 },
                &data,
            );
            for (r, t) in refined.poles.iter().zip(truth) {
                assert!((r - t).norm() < 1e-9 * t.norm(), "p {p}: {r} vs {t}");
            }
        }
    }
}

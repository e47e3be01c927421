//! First-order (linear) propagation of measurement errors through g, S and b to the
//! per-mode corrections Z_r of eq. (13).
//!
//! Z(y~, lambda) is the weighted least-squares solution of A Z = c with A = W S_r(g),
//! c = W b_r(g, lambda), g = Y~^+ y~. At the noise-free point (y~_0, lambda_0), with
//! r_0 = c_0 - A_0 Z_0, a perturbation gives
//!
//! ```text
//!   dZ = (A_0^T A_0)^-1 [ dA^T r_0 + A_0^T (dc - dA Z_0) ]
//! ```
//!
//! (the derivative of the least-squares solution, residual term included). A and c are linear
//! in g and affine in lambda, so dA, dc for the j-th shape element are A, c assembled at
//! g = Y~^+ e_j, and for lambda the difference of the assemblies at lambda = 1 and 0.
//! The shape errors are independent with variance v_e = var(e) y~_0j^2 each; the frequency
//! error gives d lambda = 2 lambda_0 eps. Then
//! Var(Delta p_i) = p_i^2 [ sum_j (dZ_i/dy~_j)^2 v_e y~_0j^2 + (dZ_i/dlambda)^2 4 lambda_0^2 sigma_f^2 ].

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};

use super::{ModeSystem, Projector};

/// dZ/dy~ (q x n_id) and dZ/dlambda (q) at a point.
pub struct Jacobian {
    /// dZ_i / dy~_j.
    pub shape: Mat<f64>,
    /// dZ_i / dlambda.
    pub lambda: Vec<f64>,
}

/// The Jacobian of Z at the shape `shape` (over the projector's DOFs) and eigenvalue `lambda`;
/// `None` when the system is rank deficient there.
pub fn jacobian(
    projector: &Projector,
    system: &ModeSystem,
    shape: &[f64],
    lambda: f64,
) -> Option<Jacobian> {
    let (m, q, n) = (system.m(), system.q(), projector.column(0).len());
    let assemble = |g: &[f64], lambda: f64| {
        let (mut a, mut c) = (vec![0.0; m * q], vec![0.0; m]);
        system.assemble(g, lambda, &mut a, &mut c);
        (
            Mat::from_fn(m, q, |r, i| a[i * m + r]),
            Mat::from_fn(m, 1, |r, _| c[r]),
        )
    };
    let mut g0 = vec![0.0; n];
    projector.project(shape, &mut g0);
    let (a0, c0) = assemble(&g0, lambda);
    let ata = a0.transpose() * &a0;
    let llt = ata.llt(Side::Lower).ok()?;
    let z0 = llt.solve(a0.transpose() * &c0);
    let r0 = &c0 - &a0 * &z0;
    let derivative = |da: &Mat<f64>, dc: &Mat<f64>| {
        llt.solve(da.transpose() * &r0 + a0.transpose() * (dc - da * &z0))
    };
    let mut jac = Mat::zeros(q, shape.len());
    for j in 0..shape.len() {
        let (da, dc) = assemble(projector.column(j), lambda);
        let dz = derivative(&da, &dc);
        for i in 0..q {
            jac[(i, j)] = dz[(i, 0)];
        }
    }
    let (a1, c1) = assemble(&g0, 1.0);
    let (a_zero, c_zero) = assemble(&g0, 0.0);
    let dz = derivative(&(&a1 - &a_zero), &(&c1 - &c_zero));
    Some(Jacobian {
        shape: jac,
        lambda: (0..q).map(|i| dz[(i, 0)]).collect(),
    })
}

/// Standard deviations of Delta p_i = p_i Z_i for independent relative shape errors of
/// variance `shape_variance` and a relative frequency error of variance `frequency_variance`.
pub fn propagated_std(
    jac: &Jacobian,
    shape: &[f64],
    lambda: f64,
    values: &[f64],
    shape_variance: f64,
    frequency_variance: f64,
) -> Vec<f64> {
    combine(jac, lambda, values, frequency_variance, |i| {
        let s: f64 = shape
            .iter()
            .enumerate()
            .map(|(j, y)| (jac.shape[(i, j)] * y).powi(2))
            .sum();
        s * shape_variance
    })
}

/// Standard deviations of Delta p_i = p_i Z_i for independent shape errors of variances
/// `shape_variances` (one per component, in the shape's units) and a relative frequency error
/// of variance `frequency_variance`: the data's own standard errors.
pub fn std_of(
    jac: &Jacobian,
    shape_variances: &[f64],
    lambda: f64,
    values: &[f64],
    frequency_variance: f64,
) -> Vec<f64> {
    combine(jac, lambda, values, frequency_variance, |i| {
        shape_variances
            .iter()
            .enumerate()
            .map(|(j, v)| jac.shape[(i, j)].powi(2) * v)
            .sum()
    })
}

/// p_i sqrt(shape part of parameter i + its frequency part).
fn combine(
    jac: &Jacobian,
    lambda: f64,
    values: &[f64],
    frequency_variance: f64,
    shape_part: impl Fn(usize) -> f64,
) -> Vec<f64> {
    values
        .iter()
        .enumerate()
        .map(|(i, p)| {
            let f = (jac.lambda[i] * 2.0 * lambda).powi(2);
            p * (shape_part(i) + f * frequency_variance).sqrt()
        })
        .collect()
}

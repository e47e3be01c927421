//! Standard errors of the extracted modal parameters, from the noise of the FRFs propagated
//! through the estimator.
//!
//! **The noise of the FRFs.** Each line k of response o carries a complex error of variance
//! v_ok = E|H^_ok - H_ok|^2 (circular: half in the real part, half in the imaginary):
//! - from the coherence gamma^2 of an H1 estimate over n_d averages:
//!   v_ok = |H_ok|^2 (1 - gamma_ok^2) / ((n_d - 1) gamma_ok^2).
//!   With output noise N and input spectrum estimate G_xx = sum |X_i|^2 / n_d, the H1 estimate
//!   errs by sum N_i X_i* / sum |X_i|^2, of variance G_nn / (n_d G_xx) given the inputs; the
//!   coherence gives (1 - gamma^2) G_yy = G_yy - |G_xy|^2 / G_xx, the noise spectrum left
//!   after fitting H, whose expectation is G_nn (n_d - 1) / n_d (one complex unknown fitted);
//!   and gamma^2 G_yy = |H|^2 G_xx. Hence the formula, Bendat & Piersol's ("Random Data", 4th
//!   ed., section 9.2.4: normalised random errors of gain and phase both
//!   sqrt(1 - gamma^2) / (|gamma| sqrt(2 n_d))) with n_d - 1 for the fitted unknown;
//! - else from the residuals of the final LSFD fit, one variance per response (the noise taken
//!   white over the band): v_o = sum_k w_k^2 |r_ok|^2 / (sum_k w_k^2 (1 - p_o / 2 nf)), p_o the
//!   unknowns of that response (its residues and residual terms, and its share of the poles).
//!
//! **The propagation.** The estimate (theta, x_1 .. x_N) minimises
//! sum_o || y_o - A(theta) x_o ||^2, y_o = W H_o real-stacked, theta the poles, x_o the
//! residues and residual terms of response o ([`super::lsfd`], [`super::refine`]). To first
//! order in a data error e_o (covariance Sigma_o = diag(w_k^2 v_ok / 2)):
//!
//! ```text
//!   d theta = S^-1 sum_o U_o^T e_o,        U_o = P_perp T_o,   S = sum_o U_o^T U_o,
//!   d x_o   = N^-1 A^T (e_o - T_o d theta) = N^-1 A^T e_o - a_o d theta,   a_o = N^-1 A^T T_o,
//! ```
//!
//! T_o = W dA/dtheta x_o ([`super::lsfd::pole_jacobian`]), N = A^T A, P_perp = I - A N^-1 A^T
//! (the variable-projection form of the Gauss-Newton step of the joint fit). Hence the
//! covariances, with b_o = N^-1 A^T Sigma_o U_o S^-1 and c_o = N^-1 A^T Sigma_o A N^-1:
//!
//! ```text
//!   Cov(theta)      = S^-1 (sum_o U_o^T Sigma_o U_o) S^-1 = C,
//!   Cov(x_o, x_o')  = [o = o'] c_o - b_o a_o'^T - a_o b_o'^T + a_o C a_o'^T,
//! ```
//!
//! the sandwich form, right whatever the line weights W (the coherence weighting of
//! [`super::frf::band`] is not the inverse of v). N^-1 A^T is applied through the QR of the
//! column-scaled A ([`crate::optim::lstsq::solve`]), never formed from N.
//!
//! **The modal parameters.** f = |lambda| / 2 pi and zeta = -Re lambda / |lambda| by their
//! analytic gradients in (Re lambda, Im lambda); the real shape ([`super::shapes`]: principal
//! axis, largest component +1) by central differences in the residues of the mode, its peak
//! component held (that component is 1 by definition: its standard error is 0). The errors are
//! those of the output-error estimate; when the refinement was refused (the chart's poles
//! kept) they are those the refined estimate would have.

use std::f64::consts::PI;

use faer::{Mat, MatRef, c64};

use super::lsfd::{Basis, pole_jacobian};
use super::shapes;
use crate::optim::lstsq;

/// Where the noise of the FRFs came from.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum NoiseSource {
    /// The coherence of an H1 estimate over this many averages.
    Coherence {
        /// Number of averages n_d.
        averages: usize,
    },
    /// The residuals of the LSFD fit, per response.
    Residuals,
    /// The residuals, though the coherence was asked for: a response's coherence is 1 on every
    /// line of the band (an export rounded to 1, or noise-free data), which says its noise is
    /// below what the file resolves, not zero.
    ResidualsCoherenceOne {
        /// The first such response (from 0).
        response: usize,
    },
}

/// Standard errors of one mode's parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeStd {
    /// Of the undamped natural frequency (Hz).
    pub frequency_hz: f64,
    /// Of the damping ratio.
    pub damping_ratio: f64,
    /// Of each component of the real shape (largest component +1; its own error 0).
    pub shape: Vec<f64>,
}

/// Smallest coherence taken at its value: below it a line counts as this coherent (a zero
/// coherence would give it an infinite variance, a line the fit still sees through its weight).
pub const COHERENCE_FLOOR: f64 = 1e-3;

/// The variance of every line, `[response][line]`, from the coherence over `averages` >= 2
/// (see the module docs).
pub fn from_coherence(
    responses: &[Vec<c64>],
    coherence: &[Vec<f64>],
    averages: usize,
) -> Vec<Vec<f64>> {
    responses
        .iter()
        .zip(coherence)
        .map(|(h, g)| {
            h.iter()
                .zip(g)
                .map(|(h, &g)| {
                    let g = g.max(COHERENCE_FLOOR);
                    h.norm_sqr() * (1.0 - g) / ((averages - 1) as f64 * g)
                })
                .collect()
        })
        .collect()
}

/// The variance of every line, `[response][line]`, from the residuals of the fit `model` of
/// `responses` with `unknowns` real unknowns per response (see the module docs).
pub fn from_residuals(
    weights: &[f64],
    responses: &[Vec<c64>],
    model: &[Vec<c64>],
    unknowns: f64,
) -> Vec<Vec<f64>> {
    let rows = 2.0 * weights.len() as f64;
    let kept = (1.0 - unknowns / rows).max(1.0 / rows);
    let w2: f64 = weights.iter().map(|w| w * w).sum();
    responses
        .iter()
        .zip(model)
        .map(|(h, m)| {
            let sum: f64 = h
                .iter()
                .zip(m)
                .zip(weights)
                .map(|((h, m), w)| w * w * (h - m).norm_sqr())
                .sum();
            vec![sum / (w2 * kept); h.len()]
        })
        .collect()
}

/// The pieces of the first-order solution of one response (see the module docs).
struct Response {
    /// a_o = N^-1 A^T T_o (m x 2K).
    a: Mat<f64>,
    /// N^-1 A^T Sigma_o U_o, b_o before its S^-1 (m x 2K).
    e: Mat<f64>,
    /// c_o = N^-1 A^T Sigma_o A N^-1 (m x m).
    c: Mat<f64>,
}

/// Row i of diag(s) M.
fn scale_rows(s: &[f64], m: MatRef<'_, f64>) -> Mat<f64> {
    Mat::from_fn(m.nrows(), m.ncols(), |i, j| s[i] * m[(i, j)])
}

/// Q^T of the QR applied to `m`, its first `top` rows.
fn qt_top(ls: &lstsq::LeastSquares, m: MatRef<'_, f64>, top: usize) -> (Mat<f64>, Mat<f64>) {
    let mut q = m.to_owned();
    lstsq::apply_qt(&ls.qr, q.as_mut());
    let head = q.as_ref().subrows(0, top).to_owned();
    (head, q)
}

/// The standard errors of every mode of `poles` (see the module docs): `ls` the LSFD solution
/// of the data on `omega` with line weights `weights` ([`super::lsfd::least_squares`]), line
/// variances `variances[response][line]`.
pub fn standard_errors(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    basis: Basis,
    ls: &lstsq::LeastSquares,
    variances: &[Vec<f64>],
) -> Vec<ModeStd> {
    let nf = omega.len();
    let k2 = 2 * poles.len();
    let m = ls.x.nrows();
    // Z = D R^+ : N^-1 A^T = Z Q_m^T for the QR of A D.
    let r = ls.qr.thin_R();
    let r = Mat::from_fn(m, m, |i, j| if i <= j { r[(i, j)] } else { 0.0 });
    let (r_inv, _) = lstsq::pseudo_inverse(r.as_ref());
    let z = Mat::from_fn(m, m, |i, j| ls.scale[i] * r_inv[(i, j)]);
    let mut q_m = Mat::<f64>::zeros(2 * nf, m);
    for j in 0..m {
        q_m[(j, j)] = 1.0;
    }
    lstsq::apply_q(&ls.qr, q_m.as_mut());

    let mut s = Mat::<f64>::zeros(k2, k2);
    let mut middle = Mat::<f64>::zeros(k2, k2);
    let mut parts = Vec::with_capacity(variances.len());
    for (o, variance) in variances.iter().enumerate() {
        let sigma: Vec<f64> = (0..2 * nf)
            .map(|i| {
                let k = i % nf;
                weights[k] * weights[k] * variance[k] / 2.0
            })
            .collect();
        let t = pole_jacobian(omega, weights, poles, basis.power, ls.x.col(o));
        let (head, mut u) = qt_top(ls, t.as_ref(), m);
        for i in 0..m {
            for j in 0..k2 {
                u[(i, j)] = 0.0;
            }
        }
        s += u.transpose() * &u;
        lstsq::apply_q(&ls.qr, u.as_mut());
        let su = scale_rows(&sigma, u.as_ref());
        middle += u.transpose() * &su;
        let (su_head, _) = qt_top(ls, su.as_ref(), m);
        let sq = scale_rows(&sigma, q_m.as_ref());
        parts.push(Response {
            a: &z * &head,
            e: &z * su_head,
            c: &z * (q_m.transpose() * sq) * z.transpose(),
        });
    }
    let (s_inv, _) = lstsq::pseudo_inverse(s.as_ref());
    let c_theta = &s_inv * &middle * &s_inv;
    let b: Vec<Mat<f64>> = parts.iter().map(|p| &p.e * &s_inv).collect();
    let a_c: Vec<Mat<f64>> = parts.iter().map(|p| &p.a * &c_theta).collect();
    poles
        .iter()
        .enumerate()
        .map(|(mode, &lambda)| {
            let block = Mat::from_fn(2, 2, |i, j| c_theta[(2 * mode + i, 2 * mode + j)]);
            let residues: Vec<c64> = (0..ls.x.ncols())
                .map(|o| c64::new(ls.x[(2 * mode, o)], ls.x[(2 * mode + 1, o)]))
                .collect();
            let cov = residue_covariance(mode, &parts, &b, &a_c);
            ModeStd {
                frequency_hz: quadratic(&frequency_gradient(lambda), &block).sqrt(),
                damping_ratio: quadratic(&damping_gradient(lambda), &block).sqrt(),
                shape: shape_std(&residues, &cov),
            }
        })
        .collect()
}

/// Cov of (Re R_mode,o, Im R_mode,o) over the responses o (2N x 2N, response-major); `b` the
/// b_o and `a_c` the a_o C of every response (see the module docs).
fn residue_covariance(
    mode: usize,
    parts: &[Response],
    b: &[Mat<f64>],
    a_c: &[Mat<f64>],
) -> Mat<f64> {
    let n = parts.len();
    let k2 = b.first().map_or(0, |m| m.ncols());
    Mat::from_fn(2 * n, 2 * n, |i, j| {
        let (o, alpha) = (i / 2, i % 2);
        let (q, beta) = (j / 2, j % 2);
        let (ri, rj) = (2 * mode + alpha, 2 * mode + beta);
        let mut v = if o == q { parts[o].c[(ri, rj)] } else { 0.0 };
        for t in 0..k2 {
            v += -b[o][(ri, t)] * parts[q].a[(rj, t)] - parts[o].a[(ri, t)] * b[q][(rj, t)]
                + a_c[o][(ri, t)] * parts[q].a[(rj, t)];
        }
        v
    })
}

/// g^T C g for a 2-vector g and a 2 x 2 C (0 when round-off makes it negative).
fn quadratic(g: &[f64; 2], c: &Mat<f64>) -> f64 {
    let v = g[0] * g[0] * c[(0, 0)] + 2.0 * g[0] * g[1] * c[(0, 1)] + g[1] * g[1] * c[(1, 1)];
    v.max(0.0)
}

/// d f / d(Re lambda, Im lambda), f = |lambda| / 2 pi.
pub fn frequency_gradient(lambda: c64) -> [f64; 2] {
    let r = lambda.norm();
    [lambda.re / (2.0 * PI * r), lambda.im / (2.0 * PI * r)]
}

/// d zeta / d(Re lambda, Im lambda), zeta = -Re lambda / |lambda|.
pub fn damping_gradient(lambda: c64) -> [f64; 2] {
    let r3 = lambda.norm().powi(3);
    [-lambda.im * lambda.im / r3, lambda.re * lambda.im / r3]
}

/// The standard error of every component of the real shape of `residues` whose (Re, Im)
/// covariance is `cov` (see the module docs).
fn shape_std(residues: &[c64], cov: &Mat<f64>) -> Vec<f64> {
    let n = residues.len();
    let peak = (0..n)
        .max_by(|&a, &b| residues[a].norm().total_cmp(&residues[b].norm()))
        .unwrap_or(0);
    let scale = residues[peak].norm();
    if scale == 0.0 {
        return vec![0.0; n];
    }
    // gradient[p] = d shape / d(Re or Im of residue p / 2).
    let h = 1e-6 * scale;
    let gradient: Vec<Vec<f64>> = (0..2 * n)
        .map(|p| {
            let dir = if p % 2 == 0 {
                c64::new(h, 0.0)
            } else {
                c64::new(0.0, h)
            };
            let (mut plus, mut minus) = (residues.to_vec(), residues.to_vec());
            plus[p / 2] += dir;
            minus[p / 2] -= dir;
            let sp = shapes::real_shape_scaled_at(&plus, peak);
            let sm = shapes::real_shape_scaled_at(&minus, peak);
            sp.iter()
                .zip(&sm)
                .map(|(a, b)| (a - b) / (2.0 * h))
                .collect()
        })
        .collect();
    (0..n)
        .map(|j| {
            let mut v = 0.0;
            for p in 0..2 * n {
                for q in 0..2 * n {
                    v += gradient[p][j] * cov[(p, q)] * gradient[q][j];
                }
            }
            if j == peak { 0.0 } else { v.max(0.0).sqrt() }
        })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::super::refine::tests::model;
    use super::super::{lsfd, refine};
    use super::*;

    /// The estimator itself: poles refined from `start`, residues by LSFD; per mode the
    /// frequency, the damping ratio and the real shape scaled at the peak of the truth.
    fn estimate(
        omega: &[f64],
        start: &[c64],
        basis: Basis,
        data: &[Vec<c64>],
        peaks: &[usize],
    ) -> Vec<(f64, f64, Vec<f64>)> {
        let weights = vec![1.0; omega.len()];
        let poles = refine::refine(omega, &weights, start, basis, data).poles;
        let fit = lsfd::fit(omega, &weights, &poles, basis, data);
        poles
            .iter()
            .zip(&fit.residues)
            .zip(peaks)
            .map(|((l, r), &peak)| {
                (
                    l.norm() / (2.0 * PI),
                    -l.re / l.norm(),
                    shapes::real_shape_scaled_at(r, peak),
                )
            })
            .collect()
    }

    /// The first-order propagation against finite differences of the whole estimator: with
    /// the noise on one line of one response only (variance 2s, so s on its real and its
    /// imaginary row), Var(q) = s ((dq/d Re H)^2 + (dq/d Im H)^2) for every modal parameter q,
    /// the derivatives taken by refitting data perturbed by +-eps and +-i eps.
    #[test]
    fn propagation_matches_finite_differences_of_the_estimator() {
        let omega: Vec<f64> = (1..300).map(|k| k as f64 * 8.0).collect();
        let truth = [c64::new(-9.0, 900.0), c64::new(-22.0, 1700.0)];
        let residues = [
            [c64::new(0.1, -2.0), c64::new(-0.3, 1.0), c64::new(0.0, 0.6)],
            [c64::new(0.0, 1.5), c64::new(0.2, 0.7), c64::new(0.1, -1.2)],
        ];
        let peaks = [0, 0];
        for p in [0, 2] {
            let basis = Basis { power: p, terms: 1 };
            let data = model(&omega, &truth, &residues, p);
            // Line 112 (896 rad/s) next to mode 1, response 1; line 214 (1712 rad/s), response 2.
            for (o, k) in [(1usize, 112usize), (2, 214)] {
                let s = 1.0;
                let mut variances = vec![vec![0.0; omega.len()]; 3];
                variances[o][k] = 2.0 * s;
                let weights = vec![1.0; omega.len()];
                let ls = lsfd::least_squares(&omega, &weights, &truth, basis, &data);
                let std = standard_errors(&omega, &weights, &truth, basis, &ls, &variances);
                let eps = 1e-5 * data[o][k].norm();
                let shifted = |d: c64| {
                    let mut plus = data.clone();
                    let mut minus = data.clone();
                    plus[o][k] += d;
                    minus[o][k] -= d;
                    (
                        estimate(&omega, &truth, basis, &plus, &peaks),
                        estimate(&omega, &truth, basis, &minus, &peaks),
                    )
                };
                let (re_p, re_m) = shifted(c64::new(eps, 0.0));
                let (im_p, im_m) = shifted(c64::new(0.0, eps));
                let fd = |a: f64, b: f64, c: f64, d: f64| {
                    (((a - b) / (2.0 * eps)).powi(2) + ((c - d) / (2.0 * eps)).powi(2)).sqrt()
                };
                for mode in 0..2 {
                    let close = |got: f64, want: f64, what: &str| {
                        assert!(
                            (got - want).abs() <= 1e-4 * want.abs() + 1e-14,
                            "p {p} line {k} mode {mode} {what}: propagated {got:e}, differences {want:e}"
                        );
                    };
                    let f = fd(re_p[mode].0, re_m[mode].0, im_p[mode].0, im_m[mode].0);
                    close(std[mode].frequency_hz, s.sqrt() * f, "frequency");
                    let z = fd(re_p[mode].1, re_m[mode].1, im_p[mode].1, im_m[mode].1);
                    close(std[mode].damping_ratio, s.sqrt() * z, "damping");
                    for j in 1..3 {
                        let v = fd(
                            re_p[mode].2[j],
                            re_m[mode].2[j],
                            im_p[mode].2[j],
                            im_m[mode].2[j],
                        );
                        close(std[mode].shape[j], s.sqrt() * v, "shape");
                    }
                    assert_eq!(std[mode].shape[0], 0.0);
                }
            }
        }
    }

    #[test]
    fn gradients_of_frequency_and_damping_match_central_differences() {
        let lambda = c64::new(-7.0, 640.0);
        let h = 1e-2;
        let f = |l: c64| l.norm() / (2.0 * PI);
        let z = |l: c64| -l.re / l.norm();
        for (c, dir) in [(0, c64::new(h, 0.0)), (1, c64::new(0.0, h))] {
            let df = (f(lambda + dir) - f(lambda - dir)) / (2.0 * h);
            let dz = (z(lambda + dir) - z(lambda - dir)) / (2.0 * h);
            assert!(
                (frequency_gradient(lambda)[c] - df).abs() < 1e-7 * df.abs(),
                "{c}: {df}"
            );
            assert!(
                (damping_gradient(lambda)[c] - dz).abs() < 1e-7 * dz.abs(),
                "{c}: {dz}"
            );
        }
    }

    /// From the coherence: |H|^2 (1 - g) / ((n_d - 1) g), and the floor on g.
    #[test]
    fn coherence_variances_follow_the_h1_formula() {
        let h = vec![vec![c64::new(3.0, 4.0), c64::new(1.0, 0.0)]];
        let v = from_coherence(&h, &[vec![0.8, 0.0]], 10);
        assert!((v[0][0] - 25.0 * 0.2 / (9.0 * 0.8)).abs() < 1e-12);
        assert!((v[0][1] - (1.0 - COHERENCE_FLOOR) / (9.0 * COHERENCE_FLOOR)).abs() < 1e-9);
    }
}

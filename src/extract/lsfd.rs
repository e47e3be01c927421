//! Residues by least squares in the frequency domain (LSFD) for given poles, with the residual
//! terms of the modes outside the band, written for the quantity of the FRFs.
//!
//! Receptance of a linear system, one reference, modes r with poles lambda_r and (receptance)
//! residues R_r: H_d(w) = sum_r [ R_r / (iw - lambda_r) + conj(R_r) / (iw - conj(lambda_r)) ].
//! A response of quantity p (0 displacement, 1 velocity, 2 acceleration) is
//! H_p(w) = (iw)^p H_d(w), so each in-band mode contributes
//!   (iw)^p [ R_r / (iw - lambda_r) + conj(R_r) / (iw - conj(lambda_r)) ]
//! with the same receptance residue R_r whatever the quantity (the shapes, and even the
//! residues, of the three quantities are then directly comparable).
//!
//! Residual terms, from the expansion of the out-of-band modes in receptance (real modes,
//! A = 2 i w_d R real, w_r the mode's natural frequency):
//! - a mode far below the band (w_r << w, rigid-body modes included) behaves as a mass:
//!   A / (w_r^2 - w^2) = -(A / w^2) (1 + w_r^2 / w^2 + ...), terms in (iw)^-2 and (iw)^-4;
//! - a mode far above (w_r >> w) behaves as a spring:
//!   A / (w_r^2 - w^2) = (A / w_r^2) (1 + w^2 / w_r^2 + ...), terms in (iw)^0 and (iw)^2.
//!
//! The first term of each is the classical pair (mass-like lower residual, stiffness-like upper
//! residual); the second corrects for an out-of-band mode close to a band edge (a mode at half
//! the lower edge leaves 25% of its first-order term at the edge). `terms` (0, 1 or 2) of each
//! are fitted, with real coefficients L_1, L_2, U_1, U_2. Multiplied by (iw)^p they change form
//! with the quantity:
//!
//! | quantity     | lower residual                      | upper residual                 |
//! |--------------|-------------------------------------|--------------------------------|
//! | displacement | L_1 (iw)^-2 + L_2 (iw)^-4 = -L_1/w^2 + L_2/w^4 | U_1 + U_2 (iw)^2 = U_1 - U_2 w^2 |
//! | velocity     | L_1 (iw)^-1 + L_2 (iw)^-3 = -i L_1/w + i L_2/w^3 | i w U_1 - i w^3 U_2 |
//! | acceleration | L_1 + L_2 (iw)^-2 = L_1 - L_2/w^2 (a constant mass line first) | -w^2 U_1 + w^4 U_2 |
//!
//! so for accelerance the lower residual is the constant 1/mass line and the upper residual
//! grows as w^2. (Damping adds odd powers, (iw)^-3 below and (iw)^1 above, of relative size
//! zeta: neglected.) Unknowns per response: Re R_r, Im R_r for every pole and the residual
//! coefficients, all real; the complex equations are stacked as real and imaginary rows,
//! weighted by the line weight, and solved by QR ([`crate::optim::lstsq`]); the design matrix
//! is common to every response.

use faer::{Mat, c64};

use crate::optim::lstsq;

/// The form of the model: the quantity and the number of residual terms.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Basis {
    /// The power p of (iw) of the quantity (0, 1, 2).
    pub power: i32,
    /// Terms of each residual expansion, 0..=2.
    pub terms: usize,
}

impl Basis {
    /// Number of columns for `poles` poles.
    pub fn width(&self, poles: usize) -> usize {
        2 * poles + 2 * self.terms
    }
}

/// The identified modal model of every response for given poles.
#[derive(Debug, Clone)]
pub struct Fit {
    /// Receptance residues, `residues[mode][response]`.
    pub residues: Vec<Vec<c64>>,
    /// Lower residual coefficients [L_1, L_2] per response (those not fitted are 0).
    pub lower: Vec<[f64; 2]>,
    /// Upper residual coefficients [U_1, U_2] per response.
    pub upper: Vec<[f64; 2]>,
    /// Numerical rank of the design matrix (its width when the poles are distinct).
    pub rank: usize,
}

/// (iw)^p for an integer p (negative allowed).
fn iw_pow(w: f64, p: i32) -> c64 {
    let m = w.powi(p);
    match p.rem_euclid(4) {
        0 => c64::new(m, 0.0),
        1 => c64::new(0.0, m),
        2 => c64::new(-m, 0.0),
        _ => c64::new(0.0, -m),
    }
}

/// The complex columns of one line: (u_r, v_r) per pole, then the lower residual terms
/// (iw)^(p-2), (iw)^(p-4) and the upper (iw)^p, (iw)^(p+2), the first `terms` of each.
/// u = g1 + g2, v = i (g1 - g2), g1 = (iw)^p / (iw - lambda), g2 = (iw)^p / (iw - conj lambda):
/// R g1 + conj(R) g2 = Re R u + Im R v.
pub fn columns(w: f64, poles: &[c64], basis: Basis, out: &mut Vec<c64>) {
    out.clear();
    let p = basis.power;
    let iw = c64::new(0.0, w);
    let q = iw_pow(w, p);
    for &lambda in poles {
        let g1 = q / (iw - lambda);
        let g2 = q / (iw - lambda.conj());
        out.push(g1 + g2);
        out.push(c64::new(0.0, 1.0) * (g1 - g2));
    }
    for t in 0..basis.terms {
        out.push(iw_pow(w, p - 2 - 2 * t as i32));
    }
    for t in 0..basis.terms {
        out.push(iw_pow(w, p + 2 * t as i32));
    }
}

/// The derivatives of (u_r, v_r) of one line with respect to (Re lambda_r, Im lambda_r):
/// [du/dsigma, dv/dsigma, du/domega, dv/domega] for every pole.
pub fn column_derivatives(w: f64, poles: &[c64], p: i32, out: &mut Vec<[c64; 4]>) {
    out.clear();
    let iw = c64::new(0.0, w);
    let q = iw_pow(w, p);
    let i = c64::new(0.0, 1.0);
    for &lambda in poles {
        let a = iw - lambda;
        let b = iw - lambda.conj();
        let d1 = q / (a * a);
        let d2 = q / (b * b);
        // dg1/dsigma = d1, dg1/domega = i d1; dg2/dsigma = d2, dg2/domega = -i d2.
        out.push([d1 + d2, i * (d1 - d2), i * (d1 - d2), -(d1 + d2)]);
    }
}

/// T = W dA/dtheta x (2 nf x 2K, real-stacked like [`design`]): the derivative of the weighted
/// model of one response, whose unknowns are `x` (a column of the solution), with respect to
/// theta = (Re lambda_1, Im lambda_1, Re lambda_2, ...).
pub fn pole_jacobian(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    power: i32,
    x: faer::ColRef<'_, f64>,
) -> Mat<f64> {
    let nf = omega.len();
    let mut t = Mat::<f64>::zeros(2 * nf, 2 * poles.len());
    let mut derivatives = Vec::new();
    for k in 0..nf {
        column_derivatives(omega[k], poles, power, &mut derivatives);
        for (r, d) in derivatives.iter().enumerate() {
            let (xa, xb) = (x[2 * r], x[2 * r + 1]);
            for c in 0..2 {
                let v = d[2 * c] * xa + d[2 * c + 1] * xb;
                t[(k, 2 * r + c)] = weights[k] * v.re;
                t[(nf + k, 2 * r + c)] = weights[k] * v.im;
            }
        }
    }
    t
}

/// The weighted real-stacked design matrix (2 nf x (2K + 2)).
pub fn design(omega: &[f64], weights: &[f64], poles: &[c64], basis: Basis) -> Mat<f64> {
    let nf = omega.len();
    let m = basis.width(poles.len());
    let mut a = Mat::<f64>::zeros(2 * nf, m);
    let mut cols = Vec::with_capacity(m);
    for k in 0..nf {
        columns(omega[k], poles, basis, &mut cols);
        for (j, c) in cols.iter().enumerate() {
            a[(k, j)] = weights[k] * c.re;
            a[(nf + k, j)] = weights[k] * c.im;
        }
    }
    a
}

/// The weighted real-stacked data (2 nf x responses).
pub fn data(weights: &[f64], responses: &[Vec<c64>]) -> Mat<f64> {
    let nf = weights.len();
    Mat::from_fn(2 * nf, responses.len(), |row, o| {
        let k = row % nf;
        let h = responses[o][k];
        weights[k] * if row < nf { h.re } else { h.im }
    })
}

/// Unpacks the solution (one column per response) into a [`Fit`].
pub fn unpack(x: &Mat<f64>, modes: usize, basis: Basis, rank: usize) -> Fit {
    let responses = x.ncols();
    let residues = (0..modes)
        .map(|r| {
            (0..responses)
                .map(|o| c64::new(x[(2 * r, o)], x[(2 * r + 1, o)]))
                .collect()
        })
        .collect();
    Fit {
        residues,
        lower: (0..responses)
            .map(|o| {
                let mut l = [0.0; 2];
                for (t, v) in l.iter_mut().take(basis.terms).enumerate() {
                    *v = x[(2 * modes + t, o)];
                }
                l
            })
            .collect(),
        upper: (0..responses)
            .map(|o| {
                let mut u = [0.0; 2];
                for (t, v) in u.iter_mut().take(basis.terms).enumerate() {
                    *v = x[(2 * modes + basis.terms + t, o)];
                }
                u
            })
            .collect(),
        rank,
    }
}

/// Residues and residual terms of every response for `poles` (positive-frequency members of the
/// conjugate pairs). `responses[o][k]` on angular frequency `omega[k]`, weight `weights[k]`.
pub fn fit(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    basis: Basis,
    responses: &[Vec<c64>],
) -> Fit {
    let ls = least_squares(omega, weights, poles, basis, responses);
    unpack(&ls.x, poles.len(), basis, ls.rank)
}

/// The least-squares solution behind [`fit`] (one column per response), with its QR for
/// projections of other vectors.
pub fn least_squares(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    basis: Basis,
    responses: &[Vec<c64>],
) -> lstsq::LeastSquares {
    let a = design(omega, weights, poles, basis);
    let b = data(weights, responses);
    lstsq::solve(a.as_ref(), b.as_ref())
}

/// The FRFs of the model (poles, fit) on `omega`, `[response][line]`.
pub fn synthesize(omega: &[f64], poles: &[c64], basis: Basis, fit: &Fit) -> Vec<Vec<c64>> {
    let responses = fit.lower.len();
    let k = poles.len();
    let mut out = vec![Vec::with_capacity(omega.len()); responses];
    let mut cols = Vec::new();
    for &w in omega {
        columns(w, poles, basis, &mut cols);
        for (o, series) in out.iter_mut().enumerate() {
            let mut h = c64::new(0.0, 0.0);
            for t in 0..basis.terms {
                h += cols[2 * k + t] * fit.lower[o][t]
                    + cols[2 * k + basis.terms + t] * fit.upper[o][t];
            }
            for (r, res) in fit.residues.iter().enumerate() {
                h += cols[2 * r] * res[o].re + cols[2 * r + 1] * res[o].im;
            }
            series.push(h);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The analytic derivatives of the columns against central differences in Re and Im of
    /// each pole, for every quantity.
    #[test]
    fn column_derivatives_match_central_differences() {
        let poles = [c64::new(-4.0, 600.0), c64::new(-30.0, 1900.0)];
        for p in 0..3 {
            for &w in &[300.0, 610.0, 2500.0] {
                let mut d = Vec::new();
                column_derivatives(w, &poles, p, &mut d);
                for r in 0..poles.len() {
                    for (part, dir) in [(0usize, c64::new(1.0, 0.0)), (1, c64::new(0.0, 1.0))] {
                        // A step small against the distance to the pole (the scale of change).
                        let h = 1e-4 * (c64::new(0.0, w) - poles[r]).norm();
                        let mut plus = poles;
                        let mut minus = poles;
                        plus[r] += dir * h;
                        minus[r] -= dir * h;
                        let (mut cp, mut cm) = (Vec::new(), Vec::new());
                        let basis = Basis { power: p, terms: 2 };
                        columns(w, &plus, basis, &mut cp);
                        columns(w, &minus, basis, &mut cm);
                        for c in 0..2 {
                            let fd = (cp[2 * r + c] - cm[2 * r + c]) / (2.0 * h);
                            let an = d[r][2 * part + c];
                            assert!(
                                (fd - an).norm() < 1e-7 * an.norm(),
                                "p {p} w {w} pole {r} part {part} col {c}: {fd} vs {an}"
                            );
                        }
                    }
                }
            }
        }
    }

    /// Residual terms of the table in the module docs.
    #[test]
    fn residual_columns_follow_the_quantity() {
        let w: f64 = 7.0;
        let close = |a: c64, b: c64| (a - b).norm() <= 1e-15 * b.norm();
        let mut c = Vec::new();
        let cases = [
            (
                0,
                [
                    c64::new(-1.0 / 49.0, 0.0),
                    c64::new(w.powi(-4), 0.0),
                    c64::new(1.0, 0.0),
                    c64::new(-49.0, 0.0),
                ],
            ),
            (
                1,
                [
                    c64::new(0.0, -1.0 / 7.0),
                    c64::new(0.0, w.powi(-3)),
                    c64::new(0.0, 7.0),
                    c64::new(0.0, -343.0),
                ],
            ),
            (
                2,
                [
                    c64::new(1.0, 0.0),
                    c64::new(-1.0 / 49.0, 0.0),
                    c64::new(-49.0, 0.0),
                    c64::new(2401.0, 0.0),
                ],
            ),
        ];
        for (p, expected) in cases {
            columns(w, &[], Basis { power: p, terms: 2 }, &mut c);
            // Order: L_1, L_2, U_1, U_2.
            for (got, want) in c.iter().zip(expected) {
                assert!(close(*got, want), "p {p}: {c:?}");
            }
            columns(w, &[], Basis { power: p, terms: 1 }, &mut c);
            assert!(close(c[0], expected[0]) && close(c[1], expected[2]) && c.len() == 2);
        }
    }
}

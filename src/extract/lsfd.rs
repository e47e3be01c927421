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
//! Residual terms, from the leading term of the out-of-band modes in receptance:
//! - modes far below the band (|lambda| << w, rigid-body modes included) behave as masses:
//!   R/(iw - lambda) + c.c. ~ (R + conj R)/(iw) + 2 Re(R lambda)/(iw)^2, and R + conj R = 0 for
//!   real modes, so the lower residual is L (iw)^-2 (the familiar -L/w^2), L real;
//! - modes far above (|lambda| >> w) behave as springs: a constant U, U real.
//!
//! Multiplied by (iw)^p the two terms change form with the quantity:
//!
//! | quantity     | lower residual       | upper residual        |
//! |--------------|----------------------|-----------------------|
//! | displacement | L (iw)^-2 = -L / w^2 | U                     |
//! | velocity     | L (iw)^-1 = -i L / w | U (iw) = i w U        |
//! | acceleration | L (a constant mass line) | U (iw)^2 = -w^2 U |
//!
//! so for accelerance the lower residual is the constant 1/mass line and the upper residual
//! grows as w^2. Unknowns per response: Re R_r, Im R_r for every pole, L and U, all real; the
//! complex equations are stacked as real and imaginary rows, weighted by the line weight, and
//! solved by QR ([`super::lstsq`]); the design matrix is common to every response.

use faer::{Mat, c64};

use super::lstsq;

/// The identified modal model of every response for given poles.
#[derive(Debug, Clone)]
pub struct Fit {
    /// Receptance residues, `residues[mode][response]`.
    pub residues: Vec<Vec<c64>>,
    /// Lower residual L per response (see the module docs).
    pub lower: Vec<f64>,
    /// Upper residual U per response.
    pub upper: Vec<f64>,
    /// Numerical rank of the design matrix (2 K + 2 when the poles are distinct).
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

/// The complex columns of one line: (u_r, v_r) per pole, then the lower and upper residual.
/// u = g1 + g2, v = i (g1 - g2), g1 = (iw)^p / (iw - lambda), g2 = (iw)^p / (iw - conj lambda):
/// R g1 + conj(R) g2 = Re R u + Im R v.
pub fn columns(w: f64, poles: &[c64], p: i32, out: &mut Vec<c64>) {
    out.clear();
    let iw = c64::new(0.0, w);
    let q = iw_pow(w, p);
    for &lambda in poles {
        let g1 = q / (iw - lambda);
        let g2 = q / (iw - lambda.conj());
        out.push(g1 + g2);
        out.push(c64::new(0.0, 1.0) * (g1 - g2));
    }
    out.push(iw_pow(w, p - 2));
    out.push(q);
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

/// The weighted real-stacked design matrix (2 nf x (2K + 2)).
pub fn design(omega: &[f64], weights: &[f64], poles: &[c64], p: i32) -> Mat<f64> {
    let nf = omega.len();
    let m = 2 * poles.len() + 2;
    let mut a = Mat::<f64>::zeros(2 * nf, m);
    let mut cols = Vec::with_capacity(m);
    for k in 0..nf {
        columns(omega[k], poles, p, &mut cols);
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

/// Unpacks the solution (2K + 2 rows, one column per response) into a [`Fit`].
pub fn unpack(x: &Mat<f64>, modes: usize, rank: usize) -> Fit {
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
        lower: (0..responses).map(|o| x[(2 * modes, o)]).collect(),
        upper: (0..responses).map(|o| x[(2 * modes + 1, o)]).collect(),
        rank,
    }
}

/// Residues and residual terms of every response for `poles` (positive-frequency members of the
/// conjugate pairs). `responses[o][k]` on angular frequency `omega[k]`, weight `weights[k]`.
pub fn fit(
    omega: &[f64],
    weights: &[f64],
    poles: &[c64],
    p: i32,
    responses: &[Vec<c64>],
) -> Fit {
    let a = design(omega, weights, poles, p);
    let b = data(weights, responses);
    let ls = lstsq::solve(a.as_ref(), b.as_ref());
    unpack(&ls.x, poles.len(), ls.rank)
}

/// The FRFs of the model (poles, fit) on `omega`, `[response][line]`.
pub fn synthesize(omega: &[f64], poles: &[c64], p: i32, fit: &Fit) -> Vec<Vec<c64>> {
    let responses = fit.lower.len();
    let mut out = vec![Vec::with_capacity(omega.len()); responses];
    let mut cols = Vec::new();
    for &w in omega {
        columns(w, poles, p, &mut cols);
        for (o, series) in out.iter_mut().enumerate() {
            let mut h = cols[2 * poles.len()] * fit.lower[o] + cols[2 * poles.len() + 1] * fit.upper[o];
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
                        columns(w, &plus, p, &mut cp);
                        columns(w, &minus, p, &mut cm);
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
        let w = 7.0;
        let mut c = Vec::new();
        columns(w, &[], 0, &mut c);
        assert!((c[0] - c64::new(-1.0 / 49.0, 0.0)).norm() < 1e-15 && c[1] == c64::new(1.0, 0.0));
        columns(w, &[], 1, &mut c);
        assert!((c[0] - c64::new(0.0, -1.0 / 7.0)).norm() < 1e-15 && c[1] == c64::new(0.0, 7.0));
        columns(w, &[], 2, &mut c);
        assert!(c[0] == c64::new(1.0, 0.0) && c[1] == c64::new(-49.0, 0.0));
    }
}

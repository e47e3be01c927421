//! Poles by the least-squares complex-frequency (LSCF) estimator, common denominator, z-domain
//! basis with real coefficients (Guillaume, Verboven, Vanlanduit, Van der Auweraer, Peeters,
//! "A poly-reference implementation of the least-squares complex frequency-domain estimator",
//! IMAC 2003; Peeters, Van der Auweraer, Guillaume, Leuridan, "The PolyMAX frequency-domain
//! method", Shock and Vibration 11, 2004; one reference here, so the right matrix-fraction model
//! reduces to a scalar common denominator).
//!
//! Model of response o on line k: H_o(w_k) = N_o(z_k) / D(z_k), z_k = exp(i w_k dt),
//! dt = 1 / (2 f_hi) (the band is mapped on the upper half of the unit circle), N_o and D
//! polynomials of degree n (the model order) with real coefficients beta_o, alpha.
//! Linearised equation error, weighted by the line weight w_k:
//!   e_o(k) = w_k [ sum_j z_k^j beta_oj - H_o(k) sum_j z_k^j alpha_j ],
//! stacked as real and imaginary rows: e_o = X beta_o + Y_o alpha, X common to all responses.
//!
//! Reduced equations without squaring: one Householder QR of X (all orders at once, its
//! leading columns are the lower orders), then for every response C_o = Q^T Y_o (top block)
//! and the triangle D_o of the rest of Q^T Y_o. For order n the minimum over beta leaves
//!   || [ C_o(n+1..=N, 0..=n) ; D_o(.., 0..=n) ] alpha ||   (N the maximum order),
//! and the triangles D_o of all responses are compressed once into one (R of the stacked D_o:
//! leading columns again give the lower orders). Each order then needs the QR of a small
//! matrix only; alpha_n = 1 fixes the scale (the LS solution that gives the classical clear
//! stabilisation chart), the rest from the triangle by SVD (minimum norm if rank deficient).
//! Each response is scaled by its RMS over the band first, so that every channel weighs the
//! same in the common denominator.

use faer::{Mat, c64};

use crate::optim::lstsq;

/// The LSCF problem reduced for every order up to `max_order`.
pub struct Lscf {
    max_order: usize,
    /// Sampling time of the z-domain basis (s).
    pub dt: f64,
    /// C_o = Q^T Y_o (top (N+1) rows), one per response.
    c: Vec<Mat<f64>>,
    /// The triangle of the stacked D_o, (N+1) x (N+1).
    d: Mat<f64>,
}

/// The real-stacked basis X (2 nf x (N+1)): rows 0..nf the real parts, nf..2nf the imaginary.
fn basis(omega: &[f64], weights: &[f64], dt: f64, max_order: usize) -> Mat<f64> {
    let nf = omega.len();
    Mat::from_fn(2 * nf, max_order + 1, |row, j| {
        let k = row % nf;
        let angle = omega[k] * dt * j as f64;
        if row < nf {
            weights[k] * angle.cos()
        } else {
            weights[k] * angle.sin()
        }
    })
}

impl Lscf {
    /// Reduces the problem. `responses[o][k]` is response o on band line k (angular frequency
    /// `omega[k]`, weight `weights[k]`), already scaled; `f_hi` the upper band edge (Hz).
    /// `step` is called after each response.
    pub fn new(
        omega: &[f64],
        weights: &[f64],
        responses: &[Vec<c64>],
        f_hi: f64,
        max_order: usize,
        step: &mut dyn FnMut(),
    ) -> Lscf {
        let nf = omega.len();
        let p = max_order + 1;
        let dt = 1.0 / (2.0 * f_hi);
        let x = basis(omega, weights, dt, max_order);
        let qr = x.qr();
        let mut c = Vec::with_capacity(responses.len());
        let mut d_stack = Mat::<f64>::zeros(responses.len() * p, p);
        for (o, h) in responses.iter().enumerate() {
            // Y_o: the complex column j is -w_k H_o(k) z_k^j.
            let mut y = Mat::from_fn(2 * nf, p, |row, j| {
                let k = row % nf;
                let z = c64::from_polar(1.0, omega[k] * dt * j as f64);
                let v = -(h[k] * z) * weights[k];
                if row < nf { v.re } else { v.im }
            });
            lstsq::apply_qt(&qr, y.as_mut());
            c.push(y.as_ref().subrows(0, p).to_owned());
            let d = lstsq::triangle(y.as_ref().subrows(p, 2 * nf - p));
            for i in 0..d.nrows() {
                for j in 0..p {
                    d_stack[(o * p + i, j)] = d[(i, j)];
                }
            }
            step();
        }
        let d = lstsq::triangle(d_stack.as_ref());
        Lscf {
            max_order,
            dt,
            c,
            d,
        }
    }

    /// The denominator coefficients alpha_0..=alpha_n of order n (1 <= n <= max order),
    /// alpha_n = 1.
    pub fn denominator(&self, n: usize) -> Vec<f64> {
        let big = self.max_order;
        let rows = (n + 1) + self.c.len() * (big - n);
        let mut a = Mat::<f64>::zeros(rows, n + 1);
        for i in 0..=n.min(self.d.nrows().saturating_sub(1)) {
            for j in i..=n {
                a[(i, j)] = self.d[(i, j)];
            }
        }
        let mut row = n + 1;
        for c in &self.c {
            for i in (n + 1)..=big {
                for j in 0..=n {
                    a[(row, j)] = c[(i, j)];
                }
                row += 1;
            }
        }
        let r = lstsq::triangle(a.as_ref());
        // R [alpha'; 1] = 0 in the least-squares sense: R[.., ..n] alpha' = -R[.., n].
        let lead = r.as_ref().submatrix(0, 0, n, n).to_owned();
        let rhs = Mat::from_fn(n, 1, |i, _| -r[(i, n)]);
        let (x, _) = lstsq::solve_triangle(lead.as_ref(), rhs.as_ref());
        let mut alpha: Vec<f64> = (0..n).map(|i| x[(i, 0)]).collect();
        alpha.push(1.0);
        alpha
    }
}

/// The roots of the monic polynomial sum_j alpha_j z^j (alpha_n = 1) as continuous-time poles
/// s = ln(z) / dt, from the eigenvalues of its companion matrix; an empty list when the
/// eigensolver fails.
pub fn poles(alpha: &[f64], dt: f64) -> Vec<c64> {
    let n = alpha.len() - 1;
    if n == 0 {
        return Vec::new();
    }
    let companion = Mat::from_fn(n, n, |i, j| {
        if j == n - 1 {
            -alpha[i]
        } else if i == j + 1 {
            1.0
        } else {
            0.0
        }
    });
    let Ok(roots) = companion.eigenvalues() else {
        return Vec::new();
    };
    roots
        .into_iter()
        .filter(|z| z.norm() > 0.0 && z.re.is_finite() && z.im.is_finite())
        .map(|z| z.ln() / dt)
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    /// z-domain roots placed by hand come back as the poles s = ln(z)/dt.
    #[test]
    fn companion_roots_are_the_poles() {
        let dt = 1e-3;
        let s1 = c64::new(-3.0, 400.0);
        let s2 = c64::new(-10.0, 1500.0);
        let z1 = (s1 * dt).exp();
        let z2 = (s2 * dt).exp();
        // (z - z1)(z - z1*)(z - z2)(z - z2*) with real coefficients.
        let quad = |z: c64| [z.norm_sqr(), -2.0 * z.re, 1.0];
        let (a, b) = (quad(z1), quad(z2));
        let mut alpha = [0.0; 5];
        for i in 0..3 {
            for j in 0..3 {
                alpha[i + j] += a[i] * b[j];
            }
        }
        let mut found = poles(&alpha, dt);
        found.retain(|s| s.im > 0.0);
        found.sort_by(|a, b| a.im.total_cmp(&b.im));
        assert_eq!(found.len(), 2);
        for (f, t) in found.iter().zip([s1, s2]) {
            assert!((f - t).norm() < 1e-9 * t.norm(), "{f} vs {t}");
        }
    }

    /// Noise-free data of a rational z-domain model of order 2 are fitted exactly at order 2.
    #[test]
    fn exact_z_domain_model_is_recovered() {
        let f_hi = 500.0;
        let dt = 1.0 / (2.0 * f_hi);
        let s = c64::new(-2.0, 2.0 * std::f64::consts::PI * 120.0);
        let z0 = (s * dt).exp();
        let alpha_true = [z0.norm_sqr(), -2.0 * z0.re, 1.0];
        let betas = [[0.3, -0.1, 0.05], [1.0, 0.2, -0.4]];
        let omega: Vec<f64> = (1..=400)
            .map(|k| 2.0 * std::f64::consts::PI * k as f64 * 1.25)
            .collect();
        let responses: Vec<Vec<c64>> = betas
            .iter()
            .map(|b| {
                omega
                    .iter()
                    .map(|w| {
                        let z = c64::from_polar(1.0, w * dt);
                        let num = b[0] + z * b[1] + z * z * b[2];
                        let den = alpha_true[0] + z * alpha_true[1] + z * z * alpha_true[2];
                        num / den
                    })
                    .collect()
            })
            .collect();
        let weights = vec![1.0; omega.len()];
        let lscf = Lscf::new(&omega, &weights, &responses, f_hi, 6, &mut || {});
        let alpha = lscf.denominator(2);
        for (a, t) in alpha.iter().zip(alpha_true) {
            assert!((a - t).abs() < 1e-10, "{alpha:?} vs {alpha_true:?}");
        }
    }
}

//! The three laws of a mode's stiffness and damping against the response amplitude A, each
//! with its parameters and their derivatives (what the fit of [`super::fit`] needs):
//!
//! - [`Law::Constant`]: lambda = lambda_0, zeta = zeta_0 (2 parameters);
//! - [`Law::PowerLaw`]: lambda = lambda_0 (1 - c A^b), zeta = zeta_0 + d A^g (6 parameters).
//!   This form rather than k_0 A^-alpha: a joint is linear at vanishing amplitude (a finite
//!   small-amplitude stiffness; k_0 A^-alpha grows without bound as A -> 0), and the Iwan
//!   model's microslip softening is exactly of this form (b = chi + 1);
//! - [`Law::Iwan`]: the modal stiffness is the secant stiffness of a four-parameter Iwan
//!   element ([`super::iwan`]), lambda = K_sec(A), and the damping ratio is a constant plus
//!   the element's, zeta = zeta_0 + D(A) / (2 pi K_sec(A) A^2) (5 parameters: K_T, chi, R,
//!   phi_max, zeta_0; under microslip phi_max does not enter and 4 remain). One density
//!   gives both the softening and the dissipation: the law ties the damping's growth to the
//!   stiffness's fall (docs/method.md, "Amplitude dependence").
//!
//! lambda is the modal stiffness per unit modal mass, (2 pi f)^2; A the displacement amplitude
//! at the reference sensor. Imports: [`super::iwan`].

use super::iwan::Iwan;

/// A law of stiffness and damping against amplitude (module docs).
#[derive(Debug, Clone, Copy, PartialEq, Eq, PartialOrd, Ord, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Law {
    /// Constant stiffness and damping.
    Constant,
    /// Power-law softening and damping growth.
    PowerLaw,
    /// Four-parameter Iwan element.
    Iwan,
}

/// Every law, in the order of the outputs.
pub const LAWS: [Law; 3] = [Law::Constant, Law::PowerLaw, Law::Iwan];

/// Which regime an Iwan fit is in.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Regime {
    /// Every amplitude below phi_max: phi_max is not fitted (4 parameters).
    Microslip,
    /// Some amplitude at or beyond phi_max: 5 parameters.
    Macroslip,
}

/// A law's value at one amplitude: stiffness and damping with their gradients in the law's
/// parameters.
#[derive(Debug, Clone, PartialEq)]
pub struct Evaluation {
    /// Modal stiffness lambda.
    pub stiffness: f64,
    /// d lambda / d parameters.
    pub d_stiffness: Vec<f64>,
    /// Damping ratio zeta.
    pub damping: f64,
    /// d zeta / d parameters.
    pub d_damping: Vec<f64>,
}

impl Law {
    /// The name in files.
    pub fn name(self) -> &'static str {
        match self {
            Law::Constant => "constant",
            Law::PowerLaw => "power_law",
            Law::Iwan => "iwan",
        }
    }

    /// The parameter names, in the order of the parameter vectors (for the Iwan law under
    /// `regime`; the other laws ignore it).
    pub fn parameters(self, regime: Regime) -> &'static [&'static str] {
        match (self, regime) {
            (Law::Constant, _) => &["lambda_0", "zeta_0"],
            (Law::PowerLaw, _) => &["lambda_0", "c", "b", "zeta_0", "d", "g"],
            (Law::Iwan, Regime::Microslip) => &["K_T", "chi", "R", "zeta_0"],
            (Law::Iwan, Regime::Macroslip) => &["K_T", "chi", "R", "zeta_0", "phi_max"],
        }
    }

    /// Whether the parameters are inside the law's domain at every amplitude of `amplitudes`
    /// (positive stiffness; exponents > 0; -1 < chi <= 0, R >= 0, S >= 0 and phi_max above
    /// the amplitudes under microslip).
    pub fn admissible(self, regime: Regime, p: &[f64], amplitudes: &[f64]) -> bool {
        let finite = p.iter().all(|v| v.is_finite());
        finite
            && match self {
                Law::Constant => p[0] > 0.0,
                Law::PowerLaw => {
                    p[0] > 0.0
                        && p[2] > 0.0
                        && p[2] <= 10.0
                        && p[5] > 0.0
                        && p[5] <= 10.0
                        && amplitudes.iter().all(|&a| 1.0 - p[1] * a.powf(p[2]) > 0.0)
                }
                Law::Iwan => {
                    let m = iwan(regime, p, amplitudes);
                    p[0] > 0.0
                        && p[1] > -1.0
                        && p[1] <= 0.0
                        && p[2] >= 0.0
                        && m.s() >= 0.0
                        && m.phi_max > 0.0
                        && amplitudes.iter().all(|&a| m.secant(a).value > 0.0)
                }
            }
    }

    /// The law with parameters `p` at amplitude `a` > 0.
    pub fn evaluate(self, regime: Regime, p: &[f64], a: f64) -> Evaluation {
        match self {
            Law::Constant => Evaluation {
                stiffness: p[0],
                d_stiffness: vec![1.0, 0.0],
                damping: p[1],
                d_damping: vec![0.0, 1.0],
            },
            Law::PowerLaw => {
                let (l0, c, b, z0, d, g) = (p[0], p[1], p[2], p[3], p[4], p[5]);
                let (ab, ag) = (a.powf(b), a.powf(g));
                Evaluation {
                    stiffness: l0 * (1.0 - c * ab),
                    d_stiffness: vec![1.0 - c * ab, -l0 * ab, -l0 * c * ab * a.ln(), 0.0, 0.0, 0.0],
                    damping: z0 + d * ag,
                    d_damping: vec![0.0, 0.0, 0.0, 1.0, ag, d * ag * a.ln()],
                }
            }
            Law::Iwan => {
                let m = iwan(regime, p, &[a]);
                let (k, z) = (m.secant(a), m.damping_ratio(a));
                // Iwan gradients are in (K_T, chi, R, phi_max); the law's order puts zeta_0
                // fourth and phi_max (macroslip only) fifth.
                let mut d_stiffness = vec![k.grad[0], k.grad[1], k.grad[2], 0.0];
                let mut d_damping = vec![z.grad[0], z.grad[1], z.grad[2], 1.0];
                if regime == Regime::Macroslip {
                    d_stiffness.push(k.grad[3]);
                    d_damping.push(z.grad[3]);
                }
                Evaluation {
                    stiffness: k.value,
                    d_stiffness,
                    damping: p[3] + z.value,
                    d_damping,
                }
            }
        }
    }
}

/// The Iwan element of an Iwan law's parameters: under microslip phi_max lies beyond the
/// largest of `amplitudes` (it does not enter the values; twice the largest amplitude, or
/// where S = 0 if that comes first).
pub fn iwan(regime: Regime, p: &[f64], amplitudes: &[f64]) -> Iwan {
    let (k_t, chi, r) = (p[0], p[1], p[2]);
    let phi_max = match regime {
        Regime::Macroslip => p[4],
        Regime::Microslip => {
            let top = amplitudes.iter().fold(0.0_f64, |m, &a| m.max(a));
            let e = chi + 1.0;
            // S = K_T - R phi^e / e >= 0 up to phi = (K_T e / R)^(1/e).
            let limit = if r > 0.0 {
                (k_t * e / r).powf(1.0 / e)
            } else {
                f64::INFINITY
            };
            (2.0 * top).min(limit).max(top * (1.0 + 1e-12))
        }
    };
    Iwan {
        k_t,
        chi,
        r,
        phi_max,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn gradients_of_every_law_match_central_differences() {
        let cases: [(Law, Regime, Vec<f64>); 4] = [
            (Law::Constant, Regime::Microslip, vec![1.4e4, 0.005]),
            (
                Law::PowerLaw,
                Regime::Microslip,
                vec![1.4e4, 30.0, 0.7, 0.005, 2.0, 0.9],
            ),
            (
                Law::Iwan,
                Regime::Microslip,
                vec![1.4e4, -0.4, 5.0e5, 0.004],
            ),
            (
                Law::Iwan,
                Regime::Macroslip,
                vec![1.4e4, -0.4, 5.0e5, 0.004, 2.0e-4],
            ),
        ];
        for (law, regime, p) in cases {
            for a in [5e-5, 1e-4, 3e-4] {
                let e = law.evaluate(regime, &p, a);
                for j in 0..p.len() {
                    let h = 1e-6 * p[j].abs();
                    let mut q = p.clone();
                    q[j] += h;
                    let up = law.evaluate(regime, &q, a);
                    q[j] -= 2.0 * h;
                    let down = law.evaluate(regime, &q, a);
                    let fd_k = (up.stiffness - down.stiffness) / (2.0 * h);
                    let fd_z = (up.damping - down.damping) / (2.0 * h);
                    let (sk, sz) = (e.stiffness / p[j].abs(), e.damping / p[j].abs());
                    assert!(
                        (e.d_stiffness[j] - fd_k).abs() <= 1e-6 * (sk + fd_k.abs()),
                        "{law:?} {regime:?} a = {a} d stiffness / d p{j}: {} against {fd_k}",
                        e.d_stiffness[j]
                    );
                    assert!(
                        (e.d_damping[j] - fd_z).abs() <= 1e-6 * (sz + fd_z.abs()),
                        "{law:?} {regime:?} a = {a} d damping / d p{j}: {} against {fd_z}",
                        e.d_damping[j]
                    );
                }
            }
        }
    }

    #[test]
    fn microslip_iwan_is_the_power_law_with_b_equal_to_chi_plus_one() {
        let (k_t, chi, r) = (1.4e4, -0.4, 5.0e5);
        let e: f64 = chi + 1.0;
        let iwan_p = [k_t, chi, r, 0.0];
        let power_p = [k_t, r / (k_t * e * (e + 1.0)), e, 0.0, 1.0, 1.0];
        for a in [1e-5, 1e-4, 2e-4] {
            let i = Law::Iwan.evaluate(Regime::Microslip, &iwan_p, a);
            let p = Law::PowerLaw.evaluate(Regime::Microslip, &power_p, a);
            assert!((i.stiffness - p.stiffness).abs() <= 1e-12 * k_t);
        }
    }
}

//! Segalman's four-parameter Iwan model of a lap joint (D. J. Segalman, "A four-parameter Iwan
//! model for lap-type joints", J. Appl. Mech. 72 (2005) 752-760): closed forms of the backbone,
//! of the secant stiffness and of the dissipation per cycle of a harmonic displacement of
//! amplitude A, with their derivatives in the parameters. The derivation is in
//! `docs/method.md`, section "Amplitude dependence".
//!
//! The joint is a parallel set of Jenkins elements (a unit spring in series with a slider that
//! slips at the displacement phi), their density over phi
//!
//! ```text
//!   rho(phi) = R phi^chi [H(phi) - H(phi - phi_max)] + S delta(phi - phi_max),  -1 < chi <= 0.
//! ```
//!
//! With e = chi + 1, under microslip (A < phi_max):
//!
//! ```text
//!   K_sec(A) = F(A) / A = K_T - R A^e / (e (e + 1)),     D(A) = 4 R A^(e+2) / ((e + 1)(e + 2)),
//! ```
//!
//! and under macroslip (A >= phi_max) K_sec = F_S / A and D as in [`Iwan::dissipation`].
//! The model is held here as (K_T, chi, R, phi_max), the form the fit works in; Segalman's
//! (F_S, K_T, chi, beta) convert both ways ([`Iwan::from_segalman`], [`Iwan::segalman`]).
//!
//! Pure functions of numbers: imports nothing of the crate.

use std::f64::consts::PI;

/// A value and its gradient in (K_T, chi, R, phi_max).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Graded {
    /// The value.
    pub value: f64,
    /// d value / d (K_T, chi, R, phi_max).
    pub grad: [f64; 4],
}

/// The four-parameter Iwan model in the fit's parametrisation (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Iwan {
    /// Small-amplitude stiffness K_T (force per displacement).
    pub k_t: f64,
    /// Exponent chi of the density's power-law part, -1 < chi <= 0.
    pub chi: f64,
    /// Coefficient R of the density's power-law part (K_T per displacement^(chi+1)).
    pub r: f64,
    /// Largest slip displacement phi_max (where the delta of strength S sits).
    pub phi_max: f64,
}

/// Segalman's parameters of an Iwan model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segalman {
    /// Force of macroslip F_S.
    pub f_s: f64,
    /// Small-amplitude stiffness K_T.
    pub k_t: f64,
    /// Exponent chi.
    pub chi: f64,
    /// beta = S / (R phi_max^(chi+1) / (chi+1)): the delta's share against the power law's.
    pub beta: f64,
}

impl Iwan {
    /// The model of Segalman's parameters (eq. (17)-(19) of his paper).
    pub fn from_segalman(p: Segalman) -> Self {
        let e = p.chi + 1.0;
        let den = p.beta + e / (e + 1.0);
        let phi_max = p.f_s * (1.0 + p.beta) / (p.k_t * den);
        let r = p.f_s * e / (phi_max.powf(e + 1.0) * den);
        Self {
            k_t: p.k_t,
            chi: p.chi,
            r,
            phi_max,
        }
    }

    /// The strength S of the delta at phi_max: K_T minus the power law's share.
    pub fn s(&self) -> f64 {
        let e = self.chi + 1.0;
        self.k_t - self.r * self.phi_max.powf(e) / e
    }

    /// Segalman's parameters of this model.
    pub fn segalman(&self) -> Segalman {
        let e = self.chi + 1.0;
        let power = self.r * self.phi_max.powf(e) / e;
        Segalman {
            f_s: self.force_of_macroslip(),
            k_t: self.k_t,
            chi: self.chi,
            beta: self.s() / power,
        }
    }

    /// F_S, the force when every slider slips: F(phi_max).
    pub fn force_of_macroslip(&self) -> f64 {
        let e = self.chi + 1.0;
        let p = self.phi_max;
        self.k_t * p - self.r * p.powf(e + 1.0) / (e * (e + 1.0))
    }

    /// The secant stiffness F(A) / A of the loop of amplitude A > 0 (the backbone's force at
    /// A over A), with its gradient.
    pub fn secant(&self, a: f64) -> Graded {
        let e = self.chi + 1.0;
        let c = e * (e + 1.0);
        // d/de of 1 / (e (e+1)) = -(2e + 1) / c^2.
        let dc = (2.0 * e + 1.0) / c;
        if a < self.phi_max {
            let g = a.powf(e);
            Graded {
                value: self.k_t - self.r * g / c,
                grad: [1.0, -self.r * g * (a.ln() - dc) / c, -g / c, 0.0],
            }
        } else {
            let p = self.phi_max;
            let g = p.powf(e + 1.0);
            Graded {
                value: self.force_of_macroslip() / a,
                grad: [
                    p / a,
                    -self.r * g * (p.ln() - dc) / (c * a),
                    -g / (c * a),
                    self.s() / a,
                ],
            }
        }
    }

    /// The energy dissipated in one cycle of a harmonic displacement of amplitude A > 0:
    /// the sum over the sliders that slip (phi < A) of 4 phi (A - phi), with its gradient.
    pub fn dissipation(&self, a: f64) -> Graded {
        let e = self.chi + 1.0;
        if a < self.phi_max {
            let d = 4.0 * self.r * a.powf(e + 2.0) / ((e + 1.0) * (e + 2.0));
            Graded {
                value: d,
                grad: [
                    0.0,
                    d * (a.ln() - 1.0 / (e + 1.0) - 1.0 / (e + 2.0)),
                    d / self.r,
                    0.0,
                ],
            }
        } else {
            let (r, p) = (self.r, self.phi_max);
            let (p1, p2) = (p.powf(e + 1.0), p.powf(e + 2.0));
            let s = self.s();
            let power = a * p1 / (e + 1.0) - p2 / (e + 2.0);
            let d_power_de = a * p1 * (p.ln() / (e + 1.0) - 1.0 / (e + 1.0).powi(2))
                - p2 * (p.ln() / (e + 2.0) - 1.0 / (e + 2.0).powi(2));
            let ds_de = -r * p.powf(e) * (e * p.ln() - 1.0) / (e * e);
            let ds_dr = -p.powf(e) / e;
            let ds_dp = -r * p.powf(e - 1.0);
            let lever = p * (a - p);
            Graded {
                value: 4.0 * r * power + 4.0 * s * lever,
                grad: [
                    4.0 * lever,
                    4.0 * r * d_power_de + 4.0 * ds_de * lever,
                    4.0 * power + 4.0 * ds_dr * lever,
                    4.0 * r * (a * p.powf(e) - p1) + 4.0 * (ds_dp * lever + s * (a - 2.0 * p)),
                ],
            }
        }
    }

    /// The equivalent viscous damping ratio of the joint at amplitude A: the dissipation over
    /// 4 pi times the secant strain energy K_sec A^2 / 2, i.e. D / (2 pi K_sec A^2), with its
    /// gradient.
    pub fn damping_ratio(&self, a: f64) -> Graded {
        let (k, d) = (self.secant(a), self.dissipation(a));
        let den = 2.0 * PI * a * a;
        let value = d.value / (den * k.value);
        let mut grad = [0.0; 4];
        for (j, g) in grad.iter_mut().enumerate() {
            *g = (d.grad[j] * k.value - d.value * k.grad[j]) / (den * k.value * k.value);
        }
        Graded { value, grad }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn model() -> Iwan {
        Iwan {
            k_t: 2.0e4,
            chi: -0.6,
            r: 1.0e5,
            phi_max: 1.0e-3,
        }
    }

    #[test]
    fn segalman_parameters_round_trip() {
        let m = model();
        let back = Iwan::from_segalman(m.segalman());
        for (a, b) in [
            (m.k_t, back.k_t),
            (m.chi, back.chi),
            (m.r, back.r),
            (m.phi_max, back.phi_max),
        ] {
            assert!((a - b).abs() <= 1e-12 * a.abs(), "{a} against {b}");
        }
        assert!(m.s() > 0.0 && m.segalman().beta > 0.0);
    }

    #[test]
    fn the_two_regimes_meet_at_phi_max() {
        let m = model();
        let below = 1.0e-3 * (1.0 - 1e-12);
        for f in [Iwan::secant, Iwan::dissipation] {
            let (lo, hi) = (f(&m, below).value, f(&m, m.phi_max).value);
            assert!((lo - hi).abs() <= 1e-9 * hi.abs(), "{lo} against {hi}");
        }
    }

    #[test]
    fn gradients_match_central_differences_in_both_regimes() {
        let m = model();
        for a in [2e-4, 7e-4, 1.5e-3, 4e-3] {
            for f in [Iwan::secant, Iwan::dissipation, Iwan::damping_ratio] {
                let g = f(&m, a);
                for j in 0..4 {
                    let mut p = [m.k_t, m.chi, m.r, m.phi_max];
                    let h = 1e-6 * p[j].abs();
                    let at = |p: [f64; 4]| {
                        let q = Iwan {
                            k_t: p[0],
                            chi: p[1],
                            r: p[2],
                            phi_max: p[3],
                        };
                        f(&q, a).value
                    };
                    p[j] += h;
                    let up = at(p);
                    p[j] -= 2.0 * h;
                    let down = at(p);
                    let fd = (up - down) / (2.0 * h);
                    let scale = g.value.abs() / p[j].abs().max(1e-300) + fd.abs();
                    assert!(
                        (g.grad[j] - fd).abs() <= 1e-6 * scale,
                        "a = {a}, parameter {j}: {} against {fd}",
                        g.grad[j]
                    );
                }
            }
        }
    }
}

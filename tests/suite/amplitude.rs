//! Amplitude dependence across excitation levels (`jointid::amplitude`, `jointid amplitude`).
//!
//! Independence: the reference values here never come from the closed forms under test.
//! - The Iwan model's secant stiffness and dissipation are checked against (a) quadrature of
//!   Segalman's density (the integrals F(A) = int_0^A phi rho + A int_A^inf rho and
//!   D(A) = int_0^A 4 phi (A - phi) rho, written here, with the substitution u = phi^(chi+1)
//!   that removes the density's singularity, composite Simpson) and (b) a time-stepped loop of
//!   20 000 Jenkins elements (unit springs in series with sliders, their strengths the
//!   density's quantiles) under u = A cos t, its loop area by the trapezoid rule.
//! - The synthetic levels of the recovery tests are made by (a), from Segalman's
//!   (F_S, K_T, chi, beta) converted to (R, S, phi_max) by his eq. (17)-(19) written out here,
//!   and by the power law written out here; the fitter sees only the numbers.
//!
//! Segalman, "A four-parameter Iwan model for lap-type joints", J. Appl. Mech. 72 (2005).

use std::f64::consts::PI;

use jointid::amplitude::{Iwan, Law, Regime, Segalman, Series, estimates, fit_mode};

/// Segalman's density: (R, S, phi_max) of (F_S, K_T, chi, beta), his eq. (17)-(19).
fn density(f_s: f64, k_t: f64, chi: f64, beta: f64) -> (f64, f64, f64) {
    let den = beta + (chi + 1.0) / (chi + 2.0);
    let phi_max = f_s * (1.0 + beta) / (k_t * den);
    let r = f_s * (chi + 1.0) / (phi_max.powf(chi + 2.0) * den);
    let s = f_s / phi_max * beta / den;
    (r, s, phi_max)
}

/// int_0^top g(phi) R phi^chi dphi by u = phi^(chi+1), Simpson on 4000 intervals.
fn against_density(r: f64, chi: f64, top: f64, g: impl Fn(f64) -> f64) -> f64 {
    let e = chi + 1.0;
    let (n, ut) = (4000, top.powf(e));
    let h = ut / n as f64;
    let f = |u: f64| g(u.powf(1.0 / e));
    let mut sum = f(0.0) + f(ut);
    for i in 1..n {
        sum += if i % 2 == 1 { 4.0 } else { 2.0 } * f(i as f64 * h);
    }
    r / e * sum * h / 3.0
}

/// (secant stiffness, dissipation per cycle) at amplitude A by quadrature of the density.
fn by_quadrature(p: Segalman, a: f64) -> (f64, f64) {
    let (r, s, phi_max) = density(p.f_s, p.k_t, p.chi, p.beta);
    let top = a.min(phi_max);
    let held = against_density(r, p.chi, top, |phi| phi);
    let beyond =
        against_density(r, p.chi, phi_max, |_| 1.0) - against_density(r, p.chi, top, |_| 1.0);
    let force = if a < phi_max {
        held + a * (beyond + s)
    } else {
        held + s * phi_max
    };
    let mut d = against_density(r, p.chi, top, |phi| 4.0 * phi * (a - phi));
    if a > phi_max {
        d += 4.0 * s * phi_max * (a - phi_max);
    }
    (force / a, d)
}

/// (secant stiffness, dissipation) of a time-stepped loop of Jenkins elements (module docs).
fn by_jenkins(p: Segalman, a: f64) -> (f64, f64) {
    let (r, s, phi_max) = density(p.f_s, p.k_t, p.chi, p.beta);
    let e = p.chi + 1.0;
    let mass = r * phi_max.powf(e) / e;
    let n = 20_000;
    let mut elements: Vec<(f64, f64)> = (0..n)
        .map(|i| {
            let c = (i as f64 + 0.5) * mass / n as f64;
            (mass / n as f64, (e * c / r).powf(1.0 / e))
        })
        .collect();
    elements.push((s, phi_max));
    let mut slip = vec![0.0; elements.len()];
    let force = |u: f64, slip: &mut [f64]| -> f64 {
        let mut f = 0.0;
        for ((w, phi), x) in elements.iter().zip(slip.iter_mut()) {
            let stretch = u - *x;
            if stretch > *phi {
                *x = u - phi;
            } else if stretch < -*phi {
                *x = u + phi;
            }
            f += w * (u - *x);
        }
        f
    };
    // Virgin loading to A in steps, then one cycle A cos t.
    let mut peak = 0.0;
    for k in 1..=200 {
        peak = force(a * k as f64 / 200.0, &mut slip);
    }
    let steps = 4000;
    let (mut area, mut u0, mut f0) = (0.0, a, peak);
    for k in 1..=steps {
        let u = a * (2.0 * PI * k as f64 / steps as f64).cos();
        let f = force(u, &mut slip);
        area += 0.5 * (f + f0) * (u - u0);
        (u0, f0) = (u, f);
    }
    (peak / a, area.abs())
}

/// |value - reference| <= tol |reference|.
fn close(value: f64, reference: f64, tol: f64, what: &str) {
    assert!(
        (value - reference).abs() <= tol * reference.abs(),
        "{what}: {value} against {reference}"
    );
}

fn joint() -> Segalman {
    Segalman {
        f_s: 40.0,
        k_t: 1.0e5,
        chi: -0.5,
        beta: 0.3,
    }
}

#[test]
fn iwan_closed_forms_match_quadrature_and_jenkins_loops_in_both_regimes() {
    let p = joint();
    let m = Iwan::from_segalman(p);
    for frac in [0.05, 0.3, 0.8, 1.5, 3.0] {
        let a = frac * m.phi_max;
        let (k_q, d_q) = by_quadrature(p, a);
        let (k, d) = (m.secant(a).value, m.dissipation(a).value);
        close(k, k_q, 1e-9, &format!("secant at {frac} phi_max"));
        close(d, d_q, 1e-8, &format!("dissipation at {frac} phi_max"));
        let (k_j, d_j) = by_jenkins(p, a);
        // The elements discretise the density: the loss of stiffness and the dissipation
        // agree to 0.5%.
        close(
            p.k_t - k_j,
            p.k_t - k,
            5e-3,
            &format!("softening at {frac} phi_max"),
        );
        close(d_j, d, 5e-3, &format!("loop area at {frac} phi_max"));
    }
    let back = m.segalman();
    assert!((back.f_s - p.f_s).abs() < 1e-10 * p.f_s && (back.beta - p.beta).abs() < 1e-10);
}

/// Modal stiffness and damping of an all-Iwan mode by quadrature (the generator).
fn iwan_levels(p: Segalman, zeta_0: f64, amplitudes: &[f64], s_k: f64, s_z: f64) -> Series {
    let (k, z): (Vec<f64>, Vec<f64>) = amplitudes
        .iter()
        .map(|&a| {
            let (k, d) = by_quadrature(p, a);
            (k, zeta_0 + d / (2.0 * PI * k * a * a))
        })
        .unzip();
    Series {
        amplitude: amplitudes.to_vec(),
        stiffness_std: vec![s_k; k.len()],
        stiffness: k,
        damping_std: vec![s_z; z.len()],
        damping: z,
    }
}

pub fn param(fit: &jointid::amplitude::ModeFit, law: Law, name: &str) -> (f64, f64) {
    let j = fit.laws.iter().find(|j| j.fitted.law == law).unwrap();
    let e = estimates(j);
    let e = e
        .iter()
        .find(|e| e.name == name)
        .unwrap_or_else(|| panic!("no {name}"));
    (e.value, e.std)
}

#[test]
fn noise_free_microslip_levels_give_back_the_iwan_parameters_and_choose_it() {
    let p = joint();
    let phi_max = Iwan::from_segalman(p).phi_max;
    let amplitudes: Vec<f64> = (1..=6).map(|i| 0.1 * i as f64 * phi_max).collect();
    let data = iwan_levels(p, 0.004, &amplitudes, 1e-6, 1e-10);
    let fit = fit_mode(&data);
    assert_eq!(fit.selected, Law::Iwan);
    let m = Iwan::from_segalman(p);
    for (name, truth) in [
        ("K_T", p.k_t),
        ("chi", p.chi),
        ("R", m.r),
        ("zeta_0", 0.004),
    ] {
        close(param(&fit, Law::Iwan, name).0, truth, 1e-6, name);
    }
}

#[test]
fn noise_free_levels_into_macroslip_give_back_all_four_segalman_parameters() {
    let p = joint();
    let phi_max = Iwan::from_segalman(p).phi_max;
    let amplitudes: Vec<f64> = (1..=10).map(|i| 0.25 * i as f64 * phi_max).collect();
    let data = iwan_levels(p, 0.004, &amplitudes, 1e-6, 1e-10);
    let fit = fit_mode(&data);
    let j = fit.laws.iter().find(|j| j.fitted.law == Law::Iwan).unwrap();
    assert_eq!(j.fitted.regime, Regime::Macroslip);
    for (name, truth) in [
        ("K_T", p.k_t),
        ("chi", p.chi),
        ("F_S", p.f_s),
        ("beta", p.beta),
    ] {
        close(param(&fit, Law::Iwan, name).0, truth, 1e-5, name);
    }
}

/// Gaussian numbers from a fixed seed (xorshift64*, Box-Muller).
struct Normal(u64);

impl Normal {
    fn uniform(&mut self) -> f64 {
        self.0 ^= self.0 >> 12;
        self.0 ^= self.0 << 25;
        self.0 ^= self.0 >> 27;
        ((self.0.wrapping_mul(0x2545_F491_4F6C_DD1D) >> 11) as f64 + 0.5) / (1u64 << 53) as f64
    }
    fn next(&mut self) -> f64 {
        let (u, v) = (self.uniform(), self.uniform());
        (-2.0 * u.ln()).sqrt() * (2.0 * PI * v).cos()
    }
}

#[test]
fn noisy_levels_give_back_the_iwan_parameters_within_three_standard_errors() {
    let p = joint();
    let m = Iwan::from_segalman(p);
    let amplitudes: Vec<f64> = (1..=8).map(|i| 0.1 * i as f64 * m.phi_max).collect();
    let (s_k, s_z) = (20.0, 2e-5);
    let mut data = iwan_levels(p, 0.004, &amplitudes, s_k, s_z);
    let mut noise = Normal(0x5eed_1234);
    for (k, z) in data.stiffness.iter_mut().zip(data.damping.iter_mut()) {
        *k += s_k * noise.next();
        *z += s_z * noise.next();
    }
    let fit = fit_mode(&data);
    for (name, truth) in [
        ("K_T", p.k_t),
        ("chi", p.chi),
        ("R", m.r),
        ("zeta_0", 0.004),
    ] {
        let (v, se) = param(&fit, Law::Iwan, name);
        assert!(se.is_finite() && se > 0.0, "{name}: se {se}");
        assert!(
            (v - truth).abs() <= 3.0 * se,
            "{name}: {v} +- {se} against {truth}"
        );
    }
}

#[test]
fn a_power_law_with_its_own_damping_exponent_is_recovered_and_chosen() {
    let (l0, c, b, z0, d, g) = (1.4e4, 4.0, 0.6, 0.005, 10.0, 1.5);
    let amplitudes: Vec<f64> = (1..=6).map(|i| 1e-3 * i as f64).collect();
    let stiffness: Vec<f64> = amplitudes
        .iter()
        .map(|a| l0 * (1.0 - c * a.powf(b)))
        .collect();
    let damping: Vec<f64> = amplitudes.iter().map(|a| z0 + d * a.powf(g)).collect();
    let data = Series {
        amplitude: amplitudes.clone(),
        stiffness_std: vec![1e-6; 6],
        stiffness,
        damping_std: vec![1e-10; 6],
        damping,
    };
    let fit = fit_mode(&data);
    assert_eq!(fit.selected, Law::PowerLaw);
    for (name, truth) in [
        ("lambda_0", l0),
        ("c", c),
        ("b", b),
        ("zeta_0", z0),
        ("d", d),
        ("g", g),
    ] {
        close(param(&fit, Law::PowerLaw, name).0, truth, 1e-6, name);
    }
}

#[test]
fn levels_that_do_not_change_choose_the_constant_and_extra_scatter_is_estimated() {
    let amplitudes: Vec<f64> = (1..=6).map(|i| 1e-3 * i as f64).collect();
    let mut noise = Normal(42);
    let stiffness: Vec<f64> = (0..6).map(|_| 1.4e4 + 5.0 * noise.next()).collect();
    let damping: Vec<f64> = (0..6).map(|_| 0.005 + 1e-5 * noise.next()).collect();
    // Stated errors 50 times too small: the scatter asks for an extra variance near 5.
    let data = Series {
        amplitude: amplitudes,
        stiffness,
        stiffness_std: vec![0.1; 6],
        damping,
        damping_std: vec![1e-5; 6],
    };
    let fit = fit_mode(&data);
    assert_eq!(fit.selected, Law::Constant);
    assert!(
        fit.tau_stiffness > 1.0 && fit.tau_stiffness < 15.0,
        "{}",
        fit.tau_stiffness
    );
}

#[test]
fn few_levels_fit_the_laws_they_can_and_say_why_not_the_others() {
    let p = joint();
    let phi_max = Iwan::from_segalman(p).phi_max;
    for (levels, fitted, skipped) in [
        (2, vec![Law::Constant], vec![Law::PowerLaw, Law::Iwan]),
        (3, vec![Law::Constant, Law::Iwan], vec![Law::PowerLaw]),
    ] {
        let amplitudes: Vec<f64> = (1..=levels).map(|i| 0.2 * i as f64 * phi_max).collect();
        let fit = fit_mode(&iwan_levels(p, 0.004, &amplitudes, 1.0, 1e-5));
        let laws: Vec<Law> = fit.laws.iter().map(|j| j.fitted.law).collect();
        assert_eq!(laws, fitted, "{levels} levels");
        let not: Vec<Law> = fit.skipped.iter().map(|(l, _)| *l).collect();
        assert_eq!(not, skipped, "{levels} levels");
        assert!(
            fit.skipped
                .iter()
                .all(|(_, why)| why.starts_with("needs at least"))
        );
    }
}

/// The power of the amplitude's unit in a parameter's unit (R is per A^(chi+1), c per A^b, d
/// per A^g; phi_max and F_S are amplitudes; the others are free of it).
fn amplitude_power(name: &str, value_of: &dyn Fn(&str) -> f64) -> f64 {
    match name {
        "R" => -(value_of("chi") + 1.0),
        "c" => -value_of("b"),
        "d" => -value_of("g"),
        n if n.starts_with("phi_max") || n.starts_with("F_S") => 1.0,
        _ => 0.0,
    }
}

#[test]
fn a_change_of_the_amplitudes_unit_changes_the_parameters_by_the_conversion_only() {
    let p = joint();
    let m = Iwan::from_segalman(p);
    // Into macroslip, with noise: every law fitted, every parameter with a standard error.
    let amplitudes: Vec<f64> = (1..=10).map(|i| 0.25 * i as f64 * m.phi_max).collect();
    let (s_k, s_z) = (20.0, 2e-5);
    let mut base = iwan_levels(p, 0.004, &amplitudes, s_k, s_z);
    let mut noise = Normal(0x0dd_5eed);
    for (k, z) in base.stiffness.iter_mut().zip(base.damping.iter_mut()) {
        *k += s_k * noise.next();
        *z += s_z * noise.next();
    }
    let reference = fit_mode(&base);
    for factor in [1e150, 1e-200] {
        let mut data = base.clone();
        data.amplitude.iter_mut().for_each(|a| *a *= factor);
        let fit = fit_mode(&data);
        assert_eq!(fit.selected, reference.selected, "factor {factor:e}");
        for (j, r) in fit.laws.iter().zip(&reference.laws) {
            let law = r.fitted.law;
            assert_eq!(j.fitted.law, law);
            assert_eq!(j.fitted.regime, r.fitted.regime, "{law:?}");
            close(j.aicc, r.aicc, 1e-6, &format!("{law:?} AICc"));
            let (got, want) = (estimates(j), estimates(r));
            let value_of = |name: &str| want.iter().find(|e| e.name == name).unwrap().value;
            for (g, w) in got.iter().zip(&want) {
                let what = format!("{law:?} {} at factor {factor:e}", w.name);
                assert!(g.value.is_finite(), "{what}: {}", g.value);
                let unit = factor.powf(amplitude_power(&w.name, &value_of));
                close(g.value, w.value * unit, 1e-6, &what);
                if amplitude_power(&w.name, &value_of) == 0.0 && w.std.is_finite() {
                    close(g.std, w.std, 1e-4, &format!("{what} std"));
                }
            }
        }
        for band in &fit.bands {
            assert!(band.iter().all(|b| b.stiffness.is_finite()
                && b.damping.is_finite()
                && b.stiffness_se.is_finite()
                && b.damping_se.is_finite()));
        }
    }
}

/// Iwan levels at `0.15 i phi_max` (i = 1..levels) with Gaussian noise of `seed`.
fn noisy_levels(levels: usize, s_k: f64, s_z: f64, seed: u64) -> Series {
    let p = joint();
    let m = Iwan::from_segalman(p);
    let amplitudes: Vec<f64> = (1..=levels).map(|i| 0.15 * i as f64 * m.phi_max).collect();
    let mut data = iwan_levels(p, 0.004, &amplitudes, s_k, s_z);
    let mut noise = Normal(seed);
    for (k, z) in data.stiffness.iter_mut().zip(data.damping.iter_mut()) {
        *k += s_k * noise.next();
        *z += s_z * noise.next();
    }
    data
}

#[test]
fn a_law_that_did_not_converge_is_not_physical_or_interpolates_is_not_chosen() {
    // (levels, noise of stiffness and damping, seed, the laws of smaller AICc than the
    // chosen one and why each may not be chosen). Found by a scan of seeds: on these levels
    // the smallest AICc used to be chosen whatever its fit.
    type Case = (usize, f64, f64, u64, &'static [(Law, &'static str)]);
    let cases: [Case; 3] = [
        (
            3,
            200.0,
            1e-3,
            8,
            &[(Law::Iwan, "it interpolates the 3 levels")],
        ),
        (
            4,
            2000.0,
            3e-3,
            9,
            &[
                (Law::PowerLaw, "its fit did not converge"),
                (Law::Iwan, "zeta_0 = -2.777e-3 < 0 is not physical"),
            ],
        ),
        (
            4,
            2000.0,
            3e-3,
            13,
            &[(Law::PowerLaw, "zeta_0 = -1.156e-4 < 0")],
        ),
    ];
    for (levels, s_k, s_z, seed, better) in cases {
        let fit = fit_mode(&noisy_levels(levels, s_k, s_z, seed));
        let chosen = fit
            .laws
            .iter()
            .find(|j| j.fitted.law == fit.selected)
            .unwrap();
        assert_eq!(chosen.ineligible, None, "seed {seed}");
        assert_eq!(chosen.delta_aicc, 0.0);
        for &(law, why) in better {
            let j = fit.laws.iter().find(|j| j.fitted.law == law).unwrap();
            assert!(j.delta_aicc < 0.0, "seed {seed} {law:?}: {}", j.delta_aicc);
            assert_eq!(j.weight, 0.0);
            let reason = j.ineligible.as_deref().unwrap_or("eligible");
            assert!(reason.starts_with(why), "seed {seed} {law:?}: {reason}");
        }
        let total: f64 = fit.laws.iter().map(|j| j.weight).sum();
        assert!((total - 1.0).abs() < 1e-12);
    }
}

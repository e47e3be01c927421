//! One mode across levels: the extra variance, the three laws fitted with the same weights,
//! the choice among them, and the uncertainty band of each.
//!
//! 1. Extra variance: the most general law the levels allow (the power law from 4 levels, else
//!    the Iwan law under microslip from 3, else the constant) is fitted; per series, tau
//!    solves chi^2 = dof of that series ([`super::fit::extra_sd`]); fit and tau are iterated
//!    [`TAU_ROUNDS`] times. As Mallows' C_p takes sigma^2 from the largest model, every law is
//!    then judged with these weights.
//! 2. Every law with enough levels is fitted (the Iwan law under microslip and, from 4 levels,
//!    under macroslip with phi_max started at each of the upper amplitudes; the better AICc
//!    is kept).
//! 3. The choice: the smallest AICc = chi^2 + 2k + 2k(k+1)/(n-k-1) (n = 2 x levels data, k
//!    parameters; the small-sample form of Akaike's criterion, needed with a few levels); a
//!    law needs n - k - 1 >= 1. BIC and the Akaike weights are reported beside it. Only an
//!    eligible law is chosen ([`ineligible`]): its fit converged, the levels determine every
//!    parameter (a curve of as many parameters as levels interpolates them and has no
//!    standard errors), and its damping is physical (zeta_0 >= 0, zeta >= 0 at every level).
//!    The Akaike weights are shared among the eligible laws; when none is, the smallest AICc
//!    is chosen and every row says why it is not eligible.
//! 4. The band: the delta method, se(y(A))^2 = g^T C g, g = dy/dtheta, on a grid of
//!    amplitudes over the data's range.
//!
//! Imports: [`super::fit`], [`super::laws`].

use super::fit::{Fitted, Series, Weights, extra_sd, fit, raw_residuals};
use super::laws::{LAWS, Law, Regime};

/// Rounds of fit and extra-variance estimate.
pub const TAU_ROUNDS: usize = 6;
/// Points of a band.
pub const BAND_POINTS: usize = 41;

/// A law judged on one mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Judged {
    /// The fit.
    pub fitted: Fitted,
    /// Number of parameters k.
    pub k: usize,
    /// AICc.
    pub aicc: f64,
    /// BIC = chi^2 + k ln n.
    pub bic: f64,
    /// AICc minus the chosen law's (negative for an ineligible law of smaller AICc).
    pub delta_aicc: f64,
    /// Akaike weight exp(-delta/2) / sum over the eligible laws (0 for the others).
    pub weight: f64,
    /// Why the law may not be chosen, or None when it may ([`ineligible`]).
    pub ineligible: Option<String>,
}

/// A band point: a law's stiffness and damping at one amplitude, with standard errors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BandPoint {
    /// Amplitude (m).
    pub amplitude: f64,
    /// Modal stiffness.
    pub stiffness: f64,
    /// Its standard error (NaN when the covariance is not determined).
    pub stiffness_se: f64,
    /// Damping ratio.
    pub damping: f64,
    /// Its standard error.
    pub damping_se: f64,
}

/// One mode's laws and choice.
#[derive(Debug, Clone, PartialEq)]
pub struct ModeFit {
    /// Extra standard deviation of the stiffness ((rad/s)^2).
    pub tau_stiffness: f64,
    /// Extra standard deviation of the damping ratio.
    pub tau_damping: f64,
    /// The law whose fit set the weights.
    pub weights_from: Law,
    /// The laws fitted, in the order of [`LAWS`].
    pub laws: Vec<Judged>,
    /// The laws not fitted, with why.
    pub skipped: Vec<(Law, String)>,
    /// The chosen law (the smallest AICc of the eligible laws).
    pub selected: Law,
    /// The band of every fitted law, in the order of `laws`.
    pub bands: Vec<Vec<BandPoint>>,
}

/// Degrees of freedom the AICc needs: n - k - 1 >= 1.
fn enough(levels: usize, k: usize) -> bool {
    2 * levels >= k + 2
}

/// A straight line y = a + b x by unweighted least squares.
fn line(x: &[f64], y: &[f64]) -> (f64, f64) {
    let n = x.len() as f64;
    let (mx, my) = (x.iter().sum::<f64>() / n, y.iter().sum::<f64>() / n);
    let sxx: f64 = x.iter().map(|v| (v - mx) * (v - mx)).sum();
    let sxy: f64 = x.iter().zip(y).map(|(u, v)| (u - mx) * (v - my)).sum();
    let b = if sxx > 0.0 { sxy / sxx } else { 0.0 };
    (my - b * mx, b)
}

/// Starting points of `law` (on the amplitude scaled by its largest value) from straight
/// lines through the data.
fn starts(law: Law, data: &Series) -> Vec<Vec<f64>> {
    let top = data.amplitude.iter().fold(0.0_f64, |m, &a| m.max(a));
    let x: Vec<f64> = data.amplitude.iter().map(|a| a / top).collect();
    let (a0, a1) = line(&x, &data.stiffness);
    let (b0, b1) = line(&x, &data.damping);
    let a0 = if a0 > 0.0 {
        a0
    } else {
        data.stiffness[0].abs()
    };
    match law {
        Law::Constant => vec![vec![a0 + 0.5 * a1, b0 + 0.5 * b1]],
        Law::PowerLaw => [0.5, 1.0, 2.0]
            .iter()
            .map(|&b| vec![a0, -a1 / a0, b, b0, b1, b])
            .collect(),
        Law::Iwan => [-0.8, -0.5, -0.2]
            .iter()
            .map(|&chi: &f64| {
                let e = chi + 1.0;
                vec![a0, chi, (-a1).max(1e-6 * a0) * e * (e + 1.0), b0]
            })
            .collect(),
    }
}

/// The Iwan law under macroslip from a microslip fit: phi_max started at each amplitude of
/// the upper half (scaled).
fn macroslip_starts(micro: &Fitted, data: &Series) -> Vec<Vec<f64>> {
    let mut x: Vec<f64> = data.amplitude.iter().map(|a| a / micro.reference).collect();
    x.sort_by(f64::total_cmp);
    x[x.len() / 2..]
        .iter()
        .map(|&phi| {
            let mut s = micro.scaled.clone();
            s.push(phi * 0.999);
            s
        })
        .collect()
}

/// Fits `law` (both regimes for the Iwan law when the levels allow) with `weights`.
fn fit_law(law: Law, data: &Series, weights: &Weights) -> Option<Fitted> {
    let micro = fit(law, Regime::Microslip, data, weights, &starts(law, data))?;
    if law != Law::Iwan || !enough(data.len(), 5) {
        return Some(micro);
    }
    let macro_fit = fit(
        law,
        Regime::Macroslip,
        data,
        weights,
        &macroslip_starts(&micro, data),
    );
    let n = 2 * data.len();
    match macro_fit {
        Some(m) if aicc(m.chi2(), 5, n) < aicc(micro.chi2(), 4, n) => Some(m),
        _ => Some(micro),
    }
}

fn aicc(chi2: f64, k: usize, n: usize) -> f64 {
    let k = k as f64;
    chi2 + 2.0 * k + 2.0 * k * (k + 1.0) / (n as f64 - k - 1.0)
}

/// The extra variances from the most general law the levels allow (module docs, step 1).
fn extra_variances(data: &Series) -> (f64, f64, Law) {
    let general = if enough(data.len(), 6) {
        Law::PowerLaw
    } else if enough(data.len(), 4) {
        Law::Iwan
    } else {
        Law::Constant
    };
    // Parameters per series: the power law 3 each, the Iwan law 2 each (4 shared), the
    // constant 1 each.
    let per_series = match general {
        Law::PowerLaw => 3.0,
        Law::Iwan => 2.0,
        Law::Constant => 1.0,
    };
    let dof = data.len() as f64 - per_series;
    let (mut tau_k, mut tau_z) = (0.0, 0.0);
    for _ in 0..TAU_ROUNDS {
        let w = Weights::new(data, tau_k, tau_z);
        let Some(f) = fit(general, Regime::Microslip, data, &w, &starts(general, data)) else {
            break;
        };
        let (rk, rz) = raw_residuals(&f, data);
        tau_k = extra_sd(&rk, &data.stiffness_std, dof);
        tau_z = extra_sd(&rz, &data.damping_std, dof);
    }
    (tau_k, tau_z, general)
}

/// The band of a fitted law over the data's amplitudes (module docs, step 4).
fn band(f: &Fitted, data: &Series) -> Vec<BandPoint> {
    let lo = data.amplitude.iter().fold(f64::INFINITY, |m, &a| m.min(a));
    let hi = data.amplitude.iter().fold(0.0_f64, |m, &a| m.max(a));
    (0..BAND_POINTS)
        .map(|i| {
            let a = lo + (hi - lo) * i as f64 / (BAND_POINTS - 1) as f64;
            let e = f.evaluate(a);
            let se = |g: &[f64]| match &f.scaled_covariance {
                Some(c) => (0..g.len())
                    .map(|p| (0..g.len()).map(|q| g[p] * c[p][q] * g[q]).sum::<f64>())
                    .sum::<f64>()
                    .max(0.0)
                    .sqrt(),
                None => f64::NAN,
            };
            BandPoint {
                amplitude: a,
                stiffness: e.stiffness,
                stiffness_se: se(&e.d_stiffness),
                damping: e.damping,
                damping_se: se(&e.d_damping),
            }
        })
        .collect()
}

/// The parameters of the stiffness's own curve (the damping's own: 1, or the power law's 3).
fn stiffness_parameters(law: Law, regime: Regime) -> usize {
    match (law, regime) {
        (Law::Constant, _) => 1,
        (Law::PowerLaw, _) | (Law::Iwan, Regime::Microslip) => 3,
        (Law::Iwan, Regime::Macroslip) => 4,
    }
}

/// Why a fitted law may not be chosen (module docs, step 3), or None when it may.
pub fn ineligible(f: &Fitted, data: &Series) -> Option<String> {
    let levels = data.len();
    let curve = stiffness_parameters(f.law, f.regime);
    let damping = if f.law == Law::PowerLaw { 3 } else { 1 };
    let zeta_0 = f
        .law
        .parameters(f.regime)
        .iter()
        .position(|&n| n == "zeta_0");
    let determined = f
        .scaled_covariance
        .as_ref()
        .is_some_and(|c| (0..c.len()).all(|i| c[i][i].is_finite() && c[i][i] >= 0.0));
    if !f.converged {
        Some("its fit did not converge".to_string())
    } else if curve.max(damping) >= levels {
        Some(format!(
            "it interpolates the {levels} levels: {} parameters of one curve",
            curve.max(damping)
        ))
    } else if !determined {
        Some("the levels do not determine its parameters (no standard errors)".to_string())
    } else if let Some(z) = zeta_0.map(|i| f.parameters[i]).filter(|&z| z < 0.0) {
        Some(format!("zeta_0 = {z:.3e} < 0 is not physical"))
    } else if data.amplitude.iter().any(|&a| f.evaluate(a).damping < 0.0) {
        Some("its damping ratio is negative at a level".to_string())
    } else {
        None
    }
}

/// The law of smallest AICc among the eligible ones (all of them when none is), with every
/// law's delta AICc from it and the Akaike weights of the eligible laws.
fn choose(laws: &mut [Judged]) -> Law {
    let any = laws.iter().any(|j| j.ineligible.is_none());
    let counts = |j: &Judged| !any || j.ineligible.is_none();
    let Some(best) = laws
        .iter()
        .filter(|j| counts(j))
        .min_by(|a, b| a.aicc.total_cmp(&b.aicc))
        .map(|j| (j.aicc, j.fitted.law))
    else {
        return Law::Constant;
    };
    let weight = |j: &Judged| {
        if counts(j) {
            (-(j.aicc - best.0) / 2.0).exp()
        } else {
            0.0
        }
    };
    let total: f64 = laws.iter().map(weight).sum();
    for j in laws.iter_mut() {
        j.delta_aicc = j.aicc - best.0;
        j.weight = weight(j) / total;
    }
    best.1
}

/// Fits and judges every law on one mode's levels (module docs). At least two levels.
pub fn fit_mode(data: &Series) -> ModeFit {
    let (tau_stiffness, tau_damping, weights_from) = extra_variances(data);
    let weights = Weights::new(data, tau_stiffness, tau_damping);
    let n = 2 * data.len();
    let mut laws = Vec::new();
    let mut skipped = Vec::new();
    for law in LAWS {
        let k = law.parameters(Regime::Microslip).len();
        if !enough(data.len(), k) {
            let levels = k.div_ceil(2) + 1;
            skipped.push((law, format!("needs at least {levels} levels")));
            continue;
        }
        let Some(fitted) = fit_law(law, data, &weights) else {
            skipped.push((law, "no admissible start".to_string()));
            continue;
        };
        let k = fitted.parameters.len();
        laws.push(Judged {
            aicc: aicc(fitted.chi2(), k, n),
            bic: fitted.chi2() + k as f64 * (n as f64).ln(),
            k,
            delta_aicc: 0.0,
            weight: 0.0,
            ineligible: ineligible(&fitted, data),
            fitted,
        });
    }
    let selected = choose(&mut laws);
    let bands = laws.iter().map(|j| band(&j.fitted, data)).collect();
    ModeFit {
        tau_stiffness,
        tau_damping,
        weights_from,
        laws,
        skipped,
        selected,
        bands,
    }
}

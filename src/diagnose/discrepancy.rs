//! The error model of a fit: measurement error plus model discrepancy, the discrepancy
//! estimated with the fit.
//!
//! Every model of a real structure misses its modes by more than their measurement error. A
//! residual is taken as the sum of two independent errors: the measurement error, of known
//! standard deviation s_i (stated, or the data's own standard errors: module `fit`), and the
//! model's discrepancy, of unknown standard deviation tau per kind of quantity: tau_f for the
//! frequencies (relative to them), tau_s for the shape components (a fraction of each mode's
//! measured peak), one per mode where every mode has the sensors to estimate its own
//! ([`LEAST_MODE_DOF`]: a mode that only the structure's missing physics bends out of the beam
//! model's shapes then carries its own). The variance of residual i is v_i = s_i^2 + tau_k^2,
//! and the deviance
//!
//! ```text
//!   -2 ln L(theta, tau) = sum_i [ e_i(theta)^2 / v_i + ln v_i ]      (+ a constant)
//! ```
//!
//! is minimised over the model's unknowns theta and tau together (Beck & Yuen, "Model
//! selection using response measurements: Bayesian probabilistic approach", J. Eng. Mech.
//! 130, 2004: the prediction-error variance as a parameter of each model class; Kennedy &
//! O'Hagan, "Bayesian calibration of computer models", JRSS B 63, 2001, for the discrepancy as
//! a term of its own; Simoen, De Roeck & Lombaert, "Dealing with uncertainty in model
//! updating for damage assessment: a review", MSSP 56-57, 2015). [`fit_with`] alternates the two
//! blocks (from two starts of tau, the better end kept): the weighted least squares of theta under
//! the current tau (the fit of module `fit`, from the last optimum), then each tau^2 by its own
//! one-dimensional maximum likelihood given the residuals ([`variance`]); every step lowers the
//! deviance, and it stops when tau^2 moves by less than [`TOLERANCE`] of the total variance. Near a
//! discrepancy that the model's unknowns can trade against (a shape discrepancy falling towards 0
//! while the fit leans on the shapes) the alternation crawls, each step a few percent of the way:
//! every two steps are followed by the squared extrapolation of [`crate::optim::squared`] in the
//! variances, kept where its fit has the lower deviance ([`ROUNDS`] fits in all). A model that fits
//! within the measurement error keeps tau = 0 and its deviance is its chi^2 (plus the constant sum
//! ln s_i^2, the same for every model of the data): the error model changes nothing there.
//!
//! Each candidate's deviance at its optimum is its profile likelihood with tau as a nuisance
//! parameter: two models are compared by the difference of their deviances (module `search`),
//! each with its own discrepancy. Where tau was estimated, that comparison is the F test of
//! [`improvement`], kind by kind on the residuals each discrepancy was estimated on. A kind
//! whose residuals have less than [`LEAST_DOF`] degree of freedom left by the model's
//! unknowns ([`estimable`]: two frequencies and two joint parameters) has no discrepancy the
//! data could estimate: it is held at 0 and the report says so.

use super::fit::{
    Calibration, Discrepancy, FitError, Fitted, Residuals, measurement_sigmas, residuals,
    with_limits,
};
use crate::measured::MeasuredModes;
use crate::optim::squared;
use crate::stats::{self, Sample};

/// Largest number of refits of theta under a new tau.
pub const ROUNDS: usize = 12;
/// Converged when every tau^2 moves by less than this fraction of its kind's mean total
/// variance.
pub const TOLERANCE: f64 = 1e-2;

/// The squared residuals and measurement variances of one kind of quantity, in the units of
/// [`Discrepancy`] (relative frequencies; shape components per unit of their mode's peak).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Squares {
    /// (e_i^2, s_i^2) of every residual.
    pub pairs: Vec<(f64, f64)>,
}

impl Squares {
    /// The deviance sum [e^2 / (s^2 + t) + ln(s^2 + t)] at the discrepancy variance t.
    pub fn deviance(&self, t: f64) -> f64 {
        self.pairs
            .iter()
            .map(|&(e2, s2)| {
                let v = (s2 + t).max(f64::MIN_POSITIVE);
                e2 / v + v.ln()
            })
            .sum()
    }

    /// The first and second derivatives of [`Squares::deviance`] in t.
    fn derivatives(&self, t: f64) -> (f64, f64) {
        self.pairs.iter().fold((0.0, 0.0), |(d1, d2), &(e2, s2)| {
            let v = (s2 + t).max(f64::MIN_POSITIVE);
            (
                d1 + 1.0 / v - e2 / (v * v),
                d2 + 2.0 * e2 / (v * v * v) - 1.0 / (v * v),
            )
        })
    }

    /// Mean measurement variance.
    fn mean_variance(&self) -> f64 {
        self.pairs.iter().map(|p| p.1).sum::<f64>() / self.pairs.len().max(1) as f64
    }
}

/// The residuals of `fitted` split by kind: the frequencies, and the shapes mode by mode.
pub fn squares(
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> (Squares, Vec<Squares>) {
    squares_of(&residuals(fitted, measured), measured, calibration)
}

/// The residuals `res` split by kind (the shapes mode by mode), with the measurement
/// variances of `calibration`.
pub fn squares_of(
    res: &Residuals,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> (Squares, Vec<Squares>) {
    let (sigma_f, sigma) = measurement_sigmas(measured, calibration);
    let frequency = res
        .frequency
        .iter()
        .zip(&sigma_f)
        .map(|(e, s)| (e * e, s * s))
        .collect();
    let mut shapes = Vec::with_capacity(sigma.len());
    let mut at = 0;
    for (m, sigma) in measured.modes().iter().zip(&sigma) {
        let peak = m.peak().max(f64::MIN_POSITIVE);
        let mut pairs = Vec::with_capacity(sigma.len());
        for s in sigma {
            let e = res.shape[at].1;
            pairs.push((e * e, (s / peak).powi(2)));
            at += 1;
        }
        shapes.push(Squares { pairs });
    }
    (Squares { pairs: frequency }, shapes)
}

/// Every mode's shape squares together.
fn joined(shapes: &[Squares]) -> Squares {
    Squares {
        pairs: shapes
            .iter()
            .flat_map(|s| s.pairs.iter().copied())
            .collect(),
    }
}

/// The discrepancy variance t >= 0 that minimises [`Squares::deviance`]: the best of t = 0 and
/// a logarithmic grid from 1e-6 of the smallest measurement variance to twice the largest
/// squared residual, refined by golden sections around it (the deviance may have a local
/// minimum at 0 beside the global one when the measurement variances differ).
pub fn variance(squares: &Squares) -> f64 {
    let largest = squares.pairs.iter().fold(0.0_f64, |a, p| a.max(p.0));
    let smallest = squares
        .pairs
        .iter()
        .map(|p| p.1)
        .filter(|s| *s > 0.0)
        .fold(f64::INFINITY, f64::min);
    if squares.pairs.is_empty() || largest == 0.0 {
        return 0.0;
    }
    let (lo, hi) = (
        (1e-6 * smallest.min(largest)).ln(),
        (2.0 * largest)
            .ln()
            .max((1e-6 * smallest.min(largest)).ln() + 1.0),
    );
    const GRID: usize = 80;
    let step = (hi - lo) / GRID as f64;
    let at = |u: f64| squares.deviance(u.exp());
    let best = (0..=GRID)
        .map(|i| lo + step * i as f64)
        .min_by(|a, b| at(*a).total_cmp(&at(*b)))
        .unwrap_or(lo);
    let (mut a, mut b) = ((best - step).max(lo), (best + step).min(hi));
    let phi = 0.5 * (5.0_f64.sqrt() - 1.0);
    for _ in 0..60 {
        let (c, d) = (b - phi * (b - a), a + phi * (b - a));
        if at(c) < at(d) {
            b = d;
        } else {
            a = c;
        }
    }
    // Newton's steps on the derivative polish what the comparisons of a flat minimum leave
    // (about the square root of the rounding).
    let mut t = (0.5 * (a + b)).exp();
    for _ in 0..4 {
        let (slope, curvature) = squares.derivatives(t);
        if curvature.is_nan() || curvature <= 0.0 {
            break;
        }
        let next = t - slope / curvature;
        if next > 0.0 && squares.deviance(next) <= squares.deviance(t) {
            t = next;
        }
    }
    if squares.deviance(0.0) <= squares.deviance(t) {
        0.0
    } else {
        t
    }
}

/// Which discrepancies the data can estimate for a model: the frequencies', the shapes', and
/// the shapes' mode by mode.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Freedom {
    /// The frequencies' ([`LEAST_DOF`]).
    pub frequency: bool,
    /// The shapes' ([`LEAST_DOF`]).
    pub shape: bool,
    /// One per mode: every mode has [`LEAST_MODE_DOF`] shape degrees of freedom.
    pub per_mode: bool,
}

/// The discrepancy that maximises the likelihood of the residuals `squares` (frequencies,
/// shapes mode by mode), the model's unknowns held, where `freedom` lets it be estimated
/// (else 0).
fn most_likely((frequency, shapes): &(Squares, Vec<Squares>), freedom: Freedom) -> Discrepancy {
    let frequency = if freedom.frequency {
        variance(frequency).sqrt()
    } else {
        0.0
    };
    if !freedom.shape {
        return Discrepancy {
            frequency,
            ..Discrepancy::default()
        };
    }
    if freedom.per_mode {
        let modes: Vec<f64> = shapes.iter().map(|s| variance(s).sqrt()).collect();
        let shape = (modes.iter().map(|t| t * t).sum::<f64>() / modes.len().max(1) as f64).sqrt();
        return Discrepancy {
            frequency,
            shape,
            modes,
        };
    }
    Discrepancy {
        frequency,
        shape: variance(&joined(shapes)).sqrt(),
        modes: Vec::new(),
    }
}

/// The deviance of the residuals `squares` under the discrepancy `d`.
fn deviance_at((frequency, shapes): &(Squares, Vec<Squares>), d: &Discrepancy) -> f64 {
    frequency.deviance(d.frequency * d.frequency)
        + shapes
            .iter()
            .enumerate()
            .map(|(r, s)| s.deviance(d.shape_of(r).powi(2)))
            .sum::<f64>()
}

/// The discrepancy that maximises the likelihood of `fitted`'s residuals, its unknowns held.
pub fn estimate(
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> Discrepancy {
    most_likely(
        &squares(fitted, measured, calibration),
        freedom(fitted, measured),
    )
}

/// The deviance of `fitted`'s residuals with the discrepancy that maximises their likelihood,
/// its unknowns held: its profile over the discrepancy.
pub fn profile_deviance(
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> f64 {
    let squares = squares(fitted, measured, calibration);
    deviance_at(&squares, &most_likely(&squares, freedom(fitted, measured)))
}

/// Whether `next` is `current` to [`TOLERANCE`] of each kind's mean total variance (of each
/// mode's, one per mode).
fn settled(
    next: &Discrepancy,
    current: &Discrepancy,
    (frequency, shapes): &(Squares, Vec<Squares>),
) -> bool {
    let close = |a: f64, b: f64, s: &Squares| {
        (a * a - b * b).abs() <= TOLERANCE * (a * a + s.mean_variance()).max(f64::MIN_POSITIVE)
    };
    let all = joined(shapes);
    close(next.frequency, current.frequency, frequency)
        && close(next.shape, current.shape, &all)
        && shapes
            .iter()
            .enumerate()
            .all(|(r, s)| close(next.shape_of(r), current.shape_of(r), s))
}

/// The residual degrees of freedom of each kind in `fitted`: (frequencies, shapes), each its
/// values less its share of the unknowns (the shape scales are the shapes'; the model's
/// parameters are shared by count).
pub fn residual_dof(fitted: &Fitted, measured: &MeasuredModes) -> (f64, f64) {
    let n_f = measured.modes().len() as f64;
    let n_s: f64 = measured.modes().iter().map(|m| m.points.len() as f64).sum();
    let unknowns = fitted.estimates.len() as f64;
    let p_f = unknowns * n_f / (n_f + n_s);
    let p_s = n_f + unknowns * n_s / (n_f + n_s);
    (n_f - p_f, n_s - p_s)
}

/// Smallest residual degrees of freedom of a kind whose discrepancy is estimated: fewer, and
/// the data cannot tell a discrepancy from the fit's own freedom; the kind's discrepancy is
/// then held at 0 and the report says so, never guessed.
pub const LEAST_DOF: f64 = 1.0;

/// Smallest shape degrees of freedom of every mode for one discrepancy per mode (its values
/// less its scale and its share of the model's unknowns): with fewer (three or four sensors)
/// one discrepancy is shared by the shapes of all modes.
pub const LEAST_MODE_DOF: f64 = 3.0;

/// The shape degrees of freedom of every mode of `fitted` (module docs of [`LEAST_MODE_DOF`]).
fn mode_dof(fitted: &Fitted, measured: &MeasuredModes) -> Vec<f64> {
    let n_f = measured.modes().len() as f64;
    let n_s: f64 = measured.modes().iter().map(|m| m.points.len() as f64).sum();
    let unknowns = fitted.estimates.len() as f64;
    measured
        .modes()
        .iter()
        .map(|m| {
            let n = m.points.len() as f64;
            n - 1.0 - unknowns * n / (n_f + n_s)
        })
        .collect()
}

/// Which discrepancies the data can estimate in `fitted`.
pub fn freedom(fitted: &Fitted, measured: &MeasuredModes) -> Freedom {
    let (f, s) = residual_dof(fitted, measured);
    let shape = s >= LEAST_DOF;
    Freedom {
        frequency: f >= LEAST_DOF,
        shape,
        per_mode: shape
            && mode_dof(fitted, measured)
                .iter()
                .all(|d| *d >= LEAST_MODE_DOF),
    }
}

/// One kind of residual of an error model, with a discrepancy of its own: the frequencies,
/// the shapes of every mode together, or one mode's shape.
#[derive(Debug, Clone, Copy)]
enum Kind {
    Frequency,
    Shapes,
    Mode(usize),
}

/// The kinds of residual of `fitted`'s error model, each with the residuals its discrepancy
/// `d` was estimated on (`squares`: its residuals): their degrees of freedom n as the total
/// variance v = s^2 + tau^2 carries them (Satterthwaite: the measurement variance s^2 is
/// known, tau^2 estimated on n, so v has n (v / tau^2)^2: a discrepancy small beside the
/// measurement error leaves the variance nearly known), and their count (those degrees of
/// freedom plus the unknowns the kind absorbed); known where the discrepancy is 0 (the
/// measurement error alone).
fn kinds(
    fitted: &Fitted,
    measured: &MeasuredModes,
    (frequency, shapes): &(Squares, Vec<Squares>),
    d: &Discrepancy,
) -> Vec<(Kind, Sample)> {
    let (f, s) = residual_dof(fitted, measured);
    let carried = |tau: f64, n: f64, kind: &Squares| {
        let t = tau * tau;
        if t > 0.0 {
            let n = n.max(LEAST_DOF);
            let dof = n * ((kind.mean_variance() + t) / t).powi(2);
            Sample {
                dof,
                count: dof + (kind.pairs.len() as f64 - n).max(0.0),
            }
        } else {
            Sample::KNOWN
        }
    };
    let mut kinds = vec![(Kind::Frequency, carried(d.frequency, f, frequency))];
    if d.modes.is_empty() {
        kinds.push((Kind::Shapes, carried(d.shape, s, &joined(shapes))));
    } else {
        let per_mode = mode_dof(fitted, measured);
        kinds.extend(
            per_mode
                .iter()
                .zip(shapes)
                .enumerate()
                .map(|(r, (n, kind))| (Kind::Mode(r), carried(d.shape_of(r), *n, kind))),
        );
    }
    kinds
}

/// The chi^2 difference sum (e0_i^2 - e1_i^2) / v_i of the residuals of `kind` between
/// `before` and `after` (the same data, two models), each weighed by the smaller of the two
/// models' variances v_i = s_i^2 + tau^2 (`d0`, `d1` their discrepancies).
fn difference(
    kind: Kind,
    (f0, s0): &(Squares, Vec<Squares>),
    (f1, s1): &(Squares, Vec<Squares>),
    (d0, d1): (&Discrepancy, &Discrepancy),
) -> f64 {
    let sum = |a: &Squares, b: &Squares, tau: f64| -> f64 {
        a.pairs
            .iter()
            .zip(&b.pairs)
            .map(|(&(e0, s2), &(e1, _))| (e0 - e1) / (s2 + tau * tau).max(f64::MIN_POSITIVE))
            .sum()
    };
    let tau = |kind: Kind| tau_of(kind, d0).min(tau_of(kind, d1));
    let mode = |r: usize| sum(&s0[r], &s1[r], tau(Kind::Mode(r)));
    match kind {
        Kind::Frequency => sum(f0, f1, tau(kind)),
        Kind::Shapes => (0..s0.len()).map(mode).sum(),
        Kind::Mode(r) => mode(r),
    }
}

/// The discrepancy `d` gives `kind` (a standard deviation).
fn tau_of(kind: Kind, d: &Discrepancy) -> f64 {
    match kind {
        Kind::Frequency => d.frequency,
        Kind::Shapes => d.shape,
        Kind::Mode(r) => d.shape_of(r),
    }
}

/// Whether the larger model of `(d0, d1)` fits `kind` at least as closely as the smaller (its
/// discrepancy there no larger).
fn closer(kind: Kind, (d0, d1): (&Discrepancy, &Discrepancy)) -> bool {
    tau_of(kind, d1) <= tau_of(kind, d0)
}

/// The likelihood-ratio test of a model `larger` against `smaller`, a model it extends, both
/// fitted with their own discrepancies, as the statistic of an F test and its denominator's
/// degrees of freedom.
///
/// Per kind of `larger`'s error model (the frequencies; the shapes, or each mode's), the chi^2
/// difference of the two models' residuals under `larger`'s variances of that kind (its
/// maximum-likelihood estimate, or the measurement error alone) is read as
/// the classical F test's improvement over the kind's variance (`stats::improvement`: times
/// nu_k / n_k where the discrepancy was estimated on nu_k degrees of freedom of n_k residuals,
/// itself where it is known), and the kinds' improvements are summed. The sum's degrees of
/// freedom are the Welch-Satterthwaite combination (sum Delta_k)^2 / sum (Delta_k^2 / nu_k) of
/// the estimated kinds' (infinite when none was): each improvement is scaled by its own kind's
/// variance, so that one made in six frequencies is read on their few degrees of freedom, not
/// on the shapes' many. With one kind it is the classical F test, exactly, in the linear model.
///
/// Where the larger model fits a kind less closely than the smaller (a larger discrepancy
/// there: it gave up, say, the frequencies to fit the shapes), that kind is weighed by the
/// smaller model's variance, measured alone where the smaller fits it within the measurement
/// error: a model may not buy the variance its own loss is measured by.
/// Each model's discrepancy is taken as its residuals give it (the maximum likelihood of
/// each kind), also where its fit held it at 0 (residuals too few beside its unknowns, or a
/// refit that failed): under the measurement error alone, a misfit carried nowhere would make
/// any change of those residuals look significant.
pub fn improvement(
    smaller: &Fitted,
    larger: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> (f64, f64) {
    let before = squares(smaller, measured, calibration);
    let after = squares(larger, measured, calibration);
    // Each model's discrepancy as its residuals give it, also where the fit held it at 0.
    let of = |fitted: &Fitted, squares: &(Squares, Vec<Squares>)| {
        let freedom = Freedom {
            frequency: true,
            shape: true,
            per_mode: !fitted.discrepancy.modes.is_empty(),
        };
        most_likely(squares, freedom)
    };
    let (d0, d1) = (of(smaller, &before), of(larger, &after));
    combined(
        kinds(larger, measured, &after, &d1)
            .into_iter()
            .map(|(kind, sample)| {
                let d = difference(kind, &before, &after, (&d0, &d1));
                let known = !closer(kind, (&d0, &d1)) && known_on(kind, &d0);
                (d, if known { Sample::KNOWN } else { sample })
            }),
    )
}

/// Whether discrepancy `d` is zero on `kind`.
fn known_on(kind: Kind, d: &Discrepancy) -> bool {
    tau_of(kind, d) == 0.0
}

/// The kinds' chi^2 differences and samples `parts` combined as [`improvement`] says: the
/// sum of their improvements (at least 0) and its Welch-Satterthwaite degrees of freedom.
fn combined(parts: impl Iterator<Item = (f64, Sample)>) -> (f64, f64) {
    let (mut total, mut spread) = (0.0, 0.0);
    for (d, sample) in parts {
        let delta = stats::improvement(d, sample);
        total += delta;
        if sample.dof.is_finite() {
            spread += delta * delta / sample.dof;
        }
    }
    let dof = if spread > 0.0 {
        total * total / spread
    } else {
        f64::INFINITY
    };
    (total.max(0.0), dof)
}

/// A model fitted with its own discrepancy (module docs): `fit` fits the model's unknowns
/// under a calibration, from an earlier optimum when given (None: its own start). The
/// alternation runs from two starts of the discrepancy, `start` (the joint-only fit's, for a
/// candidate: most candidates leave much of it) and zero (the measurement error alone), and
/// the fit of least deviance is kept: the deviance over (theta, tau) can have two basins, one
/// where a large discrepancy hides what an effect would explain in the frequencies, one where
/// the effect is fitted and the discrepancy small, and each start finds its own. The returned
/// fit carries its discrepancy, its deviance under it, the discrepancy's degrees of freedom
/// and its joints' limits (module `fit`'s `limits`).
pub fn fit_with(
    measured: &MeasuredModes,
    calibration: &Calibration,
    start: Discrepancy,
    fit: impl FnMut(&Calibration, Option<&Fitted>) -> Result<Fitted, FitError>,
) -> Result<Fitted, FitError> {
    fit_from_starts(measured, calibration, start, true, fit)
}

/// As [`fit_with`], from the discrepancy `start` alone: for a model whose every evaluation
/// solves each mode again at its own frequency (the frequency-dependent joint), where a second
/// alternation would double the candidate's cost.
pub fn fit_with_start(
    measured: &MeasuredModes,
    calibration: &Calibration,
    start: Discrepancy,
    fit: impl FnMut(&Calibration, Option<&Fitted>) -> Result<Fitted, FitError>,
) -> Result<Fitted, FitError> {
    fit_from_starts(measured, calibration, start, false, fit)
}

/// The alternation from `start`, and from zero too when `both` (module docs of [`fit_with`]);
/// the fit of least deviance with its joints' limits.
fn fit_from_starts(
    measured: &MeasuredModes,
    calibration: &Calibration,
    start: Discrepancy,
    both: bool,
    mut fit: impl FnMut(&Calibration, Option<&Fitted>) -> Result<Fitted, FitError>,
) -> Result<Fitted, FitError> {
    let single = start.is_zero() || !both;
    let first = alternate(measured, calibration, start, &mut fit);
    let kept = if single {
        first?
    } else {
        let second = alternate(measured, calibration, Discrepancy::default(), &mut fit);
        match (first, second) {
            (Ok(a), Ok(b)) => {
                if b.deviance < a.deviance {
                    b
                } else {
                    a
                }
            }
            (Ok(a), Err(_)) => a,
            (Err(_), Ok(b)) => b,
            (Err(e), Err(_)) => return Err(e),
        }
    };
    let under = Calibration {
        discrepancy: kept.discrepancy.clone(),
        ..calibration.clone()
    };
    Ok(with_limits(kept, measured, &under))
}

/// The alternation of [`fit_with`] from the discrepancy `start`.
fn alternate(
    measured: &MeasuredModes,
    calibration: &Calibration,
    start: Discrepancy,
    fit: &mut impl FnMut(&Calibration, Option<&Fitted>) -> Result<Fitted, FitError>,
) -> Result<Fitted, FitError> {
    let mut current = Calibration {
        discrepancy: start.clone(),
        ..calibration.clone()
    };
    let mut fitted = fit(&current, None)?;
    let freedom = freedom(&fitted, measured);
    // What the data cannot estimate is held at 0 from the start; one discrepancy per mode
    // where they can estimate that, else one for the shapes of all modes.
    let held = Discrepancy {
        frequency: if freedom.frequency {
            start.frequency
        } else {
            0.0
        },
        shape: if freedom.shape { start.shape } else { 0.0 },
        modes: if freedom.shape && freedom.per_mode {
            (0..measured.modes().len())
                .map(|r| start.shape_of(r))
                .collect()
        } else {
            Vec::new()
        },
    };
    if held != start {
        current.discrepancy = held;
        fitted = fit(&current, None)?;
    }
    let mut rounds = 0;
    while rounds < ROUNDS {
        let now = squares(&fitted, measured, calibration);
        let next = most_likely(&now, freedom);
        if settled(&next, &current.discrepancy, &now) {
            break;
        }
        let before = std::mem::replace(&mut current.discrepancy, next);
        match fit(&current, Some(&fitted)) {
            Ok(next) => fitted = next,
            // A refit that fails under the new discrepancy leaves the last one: a fit of the
            // model under the discrepancy before, whose deviance is its own.
            Err(_) => {
                current.discrepancy = before;
                break;
            }
        }
        rounds += 1;
        // The two steps before -> current -> further, extrapolated (module docs).
        let after = squares(&fitted, measured, calibration);
        let further = most_likely(&after, freedom);
        if rounds == ROUNDS || settled(&further, &current.discrepancy, &after) {
            continue;
        }
        let of = |d: &Discrepancy| variances(d, freedom);
        let Some(x) =
            squared::extrapolate(&of(&before), &of(&current.discrepancy), &of(&further), 0.0)
        else {
            continue;
        };
        let jump = Calibration {
            discrepancy: from_variances(&x, freedom),
            ..calibration.clone()
        };
        if let Ok(jumped) = fit(&jump, Some(&fitted)) {
            rounds += 1;
            if jumped.deviance <= fitted.deviance {
                (current, fitted) = (jump, jumped);
            }
        }
    }
    Ok(fitted)
}

/// The variances of `d` as one vector, for the extrapolation of [`alternate`]: the
/// frequencies', then the shapes' (one per mode where `freedom` has them, else the shared one).
fn variances(d: &Discrepancy, freedom: Freedom) -> Vec<f64> {
    let mut x = vec![d.frequency * d.frequency];
    if freedom.per_mode {
        x.extend(d.modes.iter().map(|t| t * t));
    } else {
        x.push(d.shape * d.shape);
    }
    x
}

/// The discrepancy of the variances `x` of [`variances`].
fn from_variances(x: &[f64], freedom: Freedom) -> Discrepancy {
    let tau = |v: &f64| v.max(0.0).sqrt();
    let shapes = &x[1..];
    let shape = if freedom.per_mode {
        (shapes.iter().map(|v| v.max(0.0)).sum::<f64>() / shapes.len().max(1) as f64).sqrt()
    } else {
        shapes.first().map_or(0.0, tau)
    };
    Discrepancy {
        frequency: tau(&x[0]),
        shape,
        modes: if freedom.per_mode {
            shapes.iter().map(tau).collect()
        } else {
            Vec::new()
        },
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Kinds combined: one estimated kind is its own F test; an improvement made in a kind of
    /// few degrees of freedom is read on them, whatever kinds of many beside it did not move;
    /// known kinds add their differences as chi-square and leave the scale known.
    #[test]
    fn an_improvement_is_read_on_the_degrees_of_freedom_of_the_kinds_that_made_it() {
        let frequencies = Sample {
            dof: 5.0,
            count: 6.0,
        };
        let shapes = Sample {
            dof: 40.0,
            count: 48.0,
        };
        // Six frequencies whose variance falls 27-fold: chi^2 156 under the larger model's
        // maximum-likelihood variance, 130 under its unbiased one.
        let d = 6.0 * 26.0;
        let (alone, dof) = combined([(d, frequencies)].into_iter());
        assert!((alone - 26.0 * 5.0).abs() < 1e-9 * alone && dof == 5.0);
        let (with_shapes, dof) = combined([(d, frequencies), (0.0, shapes)].into_iter());
        assert_eq!((with_shapes, dof), (alone, 5.0));
        // Two kinds improved alike: their degrees of freedom add.
        let (_, both) = combined([(6.0, frequencies), (6.0, frequencies)].into_iter());
        assert!((both - 10.0).abs() < 1e-12);
        let (known, dof) = combined([(9.0, Sample::KNOWN), (3.0, Sample::KNOWN)].into_iter());
        assert_eq!((known, dof), (12.0, f64::INFINITY));
        // A model that fits worse is no evidence.
        assert_eq!(combined([(-4.0, frequencies)].into_iter()).0, 0.0);
    }

    /// Residuals of equal measurement variance s^2: the maximum likelihood of t is
    /// mean(e^2) - s^2 when positive, else 0.
    #[test]
    fn the_variance_is_the_excess_of_the_mean_square() {
        let s2 = 1e-6;
        let e: [f64; 6] = [3e-3, -2e-3, 1e-3, 4e-3, -1e-3, 2e-3];
        let squares = Squares {
            pairs: e.iter().map(|e| (e * e, s2)).collect(),
        };
        let mean = e.iter().map(|e| e * e).sum::<f64>() / 6.0;
        let t = variance(&squares);
        assert!(
            (t - (mean - s2)).abs() < 1e-9 * mean,
            "{t} vs {}",
            mean - s2
        );
        let within = Squares {
            pairs: e.iter().map(|e| (0.1 * e * e, 1e-5)).collect(),
        };
        assert_eq!(variance(&within), 0.0);
        assert_eq!(variance(&Squares::default()), 0.0);
    }

    /// Unequal measurement variances: the estimate is where the derivative of the deviance,
    /// sum [1 / v - e^2 / v^2], vanishes, and no point of a fine grid has a lower deviance.
    #[test]
    fn the_variance_minimises_the_deviance_with_unequal_errors() {
        let squares = Squares {
            pairs: vec![
                (4e-4, 1e-6),
                (1e-4, 1e-4),
                (9e-4, 1e-8),
                (2e-5, 4e-4),
                (5e-4, 1e-6),
            ],
        };
        let t = variance(&squares);
        assert!(t > 0.0);
        let slope: f64 = squares
            .pairs
            .iter()
            .map(|&(e2, s2)| 1.0 / (s2 + t) - e2 / (s2 + t).powi(2))
            .sum();
        let curvature: f64 = squares
            .pairs
            .iter()
            .map(|&(e2, s2)| 2.0 * e2 / (s2 + t).powi(3) - 1.0 / (s2 + t).powi(2))
            .sum();
        assert!(
            (slope / curvature).abs() < 1e-8 * t,
            "{slope} {curvature} {t}"
        );
        let at = squares.deviance(t);
        for i in 0..2000 {
            let u = 1e-9 * 1.02_f64.powi(i);
            assert!(squares.deviance(u) >= at - 1e-12 * at.abs(), "{u}");
        }
    }
}

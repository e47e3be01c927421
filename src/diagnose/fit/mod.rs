//! Calibration of the model on all measured modes at once: weighted nonlinear least squares of
//! every joint's k1, k2 (the invariant joint of the paper's references [9, 10]) and, for a
//! candidate, of the effect's parameters, by Levenberg-Marquardt, the eigenproblem re-solved at
//! every step.
//!
//! Residuals, for measured mode r paired with model mode s (weights fixed by the stated noise
//! on the measured values, so that chi^2 = |residual|^2 has the chi-square distribution when
//! the model is right):
//!
//! ```text
//!   frequency:  (f_s - f_r^m) / (sigma_f f_r^m)
//!   shape:      (c_r y_s(j) - y_r^m(j)) / sigma_j,
//!               sigma_j = sigma_s sqrt(y_r^m(j)^2 + (SHAPE_FLOOR max_j |y_r^m|)^2)
//! ```
//! c_r is a fitted scale per mode (measured shapes have any normalisation). The floor keeps the
//! components near a node of the mode, whose multiplicative error vanishes, from dominating.
//! Unknowns: x = ln(p / p_0) for the joints (they stay positive), theta / scale for the
//! effects (kept in the effect's feasible region: non-negative where it must be, within its
//! inequalities, module [`crate::optim::bounds`]), and c_r.
//!
//! The solver is [`crate::optim::lm`]'s, with the pairing fixed (re-paired after convergence,
//! and solved again if the pairing changed); converged when a full Gauss-Newton step would
//! lower chi^2 by less than 1e-8 of it (an absolute 1e-8 below chi^2 = 1), or when no step
//! lowers it (a minimum, or one on a bound); not converged after [`MAX_ITERATIONS`]. A trial point that is inadmissible (`Configured::admissible`) or
//! has no eigensolution is a step too long. The standard errors come from (J^T J)^-1 at the
//! optimum, formed as R^-1 R^-T from a QR of J ([`crate::optim::lstsq::inverse_gram`]).

mod limits;

pub use limits::{BOUND_CHI2, FREE, RIGID, ranges, structural_scale};

use std::sync::atomic::{AtomicUsize, Ordering};
use std::sync::{Arc, Mutex, PoisonError};

use faer::Mat;

use super::pairing::{Pairing, PairingRule, Unpaired, pair};
use super::sensitivity::ModeDerivatives;
use crate::measured::MeasuredModes;
use crate::modal::{ModalError, ModalSolution};
use crate::model::effects::{Configured, Effect, EffectContext};
use crate::optim::{self, Bounds, LevenbergMarquardt, Observer, Progress, Termination};
use crate::structure::reduced::Reduced;
use crate::structure::{Parameter, Structure};

/// Floor of the shape standard deviation, as a fraction of the mode's largest component.
pub const SHAPE_FLOOR: f64 = 0.02;
/// Largest number of Levenberg-Marquardt iterations.
pub const MAX_ITERATIONS: usize = 200;
/// Converged when a full Gauss-Newton step would lower chi^2 by less than this fraction of it
/// (of 1 for chi^2 below 1).
const DECREMENT_TOLERANCE: f64 = 1e-8;

/// The stated measurement noise: relative standard deviations.
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Noise {
    /// Of every measured frequency.
    pub frequency: f64,
    /// Of every measured shape component.
    pub shape: f64,
}

/// The model discrepancy of an error model: what a model misses beyond the measurement error,
/// as standard deviations added in quadrature to it (module `discrepancy`).
#[derive(Debug, Clone, Default, PartialEq, serde::Serialize)]
pub struct Discrepancy {
    /// Of every frequency, relative to it (the model's f / f_meas - 1).
    pub frequency: f64,
    /// Of every shape component, as a fraction of its mode's measured peak (with one per mode:
    /// their root mean square).
    pub shape: f64,
    /// Per measured mode, that of its shape components, where every mode has the values to
    /// estimate its own (empty: `shape` for every mode).
    #[serde(skip_serializing_if = "Vec::is_empty")]
    pub modes: Vec<f64>,
}

impl Discrepancy {
    /// Of the shape components of measured mode `r`.
    pub fn shape_of(&self, r: usize) -> f64 {
        self.modes.get(r).copied().unwrap_or(self.shape)
    }

    /// Whether it is zero.
    pub fn is_zero(&self) -> bool {
        self.frequency == 0.0 && self.shape == 0.0 && self.modes.iter().all(|t| *t == 0.0)
    }
}

/// What a calibration needs besides the model and the data.
#[derive(Debug, Clone, PartialEq)]
pub struct Calibration {
    /// The stated measurement noise.
    pub noise: Noise,
    /// The model discrepancy added to the measurement error in the weights (zero: the
    /// measurement error alone).
    pub discrepancy: Discrepancy,
    /// How measured modes pair with model modes.
    pub pairing: PairingRule,
    /// Floor of the shape standard deviation, as a fraction of the mode's largest component
    /// ([`SHAPE_FLOOR`] unless estimated from the data).
    pub shape_floor: f64,
    /// Weigh by the data's own standard errors (`frequency_std`, `value_std`) where every
    /// mode carries them ([`MeasuredModes::has_std`]), in place of `noise` and `shape_floor`.
    pub measured_std: bool,
}

/// The standard deviations of the residuals: the measurement error ([`measurement_sigmas`])
/// and the calibration's model discrepancy, in quadrature: per mode, of the frequency relative
/// to it, and of each shape component.
pub fn sigmas(measured: &MeasuredModes, calibration: &Calibration) -> (Vec<f64>, Vec<Vec<f64>>) {
    let (mut sigma_f, mut sigma) = measurement_sigmas(measured, calibration);
    let d = &calibration.discrepancy;
    for (r, ((f, s), m)) in sigma_f
        .iter_mut()
        .zip(&mut sigma)
        .zip(measured.modes())
        .enumerate()
    {
        *f = f.hypot(d.frequency);
        let floor = d.shape_of(r) * m.peak();
        s.iter_mut().for_each(|v| *v = v.hypot(floor));
    }
    (sigma_f, sigma)
}

/// The standard deviations of the measurement error: per mode, of the frequency relative to
/// it, and of each shape component. From the data's standard errors when `calibration` says so
/// and the data carry them ([`crate::measured::MeasuredMode::value_sigmas`]); else from the
/// stated noise: sigma_f, and sigma_s sqrt(u^2 + (floor peak)^2) (module docs).
pub fn measurement_sigmas(
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> (Vec<f64>, Vec<Vec<f64>>) {
    let data = calibration.measured_std && measured.has_std();
    let noise = calibration.noise;
    measured
        .modes()
        .iter()
        .map(|m| match (data, m.frequency_std, m.value_sigmas()) {
            (true, Some(f_std), Some(v_sigma)) => (f_std / m.frequency_hz, v_sigma),
            _ => {
                let peak = m.peak();
                (
                    noise.frequency,
                    m.values
                        .iter()
                        .map(|v| {
                            noise.shape * (v * v + (calibration.shape_floor * peak).powi(2)).sqrt()
                        })
                        .collect(),
                )
            }
        })
        .unzip()
}

/// Why a fit failed.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FitError {
    /// A measured mode resembles no model mode.
    #[error(transparent)]
    Unpaired(#[from] Unpaired),
    /// A fitted model has no eigensolution.
    #[error("the fitted model has no eigensolution")]
    Modal(#[from] ModalError),
    /// More unknowns than data.
    #[error(
        "{data} measured values cannot determine {parameters} unknowns: measure more modes or more DOFs"
    )]
    TooFewData {
        /// Measured values (frequencies and shape components).
        data: usize,
        /// Unknowns (joint and effect parameters, one scale per mode).
        parameters: usize,
    },
    /// A mode of the frequency-dependent joint found no frequency equal to the one its joint
    /// is evaluated at.
    #[error(
        "measured mode {mode}: the frequency at which the joint is evaluated did not settle on the mode's own frequency in {iterations} iterations (last relative change {change:.1e}): the frequency-dependent joint is refused there (the dependence is too strong for one self-consistent mode)"
    )]
    NotSelfConsistent {
        /// The measured mode.
        mode: usize,
        /// Iterations done.
        iterations: usize,
        /// The last |ln F(u) - u|.
        change: f64,
    },
    /// Levenberg-Marquardt did not converge.
    #[error("the fit{with} did not converge in {iterations} iterations (chi^2 {chi2:.4e}): the data may be inconsistent with the model (check mode numbering, units and the stated noise)", with = if effect.is_empty() { String::new() } else { format!(" with {effect}") })]
    NotConverged {
        /// Effect fitted, if any.
        effect: String,
        /// Iterations done.
        iterations: usize,
        /// Last chi^2.
        chi2: f64,
    },
}

/// A fitted parameter with its standard error.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct Estimate {
    /// Name (`k1`, `joint_mass.m`, ...).
    pub name: String,
    /// Unit.
    pub unit: &'static str,
    /// Fitted value.
    pub value: f64,
    /// Standard error (linearised at the optimum, under the fit's error model).
    pub se: f64,
    /// The limit the parameter runs to, when the data cannot tell it from that limit (a
    /// rigid joint, a glued interface): `value` is then where the fit stopped, and the limit
    /// says the bound the data do set.
    #[serde(skip_serializing_if = "Option::is_none")]
    pub limit: Option<Limit>,
}

/// A joint parameter the data cannot tell from one of its limits (module `limits`).
#[derive(Debug, Clone, Copy, PartialEq, serde::Serialize)]
pub struct Limit {
    /// Which limit.
    pub kind: LimitKind,
    /// The value the data set as a one-sided bound: at least this (rigid) or at most this
    /// (free), at 95% (chi^2 up by 3.84 from the limit's).
    pub bound: f64,
}

/// The limit of a stiffness.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "lowercase")]
pub enum LimitKind {
    /// Infinitely stiff: the parts it joins move as one.
    Rigid,
    /// Zero: the parts it joins are free of each other in its direction.
    Free,
}

/// The outcome of a fit.
#[derive(Debug, Clone)]
pub struct Fitted {
    /// The fitted model (joints and effect parameters).
    pub configured: Configured,
    /// Its eigensolution.
    pub modal: ModalSolution,
    /// Measured-to-model mode pairing at the optimum.
    pub pairing: Pairing,
    /// chi^2 at the optimum.
    pub chi2: f64,
    /// Data minus unknowns.
    pub dof: usize,
    /// Joint parameters, then effect parameters.
    pub estimates: Vec<Estimate>,
    /// Iterations used.
    pub iterations: usize,
    /// The fitted scale c_r of every measured mode's model shape.
    pub scales: Vec<f64>,
    /// Per measured mode, the model it is read from when that is not `modal`'s structure
    /// (the frequency-dependent joint: the joint evaluated at the mode's own frequency);
    /// empty when every mode is read from `modal`.
    pub own: Vec<OwnModel>,
    /// The model discrepancy the fit was made under (module `discrepancy`).
    pub discrepancy: Discrepancy,
    /// The deviance under that error model, sum [r^2 + ln v] over the data, v the variance of
    /// each residual in the units of [`Residuals`]: chi^2 plus a term that depends on the
    /// discrepancy alone.
    pub deviance: f64,
    /// The optimum in the fit's own unknowns (a start for a refit).
    pub(crate) solution: Vec<f64>,
}

/// The model one measured mode is read from when it is not the fit's one model.
#[derive(Debug, Clone)]
pub struct OwnModel {
    /// The structure, its joint evaluated for this mode.
    pub structure: Structure,
    /// Its eigensolution.
    pub modal: ModalSolution,
}

impl Fitted {
    /// The eigensolution measured mode `r` is read from.
    pub fn modal_of(&self, r: usize) -> &ModalSolution {
        self.own.get(r).map_or(&self.modal, |o| &o.modal)
    }

    /// The structure measured mode `r` is read from.
    pub fn structure_of(&self, r: usize) -> &Structure {
        self.own
            .get(r)
            .map_or(&self.configured.structure, |o| &o.structure)
    }
}

struct Problem<'a> {
    ctx: &'a Arc<EffectContext>,
    measured: &'a MeasuredModes,
    pairing: &'a PairingRule,
    effects: Vec<(Arc<dyn Effect>, Vec<f64>)>,
    joint_p0: Vec<f64>,
    /// The interval of every joint unknown x = ln(p / p0) (module `limits`).
    ranges: Vec<(f64, f64)>,
    /// Per measured mode, sigma of its frequency relative to it.
    sigma_f: Vec<f64>,
    /// Per measured mode, sigma of each shape component.
    sigma: Vec<Vec<f64>>,
    /// The discrepancy in the weights.
    discrepancy: Discrepancy,
    /// Pairs the last eigensolution needed to cover the pairing window: the next one starts
    /// there instead of doubling up from the minimum again.
    covering: AtomicUsize,
    /// The reduced model as the last solve enriched it (none: the structure's own), for the
    /// next solves: the fit's evaluations run one after the other, so the basis each one
    /// solves on does not depend on the number of threads.
    enriched: Mutex<Option<Arc<Reduced>>>,
}

struct Evaluation {
    configured: Configured,
    modal: ModalSolution,
    residual: Vec<f64>,
}

impl<'a> Problem<'a> {
    fn new(
        ctx: &'a Arc<EffectContext>,
        measured: &'a MeasuredModes,
        calibration: &'a Calibration,
        effects: &[Arc<dyn Effect>],
    ) -> Self {
        let (sigma_f, sigma) = sigmas(measured, calibration);
        Problem {
            ctx,
            measured,
            pairing: &calibration.pairing,
            effects: effects
                .iter()
                .map(|e| (e.clone(), vec![0.0; e.parameters(ctx).len()]))
                .collect(),
            sigma_f,
            sigma,
            joint_p0: ctx.structure.identified().iter().map(|p| p.value).collect(),
            ranges: ranges(&ctx.structure),
            discrepancy: calibration.discrepancy.clone(),
            covering: AtomicUsize::new(0),
            enriched: Mutex::new(None),
        }
    }

    fn joint_count(&self) -> usize {
        self.joint_p0.len()
    }

    fn effect_count(&self) -> usize {
        self.effects.iter().map(|(_, t)| t.len()).sum()
    }

    fn scales(&self) -> Vec<f64> {
        self.effects
            .iter()
            .flat_map(|(e, _)| e.parameters(self.ctx).into_iter().map(|p| p.scale))
            .collect()
    }

    fn configured(&self, x: &[f64]) -> Configured {
        let j = self.joint_count();
        let delta: Vec<f64> = self
            .joint_p0
            .iter()
            .zip(x)
            .map(|(p, xi)| p * xi.exp() - p)
            .collect();
        let structure = self.ctx.structure.with_delta(&delta);
        let scales = self.scales();
        let mut at = j;
        let effects = self
            .effects
            .iter()
            .map(|(e, t)| {
                let theta = (0..t.len())
                    .map(|k| scales[at - j + k] * x[at + k])
                    .collect();
                at += t.len();
                (e.clone(), theta)
            })
            .collect();
        Configured {
            ctx: self.ctx.clone(),
            structure,
            effects,
        }
    }

    fn rigid(&self) -> usize {
        self.ctx.structure.rigid
    }

    /// The model modes the pairing can reach: every mode up to (1 + window) times the highest
    /// measured frequency and at least those paired by number (all of them for a model solved
    /// densely, see [`ModalSolution::covering`]).
    /// On the structure's reduced model when it carries one (the enriched one of an earlier
    /// solve of this fit if any), else in full.
    fn modes(&self, configured: &mut Configured) -> Result<ModalSolution, ModalError> {
        let modes = self.measured.modes();
        let given = self.pairing.given.iter().map(|g| g.1).max().unwrap_or(0);
        let count = self.rigid() + modes.len().max(given) + 2;
        let f_max = modes.iter().map(|m| m.frequency_hz).fold(0.0, f64::max);
        let start = count.max(self.covering.load(Ordering::Relaxed));
        let mut enriched = self.enriched.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(reduced) = enriched.as_ref() {
            configured.structure.reduced = Some(Arc::clone(reduced));
        }
        let window = (1.0 + self.pairing.window) * f_max;
        let (modal, next) = configured.covering(start, window, count)?;
        if let Some(next) = next {
            configured.structure.reduced = Some(Arc::clone(&next));
            *enriched = Some(next);
        }
        self.covering.store(modal.len(), Ordering::Relaxed);
        Ok(modal)
    }

    /// Residuals at x, with the pairing fixed; model shapes signed to agree with the data.
    fn evaluate(&self, x: &[f64], pairing: &Pairing) -> Result<Evaluation, ModalError> {
        let mut configured = self.configured(x);
        let modal = self.modes(&mut configured)?;
        let scale_at = self.joint_count() + self.effect_count();
        let y = modal.vectors();
        let mut residual = Vec::new();
        for (r, m) in self.measured.modes().iter().enumerate() {
            let s = pairing.model_index[r];
            residual.push(
                (modal.frequency_hz(s) - m.frequency_hz) / (self.sigma_f[r] * m.frequency_hz),
            );
            let sign = model_sign(&modal, s, m);
            for ((p, &v), &sigma) in m.points.iter().zip(&m.values).zip(&self.sigma[r]) {
                residual.push((x[scale_at + r] * sign * p.read_column(y, s) - v) / sigma);
            }
        }
        Ok(Evaluation {
            configured,
            modal,
            residual,
        })
    }

    /// d residual / dx (rows: residuals; columns: unknowns).
    fn jacobian(&self, x: &[f64], eval: &Evaluation, pairing: &Pairing) -> Mat<f64> {
        let params: Vec<(Parameter, f64)> = eval
            .configured
            .structure
            .identified()
            .into_iter()
            .map(|p| {
                let v = p.value;
                (p, v)
            })
            .chain(
                eval.configured
                    .effect_parameters()
                    .into_iter()
                    .zip(self.scales()),
            )
            .collect();
        let mats = ModeDerivatives::needs_matrices(&eval.modal).then(|| eval.configured.assemble());
        let derivatives = ModeDerivatives::of_solution(mats.as_ref(), &eval.modal);
        let pairs: Vec<_> = params
            .iter()
            .map(|(p, _)| (&p.stiffness, &p.mass))
            .collect();
        let unknowns = x.len();
        let rows = eval.residual.len();
        let scale_at = self.joint_count() + self.effect_count();
        let mut jac = Mat::zeros(rows, unknowns);
        let mut row = 0;
        let reads: Vec<Vec<&[(usize, f64)]>> = self
            .measured
            .modes()
            .iter()
            .map(|m| m.points.iter().map(|p| p.terms.as_slice()).collect())
            .collect();
        let all = derivatives.read(&pairing.model_index, &pairs, &reads);
        for ((r, m), of_mode) in self.measured.modes().iter().enumerate().zip(all) {
            let s = pairing.model_index[r];
            let sign = model_sign(&eval.modal, s, m);
            let f = eval.modal.frequency_hz(s);
            let chains = params.iter().map(|(_, chain)| chain);
            for (col, (chain, (d_lambda, read))) in chains.zip(of_mode).enumerate() {
                let df = d_lambda
                    / (8.0
                        * std::f64::consts::PI
                        * std::f64::consts::PI
                        * f.max(f64::MIN_POSITIVE));
                jac[(row, col)] = chain * df / (self.sigma_f[r] * m.frequency_hz);
                for (k, (dc, &sigma)) in read.iter().zip(&self.sigma[r]).enumerate() {
                    jac[(row + 1 + k, col)] = chain * x[scale_at + r] * sign * dc / sigma;
                }
            }
            for (k, (p, &sigma)) in m.points.iter().zip(&self.sigma[r]).enumerate() {
                jac[(row + 1 + k, scale_at + r)] =
                    sign * p.read_column(eval.modal.vectors(), s) / sigma;
            }
            row += 1 + m.points.len();
        }
        jac
    }

    /// The joints' ranges (module `limits`), the effects' non-negative parameters and their
    /// inequalities ([`Effect::inequalities`]) on the unknowns theta / scale.
    fn bounds(&self) -> Bounds {
        let mut at = self.joint_count();
        let mut rows = Vec::new();
        for (e, _) in &self.effects {
            let params = e.parameters(self.ctx);
            for (k, p) in params.iter().enumerate() {
                if p.non_negative {
                    rows.push(vec![(at + k, 1.0)]);
                }
            }
            for row in e.inequalities(self.ctx) {
                rows.push(
                    row.into_iter()
                        .map(|(k, c)| (at + k, c * params[k].scale))
                        .collect(),
                );
            }
            at += params.len();
        }
        self.ranges
            .iter()
            .enumerate()
            .fold(Bounds::new(rows), |b, (j, &(lo, hi))| {
                b.with_interval(j, lo, hi)
            })
    }
}

/// +1 or -1: the sign that makes model mode `s` agree with the measured shape.
pub(crate) fn model_sign(
    modal: &ModalSolution,
    s: usize,
    m: &crate::measured::MeasuredMode,
) -> f64 {
    let dot: f64 = m
        .points
        .iter()
        .zip(&m.values)
        .map(|(p, v)| p.read_column(modal.vectors(), s) * v)
        .sum();
    if dot < 0.0 { -1.0 } else { 1.0 }
}

/// The unweighted residuals of a fit: relative frequency errors (f_s - f_m) / f_m, and per
/// shape component (u, e) with u the measured value and e = c_r y_s - u, both divided by the
/// mode's measured peak.
#[derive(Debug, Clone, PartialEq)]
pub struct Residuals {
    /// Relative frequency residual of every measured mode.
    pub frequency: Vec<f64>,
    /// (measured component, residual) of every shape value, per unit peak.
    pub shape: Vec<(f64, f64)>,
}

/// The unweighted residuals of `fitted` on `measured`.
pub fn residuals(fitted: &Fitted, measured: &MeasuredModes) -> Residuals {
    let mut out = Residuals {
        frequency: Vec::new(),
        shape: Vec::new(),
    };
    for (r, m) in measured.modes().iter().enumerate() {
        let s = fitted.pairing.model_index[r];
        let modal = fitted.modal_of(r);
        let y = modal.vectors();
        out.frequency
            .push((modal.frequency_hz(s) - m.frequency_hz) / m.frequency_hz);
        let sign = model_sign(modal, s, m);
        let peak = m.peak().max(f64::MIN_POSITIVE);
        for (p, &v) in m.points.iter().zip(&m.values) {
            let e = fitted.scales[r] * sign * p.read_column(y, s) - v;
            out.shape.push((v / peak, e / peak));
        }
    }
    out
}

/// chi^2 of the unweighted residuals `res` under the standard deviations of `calibration`
/// ([`sigmas`]).
pub fn chi2_of(res: &Residuals, measured: &MeasuredModes, calibration: &Calibration) -> f64 {
    let (sigma_f, sigma) = sigmas(measured, calibration);
    let frequency: f64 = res
        .frequency
        .iter()
        .zip(&sigma_f)
        .map(|(e, s)| (e / s).powi(2))
        .sum();
    let mut shape = 0.0;
    let mut at = 0;
    for (m, sigma) in measured.modes().iter().zip(&sigma) {
        let peak = m.peak().max(f64::MIN_POSITIVE);
        for s in sigma {
            shape += (res.shape[at].1 * peak / s).powi(2);
            at += 1;
        }
    }
    frequency + shape
}

/// The deviance of a fit whose weighted residuals give `chi2` under the standard deviations
/// `sigma_f` (relative, per mode) and `sigma` (per shape component), in the units of
/// [`Residuals`] (the shapes per unit of their mode's peak): chi2 + sum ln v.
pub(crate) fn deviance(
    chi2: f64,
    measured: &MeasuredModes,
    sigma_f: &[f64],
    sigma: &[Vec<f64>],
) -> f64 {
    let mut log = 0.0;
    for ((m, f), s) in measured.modes().iter().zip(sigma_f).zip(sigma) {
        let peak = m.peak().max(f64::MIN_POSITIVE);
        log += 2.0 * f.max(f64::MIN_POSITIVE).ln();
        log += s
            .iter()
            .map(|v| 2.0 * (v / peak).max(f64::MIN_POSITIVE).ln())
            .sum::<f64>();
    }
    chi2 + log
}

pub(crate) fn chi2(r: &[f64]) -> f64 {
    r.iter().map(|v| v * v).sum()
}

/// The model as given (`ctx.model`, no effect), only the shape scales c_r fitted: the
/// starting point, described in the same terms as a fit.
pub fn as_given(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> Result<Fitted, FitError> {
    run(ctx, measured, calibration, &[], None, None)
}

/// Fits the joints of `ctx.model` (and the parameters of `effects`, starting at zero) to the
/// measured modes, `observer` told every iteration (numbered on across the re-pairings).
pub fn fit(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    effects: &[Arc<dyn Effect>],
    observer: &mut dyn Observer,
) -> Result<Fitted, FitError> {
    run(ctx, measured, calibration, effects, Some(observer), None)
}

/// As [`fit`], starting from `from`, an optimum of the same model under another calibration
/// (the noise only: the same unknowns), which it reaches again in a few steps.
pub fn refit(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    effects: &[Arc<dyn Effect>],
    from: &Fitted,
    observer: &mut dyn Observer,
) -> Result<Fitted, FitError> {
    run(
        ctx,
        measured,
        calibration,
        effects,
        Some(observer),
        Some(&from.solution),
    )
}

/// As [`fit`], from the unknowns `x0` (joints, effects, shape scales: the layout of
/// [`Fitted::solution`] with the effects' parameters appended in order; without the shape
/// scales, they are solved for the start).
pub fn fit_from(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    effects: &[Arc<dyn Effect>],
    x0: &[f64],
    observer: &mut dyn Observer,
) -> Result<Fitted, FitError> {
    run(
        ctx,
        measured,
        calibration,
        effects,
        Some(observer),
        Some(x0),
    )
}

/// The start of a fit that extends `from` by `added` unknowns appended after its effects'
/// (zero: the extension absent), before the shape scales.
pub fn extended(from: &Fitted, added: usize) -> Vec<f64> {
    let at = from.solution.len() - from.scales.len();
    let mut x = from.solution[..at].to_vec();
    x.extend(std::iter::repeat_n(0.0, added));
    x.extend(&from.scales);
    x
}

/// `fitted` (a fit of its own configuration's effects under `calibration`) with the joints
/// that the data cannot tell from a limit marked ([`Estimate::limit`], module `limits`).
pub fn with_limits(
    mut fitted: Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> Fitted {
    if !fitted.own.is_empty() {
        // The frequency-dependent joint's modes are read from their own models.
        return fitted;
    }
    let effects: Vec<Arc<dyn Effect>> = fitted
        .configured
        .effects
        .iter()
        .map(|(e, _)| e.clone())
        .collect();
    let ctx = fitted.configured.ctx.clone();
    let problem = Problem::new(&ctx, measured, calibration, &effects);
    let Ok(eval) = problem.evaluate(&fitted.solution, &fitted.pairing) else {
        return fitted;
    };
    let jac = problem.jacobian(&fitted.solution, &eval, &fitted.pairing);
    let covariance = covariance(jac.as_ref(), fitted.solution.len());
    let at = chi2(&eval.residual);
    for (i, e) in fitted
        .estimates
        .iter_mut()
        .take(problem.joint_count())
        .enumerate()
    {
        let se = covariance[(i, i)].max(0.0).sqrt();
        e.limit = limits::limit(&problem, &fitted.solution, &fitted.pairing, i, at, se);
    }
    fitted
}

/// chi^2 under `calibration` of the model of `fitted` refitted under it to first order: one
/// Gauss-Newton step of all its unknowns from `fitted`'s optimum (made under another
/// calibration), the bounds set aside (the step can only lower the value); None for a model
/// whose modes are read from their own models (the frequency-dependent joint) or that has no
/// eigensolution there.
pub fn refitted_chi2(
    fitted: &Fitted,
    measured: &MeasuredModes,
    calibration: &Calibration,
) -> Option<f64> {
    if !fitted.own.is_empty() {
        return None;
    }
    let effects: Vec<Arc<dyn Effect>> = fitted
        .configured
        .effects
        .iter()
        .map(|(e, _)| e.clone())
        .collect();
    let ctx = fitted.configured.ctx.clone();
    let problem = Problem::new(&ctx, measured, calibration, &effects);
    let eval = problem.evaluate(&fitted.solution, &fitted.pairing).ok()?;
    let jac = problem.jacobian(&fitted.solution, &eval, &fitted.pairing);
    let r = Mat::from_fn(eval.residual.len(), 1, |i, _| -eval.residual[i]);
    let step = optim::lstsq::solve(jac.as_ref(), r.as_ref());
    let fitted_part = &jac * &step.x;
    let after: f64 = (0..eval.residual.len())
        .map(|i| (eval.residual[i] + fitted_part[(i, 0)]).powi(2))
        .sum();
    Some(after.min(chi2(&eval.residual)))
}

/// An observer told the iterations of one Levenberg-Marquardt run after `before` of earlier
/// runs, numbered on from them.
struct NumberedOn<'o> {
    observer: &'o mut dyn Observer,
    before: usize,
}

impl Observer for NumberedOn<'_> {
    fn observe(&mut self, progress: &Progress) {
        self.observer.observe(&Progress {
            iteration: self.before + progress.iteration,
            ..*progress
        });
    }
}

/// The fit of `effects` with the joints, from `from` or from zero; with no `observer`, the
/// starting point evaluated, not iterated ([`as_given`]).
fn run(
    ctx: &Arc<EffectContext>,
    measured: &MeasuredModes,
    calibration: &Calibration,
    effects: &[Arc<dyn Effect>],
    observer: Option<&mut dyn Observer>,
    from: Option<&[f64]>,
) -> Result<Fitted, FitError> {
    let problem = Problem::new(ctx, measured, calibration, effects);
    let unknowns = problem.joint_count() + problem.effect_count() + measured.modes().len();
    let data: usize = measured.modes().iter().map(|m| 1 + m.points.len()).sum();
    if data <= unknowns {
        return Err(FitError::TooFewData {
            data,
            parameters: unknowns,
        });
    }
    let name = effects
        .iter()
        .map(|e| e.name())
        .collect::<Vec<_>>()
        .join(" + ");
    // A start with the shape scales, or one without them (the model's unknowns only: the
    // scales are then solved for it).
    let modes = measured.modes().len();
    let given = from.filter(|x0| x0.len() == unknowns || x0.len() + modes == unknowns);
    let mut x = match given {
        Some(x0) => {
            let mut x = x0.to_vec();
            x.resize(unknowns, 0.0);
            // Inside the bounds (a start from another optimum may lie outside this model's
            // ranges).
            problem.bounds().project(x.clone()).unwrap_or(x)
        }
        None => vec![0.0; unknowns],
    };
    let mut start = problem.configured(&x);
    let start_modal = problem.modes(&mut start)?;
    let mut pairing = pair(&start_modal, measured, problem.rigid(), problem.pairing)?;
    if given.is_none_or(|x0| x0.len() < unknowns) {
        initial_scales(&problem, &start_modal, &pairing, &mut x);
    }
    let Some(observer) = observer else {
        let eval = problem.evaluate(&x, &pairing)?;
        let dof = data - measured.modes().len();
        return Ok(finish(&problem, x, eval, pairing, 0, dof));
    };
    let mut total_iterations = 0;
    let mut last_chi2 = f64::INFINITY;
    // Levenberg-Marquardt; once converged, re-pair with the fitted model and go on if the
    // pairing changed (a mode swap the nominal model hid).
    let solver = solver();
    for _ in 0..3 {
        let fixed = Paired {
            problem: &problem,
            pairing: &pairing,
        };
        let mut numbered = NumberedOn {
            observer: &mut *observer,
            before: total_iterations,
        };
        let solution = solver.minimise_observed(&fixed, x, &mut numbered)?;
        if solution.termination == Termination::MaxIterations {
            return Err(FitError::NotConverged {
                effect: name,
                iterations: solution.iterations,
                chi2: solution.cost,
            });
        }
        x = solution.x;
        total_iterations += solution.iterations;
        let eval = problem.evaluate(&x, &pairing)?;
        last_chi2 = chi2(&eval.residual);
        let repaired = pair(&eval.modal, measured, problem.rigid(), problem.pairing)?;
        if repaired.model_index == pairing.model_index {
            return Ok(finish(
                &problem,
                x,
                eval,
                repaired,
                total_iterations,
                data - unknowns,
            ));
        }
        pairing = repaired;
        initial_scales(&problem, &eval.modal, &pairing, &mut x);
    }
    Err(FitError::NotConverged {
        effect: name,
        iterations: total_iterations,
        chi2: last_chi2,
    })
}

/// c_r by weighted least squares of the measured shape on the paired model shape.
fn initial_scales(problem: &Problem, modal: &ModalSolution, pairing: &Pairing, x: &mut [f64]) {
    let at = problem.joint_count() + problem.effect_count();
    for (r, m) in problem.measured.modes().iter().enumerate() {
        let s = pairing.model_index[r];
        let sign = model_sign(modal, s, m);
        let (mut num, mut den) = (0.0, 0.0);
        for ((p, &v), &sigma) in m.points.iter().zip(&m.values).zip(&problem.sigma[r]) {
            let yhat = sign * p.read_column(modal.vectors(), s);
            num += yhat * v / (sigma * sigma);
            den += yhat * yhat / (sigma * sigma);
        }
        x[at + r] = num / den;
    }
}

/// The fit with its pairing fixed, as the solver sees it.
struct Paired<'p, 'a> {
    problem: &'p Problem<'a>,
    pairing: &'p Pairing,
}

impl optim::Problem for Paired<'_, '_> {
    type State = Evaluation;
    type Error = ModalError;

    fn evaluate(&self, x: &[f64]) -> Result<Evaluation, ModalError> {
        self.problem.evaluate(x, self.pairing)
    }

    fn cost(&self, state: &Evaluation) -> f64 {
        chi2(&state.residual)
    }

    fn linearise(&self, x: &[f64], state: &Evaluation) -> optim::Linearisation {
        optim::Linearisation::Jacobian {
            residual: state.residual.clone(),
            jacobian: self.problem.jacobian(x, state, self.pairing),
        }
    }

    fn bounds(&self) -> Bounds {
        self.problem.bounds()
    }

    fn admissible(&self, x: &[f64]) -> bool {
        self.problem.configured(x).admissible()
    }
}

/// (J^T J)^-1 of the n unknowns from the R of a QR of `jac`; infinite variances when J has
/// a dependent column.
pub(crate) fn covariance(jac: faer::MatRef<'_, f64>, n: usize) -> Mat<f64> {
    optim::lstsq::inverse_gram(jac)
        .unwrap_or_else(|| Mat::from_fn(n, n, |i, j| if i == j { f64::INFINITY } else { 0.0 }))
}

/// The identified joint parameters of `structure` with their standard errors, the first
/// unknowns of `covariance` being x_j = ln(p_j / p_j0).
pub(crate) fn joint_estimates(structure: &Structure, covariance: &Mat<f64>) -> Vec<Estimate> {
    structure
        .identified()
        .iter()
        .enumerate()
        .map(|(i, p)| Estimate {
            name: p.name.clone(),
            unit: p.unit,
            value: p.value,
            se: p.value * covariance[(i, i)].max(0.0).sqrt(),
            limit: None,
        })
        .collect()
}

/// The fit's solver (module docs).
pub(crate) fn solver() -> LevenbergMarquardt {
    LevenbergMarquardt::new(MAX_ITERATIONS)
        .and_then(|s| s.with_decrement(DECREMENT_TOLERANCE))
        .expect("the fit's settings are within the solver's ranges")
}

fn finish(
    problem: &Problem,
    x: Vec<f64>,
    eval: Evaluation,
    pairing: Pairing,
    iterations: usize,
    dof: usize,
) -> Fitted {
    let jac = problem.jacobian(&x, &eval, &pairing);
    let n = x.len();
    // (J^T J)^-1 from the R of a QR of J; infinite variances when J has a dependent column.
    let covariance = covariance(jac.as_ref(), n);
    let chi2 = chi2(&eval.residual);
    let mut estimates = joint_estimates(&eval.configured.structure, &covariance);
    let j = problem.joint_count();
    let scales = problem.scales();
    for (k, p) in eval.configured.effect_parameters().iter().enumerate() {
        estimates.push(Estimate {
            name: p.name.clone(),
            unit: p.unit,
            value: p.value,
            se: scales[k] * covariance[(j + k, j + k)].max(0.0).sqrt(),
            limit: None,
        });
    }
    let scales = x[j + problem.effect_count()..].to_vec();
    let deviance = deviance(chi2, problem.measured, &problem.sigma_f, &problem.sigma);
    Fitted {
        discrepancy: problem.discrepancy.clone(),
        deviance,
        scales,
        solution: x,
        configured: eval.configured,
        modal: eval.modal,
        own: Vec::new(),
        pairing,
        chi2,
        dof,
        estimates,
        iterations,
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;
    use crate::model::effects::by_name;
    use crate::model::fixtures::paper_model;
    use crate::simulate::{Errors, simulate};
    use crate::structure::Observation;
    use crate::study::NoiseKind;

    /// Paper case I (k1 1e7, k2 1e4) with shear 0.5, its first four modes at every other DOF
    /// with 0.1% / 2% noise (seed 3): the data, the nominal modes, the effects' context and a
    /// calibration (floor 0.01), for derivative tests.
    pub(crate) fn fixture() -> (
        MeasuredModes,
        ModalSolution,
        Arc<EffectContext>,
        Calibration,
    ) {
        let model = paper_model(1e7, 1e4);
        let dofs: Vec<Observation> = (0..38)
            .step_by(2)
            .map(|d| Observation::dof(&model.dofs, d))
            .collect();
        let errors = Errors {
            shape: 0.02,
            frequency: 0.001,
            kind: NoiseKind::Gaussian,
            seed: 3,
        };
        let measured = simulate(
            &model,
            &[("shear".into(), 0.5)],
            &[1, 2, 3, 4],
            &dofs,
            errors,
        )
        .unwrap();
        let nominal = ModalSolution::solve(&model.assemble()).unwrap();
        let ctx = Arc::new(EffectContext::new(
            model.clone(),
            &dofs,
            nominal.frequency_hz(2),
        ));
        let calibration = Calibration {
            noise: Noise {
                frequency: 0.001,
                shape: 0.02,
            },
            discrepancy: Discrepancy::default(),
            pairing: PairingRule::default(),
            shape_floor: 0.01,
            measured_std: false,
        };
        (measured, nominal, ctx, calibration)
    }

    /// The observer of a fit sees every iteration once, numbered from 1 on to the fit's count,
    /// the last at the fit's chi^2; a second Levenberg-Marquardt run (after a re-pairing)
    /// numbers on from the first.
    #[test]
    fn a_fit_tells_its_iterations_numbered_on() {
        struct Seen(Vec<(usize, f64)>);
        impl Observer for Seen {
            fn observe(&mut self, p: &Progress) {
                self.0.push((p.iteration, p.cost));
            }
        }
        let (measured, _, ctx, calibration) = fixture();
        let mut seen = Seen(Vec::new());
        let shear = [by_name("shear").unwrap()];
        let fitted = fit(&ctx, &measured, &calibration, &shear, &mut seen).unwrap();
        let numbers: Vec<usize> = seen.0.iter().map(|s| s.0).collect();
        assert!(fitted.iterations > 1);
        assert_eq!(numbers, (1..=fitted.iterations).collect::<Vec<_>>());
        // The fit's chi^2 is the cost of its last iterate, evaluated again: the same bits.
        let last = seen.0.last().unwrap().1;
        assert_eq!(
            last.to_bits(),
            fitted.chi2.to_bits(),
            "{last} vs {}",
            fitted.chi2
        );

        let mut second = NumberedOn {
            observer: &mut seen,
            before: 4,
        };
        second.observe(&Progress {
            iteration: 2,
            cost: 7.0,
            mu: 1e-3,
            accepted: true,
            trials: 1,
        });
        assert_eq!(seen.0.last(), Some(&(6, 7.0)));
    }

    /// The residual Jacobian (eigen-derivatives, chain rules of ln p and theta / scale, the
    /// shape scales) against central differences of the residuals, at a point away from zero.
    #[test]
    fn residual_jacobian_matches_central_differences() {
        let (measured, nominal, ctx, calibration) = fixture();
        let effects = ["joint_mass", "shear", "joint_coupling"].map(|n| by_name(n).unwrap());
        let problem = Problem::new(&ctx, &measured, &calibration, &effects);
        let rule = &calibration.pairing;
        // joints; joint_mass (m, J), shear, joint_coupling; four shape scales.
        let x = vec![0.1, -0.2, 2.0, 0.5, 0.4, 0.3, 0.9, 1.1, 1.0, 0.95];
        let pairing = pair(&nominal, &measured, 2, rule).unwrap();
        let eval = problem.evaluate(&x, &pairing).unwrap();
        let jac = problem.jacobian(&x, &eval, &pairing);
        // Eigenvalues are accurate to about eps * lambda_max (2e-3 here) in absolute terms: the
        // step must be large for the difference quotient, small for its truncation error.
        // The joint's rotary inertia (column 3) moves the residuals by 0.02 per unit, a weak
        // and nearly linear effect: its quotient needs a longer step to rise above round-off.
        for col in 0..x.len() {
            let h = if col == 3 { 0.3 } else { 1e-3 };
            let at = |sign: f64| {
                let mut t = x.clone();
                t[col] += sign * h;
                problem.evaluate(&t, &pairing).unwrap().residual
            };
            let (plus, minus) = (at(1.0), at(-1.0));
            let scale = (0..plus.len())
                .map(|r| jac[(r, col)].abs())
                .fold(0.0, f64::max);
            for r in 0..plus.len() {
                let fd = (plus[r] - minus[r]) / (2.0 * h);
                assert!(
                    (fd - jac[(r, col)]).abs() < 1e-5 * scale,
                    "column {col}, row {r}: {fd} vs {}",
                    jac[(r, col)]
                );
            }
        }
    }
}

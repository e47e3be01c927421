//! The paper's question as a fitted model: does the joint's stiffness change with the
//! frequency of the mode?
//!
//! Every identified joint parameter follows
//!
//! ```text
//!   p_j(f) = p_j0 (f / f_ref)^alpha_j,   f_ref the geometric mean of the measured frequencies,
//! ```
//!
//! and measured mode r is the pair its calibrated-joint pairing names of the structure with
//! the joint at p(f_r), f_r that pair's own frequency: a self-consistent solution per mode
//! (module `own`: Newton's iteration on ln f; a mode that does not settle refuses the fit
//! with the reason). The weighted nonlinear least squares over (p_j0, alpha, the shape
//! scales) is the calibration's (same residuals, weights and solver,
//! [`crate::diagnose::fit`]), with analytic derivatives through the self-consistent
//! frequency (module `problem`); alpha = 0 is the invariant joint, its start.
//!
//! Two variants: one alpha shared by every joint parameter, and one per parameter (when the
//! joint has more than one). The per-parameter one is kept when its likelihood-ratio
//! statistic over the shared one is significant at [`crate::diagnose::ALPHA`] by the
//! diagnosis's own test (F under an estimated noise scale, chi-square under a known one); the
//! candidate's description says which the data support. Its fitted model (the joint at
//! f_ref, each mode read from its own solution: [`Fitted::own`]) is the diagnosis's "after"
//! when it is selected.

mod own;
mod problem;

pub use problem::ALPHA_MAX;

use super::{Candidate, CandidateError, Fit, Stage, Tier};
use crate::diagnose::decide::ALPHA;
use crate::diagnose::discrepancy;
use crate::diagnose::fit::{self, Calibration, Discrepancy, Estimate, FitError, Fitted, OwnModel};
use crate::diagnose::progress::Iterations;
use crate::diagnose::report::Verdict;
use crate::modal::reduced;
use crate::model::effects::{Configured, EffectContext};
use crate::optim::Termination;
use crate::stats::lr_sf;
use problem::{Problem, State};

/// Name of the frequency-dependent joint among the candidates.
pub const NAME: &str = "frequency_dependence";

/// The frequency-dependent joint as a candidate (see the module docs).
#[derive(Debug, Clone, Copy)]
pub struct FrequencyDependence;

impl Candidate for FrequencyDependence {
    fn name(&self) -> &'static str {
        NAME
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "every joint parameter p scales as p0 (f / f_ref)^alpha, f_ref the geometric mean of the measured frequencies, each mode solved with the joint at its own frequency; alpha shared, or one per parameter when the data support it; size = alpha (the mean of the alphas)"
    }

    fn applies(&self, ctx: &EffectContext) -> bool {
        !ctx.structure.identified().is_empty()
    }

    fn verdict(&self) -> Verdict {
        Verdict::FrequencyDependent
    }

    /// Both variants fitted, each with its own discrepancy, the one the data support kept.
    fn fit(&self, stage: &Stage) -> Result<Fit, CandidateError> {
        let joints = stage.base.estimates.len();
        let shared = fit_variant(stage, false, None)?;
        let per = (joints > 1)
            .then(|| {
                let from = spread(&shared.fitted.solution, joints);
                fit_variant(stage, true, Some(from))
            })
            .and_then(Result::ok);
        let comparison = per.as_ref().map(|p| {
            let lrt = (shared.fitted.deviance - p.fitted.deviance).max(0.0);
            let (statistic, dof) = discrepancy::improvement(
                &shared.fitted,
                &p.fitted,
                stage.measured,
                stage.calibration,
            );
            (lrt, lr_sf(statistic, joints - 1, dof, false))
        });
        let per_supported = comparison.is_some_and(|(_, p)| p < ALPHA);
        let words = match comparison {
            Some((lrt, p)) => format!(
                "one alpha per parameter against one shared: LR {lrt:.1} on {} dof, p = {p:.2e}: the data support {}",
                joints - 1,
                if per_supported {
                    "one per parameter"
                } else {
                    "one shared"
                }
            ),
            None => "one alpha (one joint parameter)".to_string(),
        };
        let chosen = match per {
            Some(p) if per_supported => p,
            _ => shared,
        };
        let fitted = chosen.fitted;
        let describe = format!(
            "every joint parameter p scales as p0 (f / {:.4e} Hz)^alpha, each mode solved with the joint at its own frequency; {words}",
            chosen.reference_hz
        );
        let added = chosen.alphas.len();
        Ok(Fit::of_model(
            stage.measured,
            fitted,
            chosen.alphas,
            chosen.size,
            describe,
            added,
            None,
        ))
    }
}

/// One variant fitted.
struct Variant {
    fitted: Fitted,
    /// The alphas, with standard errors.
    alphas: Vec<Estimate>,
    /// The mean of the alphas and its standard error.
    size: (f64, f64),
    /// f_ref, Hz.
    reference_hz: f64,
}

/// The shared variant's optimum `x` with its alpha given to each of `joints` parameters.
fn spread(x: &[f64], joints: usize) -> Vec<f64> {
    let alpha = x[joints];
    [&x[..joints], &vec![alpha; joints], &x[joints + 1..]].concat()
}

/// The variant (`per_parameter` or shared alpha) fitted on `stage` with its own discrepancy
/// (module `discrepancy`, from none: a joint that does change with frequency fits to the
/// measurement error, and a start at the joint-only fit's discrepancy can settle short of it),
/// from `from`, or from the stage's calibrated joint with alpha = 0.
fn fit_variant(
    stage: &Stage,
    per_parameter: bool,
    from: Option<Vec<f64>>,
) -> Result<Variant, FitError> {
    let mut last = None;
    let fitted = discrepancy::fit_with_start(
        stage.measured,
        stage.calibration,
        Discrepancy::default(),
        |calibration, earlier| {
            let x = earlier.map(|f| f.solution.clone()).or_else(|| from.clone());
            // The fit is handed on, not copied: its solutions are N x pairs per mode.
            let Variant {
                fitted,
                alphas,
                size,
                reference_hz,
            } = fit_under(stage, calibration, per_parameter, x)?;
            last = Some((alphas, size, reference_hz));
            Ok(fitted)
        },
    )?;
    let (alphas, size, reference_hz) = last.expect("a fit that succeeded made a variant");
    Ok(Variant {
        fitted,
        alphas,
        size,
        reference_hz,
    })
}

/// The variant fitted under `calibration` from `from`, or from the stage's calibrated joint
/// with alpha = 0.
fn fit_under(
    stage: &Stage,
    calibration: &Calibration,
    per_parameter: bool,
    from: Option<Vec<f64>>,
) -> Result<Variant, FitError> {
    let (ctx, measured, base) = (stage.ctx, stage.measured, stage.base);
    let pairing = &base.pairing;
    let problem = Problem::new(ctx, measured, calibration, pairing, per_parameter);
    let unknowns = problem.unknowns();
    let data: usize = measured.modes().iter().map(|m| 1 + m.points.len()).sum();
    if data <= unknowns {
        return Err(FitError::TooFewData {
            data,
            parameters: unknowns,
        });
    }
    let joints = problem.joints();
    let x = from.filter(|x| x.len() == unknowns).unwrap_or_else(|| {
        let mut x = base.solution[..joints].to_vec();
        x.extend(std::iter::repeat_n(0.0, problem.alphas));
        x.extend(&base.scales);
        x
    });
    let mut told = Iterations {
        watch: stage.watch,
        candidate: NAME,
        variant: Some(if per_parameter {
            "one alpha per parameter"
        } else {
            "one alpha"
        }),
    };
    let solution = fit::solver().minimise_observed(&problem, x, &mut told)?;
    if solution.termination == Termination::MaxIterations {
        return Err(FitError::NotConverged {
            effect: NAME.into(),
            iterations: solution.iterations,
            chi2: solution.cost,
        });
    }
    finish(&problem, solution.x, solution.state, solution.iterations)
}

/// The fitted model at the optimum x: the joint at f_ref as its structure, every mode's own
/// solution, the estimates with standard errors from (J^T J)^-1.
fn finish(
    problem: &Problem,
    x: Vec<f64>,
    state: State,
    iterations: usize,
) -> Result<Variant, FitError> {
    let (joints, alphas) = (problem.joints(), problem.alphas);
    let n = x.len();
    let jac = problem.jacobian(&x, &state);
    let covariance = fit::covariance(jac.as_ref(), n);
    let (q0, _) = problem.law(&x);
    let values: Vec<f64> = q0.iter().map(|q| q.exp()).collect();
    let structure = problem.ctx.structure.with_values(&values);
    let modal = reduced::lowest(&structure, &[], problem.count())?;
    let params = structure.identified();
    let mut estimates = fit::joint_estimates(&structure, &covariance);
    let alpha_estimates: Vec<Estimate> = (0..alphas)
        .map(|a| Estimate {
            name: if alphas == 1 {
                format!("{NAME}.alpha")
            } else {
                format!("{NAME}.alpha.{}", params[a].name)
            },
            unit: "1",
            value: x[joints + a],
            se: covariance[(joints + a, joints + a)].max(0.0).sqrt(),
            limit: None,
        })
        .collect();
    estimates.extend(alpha_estimates.iter().cloned());
    let mean = x[joints..joints + alphas].iter().sum::<f64>() / alphas as f64;
    let variance: f64 = (joints..joints + alphas)
        .flat_map(|a| (joints..joints + alphas).map(move |b| (a, b)))
        .map(|(a, b)| covariance[(a, b)])
        .sum::<f64>()
        / (alphas * alphas) as f64;
    let data = state.residual.len();
    let own = state
        .modes
        .into_iter()
        .map(|sv| OwnModel {
            structure: sv.structure,
            modal: sv.modal,
        })
        .collect();
    let chi2 = fit::chi2(&state.residual);
    let fitted = Fitted {
        discrepancy: problem.discrepancy.clone(),
        deviance: problem.deviance(chi2),
        configured: Configured {
            ctx: problem.ctx.clone(),
            structure,
            effects: Vec::new(),
        },
        modal,
        own,
        pairing: problem.pairing.clone(),
        chi2,
        dof: data - n,
        estimates,
        iterations,
        scales: x[joints + alphas..].to_vec(),
        solution: x,
    };
    Ok(Variant {
        fitted,
        alphas: alpha_estimates,
        size: (mean, variance.max(0.0).sqrt()),
        reference_hz: problem.log_ref.exp(),
    })
}

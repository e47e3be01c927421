//! The paper's question as a hypothesis the data can test: does the joint's stiffness change
//! with the frequency of the mode?
//!
//! Hypothesis: mode r sees every identified joint parameter at
//!
//! ```text
//!   p_j(f_r) = p_j (f_r / f_ref)^alpha,   i.e.   x_j,r = x_j + alpha ln(f_r / f_ref)
//! ```
//!
//! (x_j = ln(p_j / p_j0), the fit's joint unknowns; f_r the measured frequency of mode r, f_ref
//! their geometric mean); alpha = 0 is the invariant joint of the calibration. Every residual
//! row of mode r then moves by d res / d alpha = sum_j (d res / d x_j) ln(f_r / f_ref): a column
//! c built from the calibration's own Jacobian J. At the calibrated optimum (J' r = 0) the
//! Gauss-Newton least squares over (x, scales, alpha),
//!
//! ```text
//!   min | r + J delta + c alpha |^2,
//! ```
//!
//! gives alpha's estimate, its standard error (the inverse normal matrix) and the decrease
//! D = |r|^2 - |r_after|^2: Rao's score statistic, chi-square with 1 degree of freedom when the
//! joint does not change with frequency (the same law as a candidate's likelihood-ratio
//! statistic, so it competes with the static candidates on equal terms). r_after, the
//! linearised residual of the frequency-dependent joint, is what the lack-of-fit tests judge.
//! The linearisation holds for small alpha; a strong dependence is fitted less well than an
//! exact model would, which errs toward `unexplained`, never toward a false finding.

use faer::linalg::solvers::Solve;
use faer::{Mat, Side};
use serde::Serialize;

use super::{Candidate, CandidateError, Fit, Stage, Tier};
use crate::diagnose::fit::{self, Estimate, Linearisation};
use crate::diagnose::report::Verdict;
use crate::measured::MeasuredModes;
use crate::model::effects::EffectContext;

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
        "every joint parameter scales as (f / f_ref)^alpha, f_ref the geometric mean of the measured frequencies (linearised at the calibrated joint: a score test); size = alpha"
    }

    fn applies(&self, ctx: &EffectContext) -> bool {
        !ctx.structure.identified().is_empty()
    }

    fn verdict(&self) -> Verdict {
        Verdict::FrequencyDependent
    }

    /// The score test at the stage's joint-only fit (nothing to start from: `earlier` is not
    /// used); no refitted model of its own.
    fn fit(&self, stage: &Stage, _earlier: Option<&Fit>) -> Result<Fit, CandidateError> {
        let base = stage.base;
        let lin = fit::linearise(stage.ctx, stage.measured, stage.calibration, base)?;
        let d = dependence(&lin, stage.measured).ok_or_else(|| {
            CandidateError::Undetermined(
                "alpha is not determined (the joint's unknowns and the shape scales absorb a trend with frequency)".into(),
            )
        })?;
        Ok(Fit {
            parameters: vec![Estimate {
                name: format!("{NAME}.alpha"),
                unit: "1",
                value: d.exponent,
                se: d.exponent_se,
            }],
            size: (d.exponent, d.exponent_se),
            describe: format!(
                "every joint parameter scales as (f / {:.4e} Hz)^alpha (linearised at the calibrated joint: a score test)",
                d.reference_hz
            ),
            chi2: d.chi2,
            dof: base.dof.saturating_sub(1).max(1),
            lrt: d.statistic,
            added: 1,
            unknowns: base.estimates.len() + 1,
            residuals: lin.unweighted(&d.residual, stage.measured),
            model: None,
            excluded: None,
            profile: None,
            members: Vec::new(),
        })
    }
}

/// The frequency-dependent joint fitted to first order at the calibrated invariant joint.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Dependence {
    /// alpha: every joint parameter scales as (f / f_ref)^alpha.
    pub exponent: f64,
    /// Its standard error under the working noise.
    pub exponent_se: f64,
    /// f_ref: the geometric mean of the measured frequencies (Hz).
    pub reference_hz: f64,
    /// Rao's score statistic D (chi-square, 1 degree of freedom, under an invariant joint).
    pub statistic: f64,
    /// chi^2 of the linearised frequency-dependent joint.
    pub chi2: f64,
    /// Weighted residuals of the linearised frequency-dependent joint (rows of the
    /// linearisation).
    #[serde(skip)]
    pub residual: Vec<f64>,
}

/// The frequency-dependent joint at the calibration `lin` of `measured`; `None` when the
/// normal matrix is singular (alpha not determined: a single mode, or no joint unknown).
pub fn dependence(lin: &Linearisation, measured: &MeasuredModes) -> Option<Dependence> {
    let modes = measured.modes();
    let log_mean =
        modes.iter().map(|m| m.frequency_hz.ln()).sum::<f64>() / modes.len().max(1) as f64;
    let level: Vec<f64> = modes
        .iter()
        .map(|m| m.frequency_hz.ln() - log_mean)
        .collect();
    let rows = lin.residual.len();
    let columns = lin.jacobian.ncols();
    let b = Mat::from_fn(rows, columns + 1, |i, k| {
        if k < columns {
            lin.jacobian[(i, k)]
        } else {
            let ell = level[lin.mode_of_row[i]];
            (0..lin.joints).map(|j| lin.jacobian[(i, j)]).sum::<f64>() * ell
        }
    });
    let normal = b.transpose() * &b;
    let n = columns + 1;
    let r = Mat::from_fn(rows, 1, |i, _| lin.residual[i]);
    let llt = normal.llt(Side::Lower).ok()?;
    let step = llt.solve(-(b.transpose() * &r));
    let unit = Mat::from_fn(n, 1, |i, _| if i == columns { 1.0 } else { 0.0 });
    let variance = llt.solve(&unit)[(columns, 0)];
    if !(variance.is_finite() && variance > 0.0) {
        return None;
    }
    let after = &r + &b * &step;
    let residual: Vec<f64> = (0..rows).map(|i| after[(i, 0)]).collect();
    let chi2_before: f64 = lin.residual.iter().map(|v| v * v).sum();
    let chi2: f64 = residual.iter().map(|v| v * v).sum();
    Some(Dependence {
        exponent: step[(columns, 0)],
        exponent_se: variance.sqrt(),
        reference_hz: log_mean.exp(),
        statistic: (chi2_before - chi2).max(0.0),
        chi2,
        residual,
    })
}

//! The search's models judged against the yardstick (the measurement error, module
//! `yardstick`): each model's chi^2 under it, its goodness of fit, the lack of fit of its
//! frequencies alone and the whiteness of its shape residuals (the probabilities of the
//! adequacy rule of module `decide`), beside what the search measured (deviance, discrepancy,
//! the likelihood-ratio test against the model it extends).
//!
//! Layer: diagnose; reads the search's models, writes their reports.

use super::decide::Judgement;
use super::fit::{Fitted, Residuals, residuals};
use super::noise::NoiseEstimate;
use super::report::{CandidateReport, ErrorSummary, Verdict};
use super::search::{Model, Search};
use super::yardstick;
use crate::measured::MeasuredModes;

/// A model's report with its fitted model and the verdict it names when standing alone.
#[derive(Debug, Clone)]
pub struct Scored {
    /// The report.
    pub report: CandidateReport,
    /// Its fitted model, if it has one.
    pub model: Option<Fitted>,
    /// The verdict that names it alone.
    pub verdict: Verdict,
}

/// What the judging stands on: the yardstick and the data.
#[derive(Debug, Clone, Copy)]
pub struct Judge<'a> {
    /// The yardstick.
    pub estimate: &'a NoiseEstimate,
    /// The measured modes.
    pub measured: &'a MeasuredModes,
}

impl Judge<'_> {
    /// The judgement of residuals `res` of a model with `unknowns` parameters besides the shape
    /// scales and `dof` degrees of freedom, with their chi^2 under the yardstick.
    fn judged(&self, res: &Residuals, unknowns: usize, dof: usize) -> (f64, Judgement) {
        yardstick::judgement(self.estimate, self.measured, res, unknowns, dof)
    }

    /// The judgement of the fitted model `fitted` (the joint-only fit).
    pub fn of_model(&self, fitted: &Fitted) -> Judgement {
        let res = residuals(fitted, self.measured);
        self.judged(&res, fitted.estimates.len(), fitted.dof).1
    }

    /// The report of one model of the search, `names` the names of all of them.
    fn report(&self, model: Model, names: &[String]) -> Scored {
        let extends = model.extends.map(|i| names[i].clone());
        let (report, fitted) = match model.outcome {
            Ok(fit) => {
                let (chi2, judgement) = self.judged(&fit.residuals, fit.unknowns, fit.dof);
                let report = CandidateReport {
                    name: model.name,
                    extends,
                    size: Some(fit.size.0),
                    size_se: Some(fit.size.1),
                    describe: fit.describe,
                    chi2: Some(chi2),
                    dof: Some(fit.dof),
                    deviance: Some(fit.deviance),
                    discrepancy: Some(fit.discrepancy),
                    lrt: model.lrt,
                    criterion: model.adjusted,
                    fit_p_value: judgement.fit,
                    frequency_p_value: judgement.frequency,
                    whiteness_p_value: judgement.whiteness,
                    summary: fit
                        .model
                        .as_ref()
                        .map(|m| ErrorSummary::of(m, self.measured, self.estimate)),
                    error: None,
                    excluded: fit.excluded,
                    profile: fit.profile,
                    parameters: fit.parameters,
                };
                (report, fit.model)
            }
            Err(e) => (
                CandidateReport {
                    extends,
                    ..CandidateReport::failed(&model.name, &model.describe, e.to_string())
                },
                None,
            ),
        };
        Scored {
            report,
            model: fitted,
            verdict: model.verdict,
        }
    }
}

/// Every model of `search` judged, in the same order.
pub fn score(search: Search, judge: &Judge) -> Vec<Scored> {
    let names: Vec<String> = search.models.iter().map(|m| m.name.clone()).collect();
    search
        .models
        .into_iter()
        .map(|m| judge.report(m, &names))
        .collect()
}

//! The candidates' fits judged under the working noise: the likelihood-ratio p-value adjusted
//! for the hypotheses tried, the goodness of fit, the lack of fit of the frequencies alone and
//! the whiteness of the shape residuals (the probabilities the rules of module `decide`
//! read), and the error summary of a candidate's model.
//!
//! Layer: diagnose; reads the candidates' fits, writes their reports.

use super::candidate::{Fit, Tried};
use super::decide::{Judgement, adjusted};
use super::fit::{Fitted, Residuals};
use super::noise::NoiseEstimate;
use super::report::{CandidateReport, ErrorSummary, Verdict};
use super::whiteness;
use crate::measured::MeasuredModes;

/// A candidate's report with its model and the verdict it names when selected alone.
#[derive(Debug, Clone)]
pub struct Scored {
    /// The report.
    pub report: CandidateReport,
    /// Its refitted model, if it has one.
    pub model: Option<Fitted>,
    /// The verdict that names it.
    pub verdict: Verdict,
}

/// What the judging stands on: the noise estimate, the data, the hypotheses tried.
#[derive(Debug, Clone, Copy)]
pub struct Judge<'a> {
    /// The noise estimate; its working noise is the yardstick.
    pub estimate: &'a NoiseEstimate,
    /// The measured modes.
    pub measured: &'a MeasuredModes,
    /// Hypotheses tried (the multiple-testing count).
    pub tried: usize,
}

impl Judge<'_> {
    /// (P of the frequencies alone, P of the whiteness) of residuals `res` of a model with
    /// `unknowns` parameters besides the shape scales.
    fn lack_of_fit(&self, res: &Residuals, unknowns: usize) -> (f64, f64) {
        let e = self.estimate;
        (
            e.frequency_lack_of_fit(res, unknowns).2,
            whiteness::of_residuals(res, self.measured, e.working, e.working_floor).p_value,
        )
    }

    /// The judgement of the joint-only fit `base`.
    pub fn of_model(&self, base: &Fitted) -> Judgement {
        let residuals = super::fit::residuals(base, self.measured);
        let (frequency, white) = self.lack_of_fit(&residuals, base.estimates.len());
        Judgement {
            fit: Some(self.estimate.fit_p_value(base.chi2, base.dof)),
            frequency: Some(frequency),
            whiteness: Some(white),
        }
    }

    /// The report of one fitted candidate.
    fn report(&self, name: &str, fit: Fit) -> (CandidateReport, Option<Fitted>) {
        let e = self.estimate;
        let (frequency_p, white_p) = self.lack_of_fit(&fit.residuals, fit.unknowns);
        let report = CandidateReport {
            name: name.to_string(),
            size: Some(fit.size.0),
            size_se: Some(fit.size.1),
            describe: fit.describe,
            chi2: Some(fit.chi2),
            dof: Some(fit.dof),
            lrt: Some(fit.lrt),
            criterion: Some(adjusted(e.lrt_p_value(fit.lrt, fit.added), self.tried)),
            fit_p_value: Some(e.fit_p_value(fit.chi2, fit.dof)),
            frequency_p_value: Some(frequency_p),
            whiteness_p_value: Some(white_p),
            summary: fit
                .model
                .as_ref()
                .map(|m| ErrorSummary::of(m, self.measured, e)),
            error: None,
            excluded: fit.excluded,
            profile: fit.profile,
            parameters: fit.parameters,
        };
        (report, fit.model)
    }
}

/// Every candidate of `tried` judged, in the same order.
pub fn score(tried: Vec<Tried>, judge: &Judge) -> Vec<Scored> {
    tried
        .into_iter()
        .map(|(candidate, outcome)| {
            let (report, model) = match outcome {
                Ok(fit) => judge.report(candidate.name(), fit),
                Err(e) => (
                    CandidateReport::failed(candidate.name(), candidate.describe(), e.to_string()),
                    None,
                ),
            };
            Scored {
                report,
                model,
                verdict: candidate.verdict(),
            }
        })
        .collect()
}

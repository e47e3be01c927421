//! The decision rules of a diagnosis, in one place: which candidates are significant, which
//! models explain the data, which candidate is named, and when the data cannot tell two apart.
//!
//! - **Multiple testing.** A candidate is significant when its likelihood-ratio p-value,
//!   times the number of hypotheses tried (one per candidate, the members of
//!   a scan: `super::candidate::hypotheses`), is below [`ALPHA`] (Bonferroni).
//! - **Explains the data.** A model explains the data when P(F(dof, nu) > chi^2 / dof), its
//!   frequencies alone and the whiteness of its shape residuals are all >= [`FIT_ALPHA`], and
//!   the estimated noise is within `noise::LARGEST_FACTOR` of the stated ([`Judgement`]).
//! - **Selection.** Among the significant candidates whose size is physical, the one with the
//!   largest likelihood-ratio statistic; every other significant one less than
//!   [`AMBIGUITY_MARGIN`] behind it in Akaike's information criterion contends with it
//!   (AIC_c = chi^2_c + 2 k_c; Burnham & Anderson, "Model Selection and Multimodel
//!   Inference", sec. 2.6) ([`select`]).
//! - **Static first** ([`static_first`]): where a static candidate within the margin
//!   explains the data, it is named before the frequency-dependent joint, which does not
//!   contend with it.
//! - **Verdict** ([`decide`]): no significant candidate and the joint-only fit explains the
//!   data: `none`; the selected candidate explains the data: the verdict it names (`effect`,
//!   or `frequency_dependent` for the frequency-dependent joint) when alone, `ambiguous` when
//!   others contend; otherwise `unexplained`.
//!
//! Layer: diagnose; pure functions of the candidates' reports.

use super::noise::{LARGEST_FACTOR, NoiseEstimate};
use super::report::{CandidateReport, Verdict};

/// Family-wise false-alarm probability of the candidate search.
pub const ALPHA: f64 = 0.01;
/// Smallest goodness-of-fit probability of a model that explains the data.
pub const FIT_ALPHA: f64 = 0.001;
/// Smallest lead in AIC of the selected candidate over every other significant one.
pub const AMBIGUITY_MARGIN: f64 = 6.0;
/// A per-mode correction whose slope against frequency exceeds this many standard errors
/// is reported as a trend (`Report::trend`; shown, not the test).
pub const TREND_SIGMAS: f64 = 3.0;

/// A likelihood-ratio p-value adjusted for `tried` hypotheses (Bonferroni, at most 1).
pub fn adjusted(p: f64, tried: usize) -> f64 {
    (p * tried as f64).min(1.0)
}

/// The lack-of-fit probabilities of one model.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Judgement {
    /// P(F(dof, nu) > chi^2 / dof).
    pub fit: Option<f64>,
    /// Of the frequencies alone.
    pub frequency: Option<f64>,
    /// Of the whiteness of the shape residuals.
    pub whiteness: Option<f64>,
}

impl Judgement {
    /// The judgement of a candidate's report.
    pub fn of(c: &CandidateReport) -> Self {
        Self {
            fit: c.fit_p_value,
            frequency: c.frequency_p_value,
            whiteness: c.whiteness_p_value,
        }
    }

    /// Whether the model explains the data, the noise estimated being `estimate`.
    pub fn explains(&self, estimate: &NoiseEstimate) -> bool {
        let pass = |p: Option<f64>| p.is_some_and(|p| p >= FIT_ALPHA);
        estimate.plausible() && pass(self.fit) && pass(self.frequency) && pass(self.whiteness)
    }
}

/// The outcome of the rules.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decision {
    /// The verdict.
    pub verdict: Verdict,
    /// The candidate whose fit is the diagnosis's "after" (index into the candidates), when
    /// the verdict is `effect`, `ambiguous` or `frequency_dependent`.
    pub best: Option<usize>,
    /// When `ambiguous`: the best, then every candidate within the margin of it.
    pub contenders: Vec<usize>,
}

/// The verdict on `candidates` (with the verdict each names when selected alone, `names`)
/// and the joint-only fit judged `base`, the noise estimated being `estimate`.
pub fn decide(
    candidates: &[CandidateReport],
    names: &[Verdict],
    base: Judgement,
    estimate: &NoiseEstimate,
) -> Decision {
    let alone = |verdict| Decision {
        verdict,
        best: None,
        contenders: Vec::new(),
    };
    let explains = |i: usize| Judgement::of(&candidates[i]).explains(estimate);
    match select(candidates).map(|(b, close)| static_first(candidates, names, b, close, explains)) {
        Some((b, close)) if explains(b) => {
            if close.is_empty() {
                Decision {
                    verdict: names[b],
                    best: Some(b),
                    contenders: Vec::new(),
                }
            } else {
                Decision {
                    verdict: Verdict::Ambiguous,
                    best: Some(b),
                    contenders: std::iter::once(b).chain(close).collect(),
                }
            }
        }
        Some(_) => alone(Verdict::Unexplained),
        None if base.explains(estimate) => alone(Verdict::None),
        None => alone(Verdict::Unexplained),
    }
}

/// The selection among fitted candidates: among the significant ones (adjusted p-value below
/// [`ALPHA`]) whose size is plausible, the one with the largest likelihood-ratio statistic,
/// and every other of them less than [`AMBIGUITY_MARGIN`] behind it in AIC (indices into
/// `candidates`; `None` when no candidate is significant).
pub fn select(candidates: &[CandidateReport]) -> Option<(usize, Vec<usize>)> {
    let mut significant = significant(candidates);
    significant.sort_by(|&a, &b| lrt(&candidates[b]).total_cmp(&lrt(&candidates[a])));
    let (&best, rest) = significant.split_first()?;
    let close = rest
        .iter()
        .copied()
        .filter(|&i| aic(&candidates[i]) - aic(&candidates[best]) < AMBIGUITY_MARGIN)
        .collect();
    Some((best, close))
}

/// The significant candidates whose size is plausible (indices into `candidates`).
fn significant(candidates: &[CandidateReport]) -> Vec<usize> {
    (0..candidates.len())
        .filter(|&i| {
            let c = &candidates[i];
            c.error.is_none() && c.excluded.is_none() && c.criterion.is_some_and(|p| p < ALPHA)
        })
        .collect()
}

/// The selection `(b, close)` with a static explanation preferred to the frequency-dependent
/// joint: when the best is the frequency-dependent joint and a static candidate within the
/// margin explains the data, that one (the first, by likelihood ratio) is the best; and the
/// frequency-dependent joint never contends with a static best. A joint that looks
/// frequency-dependent is what the paper's per-mode method reads from any unmodelled static
/// effect: where the data cannot tell them apart, the static physics is named.
fn static_first(
    candidates: &[CandidateReport],
    names: &[Verdict],
    b: usize,
    close: Vec<usize>,
    explains: impl Fn(usize) -> bool,
) -> (usize, Vec<usize>) {
    let dependent = |i: usize| names[i] == Verdict::FrequencyDependent;
    let best = if dependent(b) {
        close
            .iter()
            .copied()
            .find(|&i| !dependent(i) && explains(i))
            .unwrap_or(b)
    } else {
        b
    };
    if best == b && dependent(b) {
        return (b, close);
    }
    let mut close: Vec<usize> = significant(candidates)
        .into_iter()
        .filter(|&i| i != best && !dependent(i))
        .filter(|&i| aic(&candidates[i]) - aic(&candidates[best]) < AMBIGUITY_MARGIN)
        .collect();
    close.sort_by(|&a, &b| lrt(&candidates[b]).total_cmp(&lrt(&candidates[a])));
    (best, close)
}

/// A candidate's likelihood-ratio statistic (0 when it has none).
fn lrt(c: &CandidateReport) -> f64 {
    c.lrt.unwrap_or(0.0)
}

/// Akaike's information criterion of a fitted candidate relative to the joint-only fit
/// (AIC = chi^2 + 2 k with k its parameters; the joints' 2 p are common to all).
fn aic(c: &CandidateReport) -> f64 {
    let k = c.parameters.len();
    c.chi2.unwrap_or(f64::INFINITY) + 2.0 * k as f64
}

/// The rule of the selection in words, for the report: the noise it stood on and the counts
/// (`tried` hypotheses of `candidates` candidates).
pub fn criterion(estimate: &NoiseEstimate, tried: usize, candidates: usize) -> String {
    let count = if tried == candidates {
        format!("{tried} candidates")
    } else {
        format!("{tried} hypotheses ({candidates} candidates, a scan counting each of its members)")
    };
    let noise = if estimate.from_data {
        "the data's own standard errors (known: chi^2 tests)".to_string()
    } else if estimate.stated_kept {
        format!(
            "the stated noise ({:.0} degrees of freedom: F tests), no model's residuals passing the checks that do not stand on the noise level (whiteness along the structure, frequencies against the shapes' scale, within {LARGEST_FACTOR}x the stated)",
            estimate.dof
        )
    } else {
        format!(
            "the noise estimated from the shape residuals of the largest model that fits ({}, {:.0} degrees of freedom: F tests)",
            estimate.from_model, estimate.dof
        )
    };
    format!(
        "likelihood-ratio test under {noise}: a candidate is significant when its p-value times {count} is below {ALPHA}; a model explains the data when its chi^2, its frequencies alone and the whiteness of its shape residuals along the structure all pass at {FIT_ALPHA}; the best is named alone when every other significant candidate is {AMBIGUITY_MARGIN} or more behind it in AIC"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::fit::{Estimate, Noise};
    use crate::stats::chi2_sf;

    /// A fitted candidate with `k` parameters, chi^2 `chi2` against the joint-only 100.
    fn fitted(name: &str, k: usize, chi2: f64) -> CandidateReport {
        let lrt = 100.0 - chi2;
        CandidateReport {
            parameters: (0..k)
                .map(|i| Estimate {
                    name: format!("{name}.{i}"),
                    unit: "",
                    value: 1.0,
                    se: 0.1,
                })
                .collect(),
            size: Some(1.0),
            size_se: Some(0.1),
            chi2: Some(chi2),
            dof: Some(50),
            lrt: Some(lrt),
            criterion: Some(adjusted(chi2_sf(lrt, k as f64), 3)),
            fit_p_value: Some(0.5),
            frequency_p_value: Some(0.5),
            whiteness_p_value: Some(0.5),
            error: None,
            ..CandidateReport::failed(name, "", String::new())
        }
    }

    /// A noise estimate `factor` times the stated shape noise.
    fn estimate(factor: f64) -> NoiseEstimate {
        NoiseEstimate {
            from_model: "joint only".into(),
            shape: 0.02 * factor,
            shape_floor_abs: 0.0,
            frequency_check: 0.001,
            dof: 100.0,
            working: Noise {
                frequency: 0.001,
                shape: 0.02 * factor,
            },
            frequency_estimated: false,
            working_floor: 0.01,
            shape_factor: factor,
            frequency_factor: 1.0,
            from_differences: 0,
            from_data: false,
            stated_kept: false,
            frequency_sigmas: None,
            from_levels: 100,
            frequency_values: 6,
        }
    }

    const GOOD: Judgement = Judgement {
        fit: Some(0.5),
        frequency: Some(0.5),
        whiteness: Some(0.5),
    };

    #[test]
    fn the_best_is_selected_alone_only_with_a_lead_of_the_margin_in_aic() {
        // Leads of 6.5 and 5.5 in chi^2 at equal k: effect, then ambiguous.
        let clear = [
            fitted("a", 1, 80.0),
            fitted("b", 1, 50.0),
            fitted("c", 1, 56.5),
        ];
        assert_eq!(select(&clear), Some((1, Vec::new())));
        let close = [
            fitted("a", 1, 80.0),
            fitted("b", 1, 50.0),
            fitted("c", 1, 55.5),
        ];
        assert_eq!(select(&close), Some((1, vec![2])));
        // A lead of 9 in chi^2 with 2 more parameters is a lead of 5 in AIC: ambiguous, the
        // one with the larger statistic first.
        let penalised = [fitted("a", 3, 50.0), fitted("b", 1, 59.0)];
        assert_eq!(select(&penalised), Some((0, vec![1])));
        // A runner-up that is not significant does not contend: D = 5 < chi2_1 isf(0.01/2).
        let weak = [fitted("a", 1, 95.0), fitted("b", 1, 99.0)];
        assert_eq!(select(&weak), None);
    }

    #[test]
    fn an_implausible_or_failed_candidate_is_not_selected_nor_contends() {
        let mut heavy = fitted("heavy", 1, 40.0);
        heavy.excluded = Some("heavier than the beams".into());
        let mut failed = fitted("failed", 1, 41.0);
        failed.error = Some("did not converge".into());
        let candidates = [heavy, failed, fitted("light", 1, 50.0)];
        assert_eq!(select(&candidates), Some((2, Vec::new())));
    }

    /// Each lack-of-fit probability below FIT_ALPHA, a missing one, or a noise estimate beyond
    /// LARGEST_FACTOR of the stated makes a model fail to explain the data.
    #[test]
    fn a_model_explains_the_data_only_when_every_test_passes() {
        assert!(GOOD.explains(&estimate(1.0)));
        assert!(GOOD.explains(&estimate(LARGEST_FACTOR)));
        assert!(!GOOD.explains(&estimate(LARGEST_FACTOR * 1.01)));
        let low = Some(0.999 * FIT_ALPHA);
        for bad in [
            Judgement { fit: low, ..GOOD },
            Judgement {
                frequency: low,
                ..GOOD
            },
            Judgement {
                whiteness: low,
                ..GOOD
            },
            Judgement { fit: None, ..GOOD },
        ] {
            assert!(!bad.explains(&estimate(1.0)), "{bad:?}");
        }
        let edge = Some(FIT_ALPHA);
        assert!(
            Judgement {
                fit: edge,
                frequency: edge,
                whiteness: edge
            }
            .explains(&estimate(1.0))
        );
    }

    /// The verdicts: none, effect, the candidate's own verdict, ambiguous (best first), and
    /// unexplained when the best does not explain the data or nothing is significant and the
    /// joint alone does not either.
    #[test]
    fn verdicts_follow_the_rules() {
        let names = [
            Verdict::Effect,
            Verdict::FrequencyDependent,
            Verdict::Effect,
        ];
        let weak = [
            fitted("a", 1, 99.0),
            fitted("b", 1, 98.0),
            fitted("c", 1, 99.5),
        ];
        let e = estimate(1.0);
        assert_eq!(decide(&weak, &names, GOOD, &e).verdict, Verdict::None);
        let bad = Judgement {
            fit: Some(1e-9),
            ..GOOD
        };
        assert_eq!(decide(&weak, &names, bad, &e).verdict, Verdict::Unexplained);
        let clear = [
            fitted("a", 1, 50.0),
            fitted("b", 1, 80.0),
            fitted("c", 1, 99.0),
        ];
        let d = decide(&clear, &names, bad, &e);
        assert_eq!((d.verdict, d.best), (Verdict::Effect, Some(0)));
        let own = [
            fitted("a", 1, 80.0),
            fitted("b", 1, 50.0),
            fitted("c", 1, 99.0),
        ];
        let d = decide(&own, &names, bad, &e);
        assert_eq!((d.verdict, d.best), (Verdict::FrequencyDependent, Some(1)));
        let close = [
            fitted("a", 1, 52.0),
            fitted("b", 1, 99.0),
            fitted("c", 1, 50.0),
        ];
        let d = decide(&close, &names, GOOD, &e);
        assert_eq!(d.verdict, Verdict::Ambiguous);
        assert_eq!((d.best, d.contenders), (Some(2), vec![2, 0]));
        let mut unfit = clear.clone();
        unfit[0].whiteness_p_value = Some(1e-6);
        let d = decide(&unfit, &names, GOOD, &e);
        assert_eq!((d.verdict, d.best), (Verdict::Unexplained, None));
        assert_eq!(
            decide(&clear, &names, GOOD, &estimate(5.0)).verdict,
            Verdict::Unexplained
        );
    }

    #[test]
    fn the_criterion_counts_hypotheses_and_candidates() {
        let e = estimate(1.0);
        assert!(criterion(&e, 7, 7).contains("p-value times 7 candidates is below 0.01"));
        assert!(criterion(&e, 40, 9).contains("times 40 hypotheses (9 candidates"));
        assert_eq!(adjusted(0.2, 7), 1.0);
        assert!((adjusted(0.001, 7) - 0.007).abs() < 1e-18);
    }
}

//! The decision rules of a diagnosis, in one place: which explanation is best (relative, each
//! model with its own discrepancy), whether it is adequate (absolute, against the measurement
//! error), and the graded verdict.
//!
//! - **Which is best.** Every model is fitted with its own discrepancy (module
//!   `discrepancy`); D = deviance(extended model) - deviance(model) is the likelihood-ratio
//!   statistic of the cause added, the discrepancy profiled out of both. Its p-value is
//!   P(chi^2_k > D) where no discrepancy was estimated. Where one was, the test is the
//!   classical F test, kind by kind of residual (frequencies, shapes): the chi^2 difference of
//!   the two models under the larger's variance, times nu / n of its estimate, over k, read
//!   as F(k, nu) with nu the Welch-Satterthwaite degrees of freedom of the kinds that improved
//!   (module `discrepancy`, `improvement`); a cause whose unknowns are all held
//!   non-negative (a mass, a spring, an Euler-Bernoulli beam's shear flexibility) is zero in
//!   the model it extends, on the edge of its range, and its test is one-sided (the
//!   chi-bar-square bound of [`crate::stats::lr_sf`]). A cause is significant when that p-value, times
//!   the hypotheses tried so far (one per candidate, the members of a scan, then every
//!   addition the search tried: module `search`), is below [`ALPHA`] (Bonferroni).
//! - **Clearly best** ([`select`]): among the significant causes whose size is physical, the
//!   one of least Akaike's criterion (deviance + 2 k, each model with its own discrepancy;
//!   Burnham & Anderson, "Model Selection and Multimodel Inference", sec. 2.6); every other
//!   less than [`AMBIGUITY_MARGIN`] behind it contends with it. The criterion, not D, ranks
//!   them: the D of a cause that fits within the measurement error stands on the yardstick
//!   of its own residuals, so two causes' D are not on one scale. Where the best so found fits
//!   within the measurement error, the criterion is read again with every model's chi^2 under
//!   the yardstick of the best's residuals (module `search`, `ranked`): the scale its
//!   significance was read on, one for all, and the one the data show where they show the
//!   noise below the stated. Where the frequency-dependent joint is the best
//!   and a static cause contends, the static one is taken (what looks frequency-dependent to
//!   the paper's per-mode method is often an unmodelled static effect) and the
//!   frequency-dependent joint does not contend with a static best.
//! - **Adequate** ([`Judgement::explains`]): the model's chi^2 under the measurement error (the
//!   yardstick: module `yardstick`), its frequencies alone and the whiteness of its shape
//!   residuals all pass at [`FIT_ALPHA`], the noise estimated within `noise::LARGEST_FACTOR`
//!   of the stated.
//! - **Pairs** (module `search`): where the causes added one after another leave a misfit
//!   beyond the measurement error (or none was significant and the joint-only fit leaves
//!   one), every pair of causes not yet fitted together is, each one more hypothesis; a pair
//!   clearly best among them, the path's end and the additions tried at its last step
//!   replaces the path. One cause at a time misses two that only act together: a lap and an
//!   end mass, neither significant alone beside a frequency-dependent joint that mimics both.
//! - **Verdict** ([`decide`]): no significant cause, and the joint-only fit adequate: `none`;
//!   no significant cause otherwise: `unexplained`. A clearly best cause, extended by the
//!   search with every further cause clearly best at its step: `effect` (or
//!   `frequency_dependent`) when the model of all of them is adequate, `partial` when a misfit
//!   beyond the measurement error remains and the model lowers the joint-only fit's chi^2
//!   under the measurement error (`unexplained` when it does not: it only traded one kind of
//!   misfit for another under its own discrepancy). A best cause with contenders: `ambiguous` when it is
//!   adequate, `unexplained` when not (several partial explanations the data cannot tell
//!   apart).
//!
//! Layer: diagnose; pure functions.

use super::noise::NoiseEstimate;
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
/// Most causes the search puts together: three, the lap, the shear the user's
/// Euler-Bernoulli beams leave out and a mass the model lacks (docs/diagnosis.md); each one
/// added is tested, its p-value adjusted for every hypothesis tried up to its step.
pub const MAX_CAUSES: usize = 3;

/// A likelihood-ratio p-value adjusted for `tried` hypotheses (Bonferroni, at most 1).
pub fn adjusted(p: f64, tried: usize) -> f64 {
    (p * tried as f64).min(1.0)
}

/// What the relative rules read of one fitted cause.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rival {
    /// Deviance of its model.
    pub deviance: f64,
    /// Its parameters (the information criterion's k).
    pub parameters: usize,
    /// Its adjusted p-value.
    pub adjusted: f64,
    /// Whether it fitted to a physical size.
    pub usable: bool,
    /// Whether it is the frequency-dependent joint.
    pub dependent: bool,
}

impl Rival {
    fn aic(&self) -> f64 {
        self.deviance + 2.0 * self.parameters as f64
    }

    fn significant(&self) -> bool {
        self.usable && self.adjusted < ALPHA
    }
}

/// The clearly best of `rivals` and those that contend with it (module docs; indices into
/// `rivals`, the contenders best first); None when none is significant.
pub fn select(rivals: &[Rival]) -> Option<(usize, Vec<usize>)> {
    let mut significant: Vec<usize> = (0..rivals.len())
        .filter(|&i| rivals[i].significant())
        .collect();
    significant.sort_by(|&a, &b| rivals[a].aic().total_cmp(&rivals[b].aic()));
    let &first = significant.first()?;
    let within = |best: usize, i: usize| rivals[i].aic() - rivals[best].aic() < AMBIGUITY_MARGIN;
    // Static first: a static cause within the margin of a frequency-dependent best is taken.
    let best = if rivals[first].dependent {
        significant
            .iter()
            .copied()
            .find(|&i| !rivals[i].dependent && within(first, i))
            .unwrap_or(first)
    } else {
        first
    };
    let close = significant
        .into_iter()
        .filter(|&i| i != best && within(best, i))
        .filter(|&i| !rivals[i].dependent || rivals[best].dependent)
        .collect();
    Some((best, close))
}

/// The lack-of-fit probabilities of one model under the yardstick.
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

    /// Whether the model explains the data within the measurement error, the noise estimated
    /// being `estimate`.
    pub fn explains(&self, estimate: &NoiseEstimate) -> bool {
        let pass = |p: Option<f64>| p.is_some_and(|p| p >= FIT_ALPHA);
        estimate.plausible() && pass(self.fit) && pass(self.frequency) && pass(self.whiteness)
    }
}

/// The outcome of the search the verdict reads: the causes put together, best first
/// (indices into the models), and the models that contend with the first.
#[derive(Debug, Clone, PartialEq, Eq, Default)]
pub struct Path {
    /// The first cause, then the model of every further cause added (each index the model of
    /// all the causes so far).
    pub models: Vec<usize>,
    /// The models that contend with the first.
    pub contenders: Vec<usize>,
}

/// The outcome of the rules.
#[derive(Debug, Clone, PartialEq, Eq)]
pub struct Decision {
    /// The verdict.
    pub verdict: Verdict,
    /// The model that is the diagnosis's "after" (index into the models), when a cause is
    /// named (`effect`, `partial`, `ambiguous`, `frequency_dependent`).
    pub best: Option<usize>,
    /// The causes named, in the order the search added them (indices into the models: the
    /// first cause's model, then each extension's).
    pub causes: Vec<usize>,
    /// When `ambiguous` (or `unexplained` with several partial explanations): the best, then
    /// every model within the margin of it.
    pub contenders: Vec<usize>,
}

/// The verdict on the search's `path`, `explains` saying which models are adequate,
/// `base_explains` whether the joint-only fit is, `names` the verdict that names each model
/// when it stands alone.
pub fn decide(
    path: &Path,
    explains: impl Fn(usize) -> bool,
    lowers: impl Fn(usize) -> bool,
    base_explains: bool,
    names: &[Verdict],
) -> Decision {
    let alone = |verdict| Decision {
        verdict,
        best: None,
        causes: Vec::new(),
        contenders: Vec::new(),
    };
    let (Some(&first), Some(&last)) = (path.models.first(), path.models.last()) else {
        return alone(if base_explains {
            Verdict::None
        } else {
            Verdict::Unexplained
        });
    };
    if !path.contenders.is_empty() {
        let contenders = std::iter::once(first)
            .chain(path.contenders.iter().copied())
            .collect();
        return if explains(first) {
            Decision {
                verdict: Verdict::Ambiguous,
                best: Some(first),
                causes: vec![first],
                contenders,
            }
        } else {
            Decision {
                contenders,
                ..alone(Verdict::Unexplained)
            }
        };
    }
    let verdict = match (explains(last), path.models.len()) {
        (true, 1) => names[first],
        (true, _) => Verdict::Effect,
        // A model that lowers none of the joint-only fit's misfit under the measurement error
        // explains none of it: its significance came from trading one kind of misfit for
        // another under its own discrepancy (a damaged element: shapes fitted, frequencies
        // given up).
        (false, _) if !lowers(last) => return alone(Verdict::Unexplained),
        (false, _) => Verdict::Partial,
    };
    Decision {
        verdict,
        best: Some(last),
        causes: path.models.clone(),
        contenders: Vec::new(),
    }
}

/// The rules in words, for the report: the yardstick of adequacy and the counts (`tried`
/// hypotheses in all, of `candidates` candidates).
pub fn criterion(estimate: &NoiseEstimate, tried: usize, candidates: usize) -> String {
    let count = if tried == candidates {
        format!("{tried} candidates")
    } else {
        format!(
            "{tried} hypotheses ({candidates} candidates, a scan counting each of its members, every combination tried counting one)"
        )
    };
    let yardstick = if estimate.from_data {
        "the data's own standard errors (known: chi^2 tests)".to_string()
    } else if estimate.stated_kept {
        format!(
            "the stated noise ({:.0} degrees of freedom: F tests), no model's residuals passing the checks that do not stand on the noise level (whiteness along the structure, frequencies against the shapes' scale, within {}x the stated)",
            estimate.dof,
            super::noise::LARGEST_FACTOR
        )
    } else {
        format!(
            "the noise estimated from the shape residuals of the largest model ({}, {:.0} degrees of freedom: F tests)",
            estimate.from_model, estimate.dof
        )
    };
    format!(
        "each model with its own discrepancy, a cause is significant when its likelihood-ratio p-value (F where a discrepancy was estimated; one-sided for a mass, a spring or a shear flexibility added from zero) times {count} is below {ALPHA}, and named alone when every other significant one is {AMBIGUITY_MARGIN} or more behind it in AIC; causes are added while one is, and where they leave a misfit every other pair of causes is tried together; a model explains the data when, under {yardstick}, its chi^2, its frequencies alone and the whiteness of its shape residuals along the structure all pass at {FIT_ALPHA}"
    )
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::stats::{chi2_sf, lr_sf};

    fn rival(deviance: f64, parameters: usize) -> Rival {
        let lrt = 100.0 - deviance;
        Rival {
            deviance,
            parameters,
            adjusted: adjusted(chi2_sf(lrt, parameters as f64), 3),
            usable: true,
            dependent: false,
        }
    }

    #[test]
    fn the_best_is_selected_alone_only_with_a_lead_of_the_margin_in_aic() {
        // Leads of 6.5 and 5.5 in deviance at equal k: alone, then with a contender.
        let clear = [rival(80.0, 1), rival(50.0, 1), rival(56.5, 1)];
        assert_eq!(select(&clear), Some((1, Vec::new())));
        let close = [rival(80.0, 1), rival(50.0, 1), rival(55.5, 1)];
        assert_eq!(select(&close), Some((1, vec![2])));
        // A lead of 9 with 2 more parameters is a lead of 5 in AIC: the larger statistic
        // first, the other contends.
        let penalised = [rival(50.0, 3), rival(59.0, 1)];
        assert_eq!(select(&penalised), Some((0, vec![1])));
        // A runner-up that is not significant does not contend: D = 5 < chi2_1 isf(0.01 / 3).
        let weak = [rival(95.0, 1), rival(99.0, 1)];
        assert_eq!(select(&weak), None);
    }

    #[test]
    fn an_implausible_cause_is_not_selected_nor_contends() {
        let mut heavy = rival(40.0, 1);
        heavy.usable = false;
        assert_eq!(select(&[heavy, rival(50.0, 1)]), Some((1, Vec::new())));
    }

    /// Two causes tested on yardsticks of their own residuals (a joint coupling's D 111.8, a
    /// sensor mass's 111.2, large-s3 case 106 of the battery): the larger D does not make the
    /// best, the criterion does (here 15.6 ahead: alone).
    #[test]
    fn the_best_is_the_least_criterion_not_the_largest_statistic() {
        let coupling = rival(-246.9, 1);
        let mass = rival(-264.5, 2);
        assert_eq!(select(&[coupling, mass]), Some((1, Vec::new())));
    }

    /// A static cause within the margin of a frequency-dependent best is taken, and the
    /// frequency-dependent joint does not contend with it; clearly ahead, the dependent one
    /// is the best.
    #[test]
    fn a_static_cause_comes_before_the_frequency_dependent_joint() {
        let mut dependent = rival(50.0, 1);
        dependent.dependent = true;
        assert_eq!(select(&[dependent, rival(53.0, 1)]), Some((1, Vec::new())));
        assert_eq!(select(&[dependent, rival(70.0, 1)]), Some((0, Vec::new())));
    }

    /// Under an estimated discrepancy the test is F(k, nu): larger p than chi-square for the
    /// same statistic, equal in the limit of many degrees of freedom.
    #[test]
    fn an_estimated_discrepancy_makes_the_test_an_f_test() {
        let chi2 = lr_sf(9.0, 1, f64::INFINITY, false);
        assert!((chi2 - chi2_sf(9.0, 1.0)).abs() < 1e-15);
        assert!(lr_sf(9.0, 1, 5.0, false) > 3.0 * chi2);
        assert!((lr_sf(9.0, 1, 1e7, false) - chi2).abs() < 1e-5 * chi2);
    }

    #[test]
    fn verdicts_follow_the_rules() {
        let names = [
            Verdict::Effect,
            Verdict::FrequencyDependent,
            Verdict::Effect,
        ];
        let nothing = Path::default();
        assert_eq!(
            decide(&nothing, |_| true, |_| true, true, &names).verdict,
            Verdict::None
        );
        assert_eq!(
            decide(&nothing, |_| true, |_| true, false, &names).verdict,
            Verdict::Unexplained
        );
        let one = Path {
            models: vec![0],
            contenders: Vec::new(),
        };
        let d = decide(&one, |_| true, |_| true, false, &names);
        assert_eq!(
            (d.verdict, d.best, d.causes),
            (Verdict::Effect, Some(0), vec![0])
        );
        let d = decide(&one, |_| false, |_| true, false, &names);
        assert_eq!((d.verdict, d.best), (Verdict::Partial, Some(0)));
        let dependent = Path {
            models: vec![1],
            contenders: Vec::new(),
        };
        let d = decide(&dependent, |_| true, |_| true, false, &names);
        assert_eq!(d.verdict, Verdict::FrequencyDependent);
        // Two causes together: effect when the model of both is adequate, partial when not.
        let two = Path {
            models: vec![0, 3],
            contenders: Vec::new(),
        };
        let d = decide(&two, |i| i == 3, |_| true, false, &names);
        assert_eq!(
            (d.verdict, d.best, d.causes),
            (Verdict::Effect, Some(3), vec![0, 3])
        );
        let d = decide(&two, |_| false, |_| true, false, &names);
        assert_eq!((d.verdict, d.best), (Verdict::Partial, Some(3)));
        // ... and unexplained when it lowers none of the joint-only fit's misfit.
        let d = decide(&two, |_| false, |_| false, false, &names);
        assert_eq!((d.verdict, d.best), (Verdict::Unexplained, None));
        // Contenders: ambiguous when the best is adequate, unexplained when not.
        let close = Path {
            models: vec![2],
            contenders: vec![0],
        };
        let d = decide(&close, |_| true, |_| true, false, &names);
        assert_eq!((d.verdict, d.best), (Verdict::Ambiguous, Some(2)));
        assert_eq!(d.contenders, vec![2, 0]);
        let d = decide(&close, |_| false, |_| true, false, &names);
        assert_eq!((d.verdict, d.best), (Verdict::Unexplained, None));
        assert_eq!(d.contenders, vec![2, 0]);
    }
}

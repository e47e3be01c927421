//! The search for what the calibrated joint leaves: every candidate fitted once, with its own
//! discrepancy; the clearly best one ([`super::decide::select`]); then causes added one after
//! another (forward selection): the model of the causes so far extended by every other
//! candidate that combines (module `candidate`'s `combined`), each fitted once, the clearly
//! best significant addition kept, until the model fits within the measurement error (module
//! `yardstick`'s adequacy), none is significant, two contend, or [`MAX_CAUSES`] are together.
//! Where that ends in a misfit beyond the measurement error, every pair of candidates that
//! combine and were not yet fitted together is, from the fit of the one of smaller deviance
//! alone; a pair clearly best among them and the path's models replaces the path
//! ([`with_pairs`]).
//!
//! Multiple testing is counted honestly: the p-value of an addition is adjusted for every
//! hypothesis tried up to its step (the candidates, the members of scans, every addition tried
//! before and at that step). Which cause is best stands on the relative rules only (each model
//! judged against the one it extends, both with their own discrepancy); whether the result
//! fits within the measurement error is the yardstick's question (module `yardstick`).
//!
//! Layer: diagnose; the step after the calibration.

use std::sync::Arc;

use rayon::prelude::*;

use super::candidate::{Candidate, CandidateError, Fit, Part, Stage, combine, tell_fitted};
use super::decide::{MAX_CAUSES, Path, Rival, adjusted, select};
use super::discrepancy;
use super::fit::{Fitted, chi2_of, refitted_chi2, residuals};
use super::progress::Pass;
use super::report::Verdict;
use super::yardstick;
use crate::model::chain::assembly::LAYERED_LAP;
use crate::stats::lr_sf;

/// One model the search fitted: a candidate alone, or a combination of causes.
#[derive(Debug)]
pub struct Model {
    /// Its name: the candidate's, or the causes joined by " + ".
    pub name: String,
    /// What the candidate (or the cause added last) is.
    pub describe: String,
    /// The verdict that names it when it stands alone.
    pub verdict: Verdict,
    /// The model it extends (index into the search's models), None: the joint-only fit.
    pub extends: Option<usize>,
    /// Its fit, or why it has none.
    pub outcome: Result<Fit, CandidateError>,
    /// Likelihood-ratio statistic against the model it extends, when both fitted.
    pub lrt: Option<f64>,
    /// Its p-value adjusted for the hypotheses tried up to its step.
    pub adjusted: Option<f64>,
    /// What its test stood on.
    pub test: Option<Test>,
}

/// What a model's likelihood-ratio test against the model it extends stands on.
#[derive(Debug, Clone, Copy, PartialEq, Eq, serde::Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Test {
    /// The measurement error: the model fits within it, so its residual is noise alone and
    /// both models' chi^2 under the yardstick its residuals give are compared.
    MeasurementError,
    /// Each model's own discrepancy: the difference of their deviances.
    Discrepancy,
}

impl Model {
    /// Its fit, when it has one.
    pub fn fit(&self) -> Option<&Fit> {
        self.outcome.as_ref().ok()
    }

    /// Its fitted model, when it has one.
    pub fn fitted(&self) -> Option<&Fitted> {
        self.fit().and_then(|f| f.model.as_ref())
    }
}

/// What the search found.
#[derive(Debug)]
pub struct Search {
    /// Every model fitted: the candidates in library order, then the combinations in the
    /// order they were tried.
    pub models: Vec<Model>,
    /// The causes put together and the contenders of the first.
    pub path: Path,
    /// Hypotheses tried in all (the multiple-testing count of the last step).
    pub hypotheses: usize,
    /// Hypotheses of the candidates alone.
    pub candidates_hypotheses: usize,
    /// Where the pairs tried after the causes added one by one begin among the models (their
    /// count when none was tried): a pair the path does not end in was tried, not found, and
    /// gives no yardstick ([`Search::largest`]).
    pub pairs_from: usize,
}

/// The search on `stage` over `library` (module docs); `hypotheses` the count of the
/// candidates alone (the members of scans each one); `given` the combinations of causes the
/// user asks for (indices into `library`, each of candidates that combine), tried beside the
/// candidates alone, one hypothesis each.
pub fn search(
    library: &[Arc<dyn Candidate>],
    stage: &Stage,
    hypotheses: usize,
    given: &[Vec<usize>],
) -> Search {
    let watch = stage.watch.during(Pass::Candidates);
    let singles: Vec<Model> = library
        .par_iter()
        .map(|c| {
            let outcome = c.fit(&Stage { watch, ..*stage });
            tell_fitted(&watch, c.name(), &outcome);
            Model {
                name: c.name().to_string(),
                describe: c.describe().to_string(),
                verdict: c.verdict(),
                extends: None,
                outcome,
                lrt: None,
                adjusted: None,
                test: None,
            }
        })
        .collect();
    let lap = library
        .iter()
        .position(|c| c.name() == LAYERED_LAP)
        .and_then(|i| singles[i].fitted().cloned());
    let combinations: Vec<Model> = given
        .par_iter()
        .map(|parts| together(library, &singles, parts, stage, lap.as_ref(), ASKED))
        .collect();
    let mut models = singles;
    models.extend(combinations);
    let mut tried = hypotheses + given.len();
    for m in &mut models {
        judge(m, stage.base, tried, stage);
    }
    let all: Vec<&Model> = models.iter().collect();
    let path = ranked(&all, stage).map_or_else(Path::default, |(first, contenders)| Path {
        models: vec![first],
        contenders,
    });
    let path = add_causes(library, stage, lap.as_ref(), &mut models, &mut tried, path);
    let pairs_from = models.len();
    let path = pair_up(library, stage, lap.as_ref(), &mut models, &mut tried, path);
    Search {
        models,
        path,
        hypotheses: tried,
        candidates_hypotheses: hypotheses,
        pairs_from,
    }
}

/// The path `path` with causes added one after another while its first stands clearly alone
/// and the model of the causes so far does not fit within the measurement error (module
/// docs); every model fitted on the way appended to `models`, `tried` counting them.
fn add_causes(
    library: &[Arc<dyn Candidate>],
    stage: &Stage,
    lap: Option<&Fitted>,
    models: &mut Vec<Model>,
    tried: &mut usize,
    mut path: Path,
) -> Path {
    while let Some(&last) = path.models.last() {
        if !path.contenders.is_empty() || path.models.len() >= MAX_CAUSES {
            break;
        }
        let fits = models[last].fitted().is_some_and(|f| {
            yardstick::adequate(&models[last].name, f, stage.measured, stage.calibration)
        });
        if fits {
            break;
        }
        let Some(parts) = parts_of(&path.models, models, library) else {
            break;
        };
        let additions: Vec<(usize, Part)> = library
            .iter()
            .enumerate()
            .filter(|(i, _)| !parts.contains(i))
            .filter_map(|(i, c)| Some((i, c.part()?)))
            .filter(|(i, _)| models[*i].fit().is_some())
            .collect();
        if additions.is_empty() {
            break;
        }
        let Some(from) = models[last].fitted().cloned() else {
            break;
        };
        let step = path.models.len() + 1;
        let watch = stage.watch.during(Pass::Together(step));
        let fitted: Vec<Model> = additions
            .par_iter()
            .map(|(i, part)| {
                let name = format!("{} + {}", models[last].name, library[*i].name());
                let outcome = combine(&Stage { watch, ..*stage }, &from, part, lap, &name);
                tell_fitted(&watch, &name, &outcome);
                Model {
                    name,
                    describe: library[*i].describe().to_string(),
                    verdict: Verdict::Effect,
                    extends: Some(last),
                    outcome,
                    lrt: None,
                    adjusted: None,
                    test: None,
                }
            })
            .collect();
        let at = append_judged(models, fitted, &from, tried, stage);
        let added: Vec<&Model> = models[at..].iter().collect();
        match ranked(&added, stage) {
            Some((best, close)) if close.is_empty() => path.models.push(at + best),
            _ => break,
        }
    }
    path
}

/// The path `path`, or a pair of causes that replaces it, where the path leaves a misfit
/// beyond the measurement error (module docs, [`with_pairs`]); the pairs appended to
/// `models`, `tried` counting them.
fn pair_up(
    library: &[Arc<dyn Candidate>],
    stage: &Stage,
    lap: Option<&Fitted>,
    models: &mut Vec<Model>,
    tried: &mut usize,
    path: Path,
) -> Path {
    if ends_adequate(&path, models, stage) {
        return path;
    }
    let pairs = untried_pairs(library, models);
    if pairs.is_empty() {
        return path;
    }
    let singles = &models[..library.len()];
    let fitted: Vec<Model> = pairs
        .par_iter()
        .map(|parts| together(library, singles, parts, stage, lap, PAIRED))
        .collect();
    let at = append_judged(models, fitted, stage.base, tried, stage);
    with_pairs(path, models, at, stage)
}

/// Appends `fitted` to `models`, `tried` counting them, each judged against `from` (the model
/// it extends) for the hypotheses tried so far; where they begin among the models.
fn append_judged(
    models: &mut Vec<Model>,
    fitted: Vec<Model>,
    from: &Fitted,
    tried: &mut usize,
    stage: &Stage,
) -> usize {
    *tried += fitted.len();
    let at = models.len();
    models.extend(fitted);
    for m in &mut models[at..] {
        judge(m, from, *tried, stage);
    }
    at
}

impl Search {
    /// The largest physical model (module `yardstick`): the last model of the path when it is
    /// static, else the static model of least deviance, the pairs tried after the path left
    /// out, when below the joint-only fit `base`'s by more than [`TIE`] of it, else `base`
    /// (named `joint only`); with its name.
    pub fn largest<'a>(&'a self, base: &'a Fitted) -> (&'a str, &'a Fitted) {
        let stands = |i: usize| self.models[i].verdict != Verdict::FrequencyDependent;
        let usable = |i: usize| {
            let m = &self.models[i];
            let fit = m.fit().filter(|f| f.excluded.is_none())?;
            Some((m.name.as_str(), fit.model.as_ref()?))
        };
        if let Some(found) = self
            .path
            .models
            .last()
            .filter(|&&i| stands(i))
            .and_then(|&i| usable(i))
        {
            return found;
        }
        (0..self.pairs_from)
            .filter(|&i| stands(i))
            .filter_map(usable)
            .filter(|(_, f)| f.deviance < base.deviance - TIE * base.deviance.abs())
            .min_by(|a, b| a.1.deviance.total_cmp(&b.1.deviance))
            .unwrap_or((JOINT_ONLY, base))
    }
}

/// Relative deviance difference within which a candidate is the joint-only fit as far as the
/// fits can tell (a candidate at the bound where it is the joint-only model, such as a mass of
/// 0): two fits of one model end within the solver's decrement tolerance, 1e-8 of the cost,
/// and which of two such ends is lower is the solver's path, not the data.
pub const TIE: f64 = 1e-6;

/// The name of the joint-only fit among the models.
pub const JOINT_ONLY: &str = "joint only";

/// Why a combination fitted from the start was tried: the user asked for it.
const ASKED: &str = "asked for (--causes)";
/// Why a combination fitted from the start was tried: the pair search.
const PAIRED: &str = "a pair tried where the causes added one by one left a misfit";

/// Whether the search's path ends in a model that fits within the measurement error: its last
/// model (with contenders, its first: several explanations that fit, not a misfit), or the
/// joint-only fit when the path is empty.
fn ends_adequate(path: &Path, models: &[Model], stage: &Stage) -> bool {
    let (name, fitted) = match path.models.last() {
        Some(&i) => match models[i].fitted() {
            Some(f) => (models[i].name.as_str(), f),
            None => return false,
        },
        None => (JOINT_ONLY, stage.base),
    };
    yardstick::adequate(name, fitted, stage.measured, stage.calibration)
}

/// Every pair of candidates that combine, each fitted alone, not yet fitted together (by the
/// causes added one after another or the user's combinations): indices into `library`, the
/// one of smaller deviance alone first (the fit of the pair starts from its fit).
fn untried_pairs(library: &[Arc<dyn Candidate>], models: &[Model]) -> Vec<Vec<usize>> {
    let usable: Vec<usize> = (0..library.len())
        .filter(|&i| library[i].part().is_some())
        .filter(|&i| models[i].fitted().is_some())
        .collect();
    let done: Vec<Vec<usize>> = (0..models.len())
        .filter_map(|m| parts_of(&[m], models, library))
        .map(|mut parts| {
            parts.sort_unstable();
            parts
        })
        .collect();
    let deviance = |i: usize| models[i].fit().map_or(f64::INFINITY, |f| f.deviance);
    let mut pairs = Vec::new();
    for (n, &a) in usable.iter().enumerate() {
        for &b in &usable[n + 1..] {
            if done.iter().any(|d| d[..] == [a, b]) {
                continue;
            }
            pairs.push(if deviance(b) < deviance(a) {
                vec![b, a]
            } else {
                vec![a, b]
            });
        }
    }
    pairs
}

/// The path once the pairs `models[at..]` are judged. The pairs stand beside the path's end
/// (or its first cause and contenders) and the models that extended it at the step that
/// stopped; a pair clearly best of them by the relative rules ([`select`]) replaces the path,
/// every model within the margin of it contending; else the path stands as it is.
fn with_pairs(path: Path, models: &[Model], at: usize, stage: &Stage) -> Path {
    let mut standing: Vec<usize> = if path.contenders.is_empty() {
        path.models.last().copied().into_iter().collect()
    } else {
        path.models
            .first()
            .copied()
            .into_iter()
            .chain(path.contenders.iter().copied())
            .collect()
    };
    if let Some(&end) = path.models.last() {
        standing.extend((0..at).filter(|&i| models[i].extends == Some(end)));
    }
    standing.extend(at..models.len());
    let rivals: Vec<&Model> = standing.iter().map(|&i| &models[i]).collect();
    match ranked(&rivals, stage) {
        Some((best, close)) if standing[best] >= at => Path {
            models: vec![standing[best]],
            contenders: close.iter().map(|&c| standing[c]).collect(),
        },
        _ => path,
    }
}

/// The causes `parts` (indices into `library`) fitted together, from the first one's own fit
/// (`singles`), each further one added to the model of those before it; named by their names
/// joined by " + ", a model that extends the joint-only fit; `why` it was tried.
fn together(
    library: &[Arc<dyn Candidate>],
    singles: &[Model],
    parts: &[usize],
    stage: &Stage,
    lap: Option<&Fitted>,
    why: &str,
) -> Model {
    let name = parts
        .iter()
        .map(|&i| library[i].name())
        .collect::<Vec<_>>()
        .join(" + ");
    let watch = stage.watch.during(Pass::Together(parts.len()));
    let first = &singles[parts[0]];
    let mut outcome = match &first.outcome {
        Ok(fit) => Ok(fit.clone()),
        Err(e) => Err(e.clone()),
    };
    for &i in &parts[1..] {
        let (Ok(fit), Some(part)) = (&outcome, library[i].part()) else {
            break;
        };
        let Some(from) = fit.model.as_ref() else {
            break;
        };
        outcome = combine(&Stage { watch, ..*stage }, from, &part, lap, &name);
    }
    // The causes together add the unknowns of every one of them to the joint-only fit.
    if let Ok(fit) = &mut outcome {
        fit.added = parts
            .iter()
            .map(|&i| singles[i].fit().map_or(0, |f| f.added))
            .sum();
        fit.bounded = parts
            .iter()
            .all(|&i| singles[i].fit().is_some_and(|f| f.bounded));
        fit.describe = format!("the causes {name} together, {why}");
    }
    tell_fitted(&watch, &name, &outcome);
    Model {
        name,
        describe: first.describe.clone(),
        verdict: Verdict::Effect,
        extends: None,
        outcome,
        lrt: None,
        adjusted: None,
        test: None,
    }
}

/// The likelihood-ratio test of `m` against `from`, the model it extends, its p-value adjusted
/// for `tried` hypotheses (module `decide`): against the measurement error when `m` fits
/// within it (judged under the yardstick its own residuals give), both models' chi^2 under that
/// yardstick; else with each model's own discrepancy, their deviances.
fn judge(m: &mut Model, from: &Fitted, tried: usize, stage: &Stage) {
    let Ok(fit) = &m.outcome else {
        return;
    };
    let measured = stage.measured;
    let against_noise = fit.model.as_ref().and_then(|model| {
        let e = yardstick::of_model(&m.name, model, measured, stage.calibration);
        let (chi2, judgement) =
            yardstick::judgement(&e, measured, &fit.residuals, fit.unknowns, fit.dof);
        if !judgement.explains(&e) {
            return None;
        }
        // The model extended, as fitted under its own discrepancy, and refitted under the
        // yardstick to first order: its least chi^2 there, so that the statistic is the
        // likelihood ratio under the yardstick.
        let (own, _) = yardstick::judgement(
            &e,
            measured,
            &residuals(from, measured),
            from.estimates.len(),
            from.dof,
        );
        let before = refitted_chi2(from, measured, &e.calibration()).map_or(own, |c| c.min(own));
        let lrt = (before - chi2).max(0.0);
        Some((lrt, e.lrt_p_value(lrt, fit.added, fit.bounded)))
    });
    let (lrt, p, test) = match against_noise {
        Some((lrt, p)) => (lrt, p, Test::MeasurementError),
        None => {
            let lrt = (from.deviance - fit.deviance).max(0.0);
            let p = fit.model.as_ref().map_or(1.0, |model| {
                let (statistic, dof) =
                    discrepancy::improvement(from, model, measured, stage.calibration);
                lr_sf(statistic, fit.added, dof, fit.bounded)
            });
            (lrt, p, Test::Discrepancy)
        }
    };
    m.lrt = Some(lrt);
    m.adjusted = Some(adjusted(p, tried));
    m.test = Some(test);
}

/// The clearly best of `standing` and its contenders by the relative rules ([`select`]), the
/// models' information criteria read on one scale: where the best by its own deviance fits
/// within the measurement error (its test stood on it), every model's chi^2 under the
/// yardstick that model's residuals give, the scale its significance was read on; else each
/// model's deviance with its own discrepancy. Under a noise estimated at half the stated, the
/// stated scale shrinks every lead to a quarter of what the data show, and two causes the data
/// tell apart would contend.
fn ranked(standing: &[&Model], stage: &Stage) -> Option<(usize, Vec<usize>)> {
    let rivals: Vec<Rival> = standing.iter().map(|m| rival(m)).collect();
    let (best, close) = select(&rivals)?;
    let m = standing[best];
    let fitted = match (m.test, m.fitted()) {
        (Some(Test::MeasurementError), Some(f)) if m.verdict != Verdict::FrequencyDependent => f,
        _ => return Some((best, close)),
    };
    let measured = stage.measured;
    let scale = yardstick::of_model(&m.name, fitted, measured, stage.calibration).calibration();
    let common: Vec<Rival> = standing
        .iter()
        .zip(rivals)
        .map(|(m, r)| Rival {
            deviance: m.fitted().map_or(f64::INFINITY, |f| {
                chi2_of(&residuals(f, measured), measured, &scale)
            }),
            ..r
        })
        .collect();
    select(&common)
}

/// What the relative rules read of `m`.
fn rival(m: &Model) -> Rival {
    match (&m.outcome, m.adjusted) {
        (Ok(fit), Some(adjusted)) => Rival {
            deviance: fit.deviance,
            parameters: fit.parameters.len(),
            adjusted,
            usable: fit.excluded.is_none(),
            dependent: m.verdict == Verdict::FrequencyDependent,
        },
        _ => Rival {
            deviance: f64::INFINITY,
            parameters: 0,
            adjusted: 1.0,
            usable: false,
            dependent: false,
        },
    }
}

/// The candidates (indices into `library`) whose causes the models of `path` hold, when every
/// one of them combines; None when one stands alone.
fn parts_of(
    path: &[usize],
    models: &[Model],
    library: &[Arc<dyn Candidate>],
) -> Option<Vec<usize>> {
    let names: Vec<&str> = models[*path.last()?].name.split(" + ").collect();
    names
        .iter()
        .map(|n| {
            let i = library.iter().position(|c| c.name() == *n)?;
            library[i].part().map(|_| i)
        })
        .collect()
}

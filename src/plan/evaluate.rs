//! A sensor layout judged: every measured mode's spread ([`super::spread`]) under the method's
//! settings, held or chosen with the layout, summarised by the objective into a [`Score`].
//!
//! Everything that no layout changes is formed once ([`Evaluator::new`]): the nominal
//! eigensolution, the retained and weighted sensitivity blocks of every mode under every
//! candidate setting (eq. (10)-(12)), and each mode's fallback, the spread of one parameter
//! from its frequency alone ([`crate::identify::frequency_only`]). A layout then costs one
//! pseudo-inverse per basis size and one Jacobian per mode and setting.

use faer::Mat;
use serde::Serialize;

use super::request::{Objective, SettingsChoice};
use super::spread::{Noise, Propagated, Status, log_det, propagate};
use crate::identify::frequency_only::sensitivities;
use crate::identify::{Identifier, ModeSystem, Projector, Settings, Weighting, basis_index};
use crate::modal::ModalSolution;
use crate::structure::Structure;

/// The largest basis a chosen setting goes to beyond the highest measured mode's index.
pub const EXTRA_BASIS: usize = 4;
/// The most equations a chosen setting retains beyond one per parameter.
pub const EXTRA_EQUATIONS: usize = 4;

/// How good a layout is: fewer undetermined modes first, then a smaller objective, then (for
/// layouts that tie, as those too small for any basis do) better-conditioned target shapes.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct Score {
    /// Measured modes whose corrections the layout does not determine.
    pub undetermined: usize,
    /// The objective over the determinate modes (infinite when none is).
    pub value: f64,
    /// -ln det of the Gram matrix of the target shapes at the sensors (columns of unit norm
    /// over the candidates, a small ridge): Effective Independence's measure.
    pub shapes: f64,
}

impl Score {
    /// Whether `self` is strictly better than `other`.
    pub fn better(&self, other: &Score) -> bool {
        self.undetermined
            .cmp(&other.undetermined)
            .then(self.value.total_cmp(&other.value))
            .then(self.shapes.total_cmp(&other.shapes))
            .is_lt()
    }
}

/// One parameter of a mode identified from its frequency alone.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Fallback {
    /// The parameter (the one the mode's frequency is most sensitive to).
    pub param: String,
    /// Relative standard deviation: 2 sigma_f / |d ln lambda / d ln p|.
    pub relative_std: f64,
}

/// One mode under a layout.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct ModeSpread {
    /// Mode r.
    pub mode: usize,
    /// Determinate, or why not.
    pub status: Status,
    /// Standard deviation of Delta p_i / p_i, per parameter (determinate modes).
    pub relative_std: Option<Vec<f64>>,
    /// cond(W S_r).
    pub condition: Option<f64>,
    /// Resolution of every parameter.
    pub resolution: Option<Vec<f64>>,
    /// The fallback's spread (modes that are not determinate).
    pub fallback: Option<Fallback>,
    /// Covariance of the relative corrections (row-major), for the objective.
    #[serde(skip)]
    pub covariance: Option<Vec<f64>>,
}

/// A layout judged.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Evaluation {
    /// The settings used (`None`: fewer sensors than any basis).
    pub settings: Option<SettingsRecord>,
    /// Every measured mode.
    pub modes: Vec<ModeSpread>,
    /// The score.
    pub score: Score,
    /// The index of the settings among the evaluator's (`None`: none fits).
    #[serde(skip)]
    pub entry: Option<usize>,
}

/// n, m and W as data.
#[derive(Debug, Clone, Copy, PartialEq, Serialize)]
pub struct SettingsRecord {
    /// Basis size.
    pub n: usize,
    /// Retained equations.
    pub m: usize,
    /// Weighting.
    pub weighting: &'static str,
}

impl SettingsRecord {
    fn of(s: Settings) -> Self {
        Self {
            n: s.n,
            m: s.m,
            weighting: s.weighting.name(),
        }
    }
}

/// A candidate setting with the systems of every measured mode (`None`: beyond its basis).
struct Entry {
    settings: Settings,
    systems: Vec<Option<ModeSystem>>,
}

/// Judges layouts of candidate DOFs (see the module docs).
pub struct Evaluator {
    vectors: Mat<f64>,
    lambdas: Vec<f64>,
    modes: Vec<usize>,
    /// 0-based index of each measured mode in the eigensolution.
    columns: Vec<usize>,
    entries: Vec<Entry>,
    fallback: Vec<Option<Fallback>>,
    noise: Noise,
    objective: Objective,
    q: usize,
    /// Unit norm over the candidates of each target column.
    target_norms: Vec<f64>,
    /// Parameter names.
    pub names: Vec<String>,
    /// The smallest basis that holds every measured mode: a layout that determines every
    /// mode needs at least as many sensors (n <= sensors, eq. (15)).
    pub least_sensors: usize,
}

impl Evaluator {
    /// Forms what every layout shares. `modal` holds the nominal pairs up to the largest basis
    /// of `choice`; `candidate_dofs` are the DOFs any layout draws from.
    pub fn new(
        structure: &Structure,
        modal: &ModalSolution,
        modes: &[usize],
        choice: SettingsChoice,
        noise: Noise,
        objective: Objective,
        candidate_dofs: &[usize],
    ) -> Self {
        let rigid = structure.rigid;
        let params = structure.identified();
        let q = params.len();
        let columns: Vec<usize> = modes.iter().map(|r| r - 1 + rigid).collect();
        let settings = match choice {
            SettingsChoice::Given(s) => vec![s],
            SettingsChoice::Chosen => {
                let highest = columns.iter().max().copied().unwrap_or(rigid) + 1;
                chosen_settings(rigid, q, highest, modal.len())
            }
        };
        let entries = settings
            .into_iter()
            .filter_map(|s| {
                let id = Identifier::new(modal, params.clone(), rigid, s).ok()?;
                let systems = modes
                    .iter()
                    .map(|&r| basis_index(r, rigid, s.n).ok().map(|t| id.mode_system(t)))
                    .collect();
                Some(Entry {
                    settings: s,
                    systems,
                })
            })
            .collect::<Vec<_>>();
        let fallback = columns
            .iter()
            .map(|&t| {
                let s = sensitivities(structure, modal, t);
                let (i, si) = s
                    .iter()
                    .enumerate()
                    .max_by(|a, b| a.1.abs().total_cmp(&b.1.abs()))?;
                (si.abs() > 0.0).then(|| Fallback {
                    param: params[i].name.clone(),
                    relative_std: 2.0 * noise.frequency_variance.sqrt() / si.abs(),
                })
            })
            .collect();
        let vectors = modal.vectors().to_owned();
        let target_norms = columns
            .iter()
            .map(|&t| {
                let ss: f64 = candidate_dofs
                    .iter()
                    .map(|&d| vectors[(d, t)].powi(2))
                    .sum();
                ss.sqrt().max(f64::MIN_POSITIVE)
            })
            .collect();
        Self {
            lambdas: modal.values().to_vec(),
            vectors,
            modes: modes.to_vec(),
            columns,
            least_sensors: entries
                .iter()
                .filter(|e| e.systems.iter().all(Option::is_some))
                .map(|e| e.settings.n)
                .min()
                .unwrap_or(usize::MAX),
            entries,
            fallback,
            noise,
            objective,
            q,
            target_norms,
            names: params.into_iter().map(|p| p.name).collect(),
        }
    }

    /// The layout of DOFs `dofs` judged under the best of the settings it allows.
    pub fn evaluate(&self, dofs: &[usize]) -> Evaluation {
        self.evaluate_in(dofs, None)
    }

    /// As [`Evaluator::evaluate`], under the settings of index `entry` alone when given and the
    /// layout has the sensors its basis needs (a search holds the settings while it moves
    /// sensors, and chooses them again after).
    pub fn evaluate_in(&self, dofs: &[usize], entry: Option<usize>) -> Evaluation {
        let shapes = self.shapes_measure(dofs);
        let fits = |e: &usize| self.entries[*e].settings.n <= dofs.len();
        let chosen: Vec<usize> = match entry.filter(fits) {
            Some(e) => vec![e],
            None => (0..self.entries.len()).filter(fits).collect(),
        };
        let mut best: Option<Evaluation> = None;
        let mut projector: Option<(usize, Result<Projector, ()>)> = None;
        for e in chosen {
            let n = self.entries[e].settings.n;
            if projector.as_ref().is_none_or(|(pn, _)| *pn != n) {
                let yt = Mat::from_fn(dofs.len(), n, |i, j| self.vectors[(dofs[i], j)]);
                projector = Some((n, Projector::new(&yt).map_err(|_| ())));
            }
            let proj = &projector.as_ref().expect("set above").1;
            let candidate = self.under(e, proj.as_ref().ok(), dofs, shapes);
            if best
                .as_ref()
                .is_none_or(|b| candidate.score.better(&b.score))
            {
                best = Some(candidate);
            }
        }
        best.unwrap_or_else(|| self.too_few(shapes))
    }

    /// The layout under the entry of index `index`.
    fn under(
        &self,
        index: usize,
        projector: Option<&Projector>,
        dofs: &[usize],
        shapes: f64,
    ) -> Evaluation {
        let entry = &self.entries[index];
        let modes: Vec<ModeSpread> = self
            .modes
            .iter()
            .enumerate()
            .map(|(k, &mode)| {
                let t = self.columns[k];
                let result = match (&entry.systems[k], projector) {
                    (None, _) => Err(Status::BeyondBasis),
                    (Some(_), None) => Err(Status::Unprojectable),
                    (Some(system), Some(p)) => {
                        let shape: Vec<f64> = dofs.iter().map(|&d| self.vectors[(d, t)]).collect();
                        propagate(p, system, &shape, self.lambdas[t], self.noise)
                    }
                };
                self.spread(mode, k, result)
            })
            .collect();
        let score = self.score(&modes, shapes);
        Evaluation {
            settings: Some(SettingsRecord::of(entry.settings)),
            modes,
            score,
            entry: Some(index),
        }
    }

    fn spread(&self, mode: usize, k: usize, result: Result<Propagated, Status>) -> ModeSpread {
        match result {
            Ok(p) => ModeSpread {
                mode,
                status: Status::Determinate,
                relative_std: Some(p.relative_std),
                condition: Some(p.condition),
                resolution: Some(p.resolution),
                fallback: None,
                covariance: Some(p.covariance),
            },
            Err(status) => ModeSpread {
                mode,
                status,
                relative_std: None,
                condition: None,
                resolution: None,
                fallback: self.fallback[k].clone(),
                covariance: None,
            },
        }
    }

    fn too_few(&self, shapes: f64) -> Evaluation {
        let modes: Vec<ModeSpread> = (0..self.modes.len())
            .map(|k| self.spread(self.modes[k], k, Err(Status::TooFewSensors)))
            .collect();
        Evaluation {
            settings: None,
            score: self.score(&modes, shapes),
            modes,
            entry: None,
        }
    }

    /// The objective over the determinate modes (see [`Objective`]).
    fn score(&self, modes: &[ModeSpread], shapes: f64) -> Score {
        let determinate: Vec<&ModeSpread> = modes
            .iter()
            .filter(|m| m.status == Status::Determinate)
            .collect();
        let stds = determinate
            .iter()
            .flat_map(|m| m.relative_std.iter().flatten().copied());
        let value = if determinate.is_empty() {
            f64::INFINITY
        } else {
            match self.objective {
                Objective::Worst => stds.fold(0.0, f64::max),
                Objective::Mean => {
                    let all: Vec<f64> = stds.collect();
                    all.iter().sum::<f64>() / all.len() as f64
                }
                Objective::Det => {
                    let q = self.q;
                    let sum: f64 = determinate
                        .iter()
                        .map(|m| log_det(m.covariance.as_deref().expect("determinate"), q))
                        .sum();
                    (sum / (2.0 * q as f64 * determinate.len() as f64)).exp()
                }
            }
        };
        Score {
            undetermined: modes.len() - determinate.len(),
            value,
            shapes,
        }
    }

    /// -ln det(Phi^T Phi + ridge) of the target shapes at `dofs` (see [`Score::shapes`]).
    fn shapes_measure(&self, dofs: &[usize]) -> f64 {
        let t = self.columns.len();
        let phi = self.target_shapes(dofs);
        let gram = phi.transpose() * &phi;
        let ridged: Vec<f64> = (0..t * t)
            .map(|k| gram[(k / t, k % t)] + if k / t == k % t { 1e-9 } else { 0.0 })
            .collect();
        -log_det(&ridged, t)
    }

    /// The target shapes (measured modes) at `dofs`, each column of unit norm over the
    /// candidates: Effective Independence works on them.
    pub fn target_shapes(&self, dofs: &[usize]) -> Mat<f64> {
        Mat::from_fn(dofs.len(), self.columns.len(), |i, j| {
            self.vectors[(dofs[i], self.columns[j])] / self.target_norms[j]
        })
    }
}

/// Every (n, m, W) a chosen setting may take: n from `rigid + q` to `highest + EXTRA_BASIS`
/// (within `largest`), m from q to n - rigid (within q + EXTRA_EQUATIONS), every weighting.
fn chosen_settings(rigid: usize, q: usize, highest: usize, largest: usize) -> Vec<Settings> {
    let mut out = Vec::new();
    for n in rigid + q..=(highest + EXTRA_BASIS).min(largest) {
        for m in q..=(n - rigid).min(q + EXTRA_EQUATIONS) {
            for weighting in Weighting::ALL {
                out.push(Settings { n, m, weighting });
            }
        }
    }
    out
}

//! Pretest planning: where to put the sensors, and which n, m and weighting, so that the
//! per-mode joint corrections of eq. (5)-(13) come out with the least spread.
//!
//! The pipeline, one file a step:
//! 1. [`request`]: what is asked (sites, counts, modes, noise, fixed sensors, objective);
//! 2. [`candidates`]: the sites resolved on the model's DOFs;
//! 3. [`spread`]: one mode's first-order spread for a layout and a setting;
//! 4. [`evaluate`]: a layout judged over every measured mode and setting, into a score;
//! 5. [`search`]: greedy placement and exchange passes; the sensors a deficient layout lacks;
//! 6. [`reference`]: Effective Independence and evenly spaced layouts, to compare.
//!
//! [`plan`] runs them and returns a [`Plan`], data only: `output::plan` writes the table, the
//! figure, the study that confirms it by Monte-Carlo and the `[[sensor]]` entries.
//!
//! Layer 5 (simulation and studies; see the crate docs): imports the layers below.

pub mod candidates;
pub mod evaluate;
pub mod reference;
pub mod request;
pub mod search;
pub mod spread;

use serde::Serialize;

pub use candidates::Candidate;
pub use evaluate::{Evaluation, Evaluator, ModeSpread, Score};
pub use request::{Objective, Request, SettingsChoice, Sites};
pub use spread::{Noise, Status};

use crate::identify::{Settings, basis_index};
use crate::input::SettingError;
use crate::modal::{ModalError, ModalSolution};
use crate::structure::Structure;

/// Why a plan cannot be made.
#[derive(Debug, thiserror::Error)]
pub enum PlanError {
    /// A setting of the request, named, with its value and what is allowed.
    #[error(transparent)]
    Setting(#[from] SettingError),
    /// The model identifies nothing.
    #[error(
        "the model identifies no parameter (no joint, or every parameter held fixed): there is nothing to plan for"
    )]
    NoParameters,
    /// The model has no eigensolution.
    #[error(transparent)]
    Modal(#[from] ModalError),
}

/// Which kind of layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Kind {
    /// The plan's own (greedy and exchange on the objective).
    Chosen,
    /// Effective Independence.
    EffectiveIndependence,
    /// Evenly spaced.
    Evenly,
    /// The model's `[[sensor]]` entries.
    Model,
}

impl Kind {
    /// The name in tables and study grids.
    pub fn name(self) -> &'static str {
        match self {
            Kind::Chosen => "chosen",
            Kind::EffectiveIndependence => "efi",
            Kind::Evenly => "evenly",
            Kind::Model => "model",
        }
    }
}

/// Sensors to add to a layout that leaves modes undetermined.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Addition {
    /// Candidate indices added.
    pub added: Vec<usize>,
    /// Whether no smaller addition exists (see [`search::Completion::fewest`]).
    pub fewest: bool,
    /// The completed layout, judged.
    pub evaluation: Evaluation,
}

/// One layout of a plan.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Layout {
    /// Which kind.
    pub kind: Kind,
    /// Candidate indices, ascending.
    pub sites: Vec<usize>,
    /// Judged.
    pub evaluation: Evaluation,
    /// When modes are undetermined: the sensors that make every one determinate (`None` when
    /// no addition does, or none is needed).
    pub addition: Option<Addition>,
}

/// The layouts for one count of sensors.
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct CountPlan {
    /// The count.
    pub sensors: usize,
    /// The chosen layout first, then the references.
    pub layouts: Vec<Layout>,
}

/// A plan (see the module docs).
#[derive(Debug, Clone, PartialEq, Serialize)]
pub struct Plan {
    /// The candidates.
    pub candidates: Vec<Candidate>,
    /// Identified parameter names.
    pub parameters: Vec<String>,
    /// Their values p_i (a relative std times p_i is the std of Delta p_i).
    pub values: Vec<f64>,
    /// The measured modes.
    pub modes: Vec<usize>,
    /// The objective.
    pub objective: Objective,
    /// The fixed sensors (candidate indices).
    pub fixed: Vec<usize>,
    /// The model's own layout, when it declares sensors (judged once, whatever the count).
    pub model_layout: Option<Layout>,
    /// Model sensors that read no candidate DOF (left out of `model_layout`).
    pub model_sensors_missed: usize,
    /// One entry per count.
    pub counts: Vec<CountPlan>,
}

/// Makes the plan `request` asks of `structure` (see the module docs).
pub fn plan(structure: &Structure, request: &Request) -> Result<Plan, PlanError> {
    request.check_noise()?;
    let params = structure.identified();
    if params.is_empty() {
        return Err(PlanError::NoParameters);
    }
    check_modes(structure, request)?;
    let candidates = candidates::resolve(structure, &request.sites)?;
    let fixed = request
        .fixed
        .iter()
        .map(|f| candidates::find(structure, &candidates, f, "fixed"))
        .collect::<Result<Vec<usize>, _>>()?;
    check_counts(request, candidates.len(), fixed.len())?;
    if let (SettingsChoice::Given(s), Some(&least)) = (request.settings, request.counts.first()) {
        if least < s.n {
            return Err(SettingError::new(
                "sensors",
                least,
                format!(
                    "the held n = {} needs at least {} sensors (eq. (15) projects on n basis vectors): place more, or hold a smaller n",
                    s.n, s.n
                ),
            )
            .into());
        }
    }
    let (model_sites, missed) = candidates::model_sensors(structure, &candidates);
    let modal = eigensolution(structure, request)?;
    let dofs: Vec<usize> = candidates.iter().map(|c| c.dof).collect();
    let noise = Noise {
        shape_variance: request.noise.shape_variance(request.shape_noise),
        frequency_variance: request.frequency_noise * request.frequency_noise,
    };
    let eval = Evaluator::new(
        structure,
        &modal,
        &request.modes,
        request.settings,
        noise,
        request.objective,
        &dofs,
    );
    let layout = |kind: Kind, sites: &[usize]| {
        let placed = search::judge(&eval, &dofs, sites);
        with_addition(&eval, &dofs, kind, placed)
    };
    let counts = request
        .counts
        .iter()
        .map(|&count| {
            let efi = reference::effective_independence(&eval, &dofs, count, &fixed);
            let evenly = reference::evenly_spaced(&candidates, count, &fixed);
            let starts = [efi.clone(), evenly.clone()];
            let chosen = search::place(&eval, &dofs, count, &fixed, &starts);
            CountPlan {
                sensors: count,
                layouts: vec![
                    with_addition(&eval, &dofs, Kind::Chosen, chosen),
                    layout(Kind::EffectiveIndependence, &efi),
                    layout(Kind::Evenly, &evenly),
                ],
            }
        })
        .collect();
    Ok(Plan {
        model_layout: (!model_sites.is_empty()).then(|| layout(Kind::Model, &model_sites)),
        model_sensors_missed: missed,
        parameters: eval.names.clone(),
        values: params.iter().map(|p| p.value).collect(),
        modes: request.modes.clone(),
        objective: request.objective,
        fixed,
        candidates,
        counts,
    })
}

fn with_addition(eval: &Evaluator, dofs: &[usize], kind: Kind, placed: search::Placed) -> Layout {
    let addition = (placed.evaluation.score.undetermined > 0)
        .then(|| search::complete(eval, dofs, &placed))
        .flatten()
        .map(|c| Addition {
            added: c.added,
            fewest: c.fewest,
            evaluation: c.layout.evaluation,
        });
    Layout {
        kind,
        sites: placed.sites,
        evaluation: placed.evaluation,
        addition,
    }
}

/// Every mode within the model's elastic modes (and the held basis, if held).
fn check_modes(structure: &Structure, request: &Request) -> Result<(), SettingError> {
    let elastic = structure.elastic_count();
    if request.modes.is_empty() {
        return Err(SettingError::new(
            "modes",
            "(none)",
            "at least one mode is required",
        ));
    }
    for (k, &r) in request.modes.iter().enumerate() {
        if request.modes[..k].contains(&r) {
            return Err(SettingError::new(
                "modes",
                r,
                "each mode may be listed once",
            ));
        }
        if r == 0 || r > elastic {
            return Err(SettingError::new(
                "modes",
                r,
                format!(
                    "the model has {elastic} elastic modes: a mode must be from 1 to {elastic}"
                ),
            ));
        }
        if let SettingsChoice::Given(s) = request.settings {
            basis_index(r, structure.rigid, s.n)
                .map_err(|e| SettingError::new("n", s.n, e.to_string()))?;
        }
    }
    if let SettingsChoice::Given(s) = request.settings {
        Settings::new(s.n, s.m, s.weighting, structure)?;
        s.check_equations(structure.identified().len(), structure.rigid)?;
    }
    Ok(())
}

/// Every count within the candidates and above the fixed sensors.
fn check_counts(request: &Request, candidates: usize, fixed: usize) -> Result<(), SettingError> {
    if let Some(&count) = request
        .counts
        .iter()
        .find(|&&c| c > candidates || c < fixed.max(1))
    {
        return Err(SettingError::new(
            "sensors",
            count,
            format!(
                "it must be from {} to {candidates}, the candidate sites{}",
                fixed.max(1),
                if fixed > 0 {
                    format!(" (at least the {fixed} fixed sensors)")
                } else {
                    String::new()
                }
            ),
        ));
    }
    Ok(())
}

/// The nominal pairs every setting and mode needs.
fn eigensolution(structure: &Structure, request: &Request) -> Result<ModalSolution, PlanError> {
    let highest = request.modes.iter().max().copied().unwrap_or(1) + structure.rigid;
    let basis = match request.settings {
        SettingsChoice::Given(s) => s.n,
        SettingsChoice::Chosen => highest + evaluate::EXTRA_BASIS,
    };
    let count = basis.max(highest).min(structure.dof_count());
    Ok(ModalSolution::lowest_of(&structure.assemble(), count)?)
}

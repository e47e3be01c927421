//! Monte-Carlo robustness studies of the per-mode identification: the distribution of every
//! per-mode correction over many independent measurement errors, across a grid of basis
//! sizes n, retained equations m, unidentified DOFs NF, weightings and noise levels.
//!
//! - [`config`]: the study file;
//! - [`unidentified`]: the NF rule;
//! - [`plan`]: cells and the per-cell precomputation;
//! - the error model and the per-trial random streams are [`crate::random`]'s;
//! - [`engine`]: the parallel trials and their statistics;
//! - [`predicted`]: first-order predicted standard deviations;
//! - [`measured_noise`]: a study's noise taken from a measured file's standard errors;
//! - [`results`]: the result CSV, its columns and its writer;
//! - [`check`]: the CI gate on estimator bias;
//! - [`fingerprint`]: what makes two runs of a study the same computation.
//!
//! Layer 5 (simulation and studies; see the crate docs): may import the layers below
//! ([`crate::stats`], [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`],
//! [`crate::modal`], [`crate::model`], [`crate::measured`], [`crate::extract`],
//! [`crate::identify`]) and, without a circle, [`crate::simulate`].

pub mod check;
pub mod config;
pub mod engine;
pub mod fingerprint;
pub mod measured_noise;
pub mod plan;
pub mod predicted;
pub mod resources;
pub mod results;
pub mod unidentified;

pub use crate::random::NoiseKind;
pub use config::{CheckSpec, GateStatistic, Grid, NfSpec, Study};
pub use engine::{CellSamples, RowStats, simulate_cell, simulate_cell_until, summarize_cell};
pub use plan::{Cell, CellPlan, StudyContext};

/// The statistics of one cell.
#[derive(Debug, Clone, PartialEq)]
pub struct CellResult {
    /// The cell.
    pub cell: Cell,
    /// One row per (mode, parameter).
    pub rows: Vec<RowStats>,
}

/// Why a study cannot run.
#[derive(Debug, thiserror::Error)]
pub enum StudyError {
    /// The study or model file is invalid.
    #[error(transparent)]
    Input(#[from] crate::input::InputError),
    /// A model has no eigensolution.
    #[error("{file}: {cause}")]
    Modal {
        /// The model file.
        file: std::path::PathBuf,
        /// Why.
        cause: crate::modal::ModalError,
    },
    /// The model as given, or with the study's modification, is a mechanism.
    #[error("{file}: the {which} model: {cause}")]
    Mechanism {
        /// The study file.
        file: std::path::PathBuf,
        /// `nominal` or `modified (truth.delta)`.
        which: &'static str,
        /// The zero frequency.
        cause: crate::modal::Mechanism,
    },
    /// Some cells of the grid cannot be computed.
    #[error("{file}: {count} impossible cell(s) in the grid, nothing was computed:\n{list}", count = problems.len(), list = problems.join("\n"))]
    ImpossibleCells {
        /// The study file.
        file: std::path::PathBuf,
        /// One line per offending cell.
        problems: Vec<String>,
    },
}

/// A validated study with its shared eigensolutions, ready to run cell by cell.
pub struct StudyRun {
    /// The study.
    pub study: Study,
    /// Shared eigensolutions.
    pub context: StudyContext,
    /// The cells, in grid order.
    pub cells: Vec<Cell>,
}

impl StudyRun {
    /// Solves the models and validates every cell before anything is computed.
    pub fn new(study: Study) -> Result<Self, StudyError> {
        let context = StudyContext::new(&study)?;
        let cells = study.cells();
        let problems: Vec<String> = cells
            .iter()
            .filter_map(|cell| {
                CellPlan::new(&study, &context, cell)
                    .err()
                    .map(|e| format!("  cell {} ({}): {e}", cell.index, cell.describe()))
            })
            .collect();
        if !problems.is_empty() {
            return Err(StudyError::ImpossibleCells {
                file: study.file.clone(),
                problems,
            });
        }
        Ok(Self {
            study,
            context,
            cells,
        })
    }

    /// Plans, simulates and summarises one cell; the raw trials are returned beside the
    /// statistics for whoever keeps them, and dropped by the caller before the next cell.
    pub fn run_cell(
        &self,
        cell: &Cell,
        progress: &(dyn Fn(u64) + Sync),
    ) -> (CellResult, CellSamples) {
        self.run_cell_until(cell, progress, &std::sync::atomic::AtomicBool::new(false))
            .expect("a flag that nothing sets never stops the cell")
    }

    /// [`StudyRun::run_cell`], stopped within a block of trials once `stop` is set (an
    /// interrupted call): None then.
    pub fn run_cell_until(
        &self,
        cell: &Cell,
        progress: &(dyn Fn(u64) + Sync),
        stop: &std::sync::atomic::AtomicBool,
    ) -> Option<(CellResult, CellSamples)> {
        let plan = CellPlan::new(&self.study, &self.context, cell)
            .expect("cells are validated in StudyRun::new");
        let raw = simulate_cell_until(&self.study, cell, &plan, progress, stop)?;
        let rows = summarize_cell(&self.study, &plan, &raw);
        Some((
            CellResult {
                cell: cell.clone(),
                rows,
            },
            raw,
        ))
    }

    /// Total trials of the study, cells times trials per cell (for progress).
    pub fn trial_count(&self) -> u64 {
        (self.cells.len() * self.study.trials) as u64
    }
}

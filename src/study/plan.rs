//! The cells of a study and, per cell, everything that does not change between trials:
//! the identified DOFs, the projector Y~^+ (eq. (15)), the retained and weighted sensitivity
//! blocks of every mode (eq. (10)-(13)) and the exact truth modes.
//!
//! The nominal and truth eigensolutions are shared by every cell: the model is the same.

use crate::identify::{Identifier, IdentifyError, ModeSystem, Projector, Settings, Weighting};
use crate::modal::{ModalSolution, check_elastic};
use crate::structure::{Parameter, Structure};

use super::StudyError;
use super::config::{NfSpec, Study};
use super::unidentified;

/// One combination of the grid's axes.
#[derive(Debug, Clone, PartialEq)]
pub struct Cell {
    /// Position in the study, 0-based: grid by grid, and within a grid in the order n, m, nf,
    /// weighting, shape_noise, frequency_noise, the last varying fastest.
    pub index: usize,
    /// Field path of the cell's grid (`grid` or `grid[1]`).
    pub grid: String,
    /// Basis size n and its index in `grid.n`.
    pub n: (usize, usize),
    /// Retained equations m and its index in `grid.m`.
    pub m: (usize, usize),
    /// Index of the entry in `grid.nf`.
    pub nf_index: usize,
    /// Unidentified DOFs (ascending).
    pub unidentified: Vec<usize>,
    /// Their labels (`node:dof` on a chain).
    pub unidentified_labels: Vec<String>,
    /// Weighting.
    pub weighting: Weighting,
    /// Shape noise level.
    pub shape_noise: f64,
    /// Frequency noise level.
    pub frequency_noise: f64,
}

impl Cell {
    /// NF, the number of unidentified DOFs.
    pub fn nf(&self) -> usize {
        self.unidentified.len()
    }

    /// The unidentified DOFs as their labels (`node:dof` on a chain) separated by spaces.
    pub fn unidentified_names(&self) -> String {
        self.unidentified_labels.join(" ")
    }

    /// The cell's conditions as the result CSV writes them: n, m, nf, weighting, shape noise,
    /// frequency noise.
    pub fn condition_fields(&self) -> [String; 6] {
        [
            self.n.0.to_string(),
            self.m.0.to_string(),
            self.nf().to_string(),
            self.weighting.to_string(),
            self.shape_noise.to_string(),
            self.frequency_noise.to_string(),
        ]
    }

    /// `n = 10, m = 5, nf = 5, weighting = inverse, shape_noise = 0.04, frequency_noise = 0`.
    pub fn describe(&self) -> String {
        format!(
            "n = {}, m = {}, nf = {}, weighting = {}, shape_noise = {}, frequency_noise = {}",
            self.n.0,
            self.m.0,
            self.nf(),
            self.weighting,
            self.shape_noise,
            self.frequency_noise
        )
    }
}

impl Study {
    /// Every cell of the study, in order (see [`Cell::index`]).
    pub fn cells(&self) -> Vec<Cell> {
        let mut cells = Vec::new();
        for g in &self.grids {
            for (ni, &n) in g.n.iter().enumerate() {
                for (mi, &m) in g.m.iter().enumerate() {
                    for (fi, nf) in g.nf.iter().enumerate() {
                        let unidentified = match nf {
                            NfSpec::Count(c) => unidentified::by_rule(&self.model.dofs, *c),
                            NfSpec::Explicit(list) => list.clone(),
                        };
                        let labels: Vec<String> = unidentified
                            .iter()
                            .map(|&d| self.model.dofs.get(d).label.clone())
                            .collect();
                        for &weighting in &g.weighting {
                            for &shape_noise in &g.shape_noise {
                                for &frequency_noise in &g.frequency_noise {
                                    cells.push(Cell {
                                        index: cells.len(),
                                        grid: g.path.clone(),
                                        n: (n, ni),
                                        m: (m, mi),
                                        nf_index: fi,
                                        unidentified: unidentified.clone(),
                                        unidentified_labels: labels.clone(),
                                        weighting,
                                        shape_noise,
                                        frequency_noise,
                                    });
                                }
                            }
                        }
                    }
                }
            }
        }
        cells
    }
}

/// The eigensolutions shared by every cell.
#[derive(Debug, Clone)]
pub struct StudyContext {
    /// The nominal (initial) model's eigensolution.
    pub nominal: ModalSolution,
    /// The truth (simulated identified) model's eigensolution.
    pub truth: ModalSolution,
    /// The identified parameters at their nominal values.
    pub params: Vec<Parameter>,
    /// Rigid-body modes of the model.
    pub rigid: usize,
}

impl StudyContext {
    /// Solves the nominal and the truth model for the pairs the grid uses: the truth up to
    /// the highest mode, the nominal up to the largest basis n as well (all pairs, by the
    /// dense solve, for a small model; the lowest ones by the sparse solver for a large one).
    /// Either model being a mechanism is an error.
    pub fn new(study: &Study) -> Result<Self, StudyError> {
        let rigid = study.model.rigid;
        let highest = study.modes.iter().copied().max().unwrap_or(1) + rigid;
        let largest_n = study
            .grids
            .iter()
            .flat_map(|g| g.n.iter().copied())
            .max()
            .unwrap_or(highest);
        let solve = |which: &'static str, structure: &Structure, count: usize| {
            let matrices = structure.assemble();
            let modal =
                ModalSolution::lowest_of(&matrices, count).map_err(|cause| StudyError::Modal {
                    file: study.model_file.clone(),
                    cause,
                })?;
            check_elastic(&matrices, &modal, rigid).map_err(|cause| StudyError::Mechanism {
                file: study.file.clone(),
                which,
                cause,
            })?;
            Ok::<_, StudyError>(modal)
        };
        let truth = study.model.with_delta(&study.delta);
        Ok(Self {
            nominal: solve("nominal", &study.model, largest_n.max(highest))?,
            truth: solve("modified (truth.delta)", &truth, highest)?,
            params: study.model.identified(),
            rigid,
        })
    }
}

/// One mode of a cell: its sensitivity system and its exact truth.
#[derive(Debug, Clone)]
pub struct ModePlan {
    /// Mode r.
    pub mode: usize,
    /// The retained, weighted system.
    pub system: ModeSystem,
    /// Exact truth shape at the identified DOFs.
    pub truth_shape: Vec<f64>,
    /// Exact truth eigenvalue.
    pub truth_lambda: f64,
    /// The shape noise level of this mode: the cell's, times the mode's measured relative
    /// error under a measured noise ([`Study::noise_scale`]).
    pub shape_noise: f64,
    /// The frequency noise level of this mode, likewise.
    pub frequency_noise: f64,
}

/// Everything of a cell that does not change between trials.
#[derive(Debug, Clone)]
pub struct CellPlan {
    /// Identified DOFs (ascending).
    pub identified: Vec<usize>,
    /// Y~^+ over them.
    pub projector: Projector,
    /// One plan per grid mode, in grid order.
    pub modes: Vec<ModePlan>,
    /// Parameter values p_i.
    pub values: Vec<f64>,
}

impl CellPlan {
    /// Plans `cell`, or says, with the grid field at fault, why it is impossible.
    pub fn new(study: &Study, ctx: &StudyContext, cell: &Cell) -> Result<CellPlan, String> {
        let settings = Settings {
            n: cell.n.0,
            m: cell.m.0,
            weighting: cell.weighting,
        };
        let at = |field: &str, index: usize, value: usize, e: &dyn std::fmt::Display| {
            format!("{}.{field}[{index}] = {value}: {e}", cell.grid)
        };
        let identifier = Identifier::new(&ctx.nominal, ctx.params.clone(), ctx.rigid, settings)
            .map_err(|e| match e {
                IdentifyError::Setting(ref s) if s.setting == "n" => {
                    at("n", cell.n.1, cell.n.0, &e)
                }
                _ => at("m", cell.m.1, cell.m.0, &e),
            })?;
        let identified = unidentified::complement(study.model.dof_count(), &cell.unidentified);
        let basis = identifier.basis();
        let observed = faer::Mat::from_fn(identified.len(), basis.ncols(), |i, j| {
            basis[(identified[i], j)]
        });
        let projector = Projector::new(&observed).map_err(|e| {
            format!(
                "{grid}.nf[{}] (NF = {}) with {grid}.n[{}] = {}: {e}",
                cell.nf_index,
                cell.nf(),
                cell.n.1,
                cell.n.0,
                grid = cell.grid
            )
        })?;
        let modes = study
            .modes
            .iter()
            .enumerate()
            .map(|(k, &mode)| {
                let s_r = identifier
                    .basis_index(mode)
                    .map_err(|e| at("modes", k, mode, &e))?;
                let truth = ctx.truth.vectors();
                let (shape_scale, frequency_scale) = study.noise_scale(mode);
                Ok(ModePlan {
                    mode,
                    system: identifier.mode_system(s_r),
                    truth_shape: identified.iter().map(|&d| truth[(d, s_r)]).collect(),
                    truth_lambda: ctx.truth.values()[s_r],
                    shape_noise: cell.shape_noise * shape_scale,
                    frequency_noise: cell.frequency_noise * frequency_scale,
                })
            })
            .collect::<Result<Vec<_>, String>>()?;
        Ok(CellPlan {
            identified,
            projector,
            modes,
            values: ctx.params.iter().map(|p| p.value).collect(),
        })
    }

    /// Number of parameters q.
    pub fn q(&self) -> usize {
        self.values.len()
    }
}

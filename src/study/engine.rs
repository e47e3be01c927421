//! The Monte-Carlo trials of one cell, in parallel, and their statistics.
//!
//! A trial (the paper's single simulated identification, repeated): for each mode, multiply
//! every identified element of the exact truth shape by (1 + e), perturb the frequency,
//! project (eq. (15)), assemble (eq. (10)-(12)) and solve (eq. (13)); keep
//! Delta p_i = p_i Z_r(i). Trials run on rayon's pool; each draws from its own stream
//! ([`crate::random`]) and writes its own slot, so the result does not depend on the number of
//! threads. A trial allocates nothing: buffers are per worker.
//!
//! Trials go `LANES` at a time through the projection and the assembly, whose loops then
//! run across trials and vectorise; each trial keeps its own order of operations, so its
//! result is bitwise that of the one-trial path ([`crate::identify::Identifier::identify`]
//! on the same data). On x86-64 with AVX2 the block kernel is compiled a second time with
//! AVX2 enabled and chosen at run time; both builds give the same bits. The AVX2 build
//! draws uniform shape errors with the explicit AVX2 generator
//! ([`crate::random::LaneRng::uniform_shape_errors_avx2`], bitwise the portable one).

use std::sync::atomic::{AtomicBool, Ordering};

use rayon::prelude::*;

use super::config::Study;
use super::plan::{Cell, CellPlan};
use super::predicted::predicted_std;
use crate::identify::{LANES, Lanes, wls};
use crate::random::{LaneRng, NoiseKind};
use crate::stats::{Summary, summarize};

/// Trials handed to a worker at a time (and the granularity of progress reports).
const BLOCK: usize = 512;

/// The raw outcome of every trial of a cell.
#[derive(Debug, Clone, PartialEq)]
pub struct CellSamples {
    /// Modes per trial.
    pub modes: usize,
    /// Parameters per mode.
    pub q: usize,
    /// Delta p, trial-major: `(trial * modes + k) * q + i`; 0 where the trial failed.
    pub values: Vec<f64>,
    /// Whether S_r was rank deficient: `trial * modes + k`.
    pub failed: Vec<bool>,
}

impl CellSamples {
    /// Number of trials.
    pub fn trials(&self) -> usize {
        self.failed.len() / self.modes
    }
}

/// The statistics of one (cell, mode, parameter).
#[derive(Debug, Clone, PartialEq)]
pub struct RowStats {
    /// Mode r.
    pub mode: usize,
    /// Parameter index i.
    pub param: usize,
    /// Introduced modification.
    pub introduced: f64,
    /// Trials run.
    pub trials: usize,
    /// Trials whose S_r was rank deficient (left out of the statistics).
    pub failures: usize,
    /// Statistics of the successful trials; `None` when every trial failed.
    pub summary: Option<Summary>,
    /// First-order predicted standard deviation; `None` when the noise-free S_r is rank
    /// deficient.
    pub predicted_std: Option<f64>,
}

struct Scratch {
    shape: Vec<Lanes>,
    g: Vec<Lanes>,
    ws: Vec<Lanes>,
    wb: Vec<Lanes>,
    r: Vec<Lanes>,
    z: Vec<Lanes>,
    ok: [bool; LANES],
}

impl Scratch {
    fn new(plan: &CellPlan, n: usize) -> Self {
        let (m, q) = (plan.modes.first().map_or(0, |p| p.system.m()), plan.q());
        Scratch {
            shape: vec![[0.0; LANES]; plan.identified.len()],
            g: vec![[0.0; LANES]; n],
            ws: vec![[0.0; LANES]; m * q],
            wb: vec![[0.0; LANES]; m],
            r: vec![[0.0; LANES]; q * q],
            z: vec![[0.0; LANES]; q],
            ok: [false; LANES],
        }
    }
}

/// Runs every trial of `cell`; `progress` is told how many trials finished, block by block.
pub fn simulate_cell(
    study: &Study,
    cell: &Cell,
    plan: &CellPlan,
    progress: &(dyn Fn(u64) + Sync),
) -> CellSamples {
    simulate_cell_until(study, cell, plan, progress, &AtomicBool::new(false))
        .expect("a flag that nothing sets never stops the trials")
}

/// [`simulate_cell`], stopped when `stop` is set: no block of trials starts after it is seen
/// (a block of [`BLOCK`] trials takes milliseconds), and None is returned. The trials that
/// run are those of [`simulate_cell`], so a run that is not stopped gives the same bits.
pub fn simulate_cell_until(
    study: &Study,
    cell: &Cell,
    plan: &CellPlan,
    progress: &(dyn Fn(u64) + Sync),
    stop: &AtomicBool,
) -> Option<CellSamples> {
    let (modes, q) = (plan.modes.len(), plan.q());
    let trials = study.trials;
    let mut values = vec![0.0; trials * modes * q];
    let mut failed = vec![false; trials * modes];
    values
        .par_chunks_mut(BLOCK * modes * q)
        .zip(failed.par_chunks_mut(BLOCK * modes))
        .enumerate()
        .try_for_each_init(
            || Scratch::new(plan, cell.n.0),
            |scratch, (block, (values, failed))| {
                if stop.load(Ordering::Relaxed) {
                    return Err(Stopped);
                }
                let job = Block {
                    plan,
                    cell,
                    seed: study.seed,
                    noise: study.noise,
                    first: block * BLOCK,
                };
                job.run(scratch, values, failed);
                progress((failed.len() / modes) as u64);
                Ok(())
            },
        )
        .ok()?;
    Some(CellSamples {
        modes,
        q,
        values,
        failed,
    })
}

/// The trials were stopped before their end.
struct Stopped;

/// A run of consecutive trials of one cell.
struct Block<'a> {
    plan: &'a CellPlan,
    cell: &'a Cell,
    seed: u64,
    noise: NoiseKind,
    first: usize,
}

impl Block<'_> {
    fn run(&self, s: &mut Scratch, values: &mut [f64], failed: &mut [bool]) {
        #[cfg(target_arch = "x86_64")]
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU supports AVX2, checked just above.
            return unsafe { self.run_avx2(s, values, failed) };
        }
        self.run_portable(s, values, failed)
    }

    #[cfg(target_arch = "x86_64")]
    #[target_feature(enable = "avx2")]
    fn run_avx2(&self, s: &mut Scratch, values: &mut [f64], failed: &mut [bool]) {
        self.run_lanes::<true>(s, values, failed)
    }

    fn run_portable(&self, s: &mut Scratch, values: &mut [f64], failed: &mut [bool]) {
        self.run_lanes::<false>(s, values, failed)
    }

    /// The trials, `LANES` at a time; `AVX2` (true only under [`Block::run_avx2`], after the
    /// CPU was checked) draws uniform shape errors with explicit AVX2 instructions.
    #[inline(always)]
    fn run_lanes<const AVX2: bool>(
        &self,
        s: &mut Scratch,
        values: &mut [f64],
        failed: &mut [bool],
    ) {
        let (plan, cell) = (self.plan, self.cell);
        let (modes, q) = (plan.modes.len(), plan.q());
        let count = failed.len() / modes;
        for start in (0..count).step_by(LANES) {
            let used = LANES.min(count - start);
            let mut rng = LaneRng::new(self.seed, cell.index as u64, (self.first + start) as u64);
            for (k, mode) in plan.modes.iter().enumerate() {
                if mode.shape_noise > 0.0 {
                    #[cfg(target_arch = "x86_64")]
                    if AVX2 && self.noise == NoiseKind::Uniform {
                        // SAFETY: AVX2 is true only in `run_avx2`, called after the CPU was
                        // checked for AVX2.
                        unsafe { rng.uniform_shape_errors_avx2(mode.shape_noise, &mut s.shape) };
                    } else {
                        rng.shape_errors(self.noise, mode.shape_noise, &mut s.shape);
                    }
                    #[cfg(not(target_arch = "x86_64"))]
                    rng.shape_errors(self.noise, mode.shape_noise, &mut s.shape);
                    for (y, &exact) in s.shape.iter_mut().zip(&mode.truth_shape) {
                        for e in y.iter_mut() {
                            *e = exact * (1.0 + *e);
                        }
                    }
                } else {
                    for (y, &exact) in s.shape.iter_mut().zip(&mode.truth_shape) {
                        *y = [exact; LANES];
                    }
                }
                let mut lambda = [mode.truth_lambda; LANES];
                if mode.frequency_noise > 0.0 {
                    let eps = rng.frequency_errors(self.noise, mode.frequency_noise);
                    for l in 0..LANES {
                        let f = 1.0 + eps[l];
                        lambda[l] = mode.truth_lambda * f * f;
                    }
                }
                plan.projector.project_lanes(&s.shape, &mut s.g);
                mode.system
                    .assemble_lanes(&s.g, &lambda, &mut s.ws, &mut s.wb);
                wls::solve_lanes(
                    &mut s.ws,
                    &mut s.wb,
                    mode.system.m(),
                    q,
                    &mut s.r,
                    &mut s.z,
                    &mut s.ok,
                );
                for l in 0..used {
                    let t = start + l;
                    let out = &mut values[(t * modes + k) * q..(t * modes + k + 1) * q];
                    if s.ok[l] {
                        for ((o, z), p) in out.iter_mut().zip(&s.z).zip(&plan.values) {
                            *o = p * z[l];
                        }
                    } else {
                        failed[t * modes + k] = true;
                        out.fill(0.0);
                    }
                }
            }
        }
    }
}

/// The statistics of every (mode, parameter) of a cell, in (mode, parameter) order. The
/// columns are gathered and summarised in parallel, one column per task; each column's
/// result depends on its values alone, so the output does not depend on the thread count.
pub fn summarize_cell(study: &Study, plan: &CellPlan, samples: &CellSamples) -> Vec<RowStats> {
    let (modes, q) = (samples.modes, samples.q);
    let trials = samples.trials();
    let predicted: Vec<_> = plan
        .modes
        .iter()
        .map(|mode| predicted_std(plan, mode, study.noise))
        .collect();
    (0..modes * q)
        .into_par_iter()
        .map(|column_index| {
            let (k, i) = (column_index / q, column_index % q);
            let mut column: Vec<f64> = (0..trials)
                .filter(|t| !samples.failed[t * modes + k])
                .map(|t| samples.values[(t * modes + k) * q + i])
                .collect();
            RowStats {
                mode: plan.modes[k].mode,
                param: i,
                introduced: study.delta[i],
                trials,
                failures: trials - column.len(),
                summary: summarize(&mut column, study.delta[i]),
                predicted_std: predicted[k].as_ref().map(|p| p[i]),
            }
        })
        .collect()
}

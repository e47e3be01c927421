//! Which cells shard K of N runs: a deterministic assignment balanced by the estimated cost
//! of each cell.
//!
//! Cost of a cell. Every trial of every mode draws the d identified shape errors, projects them
//! on the basis (Y~^+ is n x d: n d products, eq. (15)), assembles the m x q system (its
//! entries are sums over the n basis vectors: m q n products, eq. (10)-(12)) and solves it
//! (m q^2, eq. (13)); beside these, work that does not grow with n, m or d (the stream's
//! set-up, bookkeeping, the sorts of the statistics) costs about as much again. The estimate,
//! in multiply-adds, is
//!
//! ```text
//!   cost(cell) = trials * modes * (C + d + n d + m q n + m q^2),   C = 300
//! ```
//!
//! with d = DOFs - NF. C is a least-squares fit to single-thread times of the 27 cells of
//! paper case I (300 000 trials each, release build, `jointid study --shard K/27`): the cells
//! cost 840 to 2344 without it, and their times grow by only 2.3x, not 2.8x. It only has to
//! rank and weigh cells: a common factor cancels.
//!
//! Assignment (longest processing time first): the cells sorted by decreasing cost, ties by
//! ascending cell index, each given in turn to the shard with the least total cost so far,
//! ties to the lowest shard number. Every cell goes to exactly one shard, and the result
//! depends only on the study file and N, never on the machine: every array task computes the
//! same assignment. LPT's makespan is at most 4/3 - 1/(3N) of the optimum (Graham, "Bounds
//! on multiprocessing timing anomalies", SIAM J. Appl. Math. 17, 1969).

use crate::study::{Cell, Study};

/// Shard K of N (1 <= K <= N).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct ShardSpec {
    /// K, 1-based.
    pub index: usize,
    /// N.
    pub count: usize,
}

/// A `K/N` that is not a shard.
#[derive(Debug, Clone, PartialEq, Eq, thiserror::Error)]
pub enum ShardError {
    /// Not of the form K/N with integers.
    #[error("--shard {text} is invalid: it must be K/N with integers 1 <= K <= N, e.g. 2/8")]
    Syntax {
        /// The text given.
        text: String,
    },
    /// K outside 1..=N or N = 0.
    #[error("--shard {index}/{count} is invalid: K must be from 1 to N and N at least 1")]
    Range {
        /// K.
        index: usize,
        /// N.
        count: usize,
    },
}

impl std::str::FromStr for ShardSpec {
    type Err = ShardError;

    fn from_str(text: &str) -> Result<Self, ShardError> {
        let syntax = || ShardError::Syntax { text: text.into() };
        let (k, n) = text.split_once('/').ok_or_else(syntax)?;
        let index: usize = k.trim().parse().map_err(|_| syntax())?;
        let count: usize = n.trim().parse().map_err(|_| syntax())?;
        if count == 0 || index == 0 || index > count {
            return Err(ShardError::Range { index, count });
        }
        Ok(ShardSpec { index, count })
    }
}

impl std::fmt::Display for ShardSpec {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        write!(f, "{}/{}", self.index, self.count)
    }
}

/// The estimated cost of one cell, in multiply-adds (see the module docs).
pub fn cell_cost(study: &Study, cell: &Cell) -> f64 {
    let d = study.model.dof_count().saturating_sub(cell.nf()) as f64;
    let q = study.model.identified().len() as f64;
    let (n, m) = (cell.n.0 as f64, cell.m.0 as f64);
    study.trials as f64 * study.modes.len() as f64 * (FIXED + d + n * d + m * q * n + m * q * q)
}

/// C: the work of a trial-mode that does not grow with n, m or d, in multiply-adds.
pub const FIXED: f64 = 300.0;

/// The shard (1-based) of every cell, given the cells' costs in cell order, for `count`
/// shards.
pub fn assign(costs: &[f64], count: usize) -> Vec<usize> {
    // More shards than cells leave the extra ones empty: the same assignment as one shard per
    // cell, without a load vector of N entries.
    let count = count.clamp(1, costs.len().max(1));
    let mut order: Vec<usize> = (0..costs.len()).collect();
    order.sort_by(|&a, &b| costs[b].total_cmp(&costs[a]).then(a.cmp(&b)));
    let mut load = vec![0.0_f64; count];
    let mut shard_of = vec![0; costs.len()];
    for cell in order {
        let lightest = (0..count)
            .min_by(|&a, &b| load[a].total_cmp(&load[b]).then(a.cmp(&b)))
            .expect("count >= 1");
        load[lightest] += costs[cell];
        shard_of[cell] = lightest + 1;
    }
    shard_of
}

/// The shard of every cell of `study` (1-based, in cell order), for `count` shards.
pub fn study_assignment(study: &Study, cells: &[Cell], count: usize) -> Vec<usize> {
    let costs: Vec<f64> = cells.iter().map(|c| cell_cost(study, c)).collect();
    assign(&costs, count)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn parses_and_rejects() {
        assert_eq!(
            "2/8".parse::<ShardSpec>(),
            Ok(ShardSpec { index: 2, count: 8 })
        );
        for bad in ["0/4", "5/4", "1/0"] {
            assert!(matches!(
                bad.parse::<ShardSpec>(),
                Err(ShardError::Range { .. })
            ));
        }
        for bad in ["2", "a/4", "2/", "-1/4"] {
            assert!(matches!(
                bad.parse::<ShardSpec>(),
                Err(ShardError::Syntax { .. })
            ));
        }
    }

    #[test]
    fn every_cell_goes_to_exactly_one_shard_and_loads_are_balanced() {
        // Costs of varied size, some equal, independent of any study.
        let costs: Vec<f64> = (0..53).map(|i| ((i * 37) % 11 + 1) as f64).collect();
        for count in 1..=17 {
            let shard_of = assign(&costs, count);
            assert_eq!(shard_of.len(), costs.len());
            assert!(shard_of.iter().all(|&s| (1..=count).contains(&s)));
            let mut load = vec![0.0; count];
            for (c, &s) in costs.iter().zip(&shard_of) {
                load[s - 1] += c;
            }
            let total: f64 = costs.iter().sum();
            let largest = costs.iter().cloned().fold(0.0, f64::max);
            // The bound of any greedy list schedule: the last cell placed on the fullest
            // shard found it at most at the average load.
            let makespan = load.iter().cloned().fold(0.0, f64::max);
            assert!(
                makespan <= total / count as f64 + largest,
                "N = {count}: {makespan} > {total} / N + {largest}"
            );
            assert_eq!(assign(&costs, count), shard_of, "deterministic");
        }
    }
}

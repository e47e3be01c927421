//! The search for a layout: greedy placement, then exchange passes, both deterministic (the
//! candidates are tried in order and a tie keeps the earlier one).
//!
//! 1. Greedy: from the fixed sensors, add the candidate whose layout scores best
//!    ([`super::evaluate::Score`]), until the count is reached.
//! 2. Exchange: for every free sensor in turn, try every unused candidate in its place and keep
//!    each strict improvement; repeat the passes until one improves nothing (each accepted
//!    exchange lowers the score, so the passes end).
//! 3. The same exchange passes from the other layouts the caller gives (the references), and
//!    the best of all the ends: the chosen layout is never worse than a reference on the
//!    objective.
//!
//! [`complete`] answers the other question a plan asks of a layout that leaves modes
//! undetermined: the fewest sensors to add, and where.

use super::evaluate::{Evaluation, Evaluator};

/// A layout: candidate indices, ascending, with its evaluation.
#[derive(Debug, Clone)]
pub struct Placed {
    /// Candidate indices, ascending.
    pub sites: Vec<usize>,
    /// Its evaluation.
    pub evaluation: Evaluation,
}

/// The most exchange passes (each accepted exchange lowers the score; the bound only guards
/// against a cycle of rounding ties).
pub const MAX_PASSES: usize = 20;

/// Judges the layout of candidate indices `sites` (`dofs[i]` the DOF of candidate i) under
/// the best settings it allows.
pub fn judge(eval: &Evaluator, dofs: &[usize], sites: &[usize]) -> Placed {
    judge_in(eval, dofs, sites, None)
}

/// [`judge`] under the settings of index `entry` when given (and the layout fits them).
fn judge_in(eval: &Evaluator, dofs: &[usize], sites: &[usize], entry: Option<usize>) -> Placed {
    let mut sorted = sites.to_vec();
    sorted.sort_unstable();
    let layout: Vec<usize> = sorted.iter().map(|&i| dofs[i]).collect();
    Placed {
        evaluation: eval.evaluate_in(&layout, entry),
        sites: sorted,
    }
}

/// The best candidate to add to `current` (under its settings, chosen again after), if any
/// is unused.
fn best_addition(eval: &Evaluator, dofs: &[usize], current: &Placed) -> Option<Placed> {
    let (sites, entry) = (&current.sites, current.evaluation.entry);
    let mut best: Option<Placed> = None;
    for c in (0..dofs.len()).filter(|c| !sites.contains(c)) {
        let mut trial = sites.to_vec();
        trial.push(c);
        let placed = judge_in(eval, dofs, &trial, entry);
        if best
            .as_ref()
            .is_none_or(|b| placed.evaluation.score.better(&b.evaluation.score))
        {
            best = Some(placed);
        }
    }
    best.map(|b| judge(eval, dofs, &b.sites))
}

/// `count` sensors over the candidates `dofs`, the `fixed` ones (candidate indices) kept;
/// `starts` are other layouts of `count` sites (holding `fixed`) to exchange from as well.
pub fn place(
    eval: &Evaluator,
    dofs: &[usize],
    count: usize,
    fixed: &[usize],
    starts: &[Vec<usize>],
) -> Placed {
    let mut greedy = judge(eval, dofs, fixed);
    while greedy.sites.len() < count {
        greedy = best_addition(eval, dofs, &greedy).expect("count <= candidates");
    }
    let mut best = exchange(eval, dofs, fixed, greedy);
    for start in starts {
        let end = exchange(eval, dofs, fixed, judge(eval, dofs, start));
        if end.evaluation.score.better(&best.evaluation.score) {
            best = end;
        }
    }
    best
}

/// Exchange passes from `current` (see the module docs), each under the settings the layout
/// had at its start, which are chosen again after it.
fn exchange(eval: &Evaluator, dofs: &[usize], fixed: &[usize], mut current: Placed) -> Placed {
    for _ in 0..MAX_PASSES {
        let entry = current.evaluation.entry;
        let mut improved = false;
        for slot in 0..current.sites.len() {
            if fixed.contains(&current.sites[slot]) {
                continue;
            }
            for c in 0..dofs.len() {
                if current.sites.contains(&c) {
                    continue;
                }
                let mut trial = current.sites.clone();
                trial[slot] = c;
                let placed = judge_in(eval, dofs, &trial, entry);
                if placed.evaluation.score.better(&current.evaluation.score) {
                    current = placed;
                    improved = true;
                }
            }
        }
        current = judge(eval, dofs, &current.sites);
        if !improved {
            break;
        }
    }
    current
}

/// The sensors to add to a layout that leaves modes undetermined.
#[derive(Debug, Clone)]
pub struct Completion {
    /// Candidate indices added, in the order added.
    pub added: Vec<usize>,
    /// The completed layout.
    pub layout: Placed,
    /// Whether `added` is provably the fewest: one sensor, or as many as the smallest basis
    /// that holds every measured mode needs (n <= sensors), so no smaller addition exists.
    pub fewest: bool,
}

/// Sensors added greedily to `layout` (kept) until every measured mode is determinate; `None`
/// when even every candidate leaves one undetermined. When the count reached is the least
/// any basis needs, the addition is the fewest; otherwise it is the fewest greedily found and
/// every smaller addition was tried greedily only.
pub fn complete(eval: &Evaluator, dofs: &[usize], layout: &Placed) -> Option<Completion> {
    let mut current = layout.clone();
    let mut added = Vec::new();
    while current.evaluation.score.undetermined > 0 {
        let next = best_addition(eval, dofs, &current)?;
        let new = next
            .sites
            .iter()
            .copied()
            .find(|s| !current.sites.contains(s))
            .expect("one added");
        added.push(new);
        current = next;
    }
    let needed = eval.least_sensors.max(layout.sites.len() + 1);
    Some(Completion {
        fewest: current.sites.len() <= needed,
        added,
        layout: current,
    })
}

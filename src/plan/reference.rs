//! The layouts a plan is measured against: Effective Independence and evenly spaced sensors.
//!
//! Effective Independence (Kammer, "Sensor placement for on-orbit modal identification and
//! correlation of large space structures", J. Guidance 14(2), 1991): from every candidate,
//! delete one at a time the candidate with the smallest effective independence
//! E_D(i) = [Phi (Phi^T Phi)^-1 Phi^T]_ii, Phi the target mode shapes at the remaining
//! candidates, until the count remains. It keeps the target shapes linearly independent; it
//! knows nothing of the joint. Fixed sensors are never deleted; a tiny ridge on Phi^T Phi
//! lets the deletion go on below as many sensors as target modes.

use faer::Side;
use faer::linalg::solvers::Solve;

use super::candidates::Candidate;
use super::evaluate::Evaluator;

/// Effective Independence's `count` candidates (indices into `dofs`, ascending), `fixed` kept.
pub fn effective_independence(
    eval: &Evaluator,
    dofs: &[usize],
    count: usize,
    fixed: &[usize],
) -> Vec<usize> {
    let mut kept: Vec<usize> = (0..dofs.len()).collect();
    while kept.len() > count {
        let layout: Vec<usize> = kept.iter().map(|&i| dofs[i]).collect();
        let phi = eval.target_shapes(&layout);
        let mut gram = phi.transpose() * &phi;
        let t = gram.ncols();
        let ridge = 1e-12
            * (0..t)
                .map(|j| gram[(j, j)])
                .sum::<f64>()
                .max(f64::MIN_POSITIVE);
        for j in 0..t {
            gram[(j, j)] += ridge;
        }
        let Ok(llt) = gram.llt(Side::Lower) else {
            break;
        };
        let solved = llt.solve(phi.transpose());
        let independence = |k: usize| (0..t).map(|j| phi[(k, j)] * solved[(j, k)]).sum::<f64>();
        let least = (0..kept.len())
            .filter(|&k| !fixed.contains(&kept[k]))
            .min_by(|&a, &b| independence(a).total_cmp(&independence(b)));
        match least {
            Some(k) => {
                kept.remove(k);
            }
            None => break,
        }
    }
    kept
}

/// `count` sensors spread evenly along the candidates' span (the ends included), each the
/// unused candidate nearest its abscissa, `fixed` kept and counted.
pub fn evenly_spaced(candidates: &[Candidate], count: usize, fixed: &[usize]) -> Vec<usize> {
    let mut out = fixed.to_vec();
    let free = count.saturating_sub(fixed.len());
    let lo = candidates.iter().map(|c| c.x).fold(f64::INFINITY, f64::min);
    let hi = candidates
        .iter()
        .map(|c| c.x)
        .fold(f64::NEG_INFINITY, f64::max);
    for k in 0..free {
        let x = if free == 1 {
            0.5 * (lo + hi)
        } else {
            lo + (hi - lo) * k as f64 / (free - 1) as f64
        };
        let nearest = (0..candidates.len())
            .filter(|i| !out.contains(i))
            .min_by(|&a, &b| {
                (candidates[a].x - x)
                    .abs()
                    .total_cmp(&(candidates[b].x - x).abs())
            });
        if let Some(i) = nearest {
            out.push(i);
        }
    }
    out.sort_unstable();
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64) -> Candidate {
        Candidate {
            dof: 0,
            label: String::new(),
            x,
            direction: "w".into(),
        }
    }

    #[test]
    fn evenly_spaced_takes_the_ends_and_the_nearest_free_sites() {
        let c: Vec<Candidate> = (0..11).map(|i| at(0.1 * i as f64)).collect();
        assert_eq!(evenly_spaced(&c, 3, &[]), vec![0, 5, 10]);
        assert_eq!(evenly_spaced(&c, 4, &[]), vec![0, 3, 7, 10]);
        // A fixed sensor is kept and counted.
        assert_eq!(evenly_spaced(&c, 3, &[4]), vec![0, 4, 10]);
    }
}

//! The assignment problem: pair rows with columns, each used at most once, pairing as many rows
//! as the allowed pairs permit and, among those pairings, the one of largest total weight.
//!
//! Solved exactly by the Hungarian method with potentials (Kuhn 1955, Munkres 1957; the
//! O(n^2 m) form with a shortest augmenting path per row) on costs -(C + w) for an allowed pair
//! of weight w in [0, 1] and 0 for leaving a row alone (one dummy column per row), with
//! C = rows + 1: one more pair is worth more than any gain of weight, so the cardinality comes
//! first. A greedy pairing by decreasing weight can leave a row alone whose only partner a
//! heavier pair took, where an exact one pairs both.

/// Cost of a pair that is not allowed: never chosen, a dummy column is always free.
const FORBIDDEN: f64 = 1e12;

/// The column of every row (None: left alone), for `weights[r][c]` = Some(w) (w in [0, 1]) where
/// row r may pair with column c. Ties go to the lower column of the lower row.
pub fn assign(weights: &[Vec<Option<f64>>]) -> Vec<Option<usize>> {
    let n = weights.len();
    if n == 0 {
        return Vec::new();
    }
    let columns = weights.iter().map(Vec::len).max().unwrap_or(0);
    let m = columns + n;
    let bonus = n as f64 + 1.0;
    let cost = |r: usize, c: usize| -> f64 {
        if c >= columns {
            0.0
        } else {
            match weights[r].get(c).copied().flatten() {
                Some(w) => -(bonus + w),
                None => FORBIDDEN,
            }
        }
    };
    // 1-based potentials u (rows), v (columns); p[c] = row owning column c (0 = none)
    let mut u = vec![0.0; n + 1];
    let mut v = vec![0.0; m + 1];
    let mut p = vec![0usize; m + 1];
    let mut way = vec![0usize; m + 1];
    for row in 1..=n {
        p[0] = row;
        let mut j0 = 0usize;
        let mut minv = vec![f64::INFINITY; m + 1];
        let mut used = vec![false; m + 1];
        loop {
            used[j0] = true;
            let i0 = p[j0];
            let mut delta = f64::INFINITY;
            let mut j1 = 0usize;
            for j in 1..=m {
                if used[j] {
                    continue;
                }
                let cur = cost(i0 - 1, j - 1) - u[i0] - v[j];
                if cur < minv[j] {
                    minv[j] = cur;
                    way[j] = j0;
                }
                if minv[j] < delta {
                    delta = minv[j];
                    j1 = j;
                }
            }
            for j in 0..=m {
                if used[j] {
                    u[p[j]] += delta;
                    v[j] -= delta;
                } else {
                    minv[j] -= delta;
                }
            }
            j0 = j1;
            if p[j0] == 0 {
                break;
            }
        }
        loop {
            let j1 = way[j0];
            p[j0] = p[j1];
            j0 = j1;
            if j0 == 0 {
                break;
            }
        }
    }
    let mut out = vec![None; n];
    for c in 1..=columns {
        let r = p[c];
        if r != 0 && weights[r - 1].get(c - 1).copied().flatten().is_some() {
            out[r - 1] = Some(c - 1);
        }
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;

    /// Every assignment of rows to distinct columns or to none, by enumeration.
    fn brute(weights: &[Vec<Option<f64>>]) -> (usize, f64) {
        fn go(
            w: &[Vec<Option<f64>>],
            r: usize,
            used: &mut Vec<bool>,
            acc: (usize, f64),
            best: &mut (usize, f64),
        ) {
            if r == w.len() {
                if acc.0 > best.0 || (acc.0 == best.0 && acc.1 > best.1 + 1e-12) {
                    *best = acc;
                }
                return;
            }
            go(w, r + 1, used, acc, best);
            for c in 0..w[r].len() {
                if let (Some(x), false) = (w[r][c], used[c]) {
                    used[c] = true;
                    go(w, r + 1, used, (acc.0 + 1, acc.1 + x), best);
                    used[c] = false;
                }
            }
        }
        let cols = weights.iter().map(Vec::len).max().unwrap_or(0);
        let mut best = (0, 0.0);
        go(weights, 0, &mut vec![false; cols], (0, 0.0), &mut best);
        best
    }

    #[test]
    fn a_heavier_pair_does_not_leave_a_row_alone() {
        // row 1's only partner is column 0, which row 0 prefers: greedy pairs (0, 0) and
        // leaves row 1 alone; the exact pairing gives row 0 its second choice
        let w = vec![vec![Some(0.99), Some(0.9)], vec![Some(0.985), None]];
        assert_eq!(assign(&w), vec![Some(1), Some(0)]);
    }

    #[test]
    fn the_exact_pairing_matches_enumeration_on_random_tables() {
        let mut state = 12345u64;
        let mut next = || {
            state = state
                .wrapping_mul(6364136223846793005)
                .wrapping_add(1442695040888963407);
            (state >> 11) as f64 / (1u64 << 53) as f64
        };
        for case in 0..300 {
            let rows = 1 + case % 5;
            let cols = 1 + (case / 5) % 6;
            let w: Vec<Vec<Option<f64>>> = (0..rows)
                .map(|_| {
                    (0..cols)
                        .map(|_| if next() < 0.6 { Some(next()) } else { None })
                        .collect()
                })
                .collect();
            let got = assign(&w);
            let mut seen = vec![false; cols];
            let mut total = (0usize, 0.0);
            for (r, c) in got.iter().enumerate() {
                if let Some(c) = *c {
                    assert!(!seen[c], "case {case}: column {c} used twice");
                    seen[c] = true;
                    total.0 += 1;
                    total.1 += w[r][c].expect("an allowed pair");
                }
            }
            let best = brute(&w);
            assert_eq!(total.0, best.0, "case {case}: {w:?}");
            assert!(
                (total.1 - best.1).abs() < 1e-9,
                "case {case}: {} vs {}",
                total.1,
                best.1
            );
        }
    }

    #[test]
    fn no_rows_no_pairs() {
        assert!(assign(&[]).is_empty());
        assert_eq!(assign(&[vec![None, None]]), vec![None]);
    }
}

//! Which sensitivity equations are retained for mode r, and their weights (eq. (16)).
//!
//! Basis indices here are 0-based; the paper's are 1-based. Mode r (1 = first elastic mode)
//! pairs with basis index s_r = r - 1 + (number of rigid-body modes). The retained rows are
//! the `m` deformable indices nearest to s_r, ties to the lower index; rigid-body rows are never
//! retained (their sensitivity to a joint parameter is identically zero).
//!
//! Weights use d = |s - s_r| + 1. The paper prints 1/|s - r + 1|, which is singular at
//! s = r - 1; d is the reading that gives weight 1 at s_r.

use std::fmt;
use std::str::FromStr;

/// The weighting matrix W_r of eq. (13).
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, PartialOrd, Ord)]
pub enum Weighting {
    /// W = 1 (the paper's W = 1).
    Equal,
    /// w_ss = 1/d, eq. (16-a) (the paper's W = 2).
    Inverse,
    /// w_ss = 1/sqrt(d), eq. (16-b) (the paper's W = 3).
    InverseSqrt,
}

impl Weighting {
    /// All weightings, in the paper's order W = 1, 2, 3.
    pub const ALL: [Weighting; 3] = [Weighting::Equal, Weighting::Inverse, Weighting::InverseSqrt];

    /// The name used in files and on the command line.
    pub fn name(self) -> &'static str {
        match self {
            Weighting::Equal => "equal",
            Weighting::Inverse => "inverse",
            Weighting::InverseSqrt => "inverse-sqrt",
        }
    }

    /// Weight of a row at distance `|s - s_r|` from the mode's own index.
    pub fn weight(self, distance: usize) -> f64 {
        let d = (distance + 1) as f64;
        match self {
            Weighting::Equal => 1.0,
            Weighting::Inverse => 1.0 / d,
            Weighting::InverseSqrt => 1.0 / d.sqrt(),
        }
    }
}

impl fmt::Display for Weighting {
    fn fmt(&self, f: &mut fmt::Formatter<'_>) -> fmt::Result {
        f.write_str(self.name())
    }
}

impl FromStr for Weighting {
    type Err = String;
    fn from_str(s: &str) -> Result<Self, String> {
        Weighting::ALL
            .into_iter()
            .find(|w| w.name() == s)
            .ok_or_else(|| format!("`{s}` is not a weighting: use equal, inverse or inverse-sqrt"))
    }
}

/// The retained equations of one mode: basis indices (ascending) and their weights.
#[derive(Debug, Clone, PartialEq)]
pub struct RetainedRows {
    /// Basis indices s (0-based), ascending.
    pub rows: Vec<usize>,
    /// Weight w_ss of each row.
    pub weights: Vec<f64>,
}

impl RetainedRows {
    /// The `m` deformable indices in `rigid..n` nearest to `s_r`, ties to the lower index.
    /// The caller guarantees `rigid <= s_r < n` and `m <= n - rigid`.
    pub fn select(n: usize, rigid: usize, s_r: usize, m: usize, weighting: Weighting) -> Self {
        assert!(rigid <= s_r && s_r < n && m <= n - rigid);
        let mut candidates: Vec<usize> = (rigid..n).collect();
        candidates.sort_by_key(|&s| (s.abs_diff(s_r), s));
        let mut rows = candidates[..m].to_vec();
        rows.sort_unstable();
        let weights = rows
            .iter()
            .map(|&s| weighting.weight(s.abs_diff(s_r)))
            .collect();
        Self { rows, weights }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn nearest_rows_with_ties_to_the_lower_index_and_no_rigid_rows() {
        // n = 10, two rigid modes, mode r = 1 -> s_r = 2: rows 2..7.
        let r = RetainedRows::select(10, 2, 2, 5, Weighting::Equal);
        assert_eq!(r.rows, vec![2, 3, 4, 5, 6]);
        // s_r = 5, m = 4: 5, then 4 and 6 (distance 1), then 3 (tie with 7, lower wins).
        let r = RetainedRows::select(10, 2, 5, 4, Weighting::Inverse);
        assert_eq!(r.rows, vec![3, 4, 5, 6]);
        assert_eq!(r.weights, vec![1.0 / 3.0, 0.5, 1.0, 0.5]);
        // At the top of the basis the rows extend downwards.
        let r = RetainedRows::select(7, 2, 6, 3, Weighting::InverseSqrt);
        assert_eq!(r.rows, vec![4, 5, 6]);
        assert_eq!(r.weights, vec![1.0 / 3f64.sqrt(), 1.0 / 2f64.sqrt(), 1.0]);
    }

    #[test]
    fn weighting_names_round_trip_and_unknown_is_explained() {
        for w in Weighting::ALL {
            assert_eq!(w.name().parse::<Weighting>().unwrap(), w);
        }
        assert!(
            "inv"
                .parse::<Weighting>()
                .unwrap_err()
                .contains("equal, inverse or inverse-sqrt")
        );
    }
}

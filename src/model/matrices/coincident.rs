//! Coincident DOFs of an external model: two DOFs of the same direction at the same position.
//! Some entry of K or of a dK/dp ties them (the two faces of a lap joined by springs, a
//! zero-length connector), or nothing does: an open face, as the notch faces of a lap, a crack
//! or an open contact leave in any real mesh. Both are models; an untied pair changes no entry
//! of K or M. They are counted for a note, not refused: what they make ambiguous, a sensor
//! position on such a pair, asks for the DOF's label where measured modes are read.
//!
//! May import: the structure's DOF descriptions.

use std::collections::{HashMap, HashSet};

use crate::structure::{Direction, DofInfo};

/// Two coincident DOFs that nothing couples.
#[derive(Debug, Clone, PartialEq)]
pub struct Untied {
    /// The lower DOF, 0-based.
    pub first: usize,
    /// The other, 0-based.
    pub second: usize,
}

/// Every pair (in DOF order) of DOFs with the same position and direction that no entry of
/// `stiffness` (each a list of `(row, col, value)`, any triangle) couples.
pub fn untied<'a>(
    dofs: &[DofInfo],
    stiffness: impl IntoIterator<Item = &'a [(usize, usize, f64)]>,
) -> Vec<Untied> {
    let mut first: HashMap<([u64; 3], Direction), usize> = HashMap::new();
    let mut pairs: Vec<(usize, usize)> = Vec::new();
    for (i, d) in dofs.iter().enumerate() {
        // +0.0 and -0.0 are the same position.
        let key = (d.position.map(|c| (c + 0.0).to_bits()), d.direction);
        match first.get(&key) {
            Some(&j) => pairs.push((j, i)),
            None => {
                first.insert(key, i);
            }
        }
    }
    if pairs.is_empty() {
        return Vec::new();
    }
    let wanted: HashSet<(usize, usize)> = pairs.iter().copied().collect();
    // The first DOF of some pair: every other entry (nearly all of a large K) is passed over
    // without hashing.
    let mut paired = vec![false; dofs.len()];
    for &(j, _) in &pairs {
        paired[j] = true;
    }
    let mut tied: HashSet<(usize, usize)> = HashSet::new();
    for entries in stiffness {
        for &(r, c, v) in entries {
            let key = (r.min(c), r.max(c));
            if v != 0.0 && paired.get(key.0).copied().unwrap_or(false) && wanted.contains(&key) {
                tied.insert(key);
            }
        }
    }
    pairs
        .into_iter()
        .filter(|p| !tied.contains(p))
        .map(|(first, second)| Untied { first, second })
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    fn dof(label: &str, position: [f64; 3], direction: Direction) -> DofInfo {
        DofInfo {
            label: label.into(),
            position,
            direction,
            node: None,
        }
    }

    #[test]
    fn coincident_dofs_that_nothing_couples_are_found() {
        let dofs = vec![
            dof("a:x", [0.0, 0.0, 0.0], Direction::X),
            dof("a:z", [0.0, 0.0, 0.0], Direction::Z),
            dof("b:x", [0.0, -0.0, 0.0], Direction::X),
            dof("c:x", [1.0, 0.0, 0.0], Direction::X),
        ];
        let base = [(0, 0, 1.0), (3, 3, 1.0)];
        assert_eq!(
            untied(&dofs, [&base[..]]),
            vec![Untied {
                first: 0,
                second: 2
            }]
        );
        // A spring between them, in either triangle; an explicit zero is no tie.
        assert!(untied(&dofs, [&base[..], &[(0, 2, -1.0)][..]]).is_empty());
        assert!(untied(&dofs, [&[(2, 0, -1.0)][..]]).is_empty());
        assert_eq!(untied(&dofs, [&[(2, 0, 0.0)][..]]).len(), 1);
        assert!(untied(&dofs[..2], [&base[..]]).is_empty());
    }
}

//! Coincident DOFs of an external model: two DOFs of the same direction at the same position.
//! They are legitimate when something ties them (the two faces of a lap joined by springs,
//! a zero-length connector): some entry of K or of a dK/dp couples them. When nothing does,
//! the mesh has unmerged nodes, a crack the model's author did not mean (a classic error of
//! meshes joined in a pre-processor), and a sensor at that position would be ambiguous: the
//! model is refused, naming both DOFs.
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

/// The first pair (in DOF order) of DOFs with the same position and direction that no entry
/// of `stiffness` (each a list of `(row, col, value)`, any triangle) couples.
pub fn untied<'a>(
    dofs: &[DofInfo],
    stiffness: impl IntoIterator<Item = &'a [(usize, usize, f64)]>,
) -> Option<Untied> {
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
        return None;
    }
    let wanted: HashSet<(usize, usize)> = pairs.iter().copied().collect();
    let mut tied: HashSet<(usize, usize)> = HashSet::new();
    for entries in stiffness {
        for &(r, c, v) in entries {
            let key = (r.min(c), r.max(c));
            if v != 0.0 && wanted.contains(&key) {
                tied.insert(key);
            }
        }
    }
    pairs
        .into_iter()
        .find(|p| !tied.contains(p))
        .map(|(first, second)| Untied { first, second })
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
    fn coincident_dofs_must_be_coupled() {
        let dofs = vec![
            dof("a:x", [0.0, 0.0, 0.0], Direction::X),
            dof("a:z", [0.0, 0.0, 0.0], Direction::Z),
            dof("b:x", [0.0, -0.0, 0.0], Direction::X),
            dof("c:x", [1.0, 0.0, 0.0], Direction::X),
        ];
        let base = [(0, 0, 1.0), (3, 3, 1.0)];
        assert_eq!(
            untied(&dofs, [&base[..]]),
            Some(Untied {
                first: 0,
                second: 2
            })
        );
        // A spring between them, in either triangle; an explicit zero is no tie.
        assert_eq!(untied(&dofs, [&base[..], &[(0, 2, -1.0)][..]]), None);
        assert_eq!(untied(&dofs, [&[(2, 0, -1.0)][..]]), None);
        assert!(untied(&dofs, [&[(2, 0, 0.0)][..]]).is_some());
        assert_eq!(untied(&dofs[..2], [&base[..]]), None);
    }
}

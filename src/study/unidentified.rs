//! Which DOFs are left unidentified in a cell (the paper's NF).
//!
//! The rule, deterministic and documented: rotations first, then translations. k DOFs of one
//! kind are spread evenly over the chain's `nodes` nodes (all beams, in node order): node
//! floor(i (nodes - 1) / (k - 1)) for i = 0..k-1, both ends included; a single one sits at
//! node floor((nodes - 1) / 2). With 19 nodes, NF = 5 leaves the rotations of nodes 0, 4, 9,
//! 13 and 18 unidentified; NF = 23 all 19 rotations and the translations of nodes 0, 6, 12
//! and 18.

use crate::model::{Dof, dof_index};

/// The unidentified DOFs (ascending global indices) for `nf` under the rule above.
/// The caller guarantees `nf <= 2 * nodes`.
pub fn by_rule(nodes: usize, nf: usize) -> Vec<usize> {
    let rotations = nf.min(nodes);
    let translations = nf - rotations;
    let mut dofs: Vec<usize> = spread(nodes, rotations)
        .map(|node| dof_index(node, Dof::Theta))
        .chain(spread(nodes, translations).map(|node| dof_index(node, Dof::W)))
        .collect();
    dofs.sort_unstable();
    dofs
}

fn spread(nodes: usize, k: usize) -> impl Iterator<Item = usize> {
    (0..k).map(move |i| {
        if k == 1 {
            (nodes - 1) / 2
        } else {
            i * (nodes - 1) / (k - 1)
        }
    })
}

/// The identified DOFs: every DOF of `dof_count` not in `unidentified` (ascending).
pub fn complement(dof_count: usize, unidentified: &[usize]) -> Vec<usize> {
    (0..dof_count)
        .filter(|d| unidentified.binary_search(d).is_err())
        .collect()
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn paper_counts_follow_the_documented_rule() {
        assert_eq!(by_rule(19, 0), Vec::<usize>::new());
        // Rotations of nodes 0, 4, 9, 13, 18 (as in the numpy baseline's NF 5 cell).
        assert_eq!(by_rule(19, 5), vec![1, 9, 19, 27, 37]);
        let nf23 = by_rule(19, 23);
        assert_eq!(nf23.len(), 23);
        assert!((0..19).all(|node| nf23.contains(&(2 * node + 1))));
        assert_eq!(
            nf23.iter()
                .filter(|d| *d % 2 == 0)
                .copied()
                .collect::<Vec<_>>(),
            vec![0, 12, 24, 36]
        );
        assert_eq!(by_rule(19, 1), vec![19]);
        assert_eq!(by_rule(3, 6), vec![0, 1, 2, 3, 4, 5]);
        assert_eq!(complement(6, &[1, 4]), vec![0, 2, 3, 5]);
    }
}

//! Which DOFs are left unidentified in a cell (the paper's NF).
//!
//! The rule, deterministic and documented: rotations first, then translations. k DOFs of one
//! kind are spread evenly over the P DOFs of that kind, in DOF order (for a chain: node order):
//! the DOF at position floor(i (P - 1) / (k - 1)) for i = 0..k-1, both ends included; a single
//! one sits at position floor((P - 1) / 2). On the paper's free-free chain of 19 nodes, NF = 5
//! leaves the rotations of nodes 0, 4, 9, 13 and 18 unidentified; NF = 23 all 19 rotations and
//! the translations of nodes 0, 6, 12 and 18.

use crate::structure::DofMap;

/// The unidentified DOFs (ascending global indices) for `nf` under the rule above.
/// The caller guarantees `nf <= N`.
pub fn by_rule(dofs: &DofMap, nf: usize) -> Vec<usize> {
    let (rotations, translations): (Vec<usize>, Vec<usize>) =
        (0..dofs.len()).partition(|&d| dofs.get(d).direction.is_rotation());
    let from_rotations = nf.min(rotations.len());
    let mut out: Vec<usize> = spread(rotations.len(), from_rotations)
        .map(|i| rotations[i])
        .chain(spread(translations.len(), nf - from_rotations).map(|i| translations[i]))
        .collect();
    out.sort_unstable();
    out
}

fn spread(count: usize, k: usize) -> impl Iterator<Item = usize> {
    (0..k).map(move |i| {
        if k == 1 {
            (count - 1) / 2
        } else {
            i * (count - 1) / (k - 1)
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
    use crate::model::fixtures::paper_model;

    #[test]
    fn paper_counts_follow_the_documented_rule() {
        let dofs = paper_model(1e7, 1e4).dofs;
        assert_eq!(by_rule(&dofs, 0), Vec::<usize>::new());
        // Rotations of nodes 0, 4, 9, 13, 18 (as in the numpy baseline's NF 5 cell).
        assert_eq!(by_rule(&dofs, 5), vec![1, 9, 19, 27, 37]);
        let nf23 = by_rule(&dofs, 23);
        assert_eq!(nf23.len(), 23);
        assert!((0..19).all(|node| nf23.contains(&(2 * node + 1))));
        assert_eq!(
            nf23.iter()
                .filter(|d| *d % 2 == 0)
                .copied()
                .collect::<Vec<_>>(),
            vec![0, 12, 24, 36]
        );
        assert_eq!(by_rule(&dofs, 1), vec![19]);
        assert_eq!(by_rule(&dofs, 38), (0..38).collect::<Vec<_>>());
        assert_eq!(complement(6, &[1, 4]), vec![0, 2, 3, 5]);
    }
}

//! What one eigensolution leaves for the next of the same structure: the symbolic analyses of
//! its sparse Cholesky factors, by sparsity pattern, and the mass matrix it found positive
//! definite.
//!
//! Why: diagnose solves one structure's eigenproblem hundreds of times with other joint
//! values (the frequency-dependence fit about 700 times on the 212k-DOF lap), and K - sigma M
//! keeps its pattern, M its values. Measured on that lap at one thread, of a 9.5 s solve: the
//! analyses of K - sigma M (minimum degree and the DOF order, [`super::sparse_llt`]) 0.69 s,
//! the check of M 1.1 s (its analysis 0.31 s, its factorisation 0.81 s).
//!
//! Exactness: an analysis is a function of the pattern and the ordering alone, so a kept one
//! is the one that would be computed; a mass matrix is skipped only when it equals, entry for
//! entry and bit for bit, one found positive definite. Results are the same bits with or
//! without what is kept. Both are looked up by full comparison, never by a hash.
//!
//! Kept: the last [`CAPACITY`] patterns with their analyses and the last mass matrix, copies
//! of their index arrays (and M's values): on the 212k lap about 0.2 GB, beside a solve's
//! 3-4 GB. Shared by every thread; each is computed outside the lock.

use std::sync::{Arc, Mutex, PoisonError};

use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

use super::sparse_llt::Ordering;

/// Patterns kept: K - sigma M and M of two structures solved in turn.
pub const CAPACITY: usize = 4;

/// The analyses of the last patterns factorised, the most recent first.
pub struct Analyses {
    kept: Mutex<Vec<Analysis>>,
}

struct Analysis {
    ordering: Ordering,
    pattern: Pattern,
    symbolic: Arc<SymbolicCholesky<usize>>,
}

/// The compressed columns of a pattern with every column's entries contiguous.
#[derive(PartialEq)]
struct Pattern {
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl Pattern {
    /// `None` for a pattern with gaps between its columns' entries (never made here).
    fn of(a: SymbolicSparseColMatRef<'_, usize>) -> Option<Pattern> {
        a.col_nnz().is_none().then(|| Pattern {
            col_ptr: a.col_ptr().to_vec(),
            row_idx: a.row_idx().to_vec(),
        })
    }

    fn is(&self, a: SymbolicSparseColMatRef<'_, usize>) -> bool {
        a.col_nnz().is_none() && self.col_ptr == a.col_ptr() && self.row_idx == a.row_idx()
    }
}

impl Analyses {
    /// Nothing kept yet.
    pub const fn new() -> Analyses {
        Analyses {
            kept: Mutex::new(Vec::new()),
        }
    }

    /// The analysis of `a` under `ordering`: the kept one, or `analyse()`'s, then kept.
    pub fn of(
        &self,
        a: SymbolicSparseColMatRef<'_, usize>,
        ordering: Ordering,
        analyse: impl FnOnce() -> Option<SymbolicCholesky<usize>>,
    ) -> Option<Arc<SymbolicCholesky<usize>>> {
        {
            let mut kept = self.kept.lock().unwrap_or_else(PoisonError::into_inner);
            if let Some(at) = kept
                .iter()
                .position(|k| k.ordering == ordering && k.pattern.is(a))
            {
                let hit = kept.remove(at);
                let symbolic = Arc::clone(&hit.symbolic);
                kept.insert(0, hit);
                return Some(symbolic);
            }
        }
        let symbolic = Arc::new(analyse()?);
        if let Some(pattern) = Pattern::of(a) {
            let mut kept = self.kept.lock().unwrap_or_else(PoisonError::into_inner);
            kept.insert(
                0,
                Analysis {
                    ordering,
                    pattern,
                    symbolic: Arc::clone(&symbolic),
                },
            );
            kept.truncate(CAPACITY);
        }
        Some(symbolic)
    }

    /// Whether the analysis of `a` under `ordering` is kept.
    pub fn holds(&self, a: SymbolicSparseColMatRef<'_, usize>, ordering: Ordering) -> bool {
        let kept = self.kept.lock().unwrap_or_else(PoisonError::into_inner);
        kept.iter()
            .any(|k| k.ordering == ordering && k.pattern.is(a))
    }
}

impl Default for Analyses {
    fn default() -> Self {
        Analyses::new()
    }
}

/// The last mass matrix found positive definite.
pub struct CheckedMass {
    kept: Mutex<Option<(Pattern, Vec<f64>)>>,
}

impl CheckedMass {
    /// Nothing kept yet.
    pub const fn new() -> CheckedMass {
        CheckedMass {
            kept: Mutex::new(None),
        }
    }

    /// Whether `m` is positive definite: true at once when it equals the kept matrix bit for
    /// bit, else `check(m)`, whose `true` keeps `m`.
    pub fn is_definite(
        &self,
        m: SparseColMatRef<'_, usize, f64>,
        check: impl FnOnce() -> bool,
    ) -> bool {
        let same = |(pattern, values): &(Pattern, Vec<f64>)| {
            pattern.is(m.symbolic())
                && values.len() == m.val().len()
                && values
                    .iter()
                    .zip(m.val())
                    .all(|(a, b)| a.to_bits() == b.to_bits())
        };
        if self
            .kept
            .lock()
            .unwrap_or_else(PoisonError::into_inner)
            .as_ref()
            .is_some_and(same)
        {
            return true;
        }
        let definite = check();
        if let (true, Some(pattern)) = (definite, Pattern::of(m.symbolic())) {
            *self.kept.lock().unwrap_or_else(PoisonError::into_inner) =
                Some((pattern, m.val().to_vec()));
        }
        definite
    }
}

impl Default for CheckedMass {
    fn default() -> Self {
        CheckedMass::new()
    }
}

/// The analyses every factorisation of [`super::sparse_llt`] shares.
pub static ANALYSES: Analyses = Analyses::new();

/// The mass matrix every sparse eigensolution's check shares.
pub static CHECKED_MASS: CheckedMass = CheckedMass::new();

#[cfg(test)]
mod tests {
    use std::cell::Cell;

    use faer::sparse::{SparseColMat, Triplet};

    use super::*;

    /// The tridiagonal n x n matrix with `diagonal` on its diagonal and -1 beside it (lower
    /// triangle and both, as the factorisations and the check read them).
    fn tridiagonal(n: usize, diagonal: f64) -> SparseColMat<usize, f64> {
        let mut t = Vec::new();
        for i in 0..n {
            t.push(Triplet::new(i, i, diagonal));
            if i + 1 < n {
                t.push(Triplet::new(i + 1, i, -1.0));
                t.push(Triplet::new(i, i + 1, -1.0));
            }
        }
        SparseColMat::try_new_from_triplets(n, n, &t).unwrap()
    }

    fn analyse(a: &SparseColMat<usize, f64>) -> Option<SymbolicCholesky<usize>> {
        faer::sparse::linalg::cholesky::factorize_symbolic_cholesky(
            a.symbolic(),
            faer::Side::Lower,
            faer::sparse::linalg::cholesky::SymmetricOrdering::Amd,
            Default::default(),
        )
        .ok()
    }

    /// An analysis is made once per pattern and ordering, found again for other values of the
    /// same pattern, made anew for another pattern or ordering, and let go beyond
    /// [`CAPACITY`] patterns, the least recently used first.
    #[test]
    fn analyses_are_kept_per_pattern_and_ordering() {
        let memo = Analyses::new();
        let made = Cell::new(0);
        let of = |a: &SparseColMat<usize, f64>, ordering| {
            memo.of(a.symbolic(), ordering, || {
                made.set(made.get() + 1);
                analyse(a)
            })
            .unwrap()
        };
        let (a, b) = (tridiagonal(30, 4.0), tridiagonal(30, 9.0));
        let first = of(&a, Ordering::Amd);
        assert!(Arc::ptr_eq(&first, &of(&b, Ordering::Amd)));
        assert_eq!(made.get(), 1);
        of(&a, Ordering::Fewest);
        assert_eq!(made.get(), 2);
        // CAPACITY - 1 more patterns push out the least recently used: (a, Fewest) goes
        // first, (a, Amd) is used again in between and stays.
        for n in 31..31 + CAPACITY - 2 {
            of(&tridiagonal(n, 4.0), Ordering::Amd);
        }
        assert!(memo.holds(a.symbolic(), Ordering::Fewest));
        of(&a, Ordering::Amd);
        of(&tridiagonal(99, 4.0), Ordering::Amd);
        assert!(memo.holds(a.symbolic(), Ordering::Amd));
        assert!(!memo.holds(a.symbolic(), Ordering::Fewest));
        // A failed analysis is not kept.
        let c = tridiagonal(7, 4.0);
        assert!(memo.of(c.symbolic(), Ordering::Amd, || None).is_none());
        assert!(!memo.holds(c.symbolic(), Ordering::Amd));
    }

    /// The check of a mass matrix is skipped only for the matrix found definite last, bit for
    /// bit: a value one unit in the last place away is checked again, and a failed check is
    /// not kept.
    #[test]
    fn a_mass_matrix_is_checked_again_unless_it_is_the_same_bits() {
        let memo = CheckedMass::new();
        let checks = Cell::new(0);
        let check = |m: &SparseColMat<usize, f64>, result: bool| {
            memo.is_definite(m.as_ref(), || {
                checks.set(checks.get() + 1);
                result
            })
        };
        let m = tridiagonal(20, 4.0);
        assert!(check(&m, true));
        assert!(check(&m, false), "kept: not checked again");
        assert_eq!(checks.get(), 1);
        let next = tridiagonal(20, f64::from_bits(4.0f64.to_bits() + 1));
        assert!(!check(&next, false));
        assert_eq!(checks.get(), 2);
        assert!(
            check(&m, true),
            "the failed check left the kept matrix alone"
        );
        assert_eq!(checks.get(), 2);
        assert!(!check(&tridiagonal(21, 4.0), false));
        assert_eq!(checks.get(), 3);
    }
}

//! What one eigensolution leaves for the next of the same structure: the symbolic analyses of
//! its sparse Cholesky factors, by sparsity pattern, and the mass matrix it found positive
//! definite.
//!
//! Why: diagnose solves one structure's eigenproblem hundreds of times with other joint
//! values (the frequency-dependence fit 635 times on the 23,958-DOF lap), and K - sigma M
//! keeps its pattern, M its values. Measured on the 212,562-DOF lap at one thread, of a 9.5 s
//! solve: the analyses of K - sigma M (minimum degree and the DOF order,
//! [`super::sparse_llt`]) 0.69 s, the check of M 1.1 s (its analysis 0.31 s, its
//! factorisation 0.81 s). The 24k lap's diagnose takes 226 s with these kept, 250 s without
//! (docs/benchmarks.md).
//!
//! Exactness: an analysis is a function of the pattern and the ordering alone, so a kept one
//! is the one that would be computed; a mass matrix is skipped only when it equals, entry for
//! entry and bit for bit, one found positive definite. Results are the same bits with or
//! without what is kept. Both are looked up by full comparison, never by a hash.
//!
//! Kept: the last [`CAPACITY`] patterns with their analyses (the factor's structure: its
//! supernodes' row indices, a fraction of its values) and the last [`MASS_CAPACITY`] mass
//! matrices found definite, as copies of their index arrays (and M's values): the 24k lap's
//! diagnose peaks 0.1 GB higher with them (0.76 GB). Shared by every thread; an analysis or
//! a check runs outside the lock, and of two threads that made the same one, the second
//! takes the first one's.

use std::sync::{Arc, Mutex, PoisonError};

use faer::sparse::linalg::cholesky::SymbolicCholesky;
use faer::sparse::{SparseColMatRef, SymbolicSparseColMatRef};

/// Patterns kept: K - sigma M and M of two structures solved in turn.
pub const CAPACITY: usize = 4;

/// Mass matrices kept: those of two structures solved in turn (a candidate's alternative
/// model beside the nominal one).
pub const MASS_CAPACITY: usize = 2;

/// The last items used, the most recent first, at most `capacity`.
struct Recent<T> {
    items: Mutex<Vec<T>>,
    capacity: usize,
}

impl<T> Recent<T> {
    const fn new(capacity: usize) -> Self {
        Recent {
            items: Mutex::new(Vec::new()),
            capacity,
        }
    }

    /// `read` of the first item `matches` accepts, which becomes the most recent.
    fn find<R>(&self, matches: impl Fn(&T) -> bool, read: impl FnOnce(&T) -> R) -> Option<R> {
        let mut items = self.items.lock().unwrap_or_else(PoisonError::into_inner);
        let at = items.iter().position(matches)?;
        let item = items.remove(at);
        let out = read(&item);
        items.insert(0, item);
        Some(out)
    }

    /// Keeps `item` as the most recent, unless an item `matches` accepts is kept already
    /// (another thread made it meanwhile): then `read` of that one. The least recent item
    /// beyond the capacity is let go.
    fn keep<R>(&self, item: T, matches: impl Fn(&T) -> bool, read: impl Fn(&T) -> R) -> R {
        let mut items = self.items.lock().unwrap_or_else(PoisonError::into_inner);
        if let Some(there) = items.iter().find(|i| matches(i)) {
            return read(there);
        }
        let out = read(&item);
        items.insert(0, item);
        items.truncate(self.capacity);
        out
    }
}

/// The analyses of the last patterns factorised, each under an ordering `O`.
pub struct Analyses<O> {
    kept: Recent<Analysis<O>>,
}

struct Analysis<O> {
    ordering: O,
    pattern: Pattern,
    symbolic: Arc<SymbolicCholesky<usize>>,
}

/// The compressed columns of a pattern with every column's entries contiguous.
struct Pattern {
    nrows: usize,
    col_ptr: Vec<usize>,
    row_idx: Vec<usize>,
}

impl Pattern {
    /// `None` for a pattern with gaps between its columns' entries (never made here).
    fn of(a: SymbolicSparseColMatRef<'_, usize>) -> Option<Pattern> {
        a.col_nnz().is_none().then(|| Pattern {
            nrows: a.nrows(),
            col_ptr: a.col_ptr().to_vec(),
            row_idx: a.row_idx().to_vec(),
        })
    }

    fn is(&self, a: SymbolicSparseColMatRef<'_, usize>) -> bool {
        a.col_nnz().is_none()
            && self.nrows == a.nrows()
            && self.col_ptr == a.col_ptr()
            && self.row_idx == a.row_idx()
    }
}

impl<O: PartialEq + Copy> Analyses<O> {
    /// Nothing kept yet.
    pub const fn new() -> Analyses<O> {
        Analyses {
            kept: Recent::new(CAPACITY),
        }
    }

    /// The analysis of `a` under `ordering`: the kept one, or `analyse()`'s, then kept.
    pub fn of(
        &self,
        a: SymbolicSparseColMatRef<'_, usize>,
        ordering: O,
        analyse: impl FnOnce() -> Option<SymbolicCholesky<usize>>,
    ) -> Option<Arc<SymbolicCholesky<usize>>> {
        let matches = move |k: &Analysis<O>| k.ordering == ordering && k.pattern.is(a);
        let symbolic = |k: &Analysis<O>| Arc::clone(&k.symbolic);
        if let Some(kept) = self.kept.find(matches, symbolic) {
            return Some(kept);
        }
        let made = Arc::new(analyse()?);
        let Some(pattern) = Pattern::of(a) else {
            return Some(made);
        };
        let analysis = Analysis {
            ordering,
            pattern,
            symbolic: made,
        };
        Some(self.kept.keep(analysis, matches, symbolic))
    }

    /// Whether the analysis of `a` under `ordering` is kept.
    #[cfg(test)]
    fn holds(&self, a: SymbolicSparseColMatRef<'_, usize>, ordering: O) -> bool {
        let items = self
            .kept
            .items
            .lock()
            .unwrap_or_else(PoisonError::into_inner);
        items
            .iter()
            .any(|k| k.ordering == ordering && k.pattern.is(a))
    }
}

impl<O: PartialEq + Copy> Default for Analyses<O> {
    fn default() -> Self {
        Analyses::new()
    }
}

/// The last mass matrices found positive definite.
pub struct CheckedMass {
    kept: Recent<(Pattern, Vec<f64>)>,
}

impl CheckedMass {
    /// Nothing kept yet.
    pub const fn new() -> CheckedMass {
        CheckedMass {
            kept: Recent::new(MASS_CAPACITY),
        }
    }

    /// Whether `m` is positive definite: true at once when it equals a kept matrix bit for
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
        if self.kept.find(same, |_| ()).is_some() {
            return true;
        }
        let definite = check();
        if let (true, Some(pattern)) = (definite, Pattern::of(m.symbolic())) {
            self.kept.keep((pattern, m.val().to_vec()), same, |_| ());
        }
        definite
    }
}

impl Default for CheckedMass {
    fn default() -> Self {
        CheckedMass::new()
    }
}

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

    /// The lower triangle of a tridiagonal matrix, or (`moved`) the same with column 0's
    /// entry below the diagonal moved from row 1 to row 2: the same column pointers and
    /// values, other row indices.
    fn lower(n: usize, moved: bool) -> SparseColMat<usize, f64> {
        let mut t = Vec::new();
        for j in 0..n {
            t.push(Triplet::new(j, j, 4.0));
            if j + 1 < n {
                let below = if moved && j == 0 { 2 } else { j + 1 };
                t.push(Triplet::new(below, j, -1.0));
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
        let memo = Analyses::<&str>::new();
        let made = Cell::new(0);
        let of = |a: &SparseColMat<usize, f64>, ordering| {
            memo.of(a.symbolic(), ordering, || {
                made.set(made.get() + 1);
                analyse(a)
            })
            .unwrap()
        };
        let (a, b) = (tridiagonal(30, 4.0), tridiagonal(30, 9.0));
        let first = of(&a, "amd");
        assert!(Arc::ptr_eq(&first, &of(&b, "amd")));
        assert_eq!(made.get(), 1);
        of(&a, "fewest");
        assert_eq!(made.get(), 2);
        // CAPACITY - 2 more patterns fill the memo; one after them pushes out the least
        // recently used, (a, fewest), while (a, amd), used again in between, stays.
        for n in 31..31 + CAPACITY - 2 {
            of(&tridiagonal(n, 4.0), "amd");
        }
        assert!(memo.holds(a.symbolic(), "fewest"));
        of(&a, "amd");
        of(&tridiagonal(99, 4.0), "amd");
        assert!(memo.holds(a.symbolic(), "amd"));
        assert!(!memo.holds(a.symbolic(), "fewest"));
        // A failed analysis is not kept.
        let c = tridiagonal(7, 4.0);
        assert!(memo.of(c.symbolic(), "amd", || None).is_none());
        assert!(!memo.holds(c.symbolic(), "amd"));
        // Same column pointers, other row indices: another pattern.
        let (d, e) = (lower(12, false), lower(12, true));
        assert_eq!(d.symbolic().col_ptr(), e.symbolic().col_ptr());
        let before = made.get();
        let (at_d, at_e) = (of(&d, "amd"), of(&e, "amd"));
        assert_eq!(made.get(), before + 2);
        assert!(!Arc::ptr_eq(&at_d, &at_e));
        assert!(Arc::ptr_eq(&at_d, &of(&d, "amd")));
        assert!(Arc::ptr_eq(&at_e, &of(&e, "amd")));
        assert_eq!(made.get(), before + 2);
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
        // Same column pointers and values, other row indices: checked.
        assert!(check(&lower(12, false), true));
        assert!(!check(&lower(12, true), false));
        assert_eq!(checks.get(), 5);
    }
}

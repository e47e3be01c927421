//! The sparse Cholesky factor of the shifted matrix K - sigma M that the shift-invert
//! eigensolver applies as (K - sigma M)^-1, on faer's low-level sparse Cholesky (symbolic
//! analysis once, numeric factorisation, solves with a workspace kept between calls).
//! faer picks a supernodal factor (dense blocks, matrix products) or a simplicial one by the
//! flop count of the symbolic analysis; the ordering is minimum degree or the DOF order,
//! whichever fills less ([`Ordering::Fewest`]): on a banded matrix the DOF order is the band
//! (the "banded path": no fill outside it). Measured on the lap of 23,958 DOFs
//! (`bench/lap-solid.toml`): 3.65e6 factor entries in the DOF order, 4.17e6 by minimum
//! degree; the factorisation takes 0.04-0.07 s, 3-8% of the solve. Several right-hand sides
//! are solved as blocks on rayon's threads ([`SparseLlt::solve_columns_in_place`]). The
//! symbolic analysis of a pattern factorised before is taken from [`super::memo`].

use std::sync::Arc;

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Conj, MatMut, Par, Side};

use super::memo::Analyses;

/// Columns solved together by [`SparseLlt::solve_columns_in_place`]. Measured per column on
/// the factor of the 212k-DOF lap (1.3e8 entries): 0.138 s alone, 0.034 s in a block of 4,
/// 0.021 s in 8, 0.013 s in 24; on the 1e5 cantilever's band 1.1 ms alone, 0.37 ms in 8 and
/// 0.76 ms in 24 (the block no longer in cache).
pub const SOLVE_WIDTH: usize = 8;

/// Fill-reducing ordering of the factorisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (Amestoy, Davis & Duff, SIAM J. Matrix Anal. Appl. 17
    /// (1996)).
    Amd,
    /// The DOF order of the matrices (a banded matrix keeps its band).
    Natural,
    /// Of the two above, the one whose factor has fewer entries (minimum degree on a tie) (both symbolic analyses are
    /// cheap beside the numeric factorisation): the DOF order of a chain or of a solid
    /// numbered by station along its length is a band as narrow as its cross-section, which
    /// minimum degree matches on the chain and exceeds by about 15% on the 3D lap.
    Fewest,
}

/// The analyses every factorisation here shares ([`super::memo`]).
static ANALYSES: Analyses<Ordering> = Analyses::new();

/// L L^T = P A P^T of a symmetric positive definite A.
pub struct SparseLlt {
    /// Shared with the factorisations of the same pattern ([`super::memo`]).
    symbolic: Arc<SymbolicCholesky<usize>>,
    values: Vec<f64>,
    workspace: MemBuffer,
}

impl std::fmt::Debug for SparseLlt {
    fn fmt(&self, f: &mut std::fmt::Formatter<'_>) -> std::fmt::Result {
        f.debug_struct("SparseLlt")
            .field("n", &self.symbolic.nrows())
            .field("factor_entries", &self.values.len())
            .finish()
    }
}

impl SparseLlt {
    /// Factorises the N x N matrix whose lower triangle is `lower` (duplicates summed).
    /// `None`: a non-positive pivot, or out of memory.
    pub fn new(n: usize, lower: &[Triplet<usize, usize, f64>], ordering: Ordering) -> Option<Self> {
        let a = SparseColMat::try_new_from_triplets(n, n, lower).ok()?;
        Self::from_lower(a.as_ref(), ordering)
    }

    /// Factorises the matrix whose lower triangle is stored in `a` (the upper one is ignored).
    pub fn from_lower(a: SparseColMatRef<'_, usize, f64>, ordering: Ordering) -> Option<Self> {
        let symbolic = ANALYSES.of(a.symbolic(), ordering, || analysis(a, ordering))?;
        Self::numeric(a, symbolic)
    }

    /// The numeric factorisation of `a` on its analysis `symbolic`.
    fn numeric(
        a: SparseColMatRef<'_, usize, f64>,
        symbolic: Arc<SymbolicCholesky<usize>>,
    ) -> Option<Self> {
        let mut values = vec![0.0; symbolic.len_val()];
        let par = Par::Seq;
        let mut scratch = MemBuffer::try_new(
            symbolic.factorize_numeric_llt_scratch::<f64>(par, Default::default()),
        )
        .ok()?;
        symbolic
            .factorize_numeric_llt(
                &mut values,
                a,
                Side::Lower,
                LltRegularization::default(),
                par,
                MemStack::new(&mut scratch),
                Default::default(),
            )
            .ok()?;
        let workspace = MemBuffer::try_new(symbolic.solve_in_place_scratch::<f64>(1, par)).ok()?;
        Some(SparseLlt {
            symbolic,
            values,
            workspace,
        })
    }

    /// Overwrites `x` (length N) with A^-1 x.
    pub fn solve_in_place(&mut self, x: &mut [f64]) {
        let n = x.len();
        LltRef::new(&self.symbolic, &self.values).solve_in_place_with_conj(
            Conj::No,
            MatMut::from_column_major_slice_mut(x, n, 1),
            Par::Seq,
            MemStack::new(&mut self.workspace),
        );
    }

    /// Overwrites every column of `x` (N x p) with A^-1 x: the columns in blocks of
    /// [`SOLVE_WIDTH`], the blocks on the threads of rayon's pool (a block of right-hand sides
    /// goes through the supernodes as matrix products, faster per column than one at a time).
    /// The blocks do not depend on the number of threads: a column solved in another block
    /// differs in its last bits.
    pub fn solve_columns_in_place(&self, x: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let solve = |block: MatMut<'_, f64>| {
            let mut scratch = MemBuffer::new(
                self.symbolic
                    .solve_in_place_scratch::<f64>(block.ncols(), Par::Seq),
            );
            llt.solve_in_place_with_conj(Conj::No, block, Par::Seq, MemStack::new(&mut scratch));
        };
        split_columns(x, SOLVE_WIDTH, &solve);
    }

    /// Overwrites every column of `x` with A^-1 x, all of them one block on the calling
    /// thread: the least work per column (0.013 s a column in a block of 24 on the 212k-DOF
    /// lap's factor, against 0.021 s in blocks of [`SOLVE_WIDTH`]), for a caller whose own
    /// callers already run in parallel (the reduced model's check, `super::reduced`).
    pub fn solve_block_in_place(&self, x: MatMut<'_, f64>) {
        let llt = LltRef::new(&self.symbolic, &self.values);
        let mut scratch = MemBuffer::new(
            self.symbolic
                .solve_in_place_scratch::<f64>(x.ncols(), Par::Seq),
        );
        llt.solve_in_place_with_conj(Conj::No, x, Par::Seq, MemStack::new(&mut scratch));
    }

    /// Entries of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }

    /// N.
    pub fn dof_count(&self) -> usize {
        self.symbolic.nrows()
    }
}

/// The symbolic analysis of the lower triangle of `a` under `ordering`.
fn analysis(
    a: SparseColMatRef<'_, usize, f64>,
    ordering: Ordering,
) -> Option<SymbolicCholesky<usize>> {
    match ordering {
        Ordering::Fewest => {
            // The two analyses on two threads where there are.
            let (amd, natural) = super::beside(
                || symbolic_of(a, Ordering::Amd),
                || symbolic_of(a, Ordering::Natural),
            );
            let (amd, natural) = (amd?, natural?);
            Some(if natural.len_val() < amd.len_val() {
                natural
            } else {
                amd
            })
        }
        one => symbolic_of(a, one),
    }
}

/// The symbolic analysis of the lower triangle of `a` under `ordering` (Amd or Natural).
fn symbolic_of(
    a: SparseColMatRef<'_, usize, f64>,
    ordering: Ordering,
) -> Option<SymbolicCholesky<usize>> {
    let n = a.nrows();
    let identity: Vec<usize> = (0..n).collect();
    let ord = match ordering {
        Ordering::Natural => {
            // Identity as an explicit permutation: faer's symbolic analysis then reads the
            // given side like for any other ordering.
            SymmetricOrdering::Custom(PermRef::new_checked(&identity, &identity, n))
        }
        _ => SymmetricOrdering::Amd,
    };
    factorize_symbolic_cholesky(
        a.symbolic(),
        Side::Lower,
        ord,
        CholeskySymbolicParams::default(),
    )
    .ok()
}

/// Runs `f` on consecutive blocks of at most `width` columns of `x`, in parallel.
fn split_columns(x: MatMut<'_, f64>, width: usize, f: &(dyn Fn(MatMut<'_, f64>) + Sync)) {
    if x.ncols() <= width {
        f(x);
        return;
    }
    let half = (x.ncols() / 2).div_ceil(width) * width;
    let (left, right) = x.split_at_col_mut(half);
    rayon::join(
        || split_columns(left, width, f),
        || split_columns(right, width, f),
    );
}

#[cfg(test)]
mod tests {
    use super::*;
    use faer::Mat;

    /// The 3D Laplacian of a q x q x q grid plus the identity (its supernodes are dense
    /// blocks, so that the solve runs matrix products).
    fn grid(q: usize) -> (usize, Vec<Triplet<usize, usize, f64>>) {
        let n = q * q * q;
        let at = |i: usize, j: usize, l: usize| (i * q + j) * q + l;
        let mut lower = Vec::new();
        for i in 0..q {
            for j in 0..q {
                for l in 0..q {
                    let c = at(i, j, l);
                    lower.push(Triplet::new(c, c, 7.0));
                    for (di, dj, dl) in [(1, 0, 0), (0, 1, 0), (0, 0, 1)] {
                        let (a, b, e) = (i + di, j + dj, l + dl);
                        if a < q && b < q && e < q {
                            lower.push(Triplet::new(at(a, b, e), c, -1.0));
                        }
                    }
                }
            }
        }
        (n, lower)
    }

    /// A factor on a kept analysis ([`super::super::memo`]) solves to the same bits as one on
    /// an analysis made afresh, under each ordering: the analysis depends on the pattern
    /// alone.
    #[test]
    fn a_kept_analysis_factorises_to_the_same_bits_as_a_fresh_one() {
        let (n, lower) = grid(9);
        let a = SparseColMat::try_new_from_triplets(n, n, &lower).unwrap();
        let rhs: Vec<f64> = (0..n).map(|i| ((i * 13) % 7) as f64 - 3.0).collect();
        for ordering in [Ordering::Amd, Ordering::Natural, Ordering::Fewest] {
            let solve = |mut llt: SparseLlt| {
                let mut x = rhs.clone();
                llt.solve_in_place(&mut x);
                x.iter().map(|v| v.to_bits()).collect::<Vec<_>>()
            };
            let fresh = Arc::new(analysis(a.as_ref(), ordering).unwrap());
            let reference = solve(SparseLlt::numeric(a.as_ref(), fresh).unwrap());
            // Twice: the second one finds the first one's analysis kept (unless tests running
            // beside this one pushed it out: the same bits either way).
            for _ in 0..2 {
                let llt = SparseLlt::from_lower(a.as_ref(), ordering).unwrap();
                assert_eq!(solve(llt), reference, "{ordering:?}");
            }
        }
    }

    /// Columns solved together differ in their last bits from columns solved alone (faer
    /// runs a block of right-hand sides through other kernels), so the blocks are the same
    /// for any number of threads: the same bits on 1, 2 or 3 threads.
    #[test]
    fn columns_solve_alike_on_any_number_of_threads() {
        let (n, lower) = grid(14);
        let llt = SparseLlt::new(n, &lower, Ordering::Amd).unwrap();
        let b = Mat::from_fn(n, 19, |i, j| {
            ((i * 31 + j * 17) % 23) as f64 - 11.0 + 0.1 * j as f64
        });
        let solved = |threads: usize| {
            let pool = rayon::ThreadPoolBuilder::new()
                .num_threads(threads)
                .build()
                .unwrap();
            let mut x = b.clone();
            pool.install(|| llt.solve_columns_in_place(x.as_mut()));
            x
        };
        let one = solved(1);
        for threads in [2, 3] {
            assert!(solved(threads) == one, "{threads} threads");
        }
        // The check can fail: together and alone differ.
        let mut alone = b.clone();
        for j in 0..b.ncols() {
            llt.solve_columns_in_place(alone.as_mut().subcols_mut(j, 1));
        }
        assert!(alone != one);
    }
}

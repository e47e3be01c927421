//! The sparse Cholesky factor of the shifted matrix K - sigma M that the shift-invert
//! eigensolver applies as (K - sigma M)^-1, on faer's low-level sparse Cholesky (symbolic
//! analysis once, numeric factorisation, solves with a workspace kept between calls).

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::cholesky::llt::factor::LltRegularization;
use faer::perm::PermRef;
use faer::sparse::linalg::cholesky::{
    CholeskySymbolicParams, LltRef, SymbolicCholesky, SymmetricOrdering,
    factorize_symbolic_cholesky,
};
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};
use faer::{Conj, MatMut, Par, Side};

/// Fill-reducing ordering of the factorisation.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ordering {
    /// Approximate minimum degree (Amestoy, Davis & Duff, SIAM J. Matrix Anal. Appl. 17
    /// (1996)).
    Amd,
    /// The DOF order of the matrices (a banded matrix keeps its band).
    Natural,
}

/// L L^T = P A P^T of a symmetric positive definite A.
pub struct SparseLlt {
    symbolic: SymbolicCholesky<usize>,
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
        let n = a.nrows();
        let identity: Vec<usize> = (0..n).collect();
        let ord = match ordering {
            Ordering::Amd => SymmetricOrdering::Amd,
            // Identity as an explicit permutation: faer's symbolic analysis then reads the
            // given side like for any other ordering.
            Ordering::Natural => {
                SymmetricOrdering::Custom(PermRef::new_checked(&identity, &identity, n))
            }
        };
        let symbolic = factorize_symbolic_cholesky(
            a.symbolic(),
            Side::Lower,
            ord,
            CholeskySymbolicParams::default(),
        )
        .ok()?;
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

    /// Entries of the factor L.
    pub fn factor_entries(&self) -> usize {
        self.values.len()
    }
}

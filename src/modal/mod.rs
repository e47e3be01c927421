//! The modal solution of eq. (1)-(2): K y = lambda M y, every pair of a small model, the
//! lowest pairs of a large one.
//!
//! Contract of [`ModalSolution`]:
//! - eigenvalues ascending (the free-free chain's two rigid-body modes first, near zero);
//! - vectors M-normalised: Y^T M Y = E and Y^T K Y = Lambda (eq. (2));
//! - sign fixed: the component of largest magnitude of every vector is positive (the first
//!   such component on a tie).
//!
//! Up to [`DENSE_MAX_DOFS`] DOFs every pair is computed densely; above, [`ModalSolution::lowest_of`]
//! and [`ModalSolution::covering`] compute the lowest pairs by shift-invert Lanczos on the
//! sparse matrices ([`lanczos`], with the refinement of [`refine`]), and [`nelson`] gives the
//! derivatives of one pair without the others.
//!
//! Dense method: Cholesky reduction. M = L L^T, A = L^-1 K L^-T, standard symmetric eigenproblem
//! A x = lambda x, y = L^-T x. A is scaled to unit largest entry before the symmetric solver
//! and the eigenvalues rescaled after: faer's solver loses accuracy on entries of order
//! 1e12 (as L^-1 K L^-T of a fine beam mesh is) without it.
//!
//! Layer 2 (eigensolution; see the crate docs): may import the layers below: [`crate::stats`],
//! [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`].

pub mod accurate;
pub mod deflated;
pub mod elastic;
mod krylov;
pub mod lanczos;
pub mod memo;
pub mod nelson;
mod pencil;
pub mod reduced;
pub mod refine;
pub mod residual;
mod shift;
pub mod sparse_llt;

use std::sync::Arc;

use faer::sparse::SparseColMatRef;
use faer::{Mat, Side};

use crate::structure::Matrices;
use sparse_llt::SparseLlt;

pub use elastic::{Mechanism, check_elastic};

/// Largest number of DOFs solved densely (all pairs); larger models get their lowest pairs by
/// shift-invert Lanczos. Measured with `cargo run --release --example dense_threshold` on the
/// paper's chain refined (docs/benchmarks.md, "Large models"): the sparse solve of the lowest 20 pairs
/// takes 0.75 ms at N = 84 against 0.56 ms dense, 1.0 ms at N = 124 against 1.4 ms; above
/// about 160 DOFs the dense first elastic eigenvalue also loses digits to round-off (6e-8
/// relative at N = 204, 1e-1 at N = 2004).
pub const DENSE_MAX_DOFS: usize = 120;

/// Why the eigenproblem could not be solved.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ModalError {
    /// M has a non-positive pivot: some DOF carries no mass.
    #[error("the mass matrix is not positive definite; every DOF must carry mass")]
    MassNotPositiveDefinite,
    /// The matrices hold NaN or infinite entries.
    #[error("the stiffness or mass matrix has non-finite entries")]
    NonFinite,
    /// The symmetric eigensolver did not converge.
    #[error("the symmetric eigensolver did not converge")]
    NoConvergence,
    /// The Lanczos vectors handed to the refinement are not M-independent: shift-invert
    /// could not tell the lowest modes apart, their theta = 1 / (lambda - sigma) equal to
    /// working precision at a shift far beyond them (the default shift of
    /// [`lanczos::LanczosSettings::shift`] when one stiffness dwarfs the others: a joint
    /// spring of 4.4e158 N m/rad in a fit, sigma = -1.6e156).
    #[error(
        "the Lanczos vectors of the refinement are nearly dependent (rank {independent} of \
         {requested} in the M inner product): shift-invert cannot tell the lowest modes apart \
         in double precision, as in a model whose stiffness-to-mass ratios K_ii/M_ii span too \
         many orders of magnitude; check the values and their units"
    )]
    DependentVectors {
        /// M-independent directions among them.
        independent: usize,
        /// Vectors refined (the wanted pairs and a few more).
        requested: usize,
    },
    /// K and M are not square matrices of one size.
    #[error(
        "K is {}x{} and M is {}x{}: both must be square and of one size",
        k.0, k.1, m.0, m.1
    )]
    ShapeMismatch {
        /// Rows and columns of K.
        k: (usize, usize),
        /// Rows and columns of M.
        m: (usize, usize),
    },
    /// The number of wanted pairs is 0 or above the number of DOFs.
    #[error("{count} eigenpairs requested of a model with {dofs} DOFs: allowed 1 ..= {dofs}")]
    CountOutOfRange {
        /// Pairs requested.
        count: usize,
        /// DOFs N.
        dofs: usize,
    },
    /// A solver setting is out of its range.
    #[error("eigensolver setting {name} = {value} is invalid: allowed {allowed}")]
    InvalidSetting {
        /// The setting.
        name: &'static str,
        /// Its value.
        value: f64,
        /// The allowed range.
        allowed: String,
    },
    /// K - sigma M met a non-positive Cholesky pivot for every shift tried.
    #[error(
        "K - sigma M could not be factorised for sigma = {first:e} .. {last:e} ({attempts} \
         shifts): K must be positive semidefinite and M positive definite"
    )]
    ShiftNotFactorised {
        /// The first shift tried.
        first: f64,
        /// The last shift tried.
        last: f64,
        /// Number of shifts tried.
        attempts: usize,
    },
    /// The iterative eigensolver stopped before every wanted pair met the tolerance. At the
    /// default [`lanczos::LanczosSettings`], the only ones the commands use, the Krylov space
    /// converges on any well-scaled model: what is left is a model whose stiffness-to-mass
    /// ratios span too many orders of magnitude for double precision, so the message tells
    /// the user to check the model's values and units (a caller of [`lanczos::lowest_modes`]
    /// with settings of its own may raise `max_restarts` or `basis_size` instead).
    #[error(
        "eigensolver: {converged} of {requested} pairs converged ({stage} > {tolerance:.0e}: {}); \
         the model is likely ill scaled; check its values and units",
        listed(unconverged)
    )]
    NotConverged {
        /// Pairs that met the tolerance.
        converged: usize,
        /// Pairs requested.
        requested: usize,
        /// Restarts done.
        restarts: usize,
        /// The measure that failed: the shift-invert residual of the Ritz pairs, or the
        /// backward error of the refined pairs.
        stage: &'static str,
        /// The pairs that failed (1-based, lowest first) and their value of that measure.
        unconverged: Vec<(usize, f64)>,
        /// The tolerance they were held to.
        tolerance: f64,
    },
    /// K - lambda M with the pinned DOF is singular (a repeated eigenvalue: Nelson's method
    /// needs a simple one).
    #[error(
        "K - lambda M with DOF {pinned} pinned is singular at lambda = {lambda:e}: the \
         eigenvalue must be simple for Nelson's method"
    )]
    PinnedMatrixSingular {
        /// The eigenvalue.
        lambda: f64,
        /// The pinned DOF.
        pinned: usize,
    },
    /// The eigenvector given to Nelson's method is not M-normalised.
    #[error("the eigenvector has y^T M y = {norm}: it must be M-normalised (1)")]
    NotMassNormalised {
        /// y^T M y.
        norm: f64,
    },
    /// Two computed eigenvalues coincide: the derivative of their vectors is not defined.
    #[error(
        "eigenvalue {lambda:e} is repeated ({other:e} beside it): its vector's derivative is \
         defined for a simple eigenvalue only"
    )]
    RepeatedEigenvalue {
        /// The eigenvalue.
        lambda: f64,
        /// The other eigenvalue within [`deflated::SIMPLE_GAP`] of it.
        other: f64,
    },
    /// The conjugate gradients of the deflated derivative did not converge.
    #[error(
        "the derivative of mode {mode} did not converge in {iterations} conjugate-gradient \
         iterations (residual reduced by {reduction:e} only)"
    )]
    DerivativeNotConverged {
        /// The mode (1-based, rigid-body modes counted).
        mode: usize,
        /// Iterations done.
        iterations: usize,
        /// The least reduction of the preconditioned residual norm.
        reduction: f64,
    },
    /// K - lambda_s M is not positive definite beside the computed pairs.
    #[error(
        "K - lambda M of mode {mode} is not positive definite beside the computed pairs: a \
         pair below mode {mode} is missing from them"
    )]
    PairMissing {
        /// The mode (1-based, rigid-body modes counted).
        mode: usize,
    },
    /// A vector's length differs from the number of DOFs.
    #[error("a vector of length {len} was given for a model with {dofs} DOFs")]
    VectorLength {
        /// Its length.
        len: usize,
        /// DOFs N.
        dofs: usize,
    },
}

/// The first three unconverged pairs as `pair 1 2.9e-7, ...`, the count of the others after.
fn listed(unconverged: &[(usize, f64)]) -> String {
    let mut text: Vec<String> = unconverged
        .iter()
        .take(1)
        .map(|(j, r)| format!("pair {j} {r:.1e}"))
        .collect();
    if unconverged.len() > 1 {
        text.push(format!("{} more", unconverged.len() - 1));
    }
    text.join(", ")
}

/// All eigenpairs of (K, M), under the contract in the module docs.
#[derive(Debug, Clone)]
pub struct ModalSolution {
    values: Vec<f64>,
    vectors: Mat<f64>,
    /// The reduced pencil's pairs when solved on a reduced model ([`reduced`]).
    reduced: Option<std::sync::Arc<reduced::ReducedPairs>>,
    /// The factor of K - sigma M the sparse solve made, when asked to keep it
    /// ([`ModalSolution::lowest_of_factored`]).
    factor: Option<Arc<SparseLlt>>,
}

impl ModalSolution {
    /// The lowest `count` eigenpairs, or more: up to [`DENSE_MAX_DOFS`] DOFs every pair by the
    /// dense solution ([`ModalSolution::solve`]), above it exactly `count` pairs by
    /// shift-invert Lanczos ([`ModalSolution::lowest`]).
    pub fn lowest_of(mats: &Matrices, count: usize) -> Result<ModalSolution, ModalError> {
        let n = mats.size();
        if n <= DENSE_MAX_DOFS {
            return Self::solve(mats);
        }
        if count == 0 || count > n {
            return Err(ModalError::CountOutOfRange { count, dofs: n });
        }
        Self::lowest(mats.k.as_faer(), mats.m.as_faer(), count)
    }

    /// The lowest pairs up to the frequency `f_max_hz` and at least `count` of them (every
    /// pair at or below [`DENSE_MAX_DOFS`] DOFs): above the threshold, the sparse solve is
    /// repeated with half as many pairs again until its highest frequency exceeds `f_max_hz`
    /// or every pair is computed (the cost grows with the count: doubling overshoots).
    pub fn covering(
        mats: &Matrices,
        count: usize,
        f_max_hz: f64,
    ) -> Result<ModalSolution, ModalError> {
        let n = mats.size();
        let mut count = count.clamp(1, n);
        loop {
            let sol = Self::lowest_of(mats, count)?;
            let top = sol.frequency_hz(sol.len() - 1);
            if sol.len() == n || top > f_max_hz || f_max_hz.is_nan() {
                return Ok(sol);
            }
            count = (count + count.div_ceil(2)).min(n);
        }
    }

    /// Solves K y = lambda M y for all pairs (dense).
    pub fn solve(mats: &Matrices) -> Result<ModalSolution, ModalError> {
        if !mats.k.is_finite() || !mats.m.is_finite() {
            return Err(ModalError::NonFinite);
        }
        Self::solve_dense(&mats.k.to_dense(), &mats.m.to_dense())
    }

    /// Solves K y = lambda M y for all pairs of dense, finite K and M.
    pub fn solve_dense(k: &Mat<f64>, m: &Mat<f64>) -> Result<ModalSolution, ModalError> {
        let n = k.nrows();
        let llt = m
            .llt(Side::Lower)
            .map_err(|_| ModalError::MassNotPositiveDefinite)?;
        let (values, mut vectors) =
            pencil::cholesky_reduced(k, llt.L()).ok_or(ModalError::NoConvergence)?;
        for j in 0..n {
            fix_sign(&mut vectors, j);
        }
        Ok(ModalSolution {
            values,
            vectors,
            reduced: None,
            factor: None,
        })
    }

    /// The `count` lowest pairs of a sparse problem (K, M given with both triangles), by
    /// shift-invert Lanczos with the default [`lanczos::LanczosSettings`]; same contract as
    /// [`ModalSolution::solve`], [`ModalSolution::len`] is then `count`.
    pub fn lowest(
        k: SparseColMatRef<'_, usize, f64>,
        m: SparseColMatRef<'_, usize, f64>,
        count: usize,
    ) -> Result<ModalSolution, ModalError> {
        let modes = lanczos::lowest_modes(k, m, count, &lanczos::LanczosSettings::default())?;
        Ok(ModalSolution {
            values: modes.values,
            vectors: modes.vectors,
            reduced: None,
            factor: None,
        })
    }

    /// As [`ModalSolution::lowest_of`], keeping the factor of K - sigma M the sparse solve made
    /// ([`ModalSolution::take_factor`]; sigma the default shift, [`lanczos::default_shift`],
    /// moved away from the spectrum as that solve moves it: the factor [`reduced::build`]
    /// would make of the same matrices); none from the dense solution. The factor is as large
    /// as the solve's memory (1.3e8 entries, 1 GB, on the 212,562-DOF lap of bench/): a caller
    /// that keeps the solution and not the factor takes it out.
    pub fn lowest_of_factored(mats: &Matrices, count: usize) -> Result<ModalSolution, ModalError> {
        let n = mats.size();
        if n <= DENSE_MAX_DOFS {
            return Self::solve(mats);
        }
        if count == 0 || count > n {
            return Err(ModalError::CountOutOfRange { count, dofs: n });
        }
        let settings = lanczos::LanczosSettings::default();
        let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
        let (modes, llt) = lanczos::lowest_modes_factored(k, m, count, &settings)?;
        Ok(ModalSolution {
            values: modes.values,
            vectors: modes.vectors,
            reduced: None,
            factor: Some(Arc::new(llt)),
        })
    }

    /// The factor of K - sigma M kept by [`ModalSolution::lowest_of_factored`], taken out.
    pub fn take_factor(&mut self) -> Option<Arc<SparseLlt>> {
        self.factor.take()
    }

    /// Pairs solved elsewhere (a reduced model's, lifted): `values` ascending, `vectors` N x
    /// len under the contract of the module docs.
    pub(crate) fn from_parts(
        values: Vec<f64>,
        vectors: Mat<f64>,
        reduced: Option<std::sync::Arc<reduced::ReducedPairs>>,
    ) -> ModalSolution {
        ModalSolution {
            values,
            vectors,
            reduced,
            factor: None,
        }
    }

    /// The reduced pencil's pairs, when these pairs were solved on a reduced model
    /// ([`reduced`]): their residuals in the full model, and what their derivatives need.
    pub fn reduced(&self) -> Option<&reduced::ReducedPairs> {
        self.reduced.as_deref()
    }

    /// Number of computed eigenpairs (N for the dense solution, `count` for the sparse one).
    pub fn len(&self) -> usize {
        self.values.len()
    }

    /// Number of DOFs N (the length of every vector).
    pub fn dof_count(&self) -> usize {
        self.vectors.nrows()
    }

    /// Whether there is no pair (never, for a valid model).
    pub fn is_empty(&self) -> bool {
        self.values.is_empty()
    }

    /// Eigenvalues lambda = omega^2, ascending, rad^2/s^2.
    pub fn values(&self) -> &[f64] {
        &self.values
    }

    /// Eigenvectors as columns, M-normalised.
    pub fn vectors(&self) -> &Mat<f64> {
        &self.vectors
    }

    /// Natural frequency of pair `i`, Hz (zero for a round-off negative eigenvalue).
    pub fn frequency_hz(&self, i: usize) -> f64 {
        lambda_to_hz(self.values[i])
    }

    /// The modal sub-basis of eq. (2): the first `n` vectors (N x n) and their eigenvalues.
    pub fn sub_basis(&self, n: usize) -> (Mat<f64>, Vec<f64>) {
        let y = self.vectors.subcols(0, n).to_owned();
        (y, self.values[..n].to_vec())
    }
}

/// Frequency in Hz of an eigenvalue lambda = (2 pi f)^2.
pub fn lambda_to_hz(lambda: f64) -> f64 {
    lambda.max(0.0).sqrt() / (2.0 * std::f64::consts::PI)
}

/// Eigenvalue lambda = (2 pi f)^2 of a frequency in Hz.
pub fn hz_to_lambda(f: f64) -> f64 {
    let w = 2.0 * std::f64::consts::PI * f;
    w * w
}

/// `(a(), b())`: called from outside rayon's pool, `a` on a thread of its own when the pool
/// has two threads or more, `b` on the calling thread; from one of the pool's threads (a
/// study, diagnose's candidates fitted in parallel), by `rayon::join`, which lends `a` to an
/// idle thread of the pool rather than start one more; one after the other with one thread.
/// Why not `rayon::join` from outside the pool: it runs both on the pool's threads, and there
/// the factorisation of the 212k-DOF lap took 1 s longer than on the calling thread (5.6
/// against 4.6 s), likely because the calling thread's allocator arena already holds the
/// pages it needs.
pub(crate) fn beside<A: Send, B: Send>(
    a: impl FnOnce() -> A + Send,
    b: impl FnOnce() -> B + Send,
) -> (A, B) {
    if rayon::current_num_threads() < 2 {
        let first = a();
        return (first, b());
    }
    if rayon::current_thread_index().is_some() {
        return rayon::join(a, b);
    }
    std::thread::scope(|scope| {
        let first = scope.spawn(a);
        let second = b();
        let first = first
            .join()
            .unwrap_or_else(|panic| std::panic::resume_unwind(panic));
        (first, second)
    })
}

/// `y = A x` for a symmetric matrix stored with both triangles.
pub(crate) fn sparse_mul(a: SparseColMatRef<'_, usize, f64>, x: &[f64], y: &mut [f64]) {
    sparse_mul_block::<1>(a, [x], [y]);
}

/// [`sparse_mul`] of W vectors in one pass over A, into the W columns `y`. Column j
/// of a symmetric matrix is its row j: each entry of y is one gathered sum, written once.
pub(crate) fn sparse_mul_block<const W: usize>(
    a: SparseColMatRef<'_, usize, f64>,
    x: [&[f64]; W],
    mut y: [&mut [f64]; W],
) {
    let n = a.ncols();
    for j in 0..n {
        let rows = a.symbolic().row_idx_of_col_raw(j);
        let mut s = [0.0_f64; W];
        for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
            for r in 0..W {
                s[r] += v * x[r][i];
            }
        }
        for (column, value) in y.iter_mut().zip(s) {
            column[j] = value;
        }
    }
}

fn fix_sign(v: &mut Mat<f64>, j: usize) {
    let mut best = 0;
    for i in 0..v.nrows() {
        if v[(i, j)].abs() > v[(best, j)].abs() {
            best = i;
        }
    }
    if v[(best, j)] < 0.0 {
        for i in 0..v.nrows() {
            v[(i, j)] = -v[(i, j)];
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::fixtures::paper_model;

    #[test]
    fn contract_orthonormality_residual_order_and_sign() {
        let sparse = paper_model(1e7, 1e4).assemble();
        let sol = ModalSolution::solve(&sparse).unwrap();
        let (k, m) = (sparse.k.to_dense(), sparse.m.to_dense());
        let n = sol.len();
        let y = sol.vectors();
        let ytmy = y.transpose() * &m * y;
        let ytky = y.transpose() * &k * y;
        let lmax = sol.values()[n - 1];
        let tol = 100.0 * n as f64 * f64::EPSILON;
        for i in 0..n {
            for j in 0..n {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!(
                    (ytmy[(i, j)] - e).abs() < tol,
                    "YtMY({i},{j}) = {}",
                    ytmy[(i, j)]
                );
                let l = if i == j { sol.values()[i] } else { 0.0 };
                assert!((ytky[(i, j)] - l).abs() < tol * lmax, "YtKY({i},{j})");
            }
        }
        // ||K y - lambda M y|| relative to ||K|| ||y||.
        let r = &k * y
            - &m * y * faer::Mat::from_fn(n, n, |i, j| if i == j { sol.values()[i] } else { 0.0 });
        assert!(r.norm_max() < tol * lmax * y.norm_max());
        assert!(sol.values().windows(2).all(|w| w[0] <= w[1]));
        for j in 0..n {
            let col: Vec<f64> = (0..n).map(|i| y[(i, j)]).collect();
            let big = col
                .iter()
                .cloned()
                .fold(0.0_f64, |a, b| if b.abs() > a.abs() { b } else { a });
            assert!(big > 0.0);
        }
    }

    #[test]
    fn exactly_two_rigid_body_modes_and_k_semidefinite() {
        let sol = ModalSolution::solve(&paper_model(1e7, 1e4).assemble()).unwrap();
        let lmax = sol.values()[sol.len() - 1];
        // Round-off level of the eigenvalues: a few eps times the largest.
        let zero = 1e-12 * lmax;
        let near_zero = sol.values().iter().filter(|l| l.abs() < zero).count();
        assert_eq!(near_zero, 2);
        assert!(sol.values().iter().all(|&l| l > -zero));
        // The first elastic mode (about 150 Hz) is far above round-off.
        assert!(sol.values()[2] > 1e4 * zero);
    }

    #[test]
    fn mass_matrix_is_positive_definite_and_a_massless_dof_is_an_error() {
        let sparse = paper_model(1e7, 1e4).assemble();
        let (k, mut m) = (sparse.k.to_dense(), sparse.m.to_dense());
        assert!(m.llt(Side::Lower).is_ok());
        for j in 0..m.ncols() {
            m[(3, j)] = 0.0;
            m[(j, 3)] = 0.0;
        }
        assert_eq!(
            ModalSolution::solve_dense(&k, &m).unwrap_err(),
            ModalError::MassNotPositiveDefinite
        );
    }

    /// The paper's chain refined to 2 x 30 elements (124 DOFs, above the threshold), against
    /// its dense solution (accurate to 3e-9 there, docs/benchmarks.md "Large models").
    fn refined_chain() -> Matrices {
        use crate::model::chain::{Chain, Joint};
        use crate::model::fixtures::steel_bar;
        Chain::free(
            vec![steel_bar(0.2, 30), steel_bar(0.3, 30)],
            vec![Joint::identified(1e7, 1e4)],
        )
        .build()
        .assemble()
    }

    #[test]
    fn lowest_of_is_dense_up_to_the_threshold_and_sparse_above() {
        let small = paper_model(1e7, 1e4).assemble();
        assert!(small.size() <= DENSE_MAX_DOFS);
        let (a, b) = (
            ModalSolution::lowest_of(&small, 3).unwrap(),
            ModalSolution::solve(&small).unwrap(),
        );
        assert_eq!(a.len(), small.size());
        assert!(
            a.values()
                .iter()
                .zip(b.values())
                .all(|(x, y)| x.to_bits() == y.to_bits())
        );

        let large = refined_chain();
        assert!(large.size() > DENSE_MAX_DOFS);
        let sparse = ModalSolution::lowest_of(&large, 10).unwrap();
        let dense = ModalSolution::solve(&large).unwrap();
        assert_eq!(sparse.len(), 10);
        assert_eq!(sparse.dof_count(), large.size());
        for i in 2..10 {
            let (s, d) = (sparse.frequency_hz(i), dense.frequency_hz(i));
            assert!((s - d).abs() < 1e-8 * d, "mode {i}: {s} vs {d}");
            // Same vector, same sign convention.
            let diff = (0..large.size())
                .map(|r| (sparse.vectors()[(r, i)] - dense.vectors()[(r, i)]).abs())
                .fold(0.0, f64::max);
            assert!(
                diff < 1e-6 * dense.vectors().col(i).norm_max(),
                "mode {i}: {diff}"
            );
        }
        assert_eq!(
            ModalSolution::lowest_of(&large, 0).unwrap_err(),
            ModalError::CountOutOfRange {
                count: 0,
                dofs: large.size()
            }
        );
    }

    #[test]
    fn covering_reaches_the_frequency_asked_for() {
        let large = refined_chain();
        // 3 pairs end at 150 Hz, 5 at 2412 Hz: grown to 8 (the sixth is at 5356 Hz).
        let sol = ModalSolution::covering(&large, 3, 3000.0).unwrap();
        assert_eq!(sol.len(), 8);
        assert!(sol.frequency_hz(5) > 3000.0 && sol.frequency_hz(4) < 3000.0);
    }

    #[test]
    fn frequency_conversions_invert() {
        assert!((lambda_to_hz(hz_to_lambda(123.4)) - 123.4).abs() < 1e-12);
        assert_eq!(lambda_to_hz(-1e-9), 0.0);
    }
}

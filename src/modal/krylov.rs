//! The Krylov basis of shift-invert Lanczos in Krylov-Schur form, OP V = V H + beta v e^T
//! with OP = (K - sigma M)^-1 M: expansion by M-orthogonalised operator products (classical
//! Gram-Schmidt, the first pass over the coupled vectors only), the Ritz pairs of H, and the
//! thick restart that keeps the best Ritz vectors ([`super::lanczos`] drives it).
//!
//! Layer 2 (eigensolution): imports faer and the modal module's factor.

use std::time::{Duration, Instant};

use faer::linalg::matmul::matmul;
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, MatRef, Par};

use super::pencil::symmetric_eigen;
use super::sparse_llt::SparseLlt;
use super::sparse_mul;

/// The M-orthonormal Krylov basis in Krylov-Schur form: OP V = V H + beta v_size e^T.
pub(super) struct Krylov<'a> {
    m: SparseColMatRef<'a, usize, f64>,
    pub(super) llt: SparseLlt,
    /// V, N x (size + 1); column `size` is the residual direction.
    v: Mat<f64>,
    /// M V.
    z: Mat<f64>,
    /// H = V^T M OP V (size x size), filled for columns < `filled`.
    h: Mat<f64>,
    size: usize,
    /// Columns of H (and V) already built; the next expansion starts here.
    filled: usize,
    /// Coupling of the last basis vector to the residual direction.
    pub(super) beta: f64,
    pub(super) applications: usize,
    pub(super) solves: Duration,
    pub(super) orthogonalisation: Duration,
    seed: u64,
}

impl<'a> Krylov<'a> {
    pub(super) fn new(
        n: usize,
        size: usize,
        m: SparseColMatRef<'a, usize, f64>,
        llt: SparseLlt,
    ) -> Self {
        let mut krylov = Krylov {
            m,
            llt,
            v: Mat::zeros(n, size + 1),
            z: Mat::zeros(n, size + 1),
            h: Mat::zeros(size, size),
            size,
            filled: 0,
            beta: 0.0,
            applications: 0,
            solves: Duration::ZERO,
            orthogonalisation: Duration::ZERO,
            seed: 0x9e37_79b9_7f4a_7c15,
        };
        // Start: OP applied to a pseudo-random vector, which removes the components of the
        // eigenvectors of large lambda by the factor theta.
        let start = krylov.random_vector();
        krylov.z.col_as_slice_mut(0).copy_from_slice(&start);
        let mut w = krylov.apply(0);
        krylov.orthonormalise_into(&mut w, 0, 0);
        krylov
    }

    /// Whether the basis spans the whole space (no residual direction exists).
    pub(super) fn full(&self) -> bool {
        self.size == self.v.nrows()
    }

    /// OP v_j = (K - sigma M)^-1 (M v_j).
    fn apply(&mut self, j: usize) -> Vec<f64> {
        let started = Instant::now();
        let mut w = self.z.col_as_slice(j).to_vec();
        self.llt.solve_in_place(&mut w);
        self.applications += 1;
        self.solves += started.elapsed();
        w
    }

    fn random_vector(&mut self) -> Vec<f64> {
        (0..self.v.nrows())
            .map(|_| {
                // splitmix64
                self.seed = self.seed.wrapping_add(0x9e37_79b9_7f4a_7c15);
                let mut x = self.seed;
                x = (x ^ (x >> 30)).wrapping_mul(0xbf58_476d_1ce4_e5b9);
                x = (x ^ (x >> 27)).wrapping_mul(0x94d0_49bb_1331_11eb);
                x ^= x >> 31;
                (x >> 11) as f64 / (1u64 << 53) as f64 - 0.5
            })
            .collect()
    }

    /// M-orthogonalises `w` against v_0 .. v_{j-1}, stores it normalised as v_j and returns
    /// the coefficients and the norm before normalisation. Classical Gram-Schmidt in two
    /// passes ("twice is enough"), the first over v_from .. v_{j-1} only: in the Lanczos
    /// recurrence OP v_i lies in span(v_{i-1}, v_i, v_{i+1}) (after a thick restart, in the
    /// span of the kept vectors and v_{i+1}), so the first pass needs just those columns to
    /// take out the large components, and the second, over the whole basis, takes out what
    /// round-off left. A third pass follows when the second removed more than it left (the
    /// criterion of Daniel, Gragg, Kaufman & Stewart, Math. Comp. 30 (1976), eta = 1/sqrt 2).
    fn orthonormalise_into(&mut self, w: &mut [f64], j: usize, from: usize) -> (Vec<f64>, f64) {
        let started = Instant::now();
        let n = w.len();
        let mut coefficients = vec![0.0; j];
        let mut mw = vec![0.0; n];
        let from = from.min(j);
        let pass = |w: &mut [f64], from: usize, coefficients: &mut [f64]| -> f64 {
            let width = j - from;
            if width == 0 {
                return 0.0;
            }
            let mut c = Mat::<f64>::zeros(width, 1);
            let wr = MatRef::from_column_major_slice(w, n, 1);
            matmul(
                &mut c,
                Accum::Replace,
                self.z.subcols(from, width).transpose(),
                wr,
                1.0,
                Par::Seq,
            );
            let wm = faer::MatMut::from_column_major_slice_mut(w, n, 1);
            matmul(
                wm,
                Accum::Add,
                self.v.subcols(from, width),
                &c,
                -1.0,
                Par::Seq,
            );
            let c = c.col_as_slice(0);
            for (a, b) in coefficients[from..].iter_mut().zip(c) {
                *a += b;
            }
            c.iter().map(|x| x * x).sum()
        };
        pass(w, from, &mut coefficients);
        let mut removed = pass(w, 0, &mut coefficients);
        let mut extra = 0;
        let norm = loop {
            sparse_mul(self.m, w, &mut mw);
            let norm = dot(w, &mw).max(0.0).sqrt();
            if removed <= norm * norm || extra == 2 {
                break norm;
            }
            removed = pass(w, 0, &mut coefficients);
            extra += 1;
        };
        if norm > 0.0 {
            w.iter_mut().chain(mw.iter_mut()).for_each(|a| *a /= norm);
        }
        self.v.col_as_slice_mut(j).copy_from_slice(w);
        self.z.col_as_slice_mut(j).copy_from_slice(&mw);
        self.orthogonalisation += started.elapsed();
        (coefficients, norm)
    }

    /// Extends the basis to `size` vectors (and the residual direction).
    pub(super) fn expand(&mut self) {
        let n = self.v.nrows();
        let first = self.filled;
        for j in first..self.size {
            let mut w = self.apply(j);
            // The columns the recurrence couples OP v_j to: all the kept ones on the first
            // step after a restart, v_{j-1} and v_j after it.
            let coupled = if j == first { 0 } else { j - 1 };
            let next = j + 1;
            if next == n {
                // The basis spans the space: OP v_j lies in it.
                let (c, _) = self.project_only(&mut w, next);
                self.set_column(j, &c);
                self.beta = 0.0;
                break;
            }
            let (c, norm) = self.orthonormalise_into(&mut w, next, coupled);
            self.set_column(j, &c);
            let mut beta = norm;
            if norm <= 1e-12 * (dot(&c, &c) + norm * norm).sqrt() {
                // Invariant subspace: continue with a fresh direction, uncoupled.
                let mut r = self.random_vector();
                self.orthonormalise_into(&mut r, next, 0);
                beta = 0.0;
            }
            if next < self.size {
                self.h[(next, j)] = beta;
                self.h[(j, next)] = beta;
            } else {
                self.beta = beta;
            }
        }
        self.filled = self.size;
    }

    fn project_only(&mut self, w: &mut [f64], j: usize) -> (Vec<f64>, f64) {
        let n = w.len();
        let mut c = Mat::<f64>::zeros(j, 1);
        let wr = MatRef::from_column_major_slice(w, n, 1);
        matmul(
            &mut c,
            Accum::Replace,
            self.z.subcols(0, j).transpose(),
            wr,
            1.0,
            Par::Seq,
        );
        (c.col_as_slice(0).to_vec(), 0.0)
    }

    /// Column j of H from the Gram-Schmidt coefficients of OP v_j (rows 0..=j), mirrored.
    fn set_column(&mut self, j: usize, c: &[f64]) {
        for (i, &value) in c.iter().enumerate().take(j + 1) {
            self.h[(i, j)] = value;
            self.h[(j, i)] = value;
        }
    }

    /// Ritz values theta (descending) and vectors S of H.
    pub(super) fn ritz(&self) -> (Vec<f64>, Mat<f64>) {
        let size = self.size;
        let (values, u) = symmetric_eigen(&self.h)
            .expect("the symmetric eigensolver of a small finite matrix converges");
        let theta = values.into_iter().rev().collect();
        let s = Mat::from_fn(size, size, |i, j| u[(i, size - 1 - j)]);
        (theta, s)
    }

    /// V S[:, ..count].
    pub(super) fn basis(&self, s: &Mat<f64>, count: usize) -> Mat<f64> {
        self.v.subcols(0, self.size) * s.subcols(0, count)
    }

    /// The factor, the basis let go (the refinement needs only the factor: V and M V are
    /// N x (size + 1) each, the largest blocks of the solve before it).
    pub(super) fn into_factor(self) -> SparseLlt {
        self.llt
    }

    /// Thick restart: keeps the `keep` best Ritz vectors, then the residual direction.
    pub(super) fn restart(&mut self, theta: &[f64], s: &Mat<f64>, keep: usize) {
        let size = self.size;
        let kept_v = self.v.subcols(0, size) * s.subcols(0, keep);
        let kept_z = self.z.subcols(0, size) * s.subcols(0, keep);
        self.v.subcols_mut(0, keep).copy_from(&kept_v);
        self.z.subcols_mut(0, keep).copy_from(&kept_z);
        let residual_v = self.v.col(size).to_owned();
        let residual_z = self.z.col(size).to_owned();
        self.v.col_mut(keep).copy_from(&residual_v);
        self.z.col_mut(keep).copy_from(&residual_z);
        self.h.fill(0.0);
        for i in 0..keep {
            self.h[(i, i)] = theta[i];
            let b = self.beta * s[(size - 1, i)];
            self.h[(i, keep)] = b;
            self.h[(keep, i)] = b;
        }
        self.filled = keep;
    }
}

/// a . b
pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

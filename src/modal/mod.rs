//! The modal solution of eq. (1)-(2): K y = lambda M y for all pairs.
//!
//! Contract of [`ModalSolution`]:
//! - eigenvalues ascending (the free-free chain's two rigid-body modes first, near zero);
//! - vectors M-normalised: Y^T M Y = E and Y^T K Y = Lambda (eq. (2));
//! - sign fixed: the component of largest magnitude of every vector is positive (the first
//!   such component on a tie).
//!
//! Method: Cholesky reduction. M = L L^T, A = L^-1 K L^-T, standard symmetric eigenproblem
//! A x = lambda x, y = L^-T x. A is scaled to unit largest entry before the symmetric solver
//! and the eigenvalues rescaled after: faer's solver loses accuracy on entries of order
//! 1e12 (as L^-1 K L^-T of a fine beam mesh is) without it.

use faer::{Mat, Side};

use crate::structure::Matrices;

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
}

/// All eigenpairs of (K, M), under the contract in the module docs.
#[derive(Debug, Clone)]
pub struct ModalSolution {
    values: Vec<f64>,
    vectors: Mat<f64>,
}

impl ModalSolution {
    /// The lowest `count` eigenpairs (or more): every pair by the dense solution.
    pub fn lowest_of(mats: &Matrices, count: usize) -> Result<ModalSolution, ModalError> {
        let _ = count;
        Self::solve(mats)
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
        let l = llt.L();
        // A = L^-1 K L^-T, using K = K^T: X = L^-1 K, A = L^-1 X^T.
        let mut x = k.clone();
        l.solve_lower_triangular_in_place(x.as_mut());
        let mut a = x.transpose().to_owned();
        l.solve_lower_triangular_in_place(a.as_mut());
        let scale = (0..n)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| a[(i, j)].abs())
            .fold(0.0_f64, f64::max)
            .max(f64::MIN_POSITIVE);
        let a = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]) / scale);
        let evd = a
            .self_adjoint_eigen(Side::Lower)
            .map_err(|_| ModalError::NoConvergence)?;
        let values: Vec<f64> = (0..n).map(|i| evd.S()[i] * scale).collect();
        let mut vectors = evd.U().to_owned();
        l.transpose()
            .solve_upper_triangular_in_place(vectors.as_mut());
        for j in 0..n {
            fix_sign(&mut vectors, j);
        }
        Ok(ModalSolution { values, vectors })
    }

    /// Number of computed eigenpairs (N for the dense solution).
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

    #[test]
    fn frequency_conversions_invert() {
        assert!((lambda_to_hz(hz_to_lambda(123.4)) - 123.4).abs() < 1e-12);
        assert_eq!(lambda_to_hz(-1e-9), 0.0);
    }
}

//! Eigenpair derivatives with respect to a parameter p from the mode itself, by Nelson's
//! method (R. B. Nelson, "Simplified calculation of eigenvector derivatives", AIAA J. 14
//! (1976) 1201-1205): no other mode is needed, so the cost does not grow with the number of
//! modes of the model, unlike the modal expansion of [`crate::diagnose::sensitivity`].
//!
//! For a simple eigenvalue lambda_s with M-normalised vector y_s (y_s^T M y_s = 1) and the
//! derivative matrices dK = dK/dp, dM = dM/dp, differentiating (K - lambda_s M) y_s = 0 and
//! the normalisation gives
//!
//! ```text
//!   d lambda_s = y_s^T (dK - lambda_s dM) y_s
//!   (K - lambda_s M) d y_s = f = -(dK - lambda_s dM) y_s + d lambda_s M y_s
//!   y_s^T M d y_s = -1/2 y_s^T dM y_s
//! ```
//!
//! K - lambda_s M is singular (null vector y_s). Nelson writes d y_s = v + c y_s: v solves the
//! system with the DOF p of largest |y_s| pinned (row and column p of K - lambda_s M replaced
//! by those of the identity, f_p = 0, so v_p = 0), which is non-singular for a simple
//! eigenvalue, and the normalisation gives c = -y_s^T M v - 1/2 y_s^T dM y_s.
//!
//! The pinned matrix is indefinite (lambda_s lies inside the spectrum): it is factorised once
//! per mode by sparse LU with partial pivoting (faer, COLAMD ordering), and [`NelsonMode`]
//! reuses the factors for every parameter.

use faer::linalg::solvers::Solve;
use faer::sparse::linalg::solvers::{Lu, SymbolicLu};
use faer::sparse::{SparseColMat, SparseColMatRef, Triplet};

use super::ModalError;
use super::sparse_mul;
use crate::structure::SparseSym;

/// Largest allowed |y^T M y - 1| of the vector handed to [`NelsonMode::new`].
pub const NORMALISATION_TOLERANCE: f64 = 1e-8;

/// The derivative of one eigenpair with respect to one parameter.
#[derive(Debug, Clone, PartialEq)]
pub struct EigenDerivative {
    /// d lambda / dp.
    pub value: f64,
    /// d y / dp (N entries), of the M-normalised vector.
    pub vector: Vec<f64>,
}

/// One mode prepared for Nelson's method: the factorised pinned matrix and M y_s.
#[derive(Debug)]
pub struct NelsonMode {
    lambda: f64,
    y: Vec<f64>,
    my: Vec<f64>,
    pinned: usize,
    lu: Lu<usize, f64>,
}

impl NelsonMode {
    /// Prepares the mode (lambda, y) of (K, M) (both triangles stored, y M-normalised to
    /// [`NORMALISATION_TOLERANCE`]): one sparse LU factorisation.
    pub fn new(
        k: SparseColMatRef<'_, usize, f64>,
        m: SparseColMatRef<'_, usize, f64>,
        lambda: f64,
        y: &[f64],
    ) -> Result<NelsonMode, ModalError> {
        let n = k.nrows();
        if k.ncols() != n || m.nrows() != n || m.ncols() != n {
            return Err(ModalError::ShapeMismatch {
                k: (k.nrows(), k.ncols()),
                m: (m.nrows(), m.ncols()),
            });
        }
        if y.len() != n || n == 0 {
            return Err(ModalError::VectorLength {
                len: y.len(),
                dofs: n,
            });
        }
        if !(lambda.is_finite() && y.iter().all(|v| v.is_finite())) {
            return Err(ModalError::NonFinite);
        }
        let mut my = vec![0.0; n];
        sparse_mul(m, y, &mut my);
        let norm: f64 = y.iter().zip(&my).map(|(a, b)| a * b).sum();
        if (norm - 1.0).abs() > NORMALISATION_TOLERANCE {
            return Err(ModalError::NotMassNormalised { norm });
        }
        let pinned = (0..n)
            .max_by(|&a, &b| y[a].abs().total_cmp(&y[b].abs()))
            .unwrap_or(0);
        let mut entries = Vec::with_capacity(k.val().len() + m.val().len() + 1);
        for (a, scale) in [(k, 1.0), (m, -lambda)] {
            for j in (0..n).filter(|&j| j != pinned) {
                let rows = a.symbolic().row_idx_of_col_raw(j);
                for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
                    if i != pinned {
                        entries.push(Triplet::new(i, j, scale * v));
                    }
                }
            }
        }
        entries.push(Triplet::new(pinned, pinned, 1.0));
        let singular = ModalError::PinnedMatrixSingular { lambda, pinned };
        let a =
            SparseColMat::try_new_from_triplets(n, n, &entries).map_err(|_| singular.clone())?;
        let symbolic = SymbolicLu::try_new(a.symbolic()).map_err(|_| singular.clone())?;
        let lu = Lu::try_new_with_symbolic(symbolic, a.as_ref()).map_err(|_| singular)?;
        Ok(NelsonMode {
            lambda,
            y: y.to_vec(),
            my,
            pinned,
            lu,
        })
    }

    /// The eigenvalue lambda_s.
    pub fn value(&self) -> f64 {
        self.lambda
    }

    /// The pinned DOF (largest |y_s|).
    pub fn pinned(&self) -> usize {
        self.pinned
    }

    /// d lambda_s and d y_s for the derivative matrices `dk`, `dm` of one parameter (indices
    /// below N); two sparse triangular solves.
    pub fn derivative(
        &self,
        dk: &SparseSym,
        dm: &SparseSym,
    ) -> Result<EigenDerivative, ModalError> {
        let n = self.y.len();
        for &(i, j, _) in dk.entries().iter().chain(dm.entries()) {
            if i.max(j) >= n {
                return Err(ModalError::VectorLength {
                    len: i.max(j) + 1,
                    dofs: n,
                });
            }
        }
        let (mut dky, mut dmy) = (vec![0.0; n], vec![0.0; n]);
        dk.apply(&self.y, &mut dky);
        dm.apply(&self.y, &mut dmy);
        let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
        let y_dm_y = dot(&self.y, &dmy);
        let value = dot(&self.y, &dky) - self.lambda * y_dm_y;
        let mut v: Vec<f64> = (0..n)
            .map(|i| -(dky[i] - self.lambda * dmy[i]) + value * self.my[i])
            .collect();
        v[self.pinned] = 0.0;
        self.lu
            .solve_in_place(faer::MatMut::from_column_major_slice_mut(&mut v, n, 1));
        if !v.iter().all(|x| x.is_finite()) {
            return Err(ModalError::PinnedMatrixSingular {
                lambda: self.lambda,
                pinned: self.pinned,
            });
        }
        let c = -dot(&self.my, &v) - 0.5 * y_dm_y;
        let vector = v.iter().zip(&self.y).map(|(vi, yi)| vi + c * yi).collect();
        Ok(EigenDerivative { value, vector })
    }
}

#[cfg(test)]
mod tests {
    //! Against central differences of eigen-solutions of the perturbed model: the dense solve
    //! of the paper's model (38 DOFs) and the sparse solve of the chain refined to 2 x 150
    //! elements (604 DOFs, above the dense threshold), which share no code with Nelson's
    //! method.
    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::fixtures::{free_two_bars as chain, k2_and_point_mass};
    use crate::structure::{Matrices, Structure};

    /// Checks modes `modes` of `structure` for k2 of the joint and a point mass of 0.3 kg on
    /// the joint's first w DOF; `tol_value`, `tol_vector` relative to the derivative's size.
    fn check(structure: &Structure, modes: &[usize], tol_value: f64, tol_vector: f64) {
        let count = modes.iter().max().unwrap() + 1;
        let k2 = &structure.identified()[1];
        let (dk2, point_mass) = k2_and_point_mass(structure);
        let base = structure.assemble();
        let with = |dk: &SparseSym, dm: &SparseSym, p: f64| {
            let mats: Matrices = base.plus(&[(dk, dm, p)]);
            ModalSolution::lowest_of(&mats, count).unwrap()
        };
        let zero = SparseSym::zero();
        let p0 = 0.3;
        for (dk, dm, h, at) in [
            (&dk2, &zero, 1e-3 * k2.value, 0.0),
            (&zero, &point_mass, 1e-3 * p0, p0),
        ] {
            let nominal = with(dk, dm, at);
            let (plus, minus) = (with(dk, dm, at + h), with(dk, dm, at - h));
            let mats = base.plus(&[(dk, dm, at)]);
            for &s in modes {
                let y = nominal.vectors().col(s).iter().copied().collect::<Vec<_>>();
                let mode =
                    NelsonMode::new(mats.k.as_faer(), mats.m.as_faer(), nominal.values()[s], &y)
                        .unwrap();
                let d = mode.derivative(dk, dm).unwrap();
                let fd = (plus.values()[s] - minus.values()[s]) / (2.0 * h);
                assert!(
                    (d.value - fd).abs() < tol_value * d.value.abs(),
                    "mode {s}: d lambda {} vs {fd}",
                    d.value
                );
                let scale = d.vector.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
                for (i, dyi) in d.vector.iter().enumerate() {
                    let fd = (plus.vectors()[(i, s)] - minus.vectors()[(i, s)]) / (2.0 * h);
                    assert!(
                        (dyi - fd).abs() < tol_vector * scale,
                        "mode {s}, dof {i}: dy {dyi} vs {fd}"
                    );
                }
            }
        }
    }

    #[test]
    fn derivatives_match_central_differences_dense_model() {
        // Central differences at 1e-3 relative steps: truncation error about 1e-6 relative.
        check(&chain(7), &[2, 3, 5], 1e-5, 1e-5);
    }

    #[test]
    fn derivatives_match_central_differences_sparse_model() {
        check(&chain(150), &[2, 3, 6], 1e-6, 1e-5);
    }

    #[test]
    fn a_vector_not_mass_normalised_is_refused() {
        let mats = chain(7).assemble();
        let sol = ModalSolution::solve(&mats).unwrap();
        let y: Vec<f64> = sol.vectors().col(2).iter().map(|v| 2.0 * v).collect();
        let err = NelsonMode::new(mats.k.as_faer(), mats.m.as_faer(), sol.values()[2], &y);
        assert!(matches!(err, Err(ModalError::NotMassNormalised { .. })));
    }
}

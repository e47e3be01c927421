//! Eigenpair derivatives of the lowest modes of a large model from the Cholesky factor of
//! K - sigma M that the eigensolver uses, deflated by the computed pairs: no factor of an
//! indefinite matrix (Nelson's LU of K - lambda_s M, [`super::nelson`], fills far more than
//! the Cholesky factor on a 3D solid), one factor for every mode and parameter.
//!
//! For a simple eigenvalue lambda_s with M-normalised vector y_s, a parameter's derivative
//! matrices dK, dM and g = (dK - lambda_s dM) y_s, the exact derivatives are
//!
//! ```text
//!   d lambda_s = y_s^T g
//!   d y_s      = sum_{t != s} y_t (y_t^T g) / (lambda_s - lambda_t) - 1/2 y_s (y_s^T dM y_s)
//! ```
//!
//! over all N pairs. The sum splits over the computed pairs T (the lowest ones, so every
//! eigenvalue below lambda_s among them) and the rest. The rest, r, is the solution of
//!
//! ```text
//!   (K - lambda_s M) r = -(g - M Y_T Y_T^T g),   Y_T^T M r = 0,
//! ```
//!
//! on which K - lambda_s M is positive definite: its eigenvalues there are lambda_t -
//! lambda_s > 0, t outside T. r comes from conjugate gradients projected on that subspace
//! (P = I - Y_T Y_T^T M), preconditioned by P (K - sigma M)^-1 P^T: the preconditioned
//! eigenvalues (lambda_t - lambda_s) / (lambda_t - sigma) lie in (0, 1) and crowd at 1 for the
//! high modes, so few iterations are needed unless the first pair above T is close to
//! lambda_s. Every mode and parameter asked for iterates together, their solves one block.

use std::sync::Arc;

use faer::linalg::matmul::matmul;
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, Par};

use super::nelson::EigenDerivative;
use super::refine::mul_columns;
use super::shift::factor_shifted;
use super::sparse_llt::SparseLlt;
use super::{ModalError, ModalSolution, sparse_mul};
use crate::structure::SparseSym;

/// The conjugate gradients stop when the preconditioned residual norm has fallen by this
/// factor.
pub const TOLERANCE: f64 = 1e-11;

/// Largest number of conjugate-gradient iterations of one [`DeflatedModes::derivatives`].
pub const MAX_ITERATIONS: usize = 300;

/// Two eigenvalues closer than this, relative to the larger, are one repeated eigenvalue:
/// the derivative of its vectors is not defined.
pub const SIMPLE_GAP: f64 = 1e-10;

/// The derivative of an eigenpair read through linear functionals: d lambda, and c^T d y for
/// every functional c asked for.
pub type Reading = (f64, Vec<f64>);

/// Of every column (mode s, parameter j): Y_T^T g (its row s: d lambda_s), the right-hand side
/// b = -(g - M Y_T Y_T^T g) of the rest, and y_s^T dM y_s.
struct Projected {
    coefficients: Mat<f64>,
    b: Mat<f64>,
    y_dm_y: Vec<f64>,
}

/// The factor of K - sigma M and the computed pairs, ready for derivatives of any of them.
pub struct DeflatedModes<'a> {
    k: SparseColMatRef<'a, usize, f64>,
    m: SparseColMatRef<'a, usize, f64>,
    modal: &'a ModalSolution,
    /// M Y_T.
    my: Mat<f64>,
    llt: Arc<SparseLlt>,
}

impl<'a> DeflatedModes<'a> {
    /// The pairs `modal` (the lowest ones) of (K, M), both triangles stored: one Cholesky
    /// factorisation of K - sigma M at the eigensolver's default shift.
    pub fn new(
        k: SparseColMatRef<'a, usize, f64>,
        m: SparseColMatRef<'a, usize, f64>,
        modal: &'a ModalSolution,
    ) -> Result<Self, ModalError> {
        let (_, llt) = factor_shifted(k, m, None)?;
        Self::sharing(k, m, modal, Arc::new(llt))
    }

    /// As [`DeflatedModes::new`] with the factor `llt` of another model of the same DOFs as
    /// the preconditioner (its K' minus sigma M', positive definite): the derivatives are those
    /// of (K, M) all the same, in more iterations the more the two models differ. For models
    /// that differ in a joint only (a mode solved at its own frequency), no factorisation.
    pub fn sharing(
        k: SparseColMatRef<'a, usize, f64>,
        m: SparseColMatRef<'a, usize, f64>,
        modal: &'a ModalSolution,
        llt: Arc<SparseLlt>,
    ) -> Result<Self, ModalError> {
        let n = k.nrows();
        if k.ncols() != n || m.nrows() != n || m.ncols() != n {
            return Err(ModalError::ShapeMismatch {
                k: (k.nrows(), k.ncols()),
                m: (m.nrows(), m.ncols()),
            });
        }
        if modal.dof_count() != n || llt.dof_count() != n {
            return Err(ModalError::VectorLength {
                len: if modal.dof_count() != n {
                    modal.dof_count()
                } else {
                    llt.dof_count()
                },
                dofs: n,
            });
        }
        let y = modal.vectors();
        let mut my = Mat::zeros(n, modal.len());
        for t in 0..modal.len() {
            sparse_mul(m, y.col_as_slice(t), my.col_as_slice_mut(t));
        }
        Ok(DeflatedModes {
            k,
            m,
            modal,
            my,
            llt,
        })
    }

    /// The factor, to share with [`DeflatedModes::sharing`].
    pub fn factor(&self) -> Arc<SparseLlt> {
        Arc::clone(&self.llt)
    }

    /// The derivatives of the pairs `modes` (indices into the computed pairs), each for every
    /// parameter's (dK, dM) in `params` (indices below N): `[mode][parameter]`. All of them
    /// iterate together, their solves in blocks.
    pub fn derivatives(
        &self,
        modes: &[usize],
        params: &[(&SparseSym, &SparseSym)],
    ) -> Result<Vec<Vec<EigenDerivative>>, ModalError> {
        self.check(modes, params)?;
        let (lambda, y) = (self.modal.values(), self.modal.vectors());
        let p = params.len();
        let columns = mode_parameter_columns(modes, p);
        let Projected {
            coefficients,
            b,
            y_dm_y,
        } = self.projected(&columns, params)?;
        let mut vectors = self.rest(&columns, b)?;
        // d y_s = Y_T a + r.
        let a = computed_share(&columns, lambda, &coefficients, &y_dm_y);
        matmul(
            vectors.as_mut(),
            Accum::Add,
            y.as_ref(),
            a.as_ref(),
            1.0,
            Par::Seq,
        );
        let derivative = |c: usize| EigenDerivative {
            value: coefficients[(columns[c].0, c)],
            vector: vectors.col_as_slice(c).to_vec(),
        };
        Ok((0..modes.len())
            .map(|k| (k * p..(k + 1) * p).map(derivative).collect())
            .collect())
    }

    /// The derivatives of the pairs `modes`, each for every parameter in `params`, read through
    /// linear functionals rather than whole: for mode `modes[k]`, `reads[k]` lists the nonzero
    /// terms (DOF, coefficient) of every c whose c^T d y_s is wanted. `[mode][parameter]`:
    /// (d lambda_s, c^T d y_s for every c).
    ///
    /// The adjoint of [`DeflatedModes::derivatives`]: the rest r of d y_s is G b with
    /// G = sum_{t outside T} y_t y_t^T / (lambda_t - lambda_s) symmetric, so c^T r = z^T b with
    /// z = G c, the solution of the same projected system for the right-hand side
    /// c - M Y_T Y_T^T c. One solve per functional instead of one per parameter: fewer where
    /// the sensors of a mode are fewer than the parameters.
    pub fn readings(
        &self,
        modes: &[usize],
        params: &[(&SparseSym, &SparseSym)],
        reads: &[Vec<&[(usize, f64)]>],
    ) -> Result<Vec<Vec<Reading>>, ModalError> {
        self.check(modes, params)?;
        let (lambda, y) = (self.modal.values(), self.modal.vectors());
        let (n, p) = (y.nrows(), params.len());
        let columns = mode_parameter_columns(modes, p);
        let Projected {
            coefficients,
            b,
            y_dm_y,
        } = self.projected(&columns, params)?;
        // The functionals as columns, (mode, functional) each.
        let adjoint: Vec<(usize, usize)> = modes
            .iter()
            .zip(reads)
            .flat_map(|(&s, r)| (0..r.len()).map(move |i| (s, i)))
            .collect();
        let mut c = Mat::<f64>::zeros(n, adjoint.len());
        let terms = reads.iter().flatten();
        for (col, t) in terms.enumerate() {
            for &(d, v) in t.iter() {
                if d >= n {
                    return Err(ModalError::VectorLength {
                        len: d + 1,
                        dofs: n,
                    });
                }
                c[(d, col)] += v;
            }
        }
        // Y_T^T c: the computed pairs' share, and c - M Y_T Y_T^T c.
        let mut yc = Mat::zeros(self.modal.len(), adjoint.len());
        matmul(
            yc.as_mut(),
            Accum::Replace,
            y.transpose(),
            c.as_ref(),
            1.0,
            Par::Seq,
        );
        matmul(
            c.as_mut(),
            Accum::Add,
            self.my.as_ref(),
            yc.as_ref(),
            -1.0,
            Par::Seq,
        );
        let z = self.rest(&adjoint, c)?;
        // c^T d y_s = (Y_T^T c)^T a + z^T b, for every functional and column.
        let a = computed_share(&columns, lambda, &coefficients, &y_dm_y);
        let mut read = Mat::zeros(adjoint.len(), columns.len());
        matmul(
            read.as_mut(),
            Accum::Replace,
            yc.transpose(),
            a.as_ref(),
            1.0,
            Par::Seq,
        );
        matmul(
            read.as_mut(),
            Accum::Add,
            z.transpose(),
            b.as_ref(),
            1.0,
            Par::Seq,
        );
        let mut first = 0;
        let mut out = Vec::with_capacity(modes.len());
        for (k, (&s, r)) in modes.iter().zip(reads).enumerate() {
            let of_parameter = |col: usize| {
                let values = (first..first + r.len()).map(|f| read[(f, col)]).collect();
                (coefficients[(s, col)], values)
            };
            out.push((k * p..(k + 1) * p).map(of_parameter).collect());
            first += r.len();
        }
        Ok(out)
    }

    /// [`Projected`] of every column (mode s, parameter j).
    fn projected(
        &self,
        columns: &[(usize, usize)],
        params: &[(&SparseSym, &SparseSym)],
    ) -> Result<Projected, ModalError> {
        let (lambda, y) = (self.modal.values(), self.modal.vectors());
        let (g, y_dm_y) = forcing(y, lambda, columns, params);
        if !g.col_iter().all(|c| c.iter().all(|v| v.is_finite())) {
            return Err(ModalError::NonFinite);
        }
        let mut coefficients = Mat::zeros(self.modal.len(), columns.len());
        matmul(
            coefficients.as_mut(),
            Accum::Replace,
            y.transpose(),
            g.as_ref(),
            1.0,
            Par::Seq,
        );
        let mut b = g;
        matmul(
            b.as_mut(),
            Accum::Add,
            self.my.as_ref(),
            coefficients.as_ref(),
            -1.0,
            Par::Seq,
        );
        b.col_iter_mut()
            .for_each(|c| c.iter_mut().for_each(|v| *v = -*v));
        Ok(Projected {
            coefficients,
            b,
            y_dm_y,
        })
    }

    /// The modes computed and simple, the parameters' indices below N.
    fn check(
        &self,
        modes: &[usize],
        params: &[(&SparseSym, &SparseSym)],
    ) -> Result<(), ModalError> {
        let (n, count) = (self.modal.dof_count(), self.modal.len());
        let entries = params
            .iter()
            .flat_map(|(dk, dm)| dk.entries().iter().chain(dm.entries()));
        if let Some(&(i, j, _)) = entries.clone().find(|e| e.0.max(e.1) >= n) {
            return Err(ModalError::VectorLength {
                len: i.max(j) + 1,
                dofs: n,
            });
        }
        let lambda = self.modal.values();
        for &s in modes {
            if s >= count {
                return Err(ModalError::CountOutOfRange {
                    count: s + 1,
                    dofs: count,
                });
            }
            let ls = lambda[s];
            if let Some(t) = (0..count).find(|&t| {
                t != s && (lambda[t] - ls).abs() <= SIMPLE_GAP * lambda[t].abs().max(ls.abs())
            }) {
                return Err(ModalError::RepeatedEigenvalue {
                    lambda: ls,
                    other: lambda[t],
                });
            }
        }
        Ok(())
    }

    /// The solution r of (K - lambda_s M) r = b, Y_T^T M r = 0, for every column of `b`
    /// (each in the range of P^T; column c of mode `columns[c].0`), by projected
    /// preconditioned conjugate gradients.
    fn rest(&self, columns: &[(usize, usize)], b: Mat<f64>) -> Result<Mat<f64>, ModalError> {
        let (n, p) = (b.nrows(), b.ncols());
        let shift: Vec<f64> = columns.iter().map(|c| self.modal.values()[c.0]).collect();
        let mut x = Mat::<f64>::zeros(n, p);
        let mut residual = b;
        let mut direction = self.preconditioned(&residual);
        let mut rz: Vec<f64> = (0..p).map(|c| col_dot(&residual, &direction, c)).collect();
        let start: Vec<f64> = rz.clone();
        let mut done: Vec<bool> = rz.iter().map(|&v| v <= 0.0).collect();
        for _ in 0..MAX_ITERATIONS {
            if done.iter().all(|&d| d) {
                return Ok(x);
            }
            // Every column's product, the converged ones too: blocks of four columns on
            // rayon's threads.
            let (kd, _) = mul_columns(self.k, &direction, false);
            let (md, _) = mul_columns(self.m, &direction, false);
            for c in (0..p).filter(|&c| !done[c]) {
                let d = direction.col_as_slice(c);
                let q: Vec<f64> = (kd.col_as_slice(c).iter().zip(md.col_as_slice(c)))
                    .map(|(k, m)| k - shift[c] * m)
                    .collect();
                let curvature = dot(d, &q);
                if curvature.is_nan() || curvature <= 0.0 {
                    return Err(ModalError::PairMissing {
                        mode: columns[c].0 + 1,
                    });
                }
                let alpha = rz[c] / curvature;
                for (xi, di) in x.col_as_slice_mut(c).iter_mut().zip(d) {
                    *xi += alpha * di;
                }
                for (ri, qi) in residual.col_as_slice_mut(c).iter_mut().zip(&q) {
                    *ri -= alpha * qi;
                }
            }
            let z = self.preconditioned(&residual);
            for c in 0..p {
                if done[c] {
                    continue;
                }
                let rz_new = col_dot(&residual, &z, c);
                if rz_new <= TOLERANCE * TOLERANCE * start[c] {
                    done[c] = true;
                    continue;
                }
                let beta = rz_new / rz[c];
                rz[c] = rz_new;
                for (di, zi) in direction
                    .col_as_slice_mut(c)
                    .iter_mut()
                    .zip(z.col_as_slice(c))
                {
                    *di = zi + beta * *di;
                }
            }
        }
        let (c, worst) = (0..p)
            .filter(|&c| !done[c])
            .map(|c| (c, (rz[c] / start[c]).sqrt()))
            .fold((0, 0.0), |a, b| if b.1 > a.1 { b } else { a });
        Err(ModalError::DerivativeNotConverged {
            mode: columns[c].0 + 1,
            iterations: MAX_ITERATIONS,
            reduction: worst,
        })
    }

    /// P (K - sigma M)^-1 r for every column r: the factor's solve, then Y_T's components
    /// (in the M inner product) removed.
    fn preconditioned(&self, r: &Mat<f64>) -> Mat<f64> {
        let mut z = r.clone();
        self.llt.solve_columns_in_place(z.as_mut());
        let mut along = Mat::zeros(self.modal.len(), z.ncols());
        matmul(
            along.as_mut(),
            Accum::Replace,
            self.my.transpose(),
            z.as_ref(),
            1.0,
            Par::Seq,
        );
        matmul(
            z.as_mut(),
            Accum::Add,
            self.modal.vectors().as_ref(),
            along.as_ref(),
            -1.0,
            Par::Seq,
        );
        z
    }
}

/// The coefficients a of d y_s on the computed pairs Y_T, of every column (mode s, parameter):
/// (y_t^T g) / (lambda_s - lambda_t) for t != s, -1/2 y_s^T dM y_s for t = s (module docs).
fn computed_share(
    columns: &[(usize, usize)],
    lambda: &[f64],
    coefficients: &Mat<f64>,
    y_dm_y: &[f64],
) -> Mat<f64> {
    Mat::from_fn(coefficients.nrows(), columns.len(), |t, c| {
        let s = columns[c].0;
        if t == s {
            -0.5 * y_dm_y[c]
        } else {
            coefficients[(t, c)] / (lambda[s] - lambda[t])
        }
    })
}

/// The columns (mode, parameter) of every mode of `modes` for each of `p` parameters.
fn mode_parameter_columns(modes: &[usize], p: usize) -> Vec<(usize, usize)> {
    modes
        .iter()
        .flat_map(|&s| (0..p).map(move |j| (s, j)))
        .collect()
}

/// g = (dK - lambda_s dM) y_s of every column (mode s, parameter j) and y_s^T dM y_s.
fn forcing(
    y: &Mat<f64>,
    lambda: &[f64],
    columns: &[(usize, usize)],
    params: &[(&SparseSym, &SparseSym)],
) -> (Mat<f64>, Vec<f64>) {
    let n = y.nrows();
    let mut g = Mat::zeros(n, columns.len());
    let mut y_dm_y = vec![0.0; columns.len()];
    let (mut dky, mut dmy) = (vec![0.0; n], vec![0.0; n]);
    for (c, &(s, j)) in columns.iter().enumerate() {
        let (dk, dm) = params[j];
        let ys = y.col_as_slice(s);
        dky.fill(0.0);
        dmy.fill(0.0);
        dk.apply(ys, &mut dky);
        dm.apply(ys, &mut dmy);
        y_dm_y[c] = dot(ys, &dmy);
        for ((gi, k), m) in g.col_as_slice_mut(c).iter_mut().zip(&dky).zip(&dmy) {
            *gi = k - lambda[s] * m;
        }
    }
    (g, y_dm_y)
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

fn col_dot(a: &Mat<f64>, b: &Mat<f64>, c: usize) -> f64 {
    a.col(c)
        .iter()
        .zip(b.col(c).iter())
        .map(|(x, y)| x * y)
        .sum()
}

#[cfg(test)]
mod tests {
    //! Against three computations that share no code with the deflated conjugate gradients:
    //! central differences of the sparse eigensolution of the perturbed model, the modal
    //! expansion over every pair of the dense solution
    //! ([`crate::diagnose::sensitivity::eigen_derivative`]), and Nelson's method (an LU of
    //! K - lambda M with a DOF pinned).
    use super::*;
    use crate::diagnose::sensitivity::eigen_derivative;
    use crate::modal::nelson::NelsonMode;
    use crate::model::fixtures::{free_two_bars as chain, k2_and_point_mass as params};
    use crate::structure::Matrices;

    fn largest(v: &[f64]) -> f64 {
        v.iter().fold(0.0_f64, |a, b| a.max(b.abs()))
    }

    /// The 604-DOF chain (sparse solution, 12 pairs, two rigid-body): central differences at
    /// 1e-3 relative steps, truncation error about 1e-6 relative on the modes checked (on mode
    /// 9 the point mass's is 8e-6: the comparison with Nelson's method below covers it).
    #[test]
    fn derivatives_match_central_differences() {
        let structure = chain(150);
        let (dk2, point_mass) = params(&structure);
        let zero = SparseSym::zero();
        let base = structure.assemble();
        let count = 12;
        let k2 = structure.identified()[1].value;
        for (dk, dm, h, at) in [
            (&dk2, &zero, 1e-3 * k2, 0.0),
            (&zero, &point_mass, 3e-4, 0.3),
        ] {
            let with = |p: f64| -> (Matrices, ModalSolution) {
                let mats = base.plus(&[(dk, dm, p)]);
                let sol = ModalSolution::lowest_of(&mats, count).unwrap();
                (mats, sol)
            };
            let (mats, nominal) = with(at);
            let (plus, minus) = (with(at + h).1, with(at - h).1);
            let deflated =
                DeflatedModes::new(mats.k.as_faer(), mats.m.as_faer(), &nominal).unwrap();
            for s in [2, 3, 6] {
                let d = &deflated.derivatives(&[s], &[(dk, dm)]).unwrap()[0][0];
                let fd = (plus.values()[s] - minus.values()[s]) / (2.0 * h);
                assert!(
                    (d.value - fd).abs() < 1e-6 * d.value.abs(),
                    "mode {s}: {} vs {fd}",
                    d.value
                );
                let scale = largest(&d.vector);
                for (i, dyi) in d.vector.iter().enumerate() {
                    let fd = (plus.vectors()[(i, s)] - minus.vectors()[(i, s)]) / (2.0 * h);
                    assert!(
                        (dyi - fd).abs() < 1e-5 * scale,
                        "mode {s}, dof {i}: {dyi} vs {fd}"
                    );
                }
            }
        }
    }

    /// The 64-DOF chain's matrices, its dense solution (all 64 pairs), the lowest 8 of them,
    /// and the derivative matrices of k2 and of the point mass.
    fn expansion_case() -> (Matrices, ModalSolution, ModalSolution, SparseSym, SparseSym) {
        let structure = chain(15);
        let (dk2, point_mass) = params(&structure);
        let mats = structure.assemble();
        let dense = ModalSolution::solve(&mats).unwrap();
        let lowest = ModalSolution {
            values: dense.values()[..8].to_vec(),
            vectors: dense.vectors().subcols(0, 8).to_owned(),
            reduced: None,
            factor: None,
        };
        (mats, dense, lowest, dk2, point_mass)
    }

    /// The 64-DOF chain: the lowest 8 pairs of the dense solution against the expansion over
    /// all 64 of them, both parameters in one call. The same pairs on both sides, so that
    /// only the method differs (the dense pairs themselves differ from the sparse solution's
    /// by about 1e-9 relative at this size).
    #[test]
    fn derivatives_match_the_full_modal_expansion() {
        let (mats, dense, lowest, dk2, point_mass) = expansion_case();
        let deflated = DeflatedModes::new(mats.k.as_faer(), mats.m.as_faer(), &lowest).unwrap();
        let zero = SparseSym::zero();
        let both = [(&dk2, &zero), (&zero, &point_mass)];
        for s in 2..8 {
            for (d, (dk, dm)) in deflated.derivatives(&[s], &both).unwrap()[0]
                .iter()
                .zip(both)
            {
                let (value, vector) = eigen_derivative(&dense, s, dk, dm);
                assert!(
                    (d.value - value).abs() < 1e-12 * value.abs(),
                    "mode {s}: {} vs {value}",
                    d.value
                );
                let scale = largest(&vector);
                for (i, (a, b)) in d.vector.iter().zip(&vector).enumerate() {
                    assert!(
                        (a - b).abs() < 1e-9 * scale,
                        "mode {s}, dof {i}: {a} vs {b}"
                    );
                }
            }
        }
    }

    /// The adjoint readings against the modal expansion over all 64 pairs of the dense
    /// solution, read through the same functionals: a single DOF, a two-term interpolation,
    /// and a functional over many DOFs; several modes in one call, each with its own number
    /// of functionals (fewer than, as many as and more than the parameters).
    #[test]
    fn readings_match_the_full_modal_expansion_read_through_the_same_functionals() {
        let (mats, dense, lowest, dk2, point_mass) = expansion_case();
        let deflated = DeflatedModes::new(mats.k.as_faer(), mats.m.as_faer(), &lowest).unwrap();
        let zero = SparseSym::zero();
        let both = [(&dk2, &zero), (&zero, &point_mass)];
        let single: Vec<(usize, f64)> = vec![(7, 1.0)];
        let pair: Vec<(usize, f64)> = vec![(20, 0.3), (21, -0.05)];
        let wide: Vec<(usize, f64)> = (0..64)
            .step_by(3)
            .map(|d| (d, 1.0 / (1.0 + d as f64)))
            .collect();
        let modes = [2, 5, 7];
        let reads: Vec<Vec<&[(usize, f64)]>> = vec![
            vec![&single],
            vec![&pair, &wide],
            vec![&single, &pair, &wide],
        ];
        let got = deflated.readings(&modes, &both, &reads).unwrap();
        let read = |c: &[(usize, f64)], v: &[f64]| c.iter().map(|&(d, x)| x * v[d]).sum::<f64>();
        for ((&s, of_mode), r) in modes.iter().zip(&got).zip(&reads) {
            for ((value, readings), (dk, dm)) in of_mode.iter().zip(both) {
                let (expected, vector) = eigen_derivative(&dense, s, dk, dm);
                assert!((value - expected).abs() < 1e-12 * expected.abs());
                let scale = largest(&vector);
                assert_eq!(readings.len(), r.len());
                for (got, c) in readings.iter().zip(r) {
                    let want = read(c, &vector);
                    // The conjugate gradients stop at 1e-11 (measured: 2.2e-12).
                    assert!(
                        (got - want).abs() < 1e-10 * scale,
                        "mode {s}: {got} vs {want}"
                    );
                }
            }
        }
    }

    /// Against Nelson's method (one LU of K - lambda_s M with a DOF pinned, no other pair) on
    /// the 604-DOF chain with the point mass, up to the highest computed pair (11: the one
    /// whose conjugate gradients converge slowest, the next pair being unknown).
    #[test]
    fn derivatives_match_nelsons_method() {
        let structure = chain(150);
        let (dk2, point_mass) = params(&structure);
        let zero = SparseSym::zero();
        let mats = structure.assemble().plus(&[(&zero, &point_mass, 0.3)]);
        let sol = ModalSolution::lowest_of(&mats, 12).unwrap();
        let deflated = DeflatedModes::new(mats.k.as_faer(), mats.m.as_faer(), &sol).unwrap();
        let both = [(&dk2, &zero), (&zero, &point_mass)];
        for s in [2, 5, 9, 11] {
            let y: Vec<f64> = sol.vectors().col(s).iter().copied().collect();
            let nelson =
                NelsonMode::new(mats.k.as_faer(), mats.m.as_faer(), sol.values()[s], &y).unwrap();
            let ours = deflated.derivatives(&[s], &both).unwrap().remove(0);
            for (d, (dk, dm)) in ours.iter().zip(both) {
                let reference = nelson.derivative(dk, dm).unwrap();
                assert!(
                    (d.value - reference.value).abs() < 1e-12 * reference.value.abs(),
                    "mode {s}: {} vs {}",
                    d.value,
                    reference.value
                );
                let scale = largest(&reference.vector);
                for (i, (a, b)) in d.vector.iter().zip(&reference.vector).enumerate() {
                    assert!(
                        (a - b).abs() < 1e-6 * scale,
                        "mode {s}, dof {i}: {a} vs {b}"
                    );
                }
            }
        }
    }

    /// A solution with a pair left out below the mode is refused, as are a repeated
    /// eigenvalue and a mode index beyond the computed pairs.
    #[test]
    fn a_missing_pair_a_repeated_eigenvalue_and_a_mode_beyond_are_refused() {
        let structure = chain(150);
        let (dk2, _) = params(&structure);
        let zero = SparseSym::zero();
        let mats = structure.assemble();
        let full = ModalSolution::lowest_of(&mats, 8).unwrap();
        let keep = [0, 1, 2, 4, 5, 6, 7];
        let gapped = ModalSolution {
            values: keep.iter().map(|&t| full.values()[t]).collect(),
            vectors: Mat::from_fn(mats.size(), keep.len(), |i, j| full.vectors()[(i, keep[j])]),
            reduced: None,
            factor: None,
        };
        let deflated = DeflatedModes::new(mats.k.as_faer(), mats.m.as_faer(), &gapped).unwrap();
        // Pair 3 (index 3 of the full solution) is missing below the pair at index 4.
        assert_eq!(
            deflated.derivatives(&[4], &[(&dk2, &zero)]).err(),
            Some(ModalError::PairMissing { mode: 5 })
        );
        assert!(matches!(
            deflated.derivatives(&[7], &[(&dk2, &zero)]),
            Err(ModalError::CountOutOfRange { .. })
        ));
        let mut repeated = full.clone();
        repeated.values[3] = repeated.values[4] * (1.0 + 1e-12);
        let deflated = DeflatedModes::new(mats.k.as_faer(), mats.m.as_faer(), &repeated).unwrap();
        assert!(matches!(
            deflated.derivatives(&[4], &[(&dk2, &zero)]),
            Err(ModalError::RepeatedEigenvalue { .. })
        ));
    }
}

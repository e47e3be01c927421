//! Eigenpair derivatives of a reduced solution: exact for the reduced model (V held fixed),
//! by the modal expansion over every pair of the r x r pencil, which is all of them:
//!
//! ```text
//!   h          = V^T (dK - lambda_s dM) x_s,   a_t = y_t^T h
//!   d lambda_s = a_s
//!   d y_s      = sum_{t != s} y_t a_t / (lambda_s - lambda_t) - 1/2 y_s (x_s^T dM x_s)
//!   d x_s      = V d y_s
//! ```
//! h costs one pass over the entries of dK and dM (they touch few DOFs), the lift one product
//! of N x r by r. They differ from the full model's derivatives by what V lacks of the
//! vector's derivative: the basis holds the static corrections of the wanted modes in every
//! direction the model moves in ([`super::basis`]), which is the part the lowest modes miss.

use faer::Mat;

use super::super::deflated::SIMPLE_GAP;
use super::super::{ModalError, ModalSolution};
use super::ReducedPairs;
use crate::structure::SparseSym;

/// d lambda_s and d x_s of pair `s` of `modal` (a reduced solution with `pairs`) for the
/// derivative matrices `dk`, `dm`; an error when lambda_s is repeated among the reduced pairs.
pub fn derivative(
    modal: &ModalSolution,
    pairs: &ReducedPairs,
    s: usize,
    dk: &SparseSym,
    dm: &SparseSym,
) -> Result<(f64, Vec<f64>), ModalError> {
    let basis = &pairs.reduced.basis;
    let (r, rr) = (basis.ncols(), pairs.vectors.ncols());
    let x = modal.vectors().col_as_slice(s);
    let lambda = pairs.values[s];
    let mut h = vec![0.0; r];
    let mut row = vec![0.0; r];
    let mut add = |i: usize, t: f64| {
        if t != 0.0 {
            basis.row_into(i, &mut row);
            for (hq, b) in h.iter_mut().zip(&row) {
                *hq += b * t;
            }
        }
    };
    for &(i, j, v) in dk.entries() {
        add(i, v * x[j]);
    }
    for &(i, j, v) in dm.entries() {
        add(i, -lambda * v * x[j]);
    }
    let y = &pairs.vectors;
    let a: Vec<f64> = (0..rr)
        .map(|t| (0..r).map(|q| y[(q, t)] * h[q]).sum())
        .collect();
    let mass = dm.form(x, x);
    let mut dy: Vec<f64> = (0..r).map(|q| -0.5 * mass * y[(q, s)]).collect();
    for t in (0..rr).filter(|&t| t != s) {
        let other = pairs.values[t];
        let gap = lambda - other;
        if gap.abs() <= SIMPLE_GAP * lambda.abs().max(other.abs()) {
            return Err(ModalError::RepeatedEigenvalue { lambda, other });
        }
        let c = a[t] / gap;
        for (q, d) in dy.iter_mut().enumerate() {
            *d += c * y[(q, t)];
        }
    }
    let dy = Mat::from_fn(r, 1, |q, _| dy[q]);
    let dx = basis.times(dy.as_ref());
    Ok((a[s], dx.col_as_slice(0).to_vec()))
}

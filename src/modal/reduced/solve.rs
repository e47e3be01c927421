//! One solve of a structure's eigenproblem on its reduced model: the projected matrices at the
//! structure's parameter values (and any extra terms, a candidate effect's contribution), the
//! small dense pencil, the pairs lifted to the N DOFs, and each lifted pair's residual in the
//! full model.
//!
//! The residual of pair j, x_j = V y_j, is
//!
//! ```text
//!   r_j = K x_j - lambda_j M x_j
//!       = (K_base V) y_j - lambda_j (M_base V) y_j + sum_t a_t (S_t - lambda_j T_t) x_j,
//! ```
//! the sum over the parameters (a_t = p_t, S_t = dK_t, T_t = dM_t) and the extra terms, which
//! touch few DOFs. It costs two products of N x r by r x count, about what the lift x = V y
//! costs, and is exact to rounding (the products are the full model's, in another order).
//! Its size is measured as e_j = |r_j^T d_j| / max(lambda_j, scale) with the correction
//! d_j = (K_0 - sigma M_0)^-1 r_j (the estimate of [`super::TOLERANCE`]), d_j kept for the
//! enrichment.

use std::sync::Arc;

use faer::Mat;

use super::super::pencil::dense_pencil;
use super::super::{ModalError, ModalSolution};
use super::ReducedPairs;
use crate::structure::columns::Columns;
use crate::structure::reduced::Reduced;
use crate::structure::{SparseSym, Structure};

/// A reduced solve: the lifted pairs and their residual vectors in the full model.
pub(super) struct Solved {
    /// The pairs, with [`ReducedPairs`] attached.
    pub modal: ModalSolution,
    /// (K_0 - sigma M_0)^-1 r_j of the pairs checked, from pair `first` on: the
    /// enrichment's vectors.
    pub correction: Mat<f64>,
    /// The first pair checked.
    pub first: usize,
}

/// The lowest `count` pairs of `structure` plus `extra` on `reduced` (module docs), the
/// error estimates of the elastic pairs among `checked` (all of them when none; the others'
/// left at 0).
pub(super) fn solve(
    reduced: &Arc<Reduced>,
    structure: &Structure,
    extra: &[(&SparseSym, &SparseSym, f64)],
    count: usize,
    checked: Option<std::ops::Range<usize>>,
) -> Result<Solved, ModalError> {
    let (k, m) = projected(reduced, structure, extra);
    let (values, mut vectors) = dense_pencil(&k, &m).ok_or(ModalError::NoConvergence)?;
    if !values.iter().all(|v| v.is_finite()) {
        return Err(ModalError::NonFinite);
    }
    let c = count.min(values.len());
    if c == 0 {
        return Err(ModalError::NoConvergence);
    }
    let mut x = reduced.basis.times(vectors.subcols(0, c));
    for j in 0..c {
        if largest_is_negative(x.col_as_slice(j)) {
            x.col_mut(j).iter_mut().for_each(|v| *v = -*v);
            vectors.col_mut(j).iter_mut().for_each(|v| *v = -*v);
        }
    }
    // The rigid-body pairs (below a thousandth of the first elastic eigenvalue) lie in the
    // basis whatever the parameters: their estimate is not solved for.
    let elastic = values[..c]
        .iter()
        .position(|&l| l > 1e-3 * reduced.scale)
        .unwrap_or(c);
    let wanted = checked.unwrap_or(0..c);
    let (first, last) = (wanted.start.max(elastic), wanted.end.min(c).max(elastic));
    let (first, last) = (first.min(last), last);
    let lambda = &values[first..last];
    let residual = residuals(reduced, structure, extra, &vectors, &x, first..last, lambda);
    let mut correction = residual.clone();
    // Released between the caller's check of the reduction and this solve: no estimate, and
    // the caller solves in full (NaN is never accepted).
    let checked = reduced.precondition.apply(correction.as_mut());
    let norms = (0..c)
        .map(|j| {
            if !(first..last).contains(&j) {
                return 0.0;
            }
            if !checked {
                return f64::NAN;
            }
            let k = j - first;
            let (r, d) = (residual.col_as_slice(k), correction.col_as_slice(k));
            let e: f64 = r.iter().zip(d).map(|(r, d)| r * d).sum();
            e.abs() / lambda[k].max(reduced.scale)
        })
        .collect();
    let pairs = ReducedPairs {
        reduced: Arc::clone(reduced),
        values: values.clone(),
        vectors,
        residuals: norms,
    };
    Ok(Solved {
        modal: ModalSolution::from_parts(values[..c].to_vec(), x, Some(Arc::new(pairs))),
        correction,
        first,
    })
}

/// V^T K V and V^T M V at the structure's parameter values, with the extra terms.
fn projected(
    reduced: &Reduced,
    structure: &Structure,
    extra: &[(&SparseSym, &SparseSym, f64)],
) -> (Mat<f64>, Mat<f64>) {
    let (mut k, mut m) = (reduced.k.clone(), reduced.m.clone());
    let r = k.nrows();
    for (p, (pk, pm)) in structure.parameters.iter().zip(&reduced.parameters) {
        for j in 0..r {
            for i in 0..r {
                k[(i, j)] += p.value * pk[(i, j)];
                m[(i, j)] += p.value * pm[(i, j)];
            }
        }
    }
    for (sk, sm, a) in extra {
        add_projection(&mut k, sk, &reduced.basis, *a);
        add_projection(&mut m, sm, &reduced.basis, *a);
    }
    (k, m)
}

/// target += a V^T S V, entry by entry of S.
fn add_projection(target: &mut Mat<f64>, s: &SparseSym, basis: &Columns, a: f64) {
    let r = basis.ncols();
    let (mut vi, mut vj) = (vec![0.0; r], vec![0.0; r]);
    for &(i, j, v) in s.entries() {
        basis.row_into(i, &mut vi);
        basis.row_into(j, &mut vj);
        for (q, &b) in vj.iter().enumerate() {
            let t = a * v * b;
            for (p, &u) in vi.iter().enumerate() {
                target[(p, q)] += u * t;
            }
        }
    }
}

/// The residual vectors of the module docs, of the lifted pairs `pairs` (eigenvalues
/// `lambda`).
fn residuals(
    reduced: &Reduced,
    structure: &Structure,
    extra: &[(&SparseSym, &SparseSym, f64)],
    vectors: &Mat<f64>,
    x: &Mat<f64>,
    pairs: std::ops::Range<usize>,
    lambda: &[f64],
) -> Mat<f64> {
    let c = pairs.len();
    let y = vectors.subcols(pairs.start, c);
    let mut residual = reduced.k_basis.times(y);
    let my = reduced.m_basis.times(y);
    for (j, &l) in lambda.iter().enumerate() {
        let (r, mx) = (residual.col_as_slice_mut(j), my.col_as_slice(j));
        r.iter_mut().zip(mx).for_each(|(r, m)| *r -= l * m);
    }
    let terms = structure
        .parameters
        .iter()
        .map(|p| (&p.stiffness, &p.mass, p.value))
        .chain(extra.iter().copied());
    for (sk, sm, a) in terms {
        for (j, &l) in lambda.iter().enumerate() {
            let xj = x.col_as_slice(pairs.start + j);
            let r = residual.col_as_slice_mut(j);
            for &(p, q, v) in sk.entries() {
                r[p] += a * v * xj[q];
            }
            for &(p, q, v) in sm.entries() {
                r[p] -= l * a * v * xj[q];
            }
        }
    }
    residual
}

/// Whether the component of largest magnitude (the first on a tie) is negative: the sign
/// convention of [`ModalSolution`].
fn largest_is_negative(v: &[f64]) -> bool {
    let mut best = 0;
    for (i, x) in v.iter().enumerate() {
        if x.abs() > v[best].abs() {
            best = i;
        }
    }
    v.get(best).is_some_and(|&x| x < 0.0)
}

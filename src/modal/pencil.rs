//! Eigenpairs of small dense symmetric problems: the standard problem scaled for faer's
//! solver ([`symmetric_eigen`]), a pencil (a, b) by the Cholesky factor of b
//! ([`cholesky_reduced`]: the dense modal solution, [`super::ModalSolution::solve_dense`],
//! and the Rayleigh-Ritz step of the sparse eigensolver's refinement, [`super::refine`]),
//! and, when b is not numerically positive definite (nearly dependent corrections), a pencil
//! on b's independent directions ([`dense_pencil`]): then it may give fewer pairs than its
//! order, which its callers must check.
//!
//! Layer 2 (eigensolution), like [`super`].

use faer::{Mat, MatRef, Side};

/// Below this fraction of the largest eigenvalue of b scaled to unit diagonal, a direction of
/// a basis whose Gram matrix b is not numerically positive definite is left out
/// ([`dense_pencil`]). The scaling takes the columns' lengths out, so that what is measured
/// is their dependence: a short column is not a dependent one.
pub const DEPENDENT: f64 = 1e-10;

/// Eigenpairs of the symmetric part of a small dense matrix, values ascending: scaled to unit
/// largest entry before faer's symmetric solver and the values scaled back (module docs of
/// [`super`]: without it the solver loses accuracy on entries of order 1e12). `None` when
/// the solver does not converge.
pub(crate) fn symmetric_eigen(a: &Mat<f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    let n = a.nrows();
    let scale = a.norm_max().max(f64::MIN_POSITIVE);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (a[(i, j)] + a[(j, i)]) / scale);
    let evd = c.self_adjoint_eigen(Side::Lower).ok()?;
    let values = (0..n).map(|i| evd.S()[i] * scale).collect();
    Some((values, evd.U().to_owned()))
}

/// Eigenpairs of the pencil (a, b) given L, the Cholesky factor of b: the standard problem
/// L^-1 a L^-T ([`symmetric_eigen`]), its vectors mapped back by L^-T (X^T b X = E). Values
/// ascending.
pub(crate) fn cholesky_reduced(a: &Mat<f64>, l: MatRef<'_, f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    // L^-1 a L^-T, using a = a^T: X = L^-1 a, then L^-1 X^T.
    let mut x = a.clone();
    l.solve_lower_triangular_in_place(x.as_mut());
    let mut c = x.transpose().to_owned();
    l.solve_lower_triangular_in_place(c.as_mut());
    let (values, mut vectors) = symmetric_eigen(&c)?;
    l.transpose()
        .solve_upper_triangular_in_place(vectors.as_mut());
    Some((values, vectors))
}

/// Eigenpairs of the small dense pencil (a, b), b symmetric positive semidefinite: values
/// ascending, vectors X with X^T b X = E ([`cholesky_reduced`]). When b has no Cholesky
/// factor (corrections that are nearly dependent), the pencil is solved on the independent
/// directions of b scaled to unit diagonal ([`DEPENDENT`]): as many pairs as b has such
/// directions then, fewer than the pencil's order. `None` when the symmetric solver fails or
/// b has no positive direction.
pub fn dense_pencil(a: &Mat<f64>, b: &Mat<f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    let n = a.nrows();
    let sym = |x: &Mat<f64>| Mat::from_fn(n, n, |i, j| 0.5 * (x[(i, j)] + x[(j, i)]));
    match sym(b).llt(Side::Lower) {
        Ok(llt) => cholesky_reduced(&sym(a), llt.L()),
        Err(_) => independent_pencil(&sym(a), &sym(b)),
    }
}

/// [`dense_pencil`] on the independent directions of b. Scaled to unit diagonal,
/// D b D = V S V^T with D = diag(b_ii^(-1/2)) (a column of zero length drops out), W =
/// D V_k S_k^(-1/2) over the eigenvalues s_k > [`DEPENDENT`] max s, then the standard problem
/// W^T a W, X = W X'.
///
/// Why the scaling: the columns of a refinement's basis differ in length by up to 1e7 (a
/// correction enters from an M-norm of [`super::refine::NOISE_FLOOR`]), so that b's own
/// eigenvalues mix length with dependence. Unscaled, one dependent pair of short corrections
/// took every correction out of the Rayleigh-Ritz (seen in `diagnose`'s fits of a chain with
/// a layered lap: corrections of M-norm 1e-7 to 1e-6, all left out whenever b had no
/// Cholesky factor).
fn independent_pencil(a: &Mat<f64>, b: &Mat<f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    let n = a.nrows();
    let d: Vec<f64> = (0..n)
        .map(|i| {
            let bii = b[(i, i)];
            if bii > 0.0 { 1.0 / bii.sqrt() } else { 0.0 }
        })
        .collect();
    let scaled = Mat::from_fn(n, n, |i, j| d[i] * b[(i, j)] * d[j]);
    let evd = scaled.self_adjoint_eigen(Side::Lower).ok()?;
    let largest = evd.S()[n - 1];
    if !largest.is_finite() || largest <= 0.0 {
        return None;
    }
    let kept: Vec<usize> = (0..n)
        .filter(|&i| evd.S()[i] > DEPENDENT * largest)
        .collect();
    let w = Mat::from_fn(n, kept.len(), |i, c| {
        d[i] * evd.U()[(i, kept[c])] / evd.S()[kept[c]].sqrt()
    });
    let (values, inner) = symmetric_eigen(&(w.transpose() * a * &w))?;
    Some((values, w * inner))
}

#[cfg(test)]
mod tests {
    use super::*;

    /// A basis [q1, q2, q3, q1 (1 + 1e-14)]: its Gram matrix b has no Cholesky factor. The
    /// pencil's pairs are those of the three independent columns, whose Gram matrices are
    /// diag(1, 2, 3) and I (analytic: the values 1, 2, 3 with vectors e_i), and the vectors
    /// it returns satisfy X^T b X = I.
    #[test]
    fn a_pencil_on_dependent_columns_keeps_the_independent_ones() {
        let t = 1.0 + 1e-14;
        // Columns of the basis in the coordinates of q1, q2, q3.
        let q = Mat::from_fn(3, 4, |i, j| match (i, j) {
            (0, 3) => t,
            (i, j) if i == j => 1.0,
            _ => 0.0,
        });
        let k = Mat::from_fn(3, 3, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let a = q.transpose() * &k * &q;
        let b = q.transpose() * &q;
        assert!(
            b.llt(Side::Lower).is_err(),
            "b should not be positive definite"
        );
        let (values, x) = dense_pencil(&a, &b).expect("the independent part is solved");
        assert_eq!(values.len(), 3);
        for (v, want) in values.iter().zip([1.0, 2.0, 3.0]) {
            assert!((v - want).abs() < 1e-12, "{values:?}");
        }
        let xbx = x.transpose() * &b * &x;
        let xax = x.transpose() * &a * &x;
        for i in 0..3 {
            for j in 0..3 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((xbx[(i, j)] - e).abs() < 1e-10, "X^T b X ({i},{j})");
                assert!(
                    (xax[(i, j)] - e * values[i]).abs() < 1e-10,
                    "X^T a X ({i},{j})"
                );
            }
        }
    }

    /// A refinement's basis: [q1, q2, s q3, s q4, q1 (1 + 1e-14)] with s = 1e-7, two
    /// corrections at the noise floor's length beside the pairs, and a dependent copy of q1
    /// so that b has no Cholesky factor. The short columns are independent: the pencil keeps
    /// them, and its pairs are those of q1 .. q4, diag(1, 2, 3, 4) and I (analytic). Before
    /// the columns were scaled to unit length, b's eigenvalues 1e-14 fell below 1e-10 times
    /// its largest (2) and only the pairs 1 and 2 came out.
    #[test]
    fn short_independent_columns_are_kept_beside_a_dependent_one() {
        let (s, t) = (1e-7, 1.0 + 1e-14);
        let q = Mat::from_fn(4, 5, |i, j| match (i, j) {
            (0, 4) => t,
            (i, j) if i == j && i < 2 => 1.0,
            (i, j) if i == j => s,
            _ => 0.0,
        });
        let k = Mat::from_fn(4, 4, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let (a, b) = (q.transpose() * &k * &q, q.transpose() * &q);
        assert!(b.llt(Side::Lower).is_err(), "b should not be definite");
        let (values, x) = dense_pencil(&a, &b).expect("the independent part is solved");
        assert_eq!(values.len(), 4, "{values:?}");
        for (v, want) in values.iter().zip([1.0, 2.0, 3.0, 4.0]) {
            assert!((v - want).abs() < 1e-8 * want, "{values:?}");
        }
        let xbx = x.transpose() * &b * &x;
        for i in 0..4 {
            for j in 0..4 {
                let e = if i == j { 1.0 } else { 0.0 };
                assert!((xbx[(i, j)] - e).abs() < 1e-8, "X^T b X ({i},{j})");
            }
        }
    }

    /// A column of zero length (a correction that vanished) is a dependent one, not a
    /// division by zero.
    #[test]
    fn a_zero_column_drops_out() {
        let q = Mat::from_fn(2, 3, |i, j| if i == j { 1.0 } else { 0.0 });
        let k = Mat::from_fn(2, 2, |i, j| if i == j { (i + 1) as f64 } else { 0.0 });
        let (a, b) = (q.transpose() * &k * &q, q.transpose() * &q);
        let (values, x) = dense_pencil(&a, &b).expect("the independent part is solved");
        assert_eq!(values.len(), 2);
        assert!((values[0] - 1.0).abs() < 1e-14 && (values[1] - 2.0).abs() < 1e-14);
        assert!(x.col_iter().all(|c| c.iter().all(|v| v.is_finite())));
    }
}

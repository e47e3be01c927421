//! Real linear least squares: Householder QR of the tall matrix, never the normal equations,
//! then an SVD of the small triangle so that a rank-deficient problem (two coincident poles of
//! a spurious model order in the extraction, a damped step whose unknowns the data do not see)
//! gives the minimum-norm answer instead of infinities; and the covariance (A^T A)^-1 of a
//! least-squares fit from the R of a QR. Used by the extraction (`crate::extract`) and by the
//! Levenberg-Marquardt steps of [`super::lm`].

use faer::dyn_stack::{MemBuffer, MemStack};
use faer::linalg::householder;
use faer::linalg::solvers::Qr;
use faer::{Conj, Mat, MatMut, MatRef, Par};

/// Singular values below this fraction of the largest are dropped (relative to the
/// column-equilibrated triangle).
pub const RCOND: f64 = 1e-12;

/// Applies Q^T of a Householder QR to `b` in place (b has as many rows as the factored matrix).
pub fn apply_qt(qr: &Qr<f64>, b: MatMut<'_, f64>) {
    let rows = b.nrows();
    let cols = b.ncols();
    let mut buffer =
        MemBuffer::new(
            householder::apply_block_householder_sequence_transpose_on_the_left_in_place_scratch::<
                f64,
            >(rows, qr.Q_coeff().nrows(), cols),
        );
    householder::apply_block_householder_sequence_transpose_on_the_left_in_place_with_conj(
        qr.Q_basis(),
        qr.Q_coeff(),
        Conj::No,
        b,
        Par::Seq,
        MemStack::new(&mut buffer),
    );
}

/// Applies Q of a Householder QR to `b` in place.
pub fn apply_q(qr: &Qr<f64>, b: MatMut<'_, f64>) {
    let rows = b.nrows();
    let cols = b.ncols();
    let mut buffer = MemBuffer::new(
        householder::apply_block_householder_sequence_on_the_left_in_place_scratch::<f64>(
            rows,
            qr.Q_coeff().nrows(),
            cols,
        ),
    );
    householder::apply_block_householder_sequence_on_the_left_in_place_with_conj(
        qr.Q_basis(),
        qr.Q_coeff(),
        Conj::No,
        b,
        Par::Seq,
        MemStack::new(&mut buffer),
    );
}

/// The upper triangle R (min(m, n) x n) of A = QR.
pub fn triangle(a: MatRef<'_, f64>) -> Mat<f64> {
    let qr = a.qr();
    let r = qr.thin_R();
    Mat::from_fn(
        r.nrows(),
        r.ncols(),
        |i, j| if i <= j { r[(i, j)] } else { 0.0 },
    )
}

/// Solves the square system R x = b (several right-hand sides; R upper-triangular where this
/// module uses it, any square matrix works) in the sense of least squares with the SVD of R:
/// singular values below [`RCOND`] times the largest are dropped. Returns x and the numerical
/// rank.
pub fn solve_triangle(r: MatRef<'_, f64>, b: MatRef<'_, f64>) -> (Mat<f64>, usize) {
    let n = r.ncols();
    let k = b.ncols();
    if n == 0 {
        return (Mat::zeros(0, k), 0);
    }
    let Ok(svd) = r.svd() else {
        return (Mat::zeros(n, k), 0);
    };
    let s = svd.S().column_vector();
    let smax = (0..s.nrows()).map(|i| s[i]).fold(0.0_f64, f64::max);
    let keep: Vec<usize> = (0..s.nrows())
        .filter(|&i| s[i] > RCOND * smax && s[i].is_finite())
        .collect();
    let u = svd.U();
    let v = svd.V();
    // x = V S^+ U^T b over the kept singular triplets.
    let mut x = Mat::<f64>::zeros(n, k);
    for col in 0..k {
        for &i in &keep {
            let mut c = 0.0;
            for row in 0..u.nrows() {
                c += u[(row, i)] * b[(row, col)];
            }
            c /= s[i];
            for row in 0..n {
                x[(row, col)] += v[(row, i)] * c;
            }
        }
    }
    (x, keep.len())
}

/// The solution of min ||A x - B|| for a tall real A (m >= n) and several right-hand sides.
/// The columns of A are scaled to unit norm before the QR (and x unscaled after), so that the
/// rank decision of [`solve_triangle`] does not depend on the units of the unknowns.
pub struct LeastSquares {
    /// The solution, n x k.
    pub x: Mat<f64>,
    /// The numerical rank of A.
    pub rank: usize,
    /// The Householder QR of the column-scaled A (for projections of other vectors).
    pub qr: Qr<f64>,
    /// The column scales: the QR is of A diag(scale).
    pub scale: Vec<f64>,
}

/// Solves min ||A x - B|| (see [`LeastSquares`]).
pub fn solve(a: MatRef<'_, f64>, b: MatRef<'_, f64>) -> LeastSquares {
    let (m, n) = (a.nrows(), a.ncols());
    let scale: Vec<f64> = (0..n)
        .map(|j| {
            let norm = (0..m).map(|i| a[(i, j)] * a[(i, j)]).sum::<f64>().sqrt();
            if norm > 0.0 && norm.is_finite() {
                1.0 / norm
            } else {
                1.0
            }
        })
        .collect();
    let scaled = Mat::from_fn(m, n, |i, j| a[(i, j)] * scale[j]);
    let qr = scaled.qr();
    let mut qtb = b.to_owned();
    apply_qt(&qr, qtb.as_mut());
    let size = m.min(n);
    let r = qr.thin_R();
    let r = Mat::from_fn(size, n, |i, j| if i <= j { r[(i, j)] } else { 0.0 });
    let (mut x, rank) = solve_triangle(r.as_ref(), qtb.as_ref().subrows(0, size));
    for j in 0..n {
        for c in 0..x.ncols() {
            x[(j, c)] *= scale[j];
        }
    }
    LeastSquares { x, rank, qr, scale }
}

/// The pseudo-inverse of a square matrix ([`solve_triangle`] of the identity), with its rank.
pub fn pseudo_inverse(a: MatRef<'_, f64>) -> (Mat<f64>, usize) {
    let n = a.nrows();
    solve_triangle(a, Mat::<f64>::identity(n, n).as_ref())
}

/// (A^T A)^-1 of a tall A (m >= n) as R^-1 R^-T, R from the QR of A (the normal equations,
/// whose condition is that of A squared, are never formed): the covariance of the unknowns of
/// a least-squares fit whose residuals have unit variance. None when A is wide or a column is,
/// to round-off, a combination of the columns before it (|R_jj| <= [`RCOND`] ||a_j||): the
/// data do not determine that unknown.
pub fn inverse_gram(a: MatRef<'_, f64>) -> Option<Mat<f64>> {
    let (m, n) = (a.nrows(), a.ncols());
    if m < n {
        return None;
    }
    let r = triangle(a);
    for j in 0..n {
        let norm = (0..m).map(|i| a[(i, j)] * a[(i, j)]).sum::<f64>().sqrt();
        let pivot = r[(j, j)].abs();
        if !(pivot > RCOND * norm && pivot.is_finite()) {
            return None;
        }
    }
    // R^-1 by back substitution, one column of the identity at a time.
    let mut inverse = Mat::<f64>::zeros(n, n);
    for col in 0..n {
        for i in (0..=col).rev() {
            let mut v = if i == col { 1.0 } else { 0.0 };
            for k in i + 1..=col {
                v -= r[(i, k)] * inverse[(k, col)];
            }
            inverse[(i, col)] = v / r[(i, i)];
        }
    }
    Some(&inverse * inverse.transpose())
}

#[cfg(test)]
mod tests {
    use super::*;

    /// (A^T A)^-1 of a small matrix against its inverse written out, and None for a column
    /// that repeats another.
    #[test]
    fn inverse_gram_is_the_inverse_of_the_normal_matrix() {
        // A^T A = [[3, 3], [3, 5]] (rows (1, 0), (1, 1), (1, 2)); its inverse is
        // [[5, -3], [-3, 3]] / 6.
        let a = Mat::from_fn(3, 2, |i, j| if j == 0 { 1.0 } else { i as f64 });
        let c = inverse_gram(a.as_ref()).unwrap();
        let expected = [[5.0 / 6.0, -0.5], [-0.5, 0.5]];
        for (i, row) in expected.iter().enumerate() {
            for (j, e) in row.iter().enumerate() {
                assert!((c[(i, j)] - e).abs() < 1e-14, "{i}, {j}: {}", c[(i, j)]);
            }
        }
        let dependent = Mat::from_fn(3, 2, |i, _| (i + 1) as f64);
        assert!(inverse_gram(dependent.as_ref()).is_none());
        let zero = Mat::from_fn(3, 2, |i, j| if j == 0 { 1.0 + i as f64 } else { 0.0 });
        assert!(inverse_gram(zero.as_ref()).is_none());
        assert!(inverse_gram(Mat::<f64>::zeros(1, 2).as_ref()).is_none());
    }

    #[test]
    fn recovers_an_exact_solution_whatever_the_column_units() {
        // Well-conditioned columns of very different units: the column scaling keeps every
        // component of x accurate.
        let a = Mat::from_fn(6, 3, |i, j| {
            ((i + 1) as f64 * (j + 1) as f64).sin() * 1e3_f64.powi(j as i32)
        });
        let x_true = [0.5, -2e-3, 3e-6]; // every column contributes alike to b
        let b = Mat::from_fn(6, 1, |i, _| {
            (0..3).map(|j| a[(i, j)] * x_true[j]).sum::<f64>()
        });
        let ls = solve(a.as_ref(), b.as_ref());
        assert_eq!(ls.rank, 3);
        for (j, t) in x_true.iter().enumerate() {
            assert!(
                (ls.x[(j, 0)] - t).abs() < 1e-13 * t.abs(),
                "{j}: {}",
                ls.x[(j, 0)]
            );
        }
    }

    #[test]
    fn rank_deficient_gives_the_minimum_norm_solution() {
        // Two identical columns: x0 + x1 = 2 is all the data say; minimum norm is (1, 1).
        let a = Mat::from_fn(4, 2, |i, _| (i + 1) as f64);
        let b = Mat::from_fn(4, 1, |i, _| 2.0 * (i + 1) as f64);
        let ls = solve(a.as_ref(), b.as_ref());
        assert_eq!(ls.rank, 1);
        assert!((ls.x[(0, 0)] - 1.0).abs() < 1e-12 && (ls.x[(1, 0)] - 1.0).abs() < 1e-12);
    }

    #[test]
    fn q_and_qt_are_inverse() {
        let a = Mat::from_fn(7, 3, |i, j| ((i * 3 + j) as f64).sin());
        let qr = a.qr();
        let b0 = Mat::from_fn(7, 2, |i, j| ((i + 2 * j) as f64).cos());
        let mut b = b0.clone();
        apply_qt(&qr, b.as_mut());
        apply_q(&qr, b.as_mut());
        for i in 0..7 {
            for j in 0..2 {
                assert!((b[(i, j)] - b0[(i, j)]).abs() < 1e-14);
            }
        }
    }
}

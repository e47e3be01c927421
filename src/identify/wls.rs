//! Weighted least squares of eq. (13), solved through a Householder QR of W S, never through
//! the normal equations (whose conditioning is the square of that of W S).
//!
//! The system is tiny (m x q with q = 2 per joint) and is solved millions of times by the
//! study engine, so this is a small in-place QR on caller-owned buffers: no allocation.

/// A column is declared dependent when less than this fraction of its norm lies outside the
/// span of the columns before it (|R_kk| <= RANK_TOLERANCE * ||a_k||).
pub const RANK_TOLERANCE: f64 = 1e-10;

/// The system is rank deficient: `rank` independent columns out of q.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct RankDeficient {
    /// Numerical rank.
    pub rank: usize,
}

/// Minimises ||a z - b|| for the column-major `m x q` matrix `a` (already weighted: a = W S,
/// b = W b). `a` and `b` are overwritten by the factorisation; the solution goes to `z`.
pub fn solve_in_place(
    a: &mut [f64],
    b: &mut [f64],
    m: usize,
    q: usize,
    z: &mut [f64],
) -> Result<(), RankDeficient> {
    debug_assert!(a.len() == m * q && b.len() == m && z.len() == q && m >= q);
    let mut rank = 0;
    for k in 0..q {
        let original = norm(&a[k * m..(k + 1) * m]);
        let (done, rest) = a.split_at_mut((k + 1) * m);
        let col = &mut done[k * m..];
        let sigma = norm(&col[k..]);
        if sigma > RANK_TOLERANCE * original {
            rank += 1;
        }
        if sigma == 0.0 {
            continue;
        }
        // v = x - alpha e1 with alpha = -sign(x0) ||x||: no cancellation, and
        // v^T v = 2 sigma (sigma + |x0|).
        let x0 = col[k];
        let alpha = if x0 > 0.0 { -sigma } else { sigma };
        col[k] -= alpha;
        let vtv = 2.0 * sigma * (sigma + x0.abs());
        let v = &col[k..];
        for j in 0..q - k - 1 {
            reflect(v, &mut rest[j * m + k..(j + 1) * m], vtv);
        }
        reflect(v, &mut b[k..], vtv);
        col[k] = alpha;
    }
    if rank < q {
        return Err(RankDeficient { rank });
    }
    for k in (0..q).rev() {
        let s: f64 = (k + 1..q).map(|j| a[j * m + k] * z[j]).sum();
        z[k] = (b[k] - s) / a[k * m + k];
    }
    Ok(())
}

fn norm(x: &[f64]) -> f64 {
    let scale = x.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    scale
        * x.iter()
            .map(|v| (v / scale) * (v / scale))
            .sum::<f64>()
            .sqrt()
}

/// x <- (I - 2 v v^T / v^T v) x.
fn reflect(v: &[f64], x: &mut [f64], vtv: f64) {
    let f = 2.0 * v.iter().zip(x.iter()).map(|(a, b)| a * b).sum::<f64>() / vtv;
    for (xi, vi) in x.iter_mut().zip(v) {
        *xi -= f * vi;
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn lstsq_reference(a: &[f64], b: &[f64], m: usize, q: usize) -> Vec<f64> {
        let mat = faer::Mat::from_fn(m, q, |i, j| a[j * m + i]);
        let rhs = faer::Mat::from_fn(m, 1, |i, _| b[i]);
        let x = faer::linalg::solvers::SolveLstsq::solve_lstsq(&mat.qr(), &rhs);
        (0..q).map(|i| x[(i, 0)]).collect()
    }

    #[test]
    fn matches_a_reference_solver_on_an_inconsistent_system() {
        let (m, q) = (7, 3);
        let a: Vec<f64> = (0..m * q)
            .map(|i| ((i * 37 % 11) as f64 - 5.0) * 10f64.powi((i / m) as i32 * 3))
            .collect();
        let b: Vec<f64> = (0..m).map(|i| (i as f64).sin()).collect();
        let expected = lstsq_reference(&a, &b, m, q);
        let mut z = vec![0.0; q];
        solve_in_place(&mut a.clone(), &mut b.clone(), m, q, &mut z).unwrap();
        for (x, y) in z.iter().zip(&expected) {
            assert!((x - y).abs() <= 1e-12 * y.abs().max(1e-300), "{x} vs {y}");
        }
    }

    #[test]
    fn exact_solution_of_a_consistent_badly_scaled_system() {
        let (m, q) = (5, 2);
        let z_true = [0.2, 0.2];
        let a: Vec<f64> = (0..m)
            .map(|i| 1e9 * (i as f64 + 1.0))
            .chain((0..m).map(|i| 1e3 * ((i * i) as f64 - 2.0)))
            .collect();
        let b: Vec<f64> = (0..m)
            .map(|i| a[i] * z_true[0] + a[m + i] * z_true[1])
            .collect();
        let mut z = [0.0; 2];
        solve_in_place(&mut a.clone(), &mut b.clone(), m, q, &mut z).unwrap();
        // z[1] carries 1e-6 of b: its accuracy is eps * |b| / |a_1| ~ 1e-10.
        assert!(
            (z[0] - 0.2).abs() < 1e-15 && (z[1] - 0.2).abs() < 1e-10,
            "{z:?}"
        );
    }

    #[test]
    fn dependent_or_zero_columns_are_reported_with_their_rank() {
        let m = 4;
        let mut a = vec![1.0, 2.0, 3.0, 4.0, -2.0, -4.0, -6.0, -8.0];
        let mut b = vec![1.0; m];
        assert_eq!(
            solve_in_place(&mut a, &mut b, m, 2, &mut [0.0; 2]),
            Err(RankDeficient { rank: 1 })
        );
        let mut a = vec![0.0; 2 * m];
        let mut b = vec![1.0; m];
        assert_eq!(
            solve_in_place(&mut a, &mut b, m, 2, &mut [0.0; 2]),
            Err(RankDeficient { rank: 0 })
        );
    }
}

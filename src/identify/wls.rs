//! Weighted least squares of eq. (13), solved through a QR factorisation of W S, never
//! through the normal equations (whose conditioning is the square of that of W S).
//!
//! The factorisation is modified Gram-Schmidt applied to the augmented matrix [W S | W b]:
//! the least-squares solution so obtained is backward stable (Bjorck 1967; Bjorck,
//! *Numerical Methods for Least Squares Problems*, SIAM 1996, sec. 2.4.3), every column is
//! normalised as it is processed (no overflow of squared entries), and for the tiny systems
//! here (m x q with q = 2 per joint, solved millions of times by the study engine) it is the
//! cheapest QR: in place on caller-owned buffers, no allocation.

use super::system::{LANES, Lanes};

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
/// b = W b). `a` and `b` are overwritten (by Q and the residual); the solution goes to `z`.
/// R lives in a stack array: q must not exceed [`MAX_Q`].
#[inline]
pub fn solve_in_place(
    a: &mut [f64],
    b: &mut [f64],
    m: usize,
    q: usize,
    z: &mut [f64],
) -> Result<(), RankDeficient> {
    assert!(a.len() == m * q && b.len() == m && z.len() == q && m >= q && q <= MAX_Q);
    let mut rank = 0;
    let mut rb = [0.0; MAX_Q];
    let mut r = [[0.0; MAX_Q]; MAX_Q];
    let mut original = [0.0; MAX_Q];
    for (k, o) in original.iter_mut().enumerate().take(q) {
        *o = norm(&a[k * m..(k + 1) * m]);
    }
    for k in 0..q {
        let (done, rest) = a.split_at_mut((k + 1) * m);
        let col = &mut done[k * m..];
        let rkk = norm(col);
        if rkk > RANK_TOLERANCE * original[k] {
            rank += 1;
        } else {
            continue;
        }
        for v in col.iter_mut() {
            *v /= rkk;
        }
        r[k][k] = rkk;
        for j in k + 1..q {
            let aj = &mut rest[(j - k - 1) * m..(j - k) * m];
            r[k][j] = project_out(col, aj);
        }
        rb[k] = project_out(col, b);
    }
    if rank < q {
        return Err(RankDeficient { rank });
    }
    for k in (0..q).rev() {
        let mut s = rb[k];
        for j in k + 1..q {
            s -= r[k][j] * z[j];
        }
        z[k] = s / r[k][k];
    }
    Ok(())
}

/// [`solve_in_place`] for `LANES` systems at once (`a[i * m + k][l]`, `b[k][l]`), each lane
/// through the same operations in the same order: bitwise the scalar result. `ok[l]` tells
/// whether lane l had full rank; the `z` of a rank-deficient lane is meaningless.
///
/// `r` (length q * q, any content) is the caller's room for R, row-major; before column k
/// is processed its diagonal slot holds the original norm of column k, and `z` holds
/// Q^T b until the back substitution overwrites it in place. Nothing is zeroed per call.
#[inline(always)]
pub fn solve_lanes(
    a: &mut [Lanes],
    b: &mut [Lanes],
    m: usize,
    q: usize,
    r: &mut [Lanes],
    z: &mut [Lanes],
    ok: &mut [bool; LANES],
) {
    assert!(a.len() == m * q && b.len() == m && z.len() == q && r.len() == q * q && m >= q);
    for k in 0..q {
        r[k * q + k] = norm_lanes(&a[k * m..(k + 1) * m]);
    }
    *ok = [true; LANES];
    for k in 0..q {
        let (done, rest) = a.split_at_mut((k + 1) * m);
        let col = &mut done[k * m..];
        let rkk = norm_lanes(col);
        let original = r[k * q + k];
        for l in 0..LANES {
            ok[l] &= rkk[l] > RANK_TOLERANCE * original[l];
        }
        for v in col.iter_mut() {
            for l in 0..LANES {
                v[l] /= rkk[l];
            }
        }
        r[k * q + k] = rkk;
        for j in k + 1..q {
            let aj = &mut rest[(j - k - 1) * m..(j - k) * m];
            r[k * q + j] = project_out_lanes(col, aj);
        }
        z[k] = project_out_lanes(col, b);
    }
    for k in (0..q).rev() {
        let mut s = z[k];
        for j in k + 1..q {
            for l in 0..LANES {
                s[l] -= r[k * q + j][l] * z[j][l];
            }
        }
        for l in 0..LANES {
            z[k][l] = s[l] / r[k * q + k][l];
        }
    }
}

#[inline(always)]
fn norm_lanes(x: &[Lanes]) -> Lanes {
    let mut ss = [0.0; LANES];
    for v in x {
        for l in 0..LANES {
            ss[l] += v[l] * v[l];
        }
    }
    if ss.iter().all(|s| s.is_finite() && *s > f64::MIN_POSITIVE) {
        let mut out = [0.0; LANES];
        for l in 0..LANES {
            out[l] = ss[l].sqrt();
        }
        return out;
    }
    norm_lanes_rescaled(x)
}

/// [`norm`] lane by lane, for the rare columns whose plain sum of squares over- or underflows.
#[cold]
#[inline(never)]
fn norm_lanes_rescaled(x: &[Lanes]) -> Lanes {
    let mut column = [0.0; 64];
    std::array::from_fn(|l| {
        if x.len() > column.len() {
            return norm(&x.iter().map(|v| v[l]).collect::<Vec<f64>>());
        }
        for (c, v) in column.iter_mut().zip(x) {
            *c = v[l];
        }
        norm(&column[..x.len()])
    })
}

#[inline(always)]
fn project_out_lanes(u: &[Lanes], x: &mut [Lanes]) -> Lanes {
    let mut ux = [0.0; LANES];
    for (a, b) in u.iter().zip(x.iter()) {
        for l in 0..LANES {
            ux[l] += a[l] * b[l];
        }
    }
    for (xi, ui) in x.iter_mut().zip(u) {
        for l in 0..LANES {
            xi[l] -= ux[l] * ui[l];
        }
    }
    ux
}

/// Largest number of parameters the solver takes: a structure's
/// [`crate::structure::MAX_IDENTIFIED`].
pub const MAX_Q: usize = crate::structure::MAX_IDENTIFIED;

/// x <- x - (u . x) u for a unit vector u; returns u . x.
#[inline]
fn project_out(u: &[f64], x: &mut [f64]) -> f64 {
    let mut ux = 0.0;
    for (a, b) in u.iter().zip(x.iter()) {
        ux += a * b;
    }
    for (xi, ui) in x.iter_mut().zip(u) {
        *xi -= ux * ui;
    }
    ux
}

/// Euclidean norm: the plain sum of squares, rescaled only when it over- or underflows.
#[inline]
fn norm(x: &[f64]) -> f64 {
    let mut ss = 0.0;
    for v in x {
        ss += v * v;
    }
    if ss.is_finite() && ss > f64::MIN_POSITIVE {
        return ss.sqrt();
    }
    let scale = x.iter().fold(0.0_f64, |s, v| s.max(v.abs()));
    if scale == 0.0 || !scale.is_finite() {
        return scale;
    }
    let mut ss = 0.0;
    for v in x {
        ss += (v / scale) * (v / scale);
    }
    scale * ss.sqrt()
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
    fn lanes_solve_bitwise_like_the_scalar_solver_and_flag_deficient_lanes() {
        let (m, q) = (6, 3);
        let entry = |i: usize, l: usize| {
            (((i * 31 + l * 17) % 23) as f64 - 11.0) * 10f64.powi((i / m) as i32 * 2)
        };
        let mut a: Vec<Lanes> = (0..m * q)
            .map(|i| std::array::from_fn(|l| entry(i, l)))
            .collect();
        // Lane 5: third column = first + second (rank 2). Lane 6: huge entries (scaled norms).
        for k in 0..m {
            a[2 * m + k][5] = a[k][5] + a[m + k][5];
            for c in 0..q {
                a[c * m + k][6] *= 1e200;
            }
        }
        let b: Vec<Lanes> = (0..m)
            .map(|k| std::array::from_fn(|l| (k as f64 + 0.5 * l as f64).cos()))
            .collect();
        let (mut al, mut bl, mut z, mut ok) =
            (a.clone(), b.clone(), vec![[0.0; LANES]; q], [false; LANES]);
        // R's room starts as garbage: the solver must not read what it has not written.
        let mut r = vec![[f64::NAN; LANES]; q * q];
        solve_lanes(&mut al, &mut bl, m, q, &mut r, &mut z, &mut ok);
        for l in 0..LANES {
            let mut a1: Vec<f64> = a.iter().map(|v| v[l]).collect();
            let mut b1: Vec<f64> = b.iter().map(|v| v[l]).collect();
            let mut z1 = vec![0.0; q];
            let scalar = solve_in_place(&mut a1, &mut b1, m, q, &mut z1);
            assert_eq!(scalar.is_ok(), ok[l], "lane {l}");
            if ok[l] {
                for i in 0..q {
                    assert_eq!(z1[i].to_bits(), z[i][l].to_bits(), "lane {l}, z{i}");
                }
            }
        }
        assert!(!ok[5] && ok[6]);
    }

    #[test]
    fn huge_and_tiny_columns_keep_their_accuracy() {
        // Sums of squares that overflow (1e200^2) or underflow (1e-200^2) take the scaled path.
        for scale in [1e200, 1e-200] {
            let (m, q) = (3, 2);
            let a = vec![scale, 2.0 * scale, 0.0, 0.0, scale, scale];
            let b = vec![scale, 3.0 * scale, scale];
            let mut z = [0.0; 2];
            solve_in_place(&mut a.clone(), &mut b.clone(), m, q, &mut z).unwrap();
            // Consistent system: z = (1, 1).
            assert!(
                (z[0] - 1.0).abs() < 1e-14 && (z[1] - 1.0).abs() < 1e-14,
                "{scale}: {z:?}"
            );
        }
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

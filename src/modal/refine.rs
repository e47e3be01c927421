//! Refinement of approximate lowest eigenpairs with accurately computed products K y.
//!
//! Why: in the stiffness matrix of a finely meshed slender structure, the entries are of the
//! element scale EI / h^3 while K y for a low mode is of the scale lambda M y, smaller by up
//! to the condition number (about (L / h)^4 for a beam). K y computed in double precision
//! then carries a round-off of eps |K| |y| per entry, comparable to the signal from a few
//! thousand beam elements on, and so do the Cholesky factor of K - sigma M and every
//! eigenvalue sigma + 1/theta taken from it (scipy's `eigsh` loses the low modes the same
//! way). The stored matrix itself defines its low eigenpairs much better: what is lost is
//! mostly the arithmetic, up to the limit set by the rounding of the stored entries (module
//! docs of [`super::lanczos`], with measured numbers).
//!
//! Method: K y is accumulated in twice the working precision (error-free transformations:
//! Dekker's product and Knuth's sum, the "Dot2" of Ogita, Rump & Oishi, "Accurate sum and
//! dot product", SIAM J. Sci. Comput. 26 (2005)), so that the Rayleigh quotients
//! y^T K y of the stored K are exact to working precision, while the factorised K - sigma M
//! serves only as a preconditioner. One sweep of a block correction (Davidson's method):
//!
//! ```text
//!   R = K Y - M Y Lambda                       (accurate K Y)
//!   D = (K - sigma M)^-1 R, M-orthogonalised against Y
//!   Rayleigh-Ritz of (K, M) on span[Y, D]      (accurate K [Y, D])
//! ```
//!
//! A correction column whose M-norm is below [`NOISE_FLOOR`] is round-off of the vector
//! itself and is dropped; the refinement stops when every column is dropped or the Ritz
//! values stop moving.

use faer::sparse::SparseColMatRef;
use faer::{Mat, Side};

use rayon::prelude::*;

use super::residual;
use super::sparse_llt::SparseLlt;
use super::sparse_mul;

/// Corrections of M-norm below this (for M-normalised vectors) are left out, unless the
/// pair's residual asks for them (see [`refine`]): their content may be the rounding of the
/// vector, whose Rayleigh quotient is of the element scale.
pub const NOISE_FLOOR: f64 = 1e-7;

/// A wanted pair is corrected while its relative residual exceeds this many times its rounding
/// floor ([`super::residual`]).
pub const FLOOR_FACTOR: f64 = 10.0;

/// `y = A x` for a symmetric matrix stored with both triangles, every entry accumulated in
/// twice the working precision and rounded once.
pub fn accurate_mul(a: SparseColMatRef<'_, usize, f64>, x: &[f64], y: &mut [f64]) {
    #[cfg(target_arch = "x86_64")]
    if std::arch::is_x86_feature_detected!("fma") {
        // SAFETY: the processor has FMA (checked just above).
        unsafe { accurate_mul_fma(a, x, y) };
        return;
    }
    accurate_mul_with::<false>(a, x, y);
}

/// [`accurate_mul`] with the error of each product from one fused multiply-add: the same
/// error term as Dekker's product (it is exactly representable), in 2 operations for 17.
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "fma")]
unsafe fn accurate_mul_fma(a: SparseColMatRef<'_, usize, f64>, x: &[f64], y: &mut [f64]) {
    accurate_mul_with::<true>(a, x, y);
}

#[inline(always)]
fn accurate_mul_with<const FMA: bool>(
    a: SparseColMatRef<'_, usize, f64>,
    x: &[f64],
    y: &mut [f64],
) {
    for (j, yj) in y.iter_mut().enumerate() {
        // Column j of a symmetric matrix is its row j.
        let rows = a.symbolic().row_idx_of_col_raw(j);
        let (mut s, mut c) = (0.0_f64, 0.0_f64);
        for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
            let (p, e) = if FMA {
                let p = v * x[i];
                (p, v.mul_add(x[i], -p))
            } else {
                two_product(v, x[i])
            };
            let (t, f) = two_sum(s, p);
            s = t;
            c += e + f;
        }
        *yj = s + c;
    }
}

fn two_sum(a: f64, b: f64) -> (f64, f64) {
    let s = a + b;
    let bb = s - a;
    (s, (a - (s - bb)) + (b - bb))
}

fn split(a: f64) -> (f64, f64) {
    let c = 134_217_729.0 * a; // 2^27 + 1
    let hi = c - (c - a);
    (hi, a - hi)
}

fn two_product(a: f64, b: f64) -> (f64, f64) {
    let p = a * b;
    let (ah, al) = split(a);
    let (bh, bl) = split(b);
    (p, ((ah * bh - p) + ah * bl + al * bh) + al * bl)
}

/// A K Q (accurate products) or M Q (plain), the columns on rayon's threads.
fn mul_columns(a: SparseColMatRef<'_, usize, f64>, q: &Mat<f64>, accurate: bool) -> Mat<f64> {
    let n = q.nrows();
    let columns: Vec<Vec<f64>> = (0..q.ncols())
        .into_par_iter()
        .map(|j| {
            let mut out = vec![0.0; n];
            if accurate {
                accurate_mul(a, q.col_as_slice(j), &mut out);
            } else {
                sparse_mul(a, q.col_as_slice(j), &mut out);
            }
            out
        })
        .collect();
    Mat::from_fn(n, q.ncols(), |i, j| columns[j][i])
}

/// Eigenpairs of the small dense pencil (a, b), b symmetric positive definite: values
/// ascending, vectors X with X^T b X = E. Scaled to unit largest entry for faer's symmetric
/// solver (see the module docs of [`super`]).
pub fn dense_pencil(a: &Mat<f64>, b: &Mat<f64>) -> Option<(Vec<f64>, Mat<f64>)> {
    let n = a.nrows();
    let sym = |x: &Mat<f64>| Mat::from_fn(n, n, |i, j| 0.5 * (x[(i, j)] + x[(j, i)]));
    let llt = sym(b).llt(Side::Lower).ok()?;
    let l = llt.L();
    let mut x = sym(a);
    l.solve_lower_triangular_in_place(x.as_mut());
    let mut c = x.transpose().to_owned();
    l.solve_lower_triangular_in_place(c.as_mut());
    let scale = c.norm_max().max(f64::MIN_POSITIVE);
    let c = Mat::from_fn(n, n, |i, j| 0.5 * (c[(i, j)] + c[(j, i)]) / scale);
    let evd = c.self_adjoint_eigen(Side::Lower).ok()?;
    let values = (0..n).map(|i| evd.S()[i] * scale).collect();
    let mut vectors = evd.U().to_owned();
    l.transpose()
        .solve_upper_triangular_in_place(vectors.as_mut());
    Some((values, vectors))
}

/// Refined pairs.
pub struct Refined {
    /// Ritz values of (K, M), ascending.
    pub values: Vec<f64>,
    /// Ritz vectors, M-orthonormal.
    pub vectors: Mat<f64>,
    /// K Y (accurate products) and M Y of the vectors.
    pub products: (Mat<f64>, Mat<f64>),
    /// Correction sweeps done (0: the first Rayleigh-Ritz with accurate products sufficed).
    pub sweeps: usize,
}

/// Refines the M-orthonormal columns of `y` (the `wanted` lowest first) by block corrections
/// with the factor of K - sigma M, at most `max_sweeps` sweeps. A correction enters while
/// its M-norm is above [`NOISE_FLOOR`], or, for a wanted pair, while the pair's relative
/// residual ||K y - lambda M y|| / ||K y|| stands above [`FLOOR_FACTOR`] times its rounding
/// floor ([`super::residual`]) and fell at least twofold in the last sweep. Stops when no
/// correction enters, or when the Ritz values move by less than `tol * (|lambda| + |sigma|)`
/// and no correction entered for its residual.
#[allow(clippy::too_many_arguments)]
pub fn refine(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    llt: &SparseLlt,
    shift: f64,
    y: Mat<f64>,
    wanted: usize,
    tol: f64,
    max_sweeps: usize,
) -> Option<Refined> {
    let p = y.ncols();
    let (mut ky, mut my) = (mul_columns(k, &y, true), mul_columns(m, &y, false));
    let (values, x) = dense_pencil(&(y.transpose() * &ky), &(y.transpose() * &my))?;
    let mut y = &y * &x;
    ky = &ky * &x;
    my = &my * &x;
    let mut values = values;
    let mut last_residual = vec![f64::INFINITY; wanted.min(p)];
    let done = |values, vectors, products, sweeps| {
        Some(Refined {
            values,
            vectors,
            products,
            sweeps,
        })
    };
    for sweep in 1..=max_sweeps {
        let mut d = Mat::<f64>::zeros(y.nrows(), p);
        for (j, &lambda) in values.iter().enumerate() {
            let (kc, mc) = (ky.col_as_slice(j), my.col_as_slice(j));
            for ((c, a), b) in d.col_as_slice_mut(j).iter_mut().zip(kc).zip(mc) {
                *c = a - lambda * b;
            }
        }
        // Residual criterion of the wanted pairs, from R before the solve overwrites it.
        let residuals: Vec<residual::Residual> = (0..last_residual.len())
            .into_par_iter()
            .map(|j| residual::of_products(k, y.col_as_slice(j), ky.col_as_slice(j), d.col_as_slice(j)))
            .collect();
        let above_floor: Vec<bool> = residuals
            .iter()
            .zip(&last_residual)
            .map(|(r, &last)| r.relative > FLOOR_FACTOR * r.floor && r.relative < 0.5 * last)
            .collect();
        for (last, r) in last_residual.iter_mut().zip(&residuals) {
            *last = r.relative;
        }
        llt.solve_columns_in_place(d.as_mut());
        for _ in 0..2 {
            let c = my.transpose() * &d;
            d -= &y * &c;
        }
        let md = mul_columns(m, &d, false);
        let mut for_residual = false;
        let mut keep = Vec::new();
        for j in 0..p {
            let norm = residual::m_norm(d.col_as_slice(j), md.col_as_slice(j));
            let residual = above_floor.get(j).copied().unwrap_or(false);
            if norm > NOISE_FLOOR {
                keep.push((j, 1.0));
            } else if residual && norm > 0.0 {
                // Scaled to unit M-norm: the Gram matrix of Rayleigh-Ritz stays well scaled.
                keep.push((j, 1.0 / norm));
                for_residual = true;
            }
        }
        if keep.is_empty() {
            return done(values, y, (ky, my), sweep - 1);
        }
        let block = |keep: &[(usize, f64)]| {
            let mut dk = Mat::<f64>::zeros(y.nrows(), keep.len());
            for (j, &(c, scale)) in keep.iter().enumerate() {
                for (a, b) in dk.col_as_slice_mut(j).iter_mut().zip(d.col_as_slice(c)) {
                    *a = scale * b;
                }
            }
            let q = concat(&y, &dk);
            let kq = concat(&ky, &mul_columns(k, &dk, true));
            let mq = concat(&my, &mul_columns(m, &dk, false));
            let pencil = dense_pencil(&(q.transpose() * &kq), &(q.transpose() * &mq));
            pencil.map(|(values, x)| (values, x, q, kq, mq))
        };
        let rayleigh_ritz = match block(&keep) {
            Some(done) => Some(done),
            // Corrections at the rounding level that made the Gram matrix singular: without
            // them.
            None if for_residual => {
                for_residual = false;
                keep.retain(|&(_, scale)| scale == 1.0);
                if keep.is_empty() {
                    return done(values, y, (ky, my), sweep - 1);
                }
                block(&keep)
            }
            None => None,
        };
        let (new_values, x, q, kq, mq) = rayleigh_ritz?;
        let x = x.subcols(0, p).to_owned();
        let moved = (0..p)
            .map(|j| (new_values[j] - values[j]).abs() / (values[j].abs() + shift.abs()))
            .fold(0.0, f64::max);
        y = &q * &x;
        ky = &kq * &x;
        my = &mq * &x;
        values = new_values[..p].to_vec();
        if moved <= tol && !for_residual {
            return done(values, y, (ky, my), sweep);
        }
    }
    done(values, y, (ky, my), max_sweeps)
}

fn concat(a: &Mat<f64>, b: &Mat<f64>) -> Mat<f64> {
    let (n, p) = (a.nrows(), a.ncols());
    let mut out = Mat::<f64>::zeros(n, p + b.ncols());
    out.subcols_mut(0, p).copy_from(a);
    out.subcols_mut(p, b.ncols()).copy_from(b);
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::structure::SymMatrix;

    /// Row 0 of A x sums 1 + 1e16 - 1e16: the plain product loses the 1, the accurate one
    /// keeps it (exact value by hand).
    #[test]
    fn accurate_product_survives_cancellation() {
        let a = SymMatrix::from_entries(
            3,
            &[
                (0, 0, 1.0),
                (0, 1, 1e16),
                (1, 0, 1e16),
                (0, 2, -1e16),
                (2, 0, -1e16),
                (1, 1, 1.0),
                (2, 2, 1.0),
            ],
        );
        let x = [1.0, 1.0, 1.0];
        let (mut plain, mut accurate) = ([0.0; 3], [0.0; 3]);
        sparse_mul(a.as_faer(), &x, &mut plain);
        accurate_mul(a.as_faer(), &x, &mut accurate);
        assert_eq!(plain[0], 0.0);
        assert_eq!(accurate, [1.0, 1e16 + 1.0, 1.0 - 1e16]);
    }
}

//! Residual norms of computed eigenpairs, the accuracy report of the sparse solver:
//!
//! ```text
//!   relative = ||K y - lambda M y||_2 / ||K y||_2
//!   floor    = eps || |K| |y| ||_2 / ||K y||_2
//! ```
//!
//! K y is accumulated in twice the working precision ([`super::accurate`]), so
//! that the residual is that of the stored K and the stored vector, not of the arithmetic.
//! `floor` is what the rounding of y alone to double precision leaves in the residual (a
//! perturbation of eps |y| per entry moves K y by up to eps |K| |y|): no vector stored in
//! double precision has a smaller relative residual in general. It is about eps times
//! lambda_max / lambda: 1e-9 for the lowest elastic modes of a 3D solid of 1e4-1e5 DOFs,
//! above 1 for a beam of 1e5 elements (K's condition grows like (L / h)^4), whose accuracy is
//! then stated by the backward error of [`super::lanczos`] and by the analytic frequencies.
//!
//! Layer 2 (eigensolution), like [`super`]: may import the layers below.

use faer::MatRef;
use faer::sparse::SparseColMatRef;
use rayon::prelude::*;

use super::accurate::accurate_mul_bounded;
use super::sparse_mul;

/// The residual of one pair (module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Residual {
    /// ||K y - lambda M y|| / ||K y|| (NaN when K y = 0 exactly).
    pub relative: f64,
    /// eps || |K| |y| || / ||K y||, the rounding floor of `relative`.
    pub floor: f64,
}

/// The residual of every pair (`values[j]`, column j of `vectors`) of K y = lambda M y,
/// K and M stored with both triangles; the columns in parallel.
pub fn residuals(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    values: &[f64],
    vectors: MatRef<'_, f64>,
) -> Vec<Residual> {
    (0..values.len())
        .into_par_iter()
        .map(|j| {
            let y: Vec<f64> = vectors.col(j).iter().copied().collect();
            one(k, m, values[j], &y)
        })
        .collect()
}

fn one(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    lambda: f64,
    y: &[f64],
) -> Residual {
    let n = y.len();
    let (mut ky, mut my) = (vec![0.0; n], vec![0.0; n]);
    let bound = accurate_mul_bounded(k, y, &mut ky);
    sparse_mul(m, y, &mut my);
    let r: Vec<f64> = ky.iter().zip(&my).map(|(a, b)| a - lambda * b).collect();
    of_products(&ky, &r, bound)
}

/// The residual given K y (accurate), r = K y - lambda M y and `bound` >= || |K| |y| ||.
pub fn of_products(ky: &[f64], r: &[f64], bound: f64) -> Residual {
    let ky_norm = norm(ky);
    Residual {
        relative: norm(r) / ky_norm,
        floor: f64::EPSILON * bound / ky_norm,
    }
}

/// The M-norm sqrt(v^T M v) of `v` given `mv` = M v (0 for a round-off negative square).
pub fn m_norm(v: &[f64], mv: &[f64]) -> f64 {
    v.iter()
        .zip(mv)
        .map(|(a, b)| a * b)
        .sum::<f64>()
        .max(0.0)
        .sqrt()
}

/// The Euclidean norm.
pub fn norm(v: &[f64]) -> f64 {
    v.iter().map(|a| a * a).sum::<f64>().sqrt()
}

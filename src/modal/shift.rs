//! The shifted matrix K - sigma M of the shift-invert eigensolver ([`super::lanczos`]): the
//! default shift, the lower triangle assembled column by column, and its factorisation, the
//! shift moved away from the spectrum while a pivot is not positive.
//!
//! Layer 2 (eigensolution), like [`super`].

use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat};

use super::ModalError;
use super::sparse_llt::{Ordering, SparseLlt};

/// How many factorisations of K - sigma M are tried, |sigma| growing 100-fold each time.
pub const SHIFT_ATTEMPTS: usize = 6;

/// The lower triangle of a + scale b (both stored with both triangles; b absent: a alone) as
/// a column-sorted sparse matrix, duplicates summed, built column by column without a global
/// sort (`None` on a non-finite entry).
pub(super) fn lower_sum(
    a: SparseColMatRef<'_, usize, f64>,
    b: Option<(SparseColMatRef<'_, usize, f64>, f64)>,
) -> Option<SparseColMat<usize, f64>> {
    let n = a.ncols();
    let mut col_ptr = Vec::with_capacity(n + 1);
    let mut rows = Vec::with_capacity(a.val().len() / 2 + n);
    let mut values = Vec::with_capacity(a.val().len() / 2 + n);
    let mut column: Vec<(usize, f64)> = Vec::new();
    col_ptr.push(0);
    for j in 0..n {
        column.clear();
        let mut push = |m: SparseColMatRef<'_, usize, f64>, scale: f64| {
            let entries = m
                .symbolic()
                .row_idx_of_col_raw(j)
                .iter()
                .zip(m.val_of_col(j));
            column.extend(
                entries
                    .filter(|(i, _)| **i >= j)
                    .map(|(&i, &v)| (i, scale * v)),
            );
        };
        push(a, 1.0);
        if let Some((b, scale)) = b {
            push(b, scale);
        }
        column.sort_unstable_by_key(|e| e.0);
        for &(i, v) in &column {
            if rows.len() > col_ptr[j] && rows.last() == Some(&i) {
                *values.last_mut().expect("a value per row") += v;
            } else {
                rows.push(i);
                values.push(v);
            }
        }
        col_ptr.push(rows.len());
    }
    if !values.iter().all(|v| v.is_finite()) {
        return None;
    }
    let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, rows);
    Some(SparseColMat::new(symbolic, values))
}

/// The ordering of K - sigma M's factor: of minimum degree and the DOF order, the one that
/// fills less ([`Ordering::Fewest`]).
const ORDERING: Ordering = Ordering::Fewest;

/// The default shift of [`super::lanczos::LanczosSettings::shift`].
pub fn default_shift(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
) -> f64 {
    let n = k.nrows();
    let (dk, dm) = (diagonal(k), diagonal(m));
    let mean = dk
        .iter()
        .zip(&dm)
        .map(|(kk, mm)| if *mm > 0.0 { kk / mm } else { 0.0 })
        .sum::<f64>()
        / n.max(1) as f64;
    let sigma = -1e-4 * mean / (n as f64 * n as f64);
    if sigma < 0.0 && sigma.is_finite() {
        sigma
    } else {
        -1.0
    }
}

fn diagonal(a: SparseColMatRef<'_, usize, f64>) -> Vec<f64> {
    let mut d = vec![0.0; a.ncols()];
    for (j, dj) in d.iter_mut().enumerate() {
        let rows = a.symbolic().row_idx_of_col_raw(j);
        for (&i, &v) in rows.iter().zip(a.val_of_col(j)) {
            if i == j {
                *dj += v;
            }
        }
    }
    d
}

pub(super) fn factor_shifted(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    shift: Option<f64>,
) -> Result<(f64, SparseLlt), ModalError> {
    if !k.val().iter().all(|v| v.is_finite()) {
        return Err(ModalError::NonFinite);
    }
    let first = shift.unwrap_or_else(|| default_shift(k, m));
    let mut sigma = first;
    for _ in 0..SHIFT_ATTEMPTS {
        if let Some(lower) = lower_sum(k, Some((m, -sigma))) {
            if let Some(llt) = SparseLlt::from_lower(lower.as_ref(), ORDERING) {
                return Ok((sigma, llt));
            }
        }
        sigma *= 100.0;
    }
    Err(ModalError::ShiftNotFactorised {
        first,
        last: sigma / 100.0,
        attempts: SHIFT_ATTEMPTS,
    })
}

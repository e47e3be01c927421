//! Global symmetric matrices K and M in compressed sparse column form, both triangles stored.
//!
//! A matrix is built from a list of entries `(row, col, value)` by summing the entries of a
//! position in the order they were listed, starting from zero: exactly the sums a dense
//! `a[(i, j)] += v` assembly in the same order forms, so a model assembled here and converted to
//! dense is bitwise the model a dense assembly gives.

use faer::Mat;
use faer::sparse::{SparseColMat, SparseColMatRef, SymbolicSparseColMat};

use super::SparseSym;

/// A square symmetric sparse matrix (both triangles stored), N x N.
#[derive(Debug, Clone)]
pub struct SymMatrix {
    inner: SparseColMat<usize, f64>,
}

impl SymMatrix {
    /// The matrix of size `n` with the entries of `entries`, summed per position in list order.
    /// The caller lists both triangles (as [`SparseSym`] does) and indices below `n`.
    pub fn from_entries(n: usize, entries: &[(usize, usize, f64)]) -> Self {
        Self::sorted(n, entries.len(), || entries.iter().copied())
    }

    /// The matrix of size `n` whose lower triangle (row >= column) `lower` lists: the matrix
    /// [`SymMatrix::from_entries`] gives for both triangles listed as each lower entry's
    /// mirror, then itself (a diagonal entry once), bit for bit, without that list.
    pub fn from_lower(n: usize, lower: &[(usize, usize, f64)]) -> Self {
        let count = lower.iter().map(|e| 1 + usize::from(e.0 != e.1)).sum();
        Self::sorted(n, count, || {
            lower.iter().flat_map(|&(i, j, v)| {
                let mirror = (i != j).then_some((j, i, v));
                mirror.into_iter().chain(std::iter::once((i, j, v)))
            })
        })
    }

    /// The matrix of the `count` entries that `entries()` lists (called twice), summed per
    /// position in list order: a counting sort by column (stable), then each column's rows
    /// sorted (stable, a few dozen entries), in linear time where a comparison sort of all
    /// the entries took most of the time of reading a large model.
    fn sorted<I: Iterator<Item = (usize, usize, f64)>>(
        n: usize,
        count: usize,
        entries: impl Fn() -> I,
    ) -> Self {
        let mut start = vec![0usize; n + 1];
        for (i, j, _) in entries() {
            assert_inside(n, i, j);
            start[j + 1] += 1;
        }
        for j in 0..n {
            start[j + 1] += start[j];
        }
        debug_assert_eq!(start[n], count);
        let mut next = start.clone();
        let mut by_column = vec![(0usize, 0.0f64); count];
        for (i, j, v) in entries() {
            by_column[next[j]] = (i, v);
            next[j] += 1;
        }
        let mut col_ptr = Vec::with_capacity(n + 1);
        col_ptr.push(0);
        let mut row_idx: Vec<usize> = Vec::with_capacity(count);
        let mut values: Vec<f64> = Vec::with_capacity(count);
        for j in 0..n {
            let column = &mut by_column[start[j]..start[j + 1]];
            column.sort_by_key(|e| e.0);
            let first = row_idx.len();
            for &(i, v) in column.iter() {
                if row_idx.len() > first && row_idx.last() == Some(&i) {
                    *values.last_mut().expect("a value for the position") += v;
                } else {
                    row_idx.push(i);
                    values.push(0.0 + v);
                }
            }
            col_ptr.push(row_idx.len());
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, col_ptr, None, row_idx);
        Self {
            inner: SparseColMat::new(symbolic, values),
        }
    }

    /// This matrix plus `scale` times each of `terms`, summed after the present value of every
    /// position (bitwise the dense `a[(i, j)] += scale * v` in the same order).
    ///
    /// A merge, column by column, of the stored entries with the terms' entries sorted by
    /// position: the sums [`SymMatrix::from_entries`] forms from this matrix's entries
    /// followed by the terms', without sorting this matrix's own (on a large model the terms
    /// are a joint's few entries, this matrix millions).
    pub fn plus(&self, terms: &[(&SparseSym, f64)]) -> Self {
        let n = self.size();
        let mut added: Vec<(usize, usize, f64)> = terms
            .iter()
            .flat_map(|(s, scale)| s.entries().iter().map(move |&(i, j, v)| (i, j, scale * v)))
            .collect();
        for &(i, j, _) in &added {
            assert_inside(n, i, j);
        }
        // Stable: entries of one position keep their listed order.
        added.sort_by_key(|&(i, j, _)| (j, i));
        let a = self.inner.as_ref();
        let (col_ptr, row_idx, val) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
        let mut out_ptr = Vec::with_capacity(n + 1);
        out_ptr.push(0);
        let mut out_row = Vec::with_capacity(row_idx.len() + added.len());
        let mut out_val = Vec::with_capacity(row_idx.len() + added.len());
        let mut next = added.iter().peekable();
        for j in 0..n {
            let mut own = col_ptr[j]..col_ptr[j + 1];
            loop {
                let mine = own.clone().next().map(|k| row_idx[k]);
                let theirs = next.peek().filter(|e| e.1 == j).map(|e| e.0);
                let Some(i) = mine.into_iter().chain(theirs).min() else {
                    break;
                };
                // Summed from zero in listed order, as `from_entries` does.
                let mut v = 0.0;
                if mine == Some(i) {
                    v += val[own.next().expect("the stored entry")];
                }
                while let Some(&&(_, _, add)) = next.peek().filter(|e| (e.0, e.1) == (i, j)) {
                    v += add;
                    next.next();
                }
                out_row.push(i);
                out_val.push(v);
            }
            out_ptr.push(out_row.len());
        }
        let symbolic = SymbolicSparseColMat::new_checked(n, n, out_ptr, None, out_row);
        Self {
            inner: SparseColMat::new(symbolic, out_val),
        }
    }

    /// N.
    pub fn size(&self) -> usize {
        self.inner.nrows()
    }

    /// Stored entries.
    pub fn nnz(&self) -> usize {
        self.inner.val().len()
    }

    /// The stored entries `(row, col, value)`, column by column.
    pub fn entries(&self) -> Vec<(usize, usize, f64)> {
        let a = self.inner.as_ref();
        let (col_ptr, row_idx, val) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
        (0..self.size())
            .flat_map(|j| (col_ptr[j]..col_ptr[j + 1]).map(move |k| (row_idx[k], j, val[k])))
            .collect()
    }

    /// The faer view, for the sparse solvers.
    pub fn as_faer(&self) -> SparseColMatRef<'_, usize, f64> {
        self.inner.as_ref()
    }

    /// The dense N x N matrix.
    pub fn to_dense(&self) -> Mat<f64> {
        let mut out = Mat::zeros(self.size(), self.size());
        for (i, j, v) in self.entries() {
            out[(i, j)] = v;
        }
        out
    }

    /// `y = A x`.
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        let a = self.inner.as_ref();
        let (col_ptr, row_idx, val) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
        for (j, &xj) in x.iter().enumerate() {
            for k in col_ptr[j]..col_ptr[j + 1] {
                y[row_idx[k]] += val[k] * xj;
            }
        }
    }

    /// The diagonal (read column by column where it is stored: the list of all entries is
    /// not formed, which on a large model was hundreds of MB).
    pub fn diagonal(&self) -> Vec<f64> {
        let a = self.inner.as_ref();
        let (col_ptr, row_idx, val) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
        (0..self.size())
            .map(|j| {
                (col_ptr[j]..col_ptr[j + 1])
                    .find(|&k| row_idx[k] == j)
                    .map_or(0.0, |k| val[k])
            })
            .collect()
    }

    /// Whether every stored value is finite.
    pub fn is_finite(&self) -> bool {
        self.inner.val().iter().all(|v| v.is_finite())
    }

    /// The largest |a_ij - a_ji| over the stored entries (0 for a symmetric matrix).
    pub fn asymmetry(&self) -> f64 {
        let dense_free = self.entries();
        let at = |i: usize, j: usize| {
            let a = self.inner.as_ref();
            let (col_ptr, row_idx, val) = (a.symbolic().col_ptr(), a.symbolic().row_idx(), a.val());
            (col_ptr[j]..col_ptr[j + 1])
                .find(|&k| row_idx[k] == i)
                .map_or(0.0, |k| val[k])
        };
        dense_free
            .iter()
            .map(|&(i, j, v)| (v - at(j, i)).abs())
            .fold(0.0, f64::max)
    }
}

/// Panics unless entry (i, j) lies inside a matrix of size n (the callers' contract).
fn assert_inside(n: usize, i: usize, j: usize) {
    assert!(
        i < n && j < n,
        "entry ({i}, {j}) outside a matrix of size {n}"
    );
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn entries_sum_in_listed_order_like_a_dense_assembly() {
        let entries = [
            (0, 0, 0.1),
            (1, 0, 2.0),
            (0, 1, 2.0),
            (0, 0, 0.2),
            (2, 2, 1e16),
            (2, 2, 1.0),
            (0, 0, 0.3),
        ];
        let a = SymMatrix::from_entries(3, &entries);
        let mut dense = Mat::<f64>::zeros(3, 3);
        for &(i, j, v) in &entries {
            dense[(i, j)] += v;
        }
        let back = a.to_dense();
        for i in 0..3 {
            for j in 0..3 {
                assert_eq!(
                    back[(i, j)].to_bits(),
                    dense[(i, j)].to_bits(),
                    "({i}, {j})"
                );
            }
        }
        assert_eq!(a.nnz(), 4);
        assert_eq!(a.asymmetry(), 0.0);
        let mut y = [0.0; 3];
        a.apply(&[1.0, 1.0, 0.0], &mut y);
        assert_eq!(y, [0.1 + 0.2 + 0.3 + 2.0, 2.0, 0.0]);
    }

    /// `from_lower` is `from_entries` of both triangles listed mirror first, bit for bit,
    /// with duplicates of a position in the lower list, on the diagonal and off it.
    #[test]
    fn from_lower_is_bitwise_from_entries_of_both_triangles() {
        let mut rng = crate::random::TrialRng::new(11, 0, 0);
        let mut draw = || 0.5 * (rng.symmetric_unit() + 1.0);
        let n = 7;
        let mut lower = Vec::new();
        for _ in 0..60 {
            let (a, b) = ((draw() * 7.0) as usize, (draw() * 7.0) as usize);
            lower.push((
                a.max(b),
                a.min(b),
                (draw() - 0.5) * 10f64.powi((draw() * 30.0) as i32),
            ));
        }
        let both: Vec<(usize, usize, f64)> = lower
            .iter()
            .flat_map(|&(i, j, v)| {
                let mirror = (i != j).then_some((j, i, v));
                mirror.into_iter().chain(Some((i, j, v)))
            })
            .collect();
        let (a, b) = (
            SymMatrix::from_lower(n, &lower),
            SymMatrix::from_entries(n, &both),
        );
        let (a, b) = (a.as_faer(), b.as_faer());
        assert_eq!(a.symbolic().col_ptr(), b.symbolic().col_ptr());
        assert_eq!(a.symbolic().row_idx(), b.symbolic().row_idx());
        let bits = |m: SparseColMatRef<'_, usize, f64>| -> Vec<u64> {
            m.val().iter().map(|v| v.to_bits()).collect()
        };
        assert_eq!(bits(a), bits(b));
    }

    /// The merge of `plus` against the sort of `from_entries` on the concatenated entries:
    /// the same pattern and the same bits, with positions new to the matrix, positions listed
    /// several times within a term and across terms, and a row and column the matrix lacked.
    #[test]
    fn plus_is_bitwise_the_assembly_of_all_entries_in_listed_order() {
        let n = 9;
        // An irregular pattern and values.
        let mut rng = crate::random::TrialRng::new(7, 0, 0);
        let mut draw = || 0.5 * (rng.symmetric_unit() + 1.0);
        let mut entries = Vec::new();
        for _ in 0..30 {
            let (i, j) = ((draw() * 8.0) as usize, (draw() * 8.0) as usize);
            let v = draw() - 0.5;
            entries.push((i, j, v));
            entries.push((j, i, v));
        }
        let a = SymMatrix::from_entries(n, &entries);
        let mut first = SparseSym::spring(0, 8, 0.3);
        first.add(3, 3, 1e16);
        first.add(2, 7, -0.1);
        let mut second = SparseSym::spring(8, 8, 0.7);
        second.add(3, 3, 1.0);
        second.add(7, 2, 1e-3);
        let terms = [(&first, 1.7), (&second, -2.9)];
        let merged = a.plus(&terms);
        let mut all = a.entries();
        for (s, scale) in terms {
            all.extend(s.entries().iter().map(|&(i, j, v)| (i, j, scale * v)));
        }
        let sorted = SymMatrix::from_entries(n, &all);
        let (x, y) = (merged.as_faer(), sorted.as_faer());
        assert_eq!(x.symbolic().col_ptr(), y.symbolic().col_ptr());
        assert_eq!(x.symbolic().row_idx(), y.symbolic().row_idx());
        let bits = |m: SparseColMatRef<'_, usize, f64>| -> Vec<u64> {
            m.val().iter().map(|v| v.to_bits()).collect()
        };
        assert_eq!(bits(x), bits(y));
        // Column 8 and row 8 were empty in `a`: the merge made them.
        assert!(a.diagonal()[8] == 0.0 && merged.diagonal()[8] != 0.0);
        // A stored 1 given +1e16 then -1e16: 0 only when the stored value comes first, as
        // listed (last, it would stay 1). A -0.0 at a new position: +0.0, summed from zero.
        let one = SymMatrix::from_entries(2, &[(0, 0, 1.0)]);
        let mut up = SparseSym::zero();
        up.add(0, 0, 1e16);
        up.add(1, 1, -0.0);
        let mut down = SparseSym::zero();
        down.add(0, 0, -1e16);
        let summed = one.plus(&[(&up, 1.0), (&down, 1.0)]).to_dense();
        assert_eq!(summed[(0, 0)].to_bits(), 0.0f64.to_bits());
        assert_eq!(summed[(1, 1)].to_bits(), 0.0f64.to_bits());
        let none = a.plus(&[]);
        assert_eq!(bits(none.as_faer()), bits(a.as_faer()));
    }

    #[test]
    fn plus_adds_after_the_present_value() {
        let a = SymMatrix::from_entries(2, &[(0, 0, 1.0), (1, 1, 3.0)]);
        let s = SparseSym::spring(0, 1, 1.0);
        let b = a.plus(&[(&s, 0.5)]).to_dense();
        assert_eq!(b[(0, 0)], 1.5);
        assert_eq!(b[(0, 1)], -0.5);
        assert_eq!(b[(1, 1)], 3.5);
    }
}

//! Sparse symmetric matrices for the parameter derivatives dK/dp and dM/dp.
//!
//! A derivative matrix touches a handful of DOFs (eq. (17): four entries for k1, four for k2),
//! so it is stored as a list of entries and applied without ever forming the N x N matrix.

use faer::Mat;

/// A symmetric matrix stored as its entries `(row, col, value)`, both triangles listed.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct SparseSym {
    entries: Vec<(usize, usize, f64)>,
}

impl SparseSym {
    /// The zero matrix.
    pub fn zero() -> Self {
        Self::default()
    }

    /// Adds `value` at `(i, j)` and, off the diagonal, at `(j, i)`.
    pub fn add(&mut self, i: usize, j: usize, value: f64) {
        self.entries.push((i, j, value));
        if i != j {
            self.entries.push((j, i, value));
        }
    }

    /// Appends the single entry `(i, j, value)` (the caller lists its mirror).
    pub fn push(&mut self, i: usize, j: usize, value: f64) {
        self.entries.push((i, j, value));
    }

    /// The 2x2 "spring" pattern `value * [[1, -1], [-1, 1]]` between DOFs `a` and `b`.
    pub fn spring(a: usize, b: usize, value: f64) -> Self {
        let mut s = Self::zero();
        s.add(a, a, value);
        s.add(b, b, value);
        s.add(a, b, -value);
        s
    }

    /// Adds the symmetric 4x4 element block `block * scale` on DOFs `base..base + 4`
    /// (zero entries skipped).
    pub fn add_block(&mut self, base: usize, block: &[[f64; 4]; 4], scale: f64) {
        self.add_element(&std::array::from_fn(|i| Some(base + i)), block, scale);
    }

    /// Adds the symmetric 4x4 element block `block * scale` on the DOFs `dofs` (a `None` DOF,
    /// removed by a support, and zero entries skipped).
    pub fn add_element(&mut self, dofs: &[Option<usize>; 4], block: &[[f64; 4]; 4], scale: f64) {
        for (i, row) in block.iter().enumerate() {
            for (j, &v) in row.iter().enumerate().take(i + 1) {
                if let (Some(a), Some(b), true) = (dofs[i], dofs[j], v != 0.0) {
                    self.add(a, b, scale * v);
                }
            }
        }
    }

    /// Appends `scale * other`.
    pub fn extend_scaled(&mut self, other: &SparseSym, scale: f64) {
        self.entries
            .extend(other.entries.iter().map(|&(i, j, v)| (i, j, scale * v)));
    }

    /// Whether the matrix has no entry.
    pub fn is_zero(&self) -> bool {
        self.entries.is_empty()
    }

    /// The listed entries `(row, col, value)`, both triangles.
    pub fn entries(&self) -> &[(usize, usize, f64)] {
        &self.entries
    }

    /// `y = self * x`, written into `y` (overwritten).
    pub fn apply(&self, x: &[f64], y: &mut [f64]) {
        y.fill(0.0);
        for &(i, j, v) in &self.entries {
            y[i] += v * x[j];
        }
    }

    /// The bilinear form `a^T self b`.
    pub fn form(&self, a: &[f64], b: &[f64]) -> f64 {
        self.entries.iter().map(|&(i, j, v)| a[i] * v * b[j]).sum()
    }

    /// Adds `scale * self` into the dense matrix `target`.
    pub fn add_to(&self, target: &mut Mat<f64>, scale: f64) {
        for &(i, j, v) in &self.entries {
            target[(i, j)] += scale * v;
        }
    }

    /// `Y^T self Y` for the columns of `y` (an `n x n` dense matrix).
    pub fn project(&self, y: &Mat<f64>) -> Mat<f64> {
        let n = y.ncols();
        Mat::from_fn(n, n, |s, t| {
            self.entries
                .iter()
                .map(|&(i, j, v)| y[(i, s)] * v * y[(j, t)])
                .sum()
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn spring_pattern_is_symmetric_and_annihilates_equal_motion() {
        let s = SparseSym::spring(1, 3, 2.5);
        let mut dense = Mat::<f64>::zeros(4, 4);
        s.add_to(&mut dense, 1.0);
        for i in 0..4 {
            for j in 0..4 {
                assert_eq!(dense[(i, j)], dense[(j, i)]);
            }
        }
        assert_eq!(dense[(1, 1)], 2.5);
        assert_eq!(dense[(1, 3)], -2.5);
        let mut y = [0.0; 4];
        s.apply(&[7.0, 1.0, -2.0, 1.0], &mut y);
        assert_eq!(y, [0.0; 4]);
        assert_eq!(s.form(&[0.0, 1.0, 0.0, 0.0], &[0.0, 0.0, 0.0, 1.0]), -2.5);
    }

    #[test]
    fn projection_matches_dense_product() {
        let s = SparseSym::spring(0, 2, 3.0);
        let y = Mat::from_fn(3, 2, |i, j| (1 + i + 3 * j) as f64);
        let mut dense = Mat::<f64>::zeros(3, 3);
        s.add_to(&mut dense, 1.0);
        let reference = y.transpose() * &dense * &y;
        let p = s.project(&y);
        for i in 0..2 {
            for j in 0..2 {
                assert_eq!(p[(i, j)], reference[(i, j)]);
            }
        }
    }
}

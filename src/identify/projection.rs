//! Representation of a measured shape on the calculated modal sub-basis, eq. (5), (14), (15):
//! g_r = least-squares solution of Y~ g = y~ over the identified DOFs.
//!
//! The pseudo-inverse P = Y~^+ (n x n_id) is formed once from a thin SVD of Y~, so that every
//! later shape over the same DOFs costs one matrix-vector product (the study engine projects
//! millions of noisy shapes on one P).

use faer::Mat;

use super::system::{LANES, Lanes};

/// Why a shape cannot be projected.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum ProjectionError {
    /// Fewer identified DOFs than basis vectors: g is not determined.
    #[error(
        "{identified} identified DOF(s) cannot determine the {n} components of g (n must not exceed the identified DOFs)"
    )]
    Underdetermined {
        /// Identified DOFs.
        identified: usize,
        /// Basis size n.
        n: usize,
    },
    /// The basis vectors restricted to the identified DOFs are linearly dependent.
    #[error(
        "the {n} basis vectors restricted to the identified DOFs have rank {rank}: measure more DOFs or reduce n"
    )]
    RankDeficient {
        /// Basis size n.
        n: usize,
        /// Numerical rank of Y~.
        rank: usize,
    },
}

/// Relative singular-value threshold below which Y~ is declared rank deficient.
pub const RANK_TOLERANCE: f64 = 1e-12;

/// The pseudo-inverse of the sub-basis over a set of identified DOFs.
#[derive(Debug, Clone)]
pub struct Projector {
    /// Y~^+ column-major (n x n_id): column j at `j * n`.
    pinv: Vec<f64>,
    n: usize,
    condition: f64,
}

impl Projector {
    /// Builds Y~^+ for the sub-basis read at the identified points, Y~ = C Y (points x n).
    pub fn new(yt: &Mat<f64>) -> Result<Self, ProjectionError> {
        let (points, n) = (yt.nrows(), yt.ncols());
        if points < n {
            return Err(ProjectionError::Underdetermined {
                identified: points,
                n,
            });
        }
        let svd = yt
            .thin_svd()
            .map_err(|_| ProjectionError::RankDeficient { n, rank: 0 })?;
        let s = svd.S().column_vector();
        let smax = s[0];
        let rank = (0..n).filter(|&i| s[i] > RANK_TOLERANCE * smax).count();
        if rank < n {
            return Err(ProjectionError::RankDeficient { n, rank });
        }
        let (u, v) = (svd.U(), svd.V());
        // P = V S^-1 U^T, stored column by column.
        let pinv = (0..points)
            .flat_map(|j| (0..n).map(move |i| (i, j)))
            .map(|(i, j)| (0..n).map(|k| v[(i, k)] * u[(j, k)] / s[k]).sum())
            .collect();
        Ok(Self {
            pinv,
            n,
            condition: smax / s[n - 1],
        })
    }

    /// Column `j` of the pseudo-inverse: the derivative of g with respect to the j-th
    /// identified shape element.
    pub fn column(&self, j: usize) -> &[f64] {
        &self.pinv[j * self.n..(j + 1) * self.n]
    }

    /// Condition number of Y~.
    pub fn condition(&self) -> f64 {
        self.condition
    }

    /// [`Projector::project`] for `LANES` shapes at once (`shape[j][l]`, `g[i][l]`), in the
    /// same order of operations: bitwise the same result per lane.
    #[inline]
    pub fn project_lanes(&self, shape: &[Lanes], g: &mut [Lanes]) {
        for gi in g.iter_mut() {
            *gi = [0.0; LANES];
        }
        for (column, yj) in self.pinv.chunks_exact(self.n).zip(shape) {
            for (gi, pij) in g.iter_mut().zip(column) {
                for l in 0..LANES {
                    gi[l] += pij * yj[l];
                }
            }
        }
    }

    /// g = P y~, written into `g` (length n).
    #[inline]
    pub fn project(&self, shape: &[f64], g: &mut [f64]) {
        g.fill(0.0);
        for (column, &yj) in self.pinv.chunks_exact(self.n).zip(shape) {
            for (gi, pij) in g.iter_mut().zip(column) {
                *gi += pij * yj;
            }
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn recovers_coefficients_of_a_shape_in_the_span() {
        let y = Mat::from_fn(6, 3, |i, j| ((i + 1) as f64).powi(j as i32));
        let g_true = [0.5, -2.0, 0.25];
        let dofs = [0, 2, 3, 5];
        let shape: Vec<f64> = dofs
            .iter()
            .map(|&d| (0..3).map(|j| y[(d, j)] * g_true[j]).sum())
            .collect();
        let rows = |dofs: &[usize], y: &Mat<f64>| {
            Mat::from_fn(dofs.len(), y.ncols(), |i, j| y[(dofs[i], j)])
        };
        let p = Projector::new(&rows(&dofs, &y)).unwrap();
        let mut g = [0.0; 3];
        p.project(&shape, &mut g);
        for (a, b) in g.iter().zip(g_true) {
            assert!((a - b).abs() < 1e-12, "{a} vs {b}");
        }
    }

    #[test]
    fn too_few_dofs_or_dependent_columns_are_errors() {
        let y = Mat::from_fn(6, 3, |i, j| ((i + 1) as f64).powi(j as i32));
        assert_eq!(
            Projector::new(&y.subrows(0, 2).to_owned()).unwrap_err(),
            ProjectionError::Underdetermined {
                identified: 2,
                n: 3
            }
        );
        let dependent = Mat::from_fn(6, 2, |i, _| i as f64 + 1.0);
        assert_eq!(
            Projector::new(&dependent.subrows(0, 3).to_owned()).unwrap_err(),
            ProjectionError::RankDeficient { n: 2, rank: 1 }
        );
    }
}

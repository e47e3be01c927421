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

    /// The weighted projection g = (D Y~)^+ D y~, D = diag(1 / sigma_j): the least squares of
    /// the shape weighted by the standard error of each component (the same as [`Self::new`]
    /// when the points are as many as the basis vectors). Its columns are those of
    /// (D Y~)^+ scaled by 1 / sigma_j.
    pub fn weighted(yt: &Mat<f64>, sigma: &[f64]) -> Result<Self, ProjectionError> {
        let scaled = Mat::from_fn(yt.nrows(), yt.ncols(), |i, j| yt[(i, j)] / sigma[i]);
        let mut p = Self::new(&scaled)?;
        for (j, s) in sigma.iter().enumerate() {
            for v in &mut p.pinv[j * p.n..(j + 1) * p.n] {
                *v /= s;
            }
        }
        Ok(p)
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
    ///
    /// The loops run over blocks of four g_i (then two, then one), the sum over j inside and
    /// the lanes innermost: the block is 4 x `LANES` independent accumulators held in vector
    /// registers, with P_ij broadcast, so that the additions of different g_i overlap (one
    /// g_i at a time waits for each addition to finish). The terms of each g_i are still
    /// added in the order of j, as in [`Projector::project`].
    #[inline(always)]
    pub fn project_lanes(&self, shape: &[Lanes], g: &mut [Lanes]) {
        let mut i = 0;
        while i + 4 <= self.n {
            g[i..i + 4].copy_from_slice(&self.block::<4>(i, shape));
            i += 4;
        }
        if i + 2 <= self.n {
            g[i..i + 2].copy_from_slice(&self.block::<2>(i, shape));
            i += 2;
        }
        if i < self.n {
            g[i..i + 1].copy_from_slice(&self.block::<1>(i, shape));
        }
    }

    /// g_i0 .. g_(i0+B) of [`Projector::project_lanes`].
    #[inline(always)]
    fn block<const B: usize>(&self, i0: usize, shape: &[Lanes]) -> [Lanes; B] {
        let mut acc = [[0.0; LANES]; B];
        for (column, yj) in self.pinv.chunks_exact(self.n).zip(shape) {
            let p = &column[i0..i0 + B];
            for b in 0..B {
                for l in 0..LANES {
                    acc[b][l] += p[b] * yj[l];
                }
            }
        }
        acc
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

    /// The weighted projection is the weighted least squares: equal weights change nothing;
    /// a component with a vast standard error is ignored (its corruption does not reach g).
    #[test]
    fn the_weighted_projection_is_weighted_least_squares() {
        let y = Mat::from_fn(6, 3, |i, j| ((i + 1) as f64).powi(j as i32));
        let g_true = [0.5, -2.0, 0.25];
        let mut shape: Vec<f64> = (0..6)
            .map(|d| (0..3).map(|j| y[(d, j)] * g_true[j]).sum())
            .collect();
        let noisy = [0.01, -0.02, 0.015, 0.0, -0.01, 0.02];
        shape.iter_mut().zip(noisy).for_each(|(v, e)| *v += e);
        let (mut plain, mut equal) = ([0.0; 3], [0.0; 3]);
        Projector::new(&y).unwrap().project(&shape, &mut plain);
        Projector::weighted(&y, &[0.3; 6])
            .unwrap()
            .project(&shape, &mut equal);
        for (a, b) in plain.iter().zip(equal) {
            assert!((a - b).abs() < 1e-12 * a.abs().max(1.0), "{a} vs {b}");
        }
        // Corrupt component 4 and give it a standard error of 1e9: g is that of the other five.
        let mut corrupted = shape.clone();
        corrupted[4] += 50.0;
        let mut sigma = [0.01; 6];
        sigma[4] = 1e9;
        let keep = [0, 1, 2, 3, 5];
        let y5 = Mat::from_fn(5, 3, |i, j| y[(keep[i], j)]);
        let shape5: Vec<f64> = keep.iter().map(|&k| shape[k]).collect();
        let (mut five, mut weighted) = ([0.0; 3], [0.0; 3]);
        Projector::new(&y5).unwrap().project(&shape5, &mut five);
        Projector::weighted(&y, &sigma)
            .unwrap()
            .project(&corrupted, &mut weighted);
        for (a, b) in five.iter().zip(weighted) {
            assert!((a - b).abs() < 1e-6 * a.abs().max(1.0), "{a} vs {b}");
        }
    }

    #[test]
    fn lanes_give_bitwise_the_single_projection_for_every_block_size() {
        // n = 1..=7 covers blocks of four, two and one g_i and their mixtures.
        for n in 1..=7 {
            let y = Mat::from_fn(12, n, |i, j| {
                ((i * 7 + j * 3) % 11) as f64 - 4.5 + 0.1 * j as f64
            });
            let p = Projector::new(&y).unwrap();
            let shapes: Vec<Lanes> = (0..12)
                .map(|j| std::array::from_fn(|l| ((j * 13 + l * 5) as f64).sin()))
                .collect();
            let mut g = vec![[0.0; LANES]; n];
            p.project_lanes(&shapes, &mut g);
            for l in 0..LANES {
                let shape: Vec<f64> = shapes.iter().map(|v| v[l]).collect();
                let mut g1 = vec![0.0; n];
                p.project(&shape, &mut g1);
                for i in 0..n {
                    assert_eq!(g1[i].to_bits(), g[i][l].to_bits(), "n {n}, g{i}, lane {l}");
                }
            }
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

//! The feasible region of a least-squares problem's unknowns: linear inequalities c . x + d >= 0
//! (in a calibration, a non-negative mass is c = e_i, d = 0; a sensor whose radius of gyration
//! stays within its bound is G^2 m - J >= 0; a joint stiffness within its rigid limit is
//! -x_j + ln(p_max / p_0) >= 0), kept by the Levenberg-Marquardt iteration of module
//! [`super::lm`] by an active set:
//!
//! - a constraint is active at x when c . x + d <= 0 (to round-off) and the descent direction -g
//!   of the cost / 2 leaves the feasible side (c . g > 0); the step is taken in the null space
//!   of the active constraints, s = Z z with Z an orthonormal basis of that null space
//!   ([`null_space`]; for coordinate constraints, the other coordinate vectors: this freezes
//!   those unknowns and nothing else); clamping a full step instead would stall the iteration
//!   at the bound;
//! - a trial point that violates a constraint is projected back onto the feasible side by
//!   cyclic orthogonal projections onto the violated hyperplanes (for a coordinate constraint,
//!   clamping at its bound -d / c).
//!
//! Fitting inside the plausible range, rather than fitting freely and excluding a fit that
//! oversteps it, keeps an effect whose best plausible size lies on the bound: its fit there is
//! the likelihood the test should judge.
//!
//! Imports: faer only.

use faer::Mat;

/// Largest number of passes of cyclic projections.
const PROJECTION_PASSES: usize = 50;

/// Linear inequalities sum_i c_i x_i + d >= 0 on the unknowns x (module docs).
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Bounds {
    rows: Vec<Vec<(usize, f64)>>,
    /// The offset d of each row.
    offsets: Vec<f64>,
}

impl Bounds {
    /// The homogeneous inequalities sum_i c_i x_i >= 0, each as (unknown, coefficient) pairs.
    pub fn new(rows: Vec<Vec<(usize, f64)>>) -> Self {
        let offsets = vec![0.0; rows.len()];
        Self { rows, offsets }
    }

    /// These inequalities and `lower <= x_i <= upper` (either side infinite: absent).
    pub fn with_interval(mut self, i: usize, lower: f64, upper: f64) -> Self {
        if lower.is_finite() {
            self.rows.push(vec![(i, 1.0)]);
            self.offsets.push(-lower);
        }
        if upper.is_finite() {
            self.rows.push(vec![(i, -1.0)]);
            self.offsets.push(upper);
        }
        self
    }

    fn value(row: &[(usize, f64)], d: f64, x: &[f64]) -> f64 {
        row.iter().map(|&(i, c)| c * x[i]).sum::<f64>() + d
    }

    fn norm(row: &[(usize, f64)]) -> f64 {
        row.iter().map(|&(_, c)| c * c).sum::<f64>().sqrt()
    }

    /// Whether constraint `row` with offset `d` holds at x, within round-off.
    fn holds(row: &[(usize, f64)], d: f64, x: &[f64]) -> bool {
        let scale = row
            .iter()
            .map(|&(i, c)| (c * x[i]).abs())
            .fold(d.abs(), f64::max);
        Self::value(row, d, x) >= -1e-12 * scale
    }

    /// Whether every inequality holds at x (within round-off).
    pub fn feasible(&self, x: &[f64]) -> bool {
        self.rows
            .iter()
            .zip(&self.offsets)
            .all(|(row, &d)| Self::holds(row, d, x))
    }

    /// An orthonormal basis (columns of length n) of the constraints active at x under the
    /// gradient g of chi^2 / 2 (module docs); empty when none is.
    pub fn active_basis(&self, x: &[f64], g: &[f64]) -> Vec<Vec<f64>> {
        let n = x.len();
        let mut basis: Vec<Vec<f64>> = Vec::new();
        for (row, &d) in self.rows.iter().zip(&self.offsets) {
            let at_bound = Self::value(row, d, x) <= 1e-12 * Self::norm(row).max(d.abs());
            if !at_bound || Self::value(row, 0.0, g) <= 0.0 {
                continue;
            }
            let mut v = vec![0.0; n];
            for &(i, c) in row {
                v[i] += c;
            }
            let original = v.iter().map(|a| a * a).sum::<f64>().sqrt();
            // Gram-Schmidt against the basis so far, twice for stability.
            for _ in 0..2 {
                for q in &basis {
                    let d: f64 = q.iter().zip(&v).map(|(a, b)| a * b).sum();
                    for (vi, qi) in v.iter_mut().zip(q) {
                        *vi -= d * qi;
                    }
                }
            }
            let norm = v.iter().map(|a| a * a).sum::<f64>().sqrt();
            if norm > 1e-10 * original {
                basis.push(v.into_iter().map(|a| a / norm).collect());
            }
        }
        basis
    }

    /// x moved onto the feasible side (module docs); None when the projections do not reach it.
    pub fn project(&self, mut x: Vec<f64>) -> Option<Vec<f64>> {
        for _ in 0..PROJECTION_PASSES {
            if self.feasible(&x) {
                return Some(x);
            }
            for (row, &d) in self.rows.iter().zip(&self.offsets) {
                let value = Self::value(row, d, &x);
                if value < 0.0 {
                    if let [(i, c)] = row.as_slice() {
                        // A coordinate bound: clamp exactly.
                        x[*i] = -d / c;
                        continue;
                    }
                    let norm2: f64 = row.iter().map(|&(_, c)| c * c).sum();
                    for &(i, c) in row {
                        x[i] -= value / norm2 * c;
                    }
                }
            }
        }
        self.feasible(&x).then_some(x)
    }
}

/// An orthonormal basis Z (n x (n - k)) of the null space of the k orthonormal vectors `basis`
/// (of length n, as [`Bounds::active_basis`] gives them): the coordinate vectors with `basis`
/// projected out, orthonormalised by Gram-Schmidt with pivoting (at every step the one that
/// kept the most of its length, the lowest index of equals; each chosen vector
/// re-orthogonalised once more). For coordinate vectors in `basis` it is exactly the other
/// coordinate vectors, in ascending order.
pub fn null_space(basis: &[Vec<f64>], n: usize) -> Mat<f64> {
    let dim = n.saturating_sub(basis.len());
    let dot = |a: &[f64], b: &[f64]| a.iter().zip(b).map(|(x, y)| x * y).sum::<f64>();
    let remove = |v: &mut [f64], q: &[f64]| {
        let d = dot(q, v);
        for (vi, qi) in v.iter_mut().zip(q) {
            *vi -= d * qi;
        }
    };
    let mut columns: Vec<Vec<f64>> = (0..n)
        .map(|i| {
            let mut v = vec![0.0; n];
            v[i] = 1.0;
            for q in basis {
                remove(&mut v, q);
            }
            v
        })
        .collect();
    let mut left: Vec<usize> = (0..n).collect();
    let mut chosen: Vec<Vec<f64>> = Vec::new();
    while chosen.len() < dim {
        let norm = |i: usize| dot(&columns[i], &columns[i]).sqrt();
        let Some(at) =
            (0..left.len()).reduce(|a, b| if norm(left[b]) > norm(left[a]) { b } else { a })
        else {
            break;
        };
        let mut v = std::mem::take(&mut columns[left.remove(at)]);
        for q in basis.iter().chain(&chosen) {
            remove(&mut v, q);
        }
        let length = dot(&v, &v).sqrt();
        if length <= 1e-10 {
            break;
        }
        v.iter_mut().for_each(|a| *a /= length);
        for &i in &left {
            remove(&mut columns[i], &v);
        }
        chosen.push(v);
    }
    Mat::from_fn(n, chosen.len(), |i, j| chosen[j][i])
}

#[cfg(test)]
mod tests {
    use super::*;

    /// The cone of a mass and its rotary inertia: m >= 0, J >= 0, 4 m - J >= 0.
    fn cone() -> Bounds {
        Bounds::new(vec![
            vec![(0, 1.0)],
            vec![(1, 1.0)],
            vec![(0, 4.0), (1, -1.0)],
        ])
    }

    #[test]
    fn projection_lands_on_the_violated_face_and_keeps_a_feasible_point() {
        let b = cone();
        assert_eq!(b.project(vec![1.0, 2.0]), Some(vec![1.0, 2.0]));
        // Beyond the slanted face: the orthogonal projection onto 4 m = J.
        let p = b.project(vec![1.0, 5.0]).unwrap();
        assert!((4.0 * p[0] - p[1]).abs() < 1e-12, "{p:?}");
        // (1, 5) - t (4, -1) with 4 (1 - 4t) = 5 + t: t = -1/17.
        assert!((p[0] - (1.0 + 4.0 / 17.0)).abs() < 1e-12, "{p:?}");
        // Negative mass with an inertia: ends at the apex or on a face, feasible.
        let q = b.project(vec![-1.0, 0.5]).unwrap();
        assert!(b.feasible(&q), "{q:?}");
        // A coordinate bound clamps exactly.
        assert_eq!(b.project(vec![0.5, -1.0]), Some(vec![0.5, 0.0]));
    }

    /// An interval on one unknown: feasible inside, clamped exactly onto the violated side,
    /// active only where the descent leaves it.
    #[test]
    fn an_interval_clamps_to_its_ends_and_is_active_there() {
        let b = Bounds::new(vec![vec![(1, 1.0)]]).with_interval(0, -2.0, 3.0);
        assert!(b.feasible(&[-2.0, 0.0]) && b.feasible(&[3.0, 1.0]));
        assert!(!b.feasible(&[3.5, 0.0]) && !b.feasible(&[-2.5, 0.0]));
        assert_eq!(b.project(vec![7.0, 1.0]), Some(vec![3.0, 1.0]));
        assert_eq!(b.project(vec![-9.0, -1.0]), Some(vec![-2.0, 0.0]));
        // At the upper end, a gradient pushing further up (g < 0) activates it; down, not.
        assert_eq!(b.active_basis(&[3.0, 1.0], &[-1.0, 0.0]).len(), 1);
        assert!(b.active_basis(&[3.0, 1.0], &[1.0, 0.0]).is_empty());
        assert!(b.active_basis(&[0.0, 1.0], &[-1.0, 0.0]).is_empty());
        // Infinite ends are absent.
        let open = Bounds::default().with_interval(0, f64::NEG_INFINITY, f64::INFINITY);
        assert_eq!(open, Bounds::default());
    }

    #[test]
    fn a_face_is_active_only_where_the_descent_leaves_the_region() {
        let b = cone();
        // On the slanted face; the gradient g = (1, -1) descends towards larger J, smaller m.
        let x = [1.0, 4.0];
        let out = b.active_basis(&x, &[1.0, -1.0]);
        assert_eq!(out.len(), 1);
        let s = 17.0_f64.sqrt();
        assert!((out[0][0] - 4.0 / s).abs() < 1e-15 && (out[0][1] + 1.0 / s).abs() < 1e-15);
        // Descending into the region: nothing active.
        assert!(b.active_basis(&x, &[-1.0, 1.0]).is_empty());
        // At the apex with every face pushing out: at most two independent directions.
        assert_eq!(b.active_basis(&[0.0, 0.0], &[1.0, 1.0]).len(), 2);
    }

    /// The step in the null space stays on the active face and solves the reduced problem.
    #[test]
    fn the_null_space_step_moves_along_the_face() {
        let basis = vec![vec![-4.0 / 17.0_f64.sqrt(), 1.0 / 17.0_f64.sqrt()]];
        let a = [[2.0, 0.5], [0.5, 1.0]];
        let g = [-1.0, 1.0];
        let z = null_space(&basis, 2);
        assert_eq!(z.ncols(), 1);
        let zc = [z[(0, 0)], z[(1, 0)]];
        assert!((basis[0][0] * zc[0] + basis[0][1] * zc[1]).abs() < 1e-15);
        // s = Z (Z^T A Z)^-1 Z^T (-g).
        let zaz: f64 = (0..2)
            .map(|i| (0..2).map(|j| zc[i] * a[i][j] * zc[j]).sum::<f64>())
            .sum();
        let zg = zc[0] * g[0] + zc[1] * g[1];
        let s = [-zg / zaz * zc[0], -zg / zaz * zc[1]];
        // Along the face direction d = (1, 4) / sqrt(17): s = t d, t = -(d.g) / (d.A d).
        let d = [1.0 / 17.0_f64.sqrt(), 4.0 / 17.0_f64.sqrt()];
        let dg = -d[0] + d[1];
        let dad = 2.0 * d[0] * d[0] + 2.0 * 0.5 * d[0] * d[1] + d[1] * d[1];
        let t = -dg / dad;
        assert!((s[0] - t * d[0]).abs() < 1e-12 && (s[1] - t * d[1]).abs() < 1e-12);
        // Coordinate basis: the null space is the other coordinate vectors (bit for bit), so
        // the frozen unknown is exactly still and the others are unchanged.
        let z = null_space(&[vec![1.0, 0.0, 0.0]], 3);
        assert_eq!(z.ncols(), 2);
        let entries: Vec<f64> = (0..3).flat_map(|i| [z[(i, 0)], z[(i, 1)]]).collect();
        assert_eq!(entries, [0.0, 0.0, 1.0, 0.0, 0.0, 1.0]);
        // Nothing active: the identity; everything active: empty.
        assert_eq!(null_space(&[], 2).ncols(), 2);
        assert_eq!(null_space(&[vec![1.0, 0.0], vec![0.0, 1.0]], 2).ncols(), 0);
    }
}

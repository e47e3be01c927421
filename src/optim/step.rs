//! The linear subproblem of one Levenberg-Marquardt iteration (module [`super::lm`]).
//!
//! A problem linearised at x gives its residual r and Jacobian J, or their QR-compressed form
//! directly: the triangle [R g; 0 rho] of [J | -r], so that
//!
//! ```text
//!   cost(x + s) = |r + J s|^2 = |R s - g|^2 + rho^2   (to first order in r).
//! ```
//!
//! With Z an orthonormal basis of the null space of the active constraints (module
//! [`super::bounds`]; Z = I when none is active), the damped step is s = Z z with
//!
//! ```text
//!   min_z |R Z z - g|^2 + mu |D Z z|^2,   D = diag(sqrt(max(|R e_j|^2, DAMPING_FLOOR))),
//! ```
//!
//! Marquardt's column scaling (the column norms of R are those of J), solved by QR of the
//! stacked [R Z; sqrt(mu) D Z] against [g; 0] ([`lstsq::solve`]). In exact arithmetic it is the
//! step of the normal equations Z^T (J^T J + mu diag(J^T J)) Z z = -Z^T J^T r, without squaring
//! the condition of J. The Gauss-Newton decrement -(J^T r) . s, the cost a full Gauss-Newton
//! step would remove, is taken with the tiny damping [`REGULARISATION`] (it keeps a Jacobian
//! with a dependent column finite): for the damped least squares it equals g . (R s).
//!
//! Imports: faer and the modules of `optim`.

use faer::Mat;

use super::bounds::{Bounds, null_space};
use super::lstsq;

/// Floor of the damping diagonal D_j^2 (a column of J of zero norm is still damped).
pub const DAMPING_FLOOR: f64 = 1e-12;
/// Damping of the Gauss-Newton step whose decrement the convergence test measures: the
/// regularisation 1e-12 diag(J^T J) of the normal matrix.
pub const REGULARISATION: f64 = 1e-12;

/// A problem linearised at a point (module docs).
#[derive(Debug, Clone, PartialEq)]
pub enum Linearisation {
    /// The residuals r and their Jacobian J (one row per residual, one column per unknown):
    /// cost(x + s) = |r + J s|^2 to first order.
    Jacobian {
        /// r, as many as the rows of `jacobian`.
        residual: Vec<f64>,
        /// d r / d x.
        jacobian: Mat<f64>,
    },
    /// The compressed form [R g; 0 rho] (n + 1 columns for n unknowns, R upper triangular):
    /// cost(x + s) = |R s - g|^2 + rho^2 to first order.
    Triangle(Mat<f64>),
}

/// The subproblem at one point (module docs).
pub(crate) struct Subproblem {
    /// R, at most n rows.
    r: Mat<f64>,
    /// g.
    g: Vec<f64>,
    /// D, one per unknown.
    damping: Vec<f64>,
    /// Z; None when no constraint is active.
    null_space: Option<Mat<f64>>,
}

impl Subproblem {
    /// The subproblem of `linearisation` at x under `bounds`.
    pub fn new(linearisation: Linearisation, bounds: &Bounds, x: &[f64]) -> Self {
        let triangle = match linearisation {
            Linearisation::Triangle(t) => t,
            Linearisation::Jacobian { residual, jacobian } => {
                let n = jacobian.ncols();
                let stacked = Mat::from_fn(jacobian.nrows(), n + 1, |i, j| {
                    if j < n {
                        jacobian[(i, j)]
                    } else {
                        -residual[i]
                    }
                });
                lstsq::triangle(stacked.as_ref())
            }
        };
        let n = triangle.ncols().saturating_sub(1);
        let rows = triangle.nrows().min(n);
        let r = Mat::from_fn(rows, n, |i, j| triangle[(i, j)]);
        let g: Vec<f64> = (0..rows).map(|i| triangle[(i, n)]).collect();
        let damping = (0..n)
            .map(|j| {
                let squared = (0..rows).map(|i| r[(i, j)].powi(2)).sum::<f64>();
                squared.max(DAMPING_FLOOR).sqrt()
            })
            .collect();
        // The gradient of cost / 2, J^T r = -R^T g, decides which constraints are active.
        let gradient: Vec<f64> = (0..n)
            .map(|j| -(0..rows).map(|i| r[(i, j)] * g[i]).sum::<f64>())
            .collect();
        let active = bounds.active_basis(x, &gradient);
        let null_space = (!active.is_empty()).then(|| null_space(&active, n));
        Subproblem {
            r,
            g,
            damping,
            null_space,
        }
    }

    /// The damped step s for damping mu (module docs).
    pub fn step(&self, mu: f64) -> Vec<f64> {
        let (rows, n) = (self.r.nrows(), self.r.ncols());
        let root = mu.sqrt();
        let (a, cols) = match &self.null_space {
            None => {
                let mut a = Mat::<f64>::zeros(rows + n, n);
                for i in 0..rows {
                    for j in 0..n {
                        a[(i, j)] = self.r[(i, j)];
                    }
                }
                for j in 0..n {
                    a[(rows + j, j)] = root * self.damping[j];
                }
                (a, n)
            }
            Some(z) => {
                let rz = &self.r * z;
                let cols = z.ncols();
                let a = Mat::from_fn(rows + n, cols, |i, j| {
                    if i < rows {
                        rz[(i, j)]
                    } else {
                        root * self.damping[i - rows] * z[(i - rows, j)]
                    }
                });
                (a, cols)
            }
        };
        if cols == 0 {
            return vec![0.0; n];
        }
        let b = Mat::from_fn(rows + n, 1, |i, _| if i < rows { self.g[i] } else { 0.0 });
        let solved = lstsq::solve(a.as_ref(), b.as_ref()).x;
        match &self.null_space {
            None => (0..n).map(|j| solved[(j, 0)]).collect(),
            Some(z) => (0..n)
                .map(|i| (0..cols).map(|j| z[(i, j)] * solved[(j, 0)]).sum())
                .collect(),
        }
    }

    /// What step `s` removes from the cost of the linearised problem:
    /// |g|^2 - |R s - g|^2 = 2 g . (R s) - |R s|^2.
    pub fn predicted(&self, s: &[f64]) -> f64 {
        self.times_r(s)
            .zip(&self.g)
            .map(|(rs, g)| 2.0 * g * rs - rs * rs)
            .sum()
    }

    /// The Gauss-Newton decrement (module docs): what a full step in the null space of the
    /// active constraints would remove from the cost of the linearised problem.
    pub fn decrement(&self) -> f64 {
        let s = self.step(REGULARISATION);
        self.times_r(&s).zip(&self.g).map(|(rs, g)| g * rs).sum()
    }

    /// The rows of R s.
    fn times_r<'s>(&'s self, s: &'s [f64]) -> impl Iterator<Item = f64> + 's {
        (0..self.r.nrows()).map(|i| (0..self.r.ncols()).map(|j| self.r[(i, j)] * s[j]).sum())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    /// J = [[1, 0], [0, 2], [1, 1]], r = (1, -1, 0.5): the damped step of the QR form equals
    /// the solution of the normal equations (J^T J + mu diag(J^T J)) s = -J^T r, for the
    /// Jacobian and for its triangle alike, and the decrement is -(J^T r) . s at mu -> 0.
    #[test]
    fn the_qr_step_solves_the_damped_normal_equations() {
        let j = Mat::from_fn(3, 2, |i, k| [[1.0, 0.0], [0.0, 2.0], [1.0, 1.0]][i][k]);
        let r = vec![1.0, -1.0, 0.5];
        let sub = Subproblem::new(
            Linearisation::Jacobian {
                residual: r.clone(),
                jacobian: j.clone(),
            },
            &Bounds::default(),
            &[0.0, 0.0],
        );
        // J^T J = [[2, 1], [1, 5]], J^T r = (1.5, -1.5).
        let (a, jr) = ([[2.0, 1.0], [1.0, 5.0]], [1.5, -1.5]);
        for mu in [0.0, 1e-3, 0.7, 30.0] {
            let m = [
                [a[0][0] * (1.0 + mu), a[0][1]],
                [a[1][0], a[1][1] * (1.0 + mu)],
            ];
            let det = m[0][0] * m[1][1] - m[0][1] * m[1][0];
            let expected = [
                -(m[1][1] * jr[0] - m[0][1] * jr[1]) / det,
                -(m[0][0] * jr[1] - m[1][0] * jr[0]) / det,
            ];
            let s = sub.step(mu);
            for k in 0..2 {
                assert!(
                    (s[k] - expected[k]).abs() < 1e-14,
                    "mu {mu}: {s:?} vs {expected:?}"
                );
            }
        }
        let newton = sub.step(0.0);
        let decrement = -(jr[0] * newton[0] + jr[1] * newton[1]);
        assert!(
            (sub.decrement() - decrement).abs() < 1e-11,
            "{}",
            sub.decrement()
        );
        // The triangle of [J | -r] gives the same subproblem.
        let stacked = Mat::from_fn(3, 3, |i, k| if k < 2 { j[(i, k)] } else { -r[i] });
        let triangle = lstsq::triangle(stacked.as_ref());
        let compressed = Subproblem::new(
            Linearisation::Triangle(triangle),
            &Bounds::default(),
            &[0.0, 0.0],
        );
        assert_eq!(compressed.step(0.7), sub.step(0.7));
    }

    /// A coordinate bound active at x freezes exactly its unknown; a zero column is damped by
    /// the floor and stays still.
    #[test]
    fn an_active_coordinate_bound_freezes_its_unknown() {
        let j = Mat::from_fn(3, 2, |i, k| [[1.0, 0.0], [0.0, 2.0], [1.0, 1.0]][i][k]);
        // -J^T r = (-1.5, 1.5): the descent lowers x_0, which sits at its bound x_0 >= 0.
        let linearisation = Linearisation::Jacobian {
            residual: vec![1.0, -1.0, 0.5],
            jacobian: j,
        };
        let bounds = Bounds::new(vec![vec![(0, 1.0)]]);
        let s = Subproblem::new(linearisation, &bounds, &[0.0, 1.0]).step(0.0);
        assert_eq!(s[0], 0.0);
        // The reduced problem: min |J e_1 s_1 + r|^2, s_1 = -(J e_1 . r) / |J e_1|^2.
        assert!((s[1] - 1.5 / 5.0).abs() < 1e-15, "{s:?}");
        let zero = Linearisation::Jacobian {
            residual: vec![1.0, 2.0],
            jacobian: Mat::from_fn(2, 2, |i, k| if k == 0 { 1.0 + i as f64 } else { 0.0 }),
        };
        let s = Subproblem::new(zero, &Bounds::default(), &[0.0, 0.0]).step(1e-3);
        assert!(s[1].abs() < 1e-15, "{s:?}");
        assert!((s[0] + 1.0 / (1.0 + 1e-3)).abs() < 1e-14, "{s:?}");
    }
}

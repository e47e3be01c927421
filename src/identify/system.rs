//! The per-mode sensitivity system of eq. (10)-(12), restricted to the retained rows and
//! weighted (eq. (13)).
//!
//! For retained basis index s and parameter i:
//!
//! ```text
//!   S_r(s, i) = beta_r^i(s) = p_i y_s^T (dK/dp_i) Y g_r  -  lambda_r^m p_i y_s^T (dM/dp_i) Y g_r
//!   b_r(s)    = (lambda_r^m - lambda_s) g_r(s)
//! ```
//!
//! The mass term is zero for the joint stiffnesses k1, k2 of the paper; it is there for
//! parameters that carry mass (eq. (4) with M^m = M + sum_i Delta p_i dM/dp_i).
//!
//! The projected blocks p_i y_s^T (dK/dp_i) Y (one row of n per retained s) do not depend on
//! the measured data: they are formed once, and each (S_r, b_r) is then linear in g_r.

use faer::Mat;

use super::weighting::RetainedRows;
use crate::model::Parameter;

/// The retained, weighted sensitivity equations of one mode, ready for any g_r.
#[derive(Debug, Clone)]
pub struct ModeSystem {
    rows: RetainedRows,
    n: usize,
    q: usize,
    /// lambda_s of the retained rows.
    lambda_rows: Vec<f64>,
    /// For parameter i, retained row k, basis column t: p_i y_{s_k}^T dK_i y_t, at
    /// `(i * m + k) * n + t`.
    stiffness: Vec<f64>,
    /// The same with dM_i; `None` when no parameter carries mass.
    mass: Option<Vec<f64>>,
}

impl ModeSystem {
    /// Forms the projected derivative blocks for the sub-basis `y` (N x n), its eigenvalues
    /// `lambdas` (length n) and the retained `rows`.
    pub fn new(y: &Mat<f64>, lambdas: &[f64], params: &[Parameter], rows: RetainedRows) -> Self {
        let n = y.ncols();
        let blocks = |pick: &dyn Fn(&Parameter) -> &crate::model::SparseSym| {
            let mut out = Vec::with_capacity(params.len() * rows.rows.len() * n);
            for p in params {
                let projected = pick(p).project(y);
                for &s in &rows.rows {
                    out.extend((0..n).map(|t| p.value * projected[(s, t)]));
                }
            }
            out
        };
        let stiffness = blocks(&|p| &p.stiffness);
        let mass = params
            .iter()
            .any(|p| !p.mass.is_zero())
            .then(|| blocks(&|p| &p.mass));
        let lambda_rows = rows.rows.iter().map(|&s| lambdas[s]).collect();
        Self {
            n,
            q: params.len(),
            lambda_rows,
            stiffness,
            mass,
            rows,
        }
    }

    /// Number of retained equations m.
    pub fn m(&self) -> usize {
        self.rows.rows.len()
    }

    /// Number of parameters q.
    pub fn q(&self) -> usize {
        self.q
    }

    /// The retained rows and their weights.
    pub fn rows(&self) -> &RetainedRows {
        &self.rows
    }

    /// Writes W S_r (column-major m x q) into `ws` and W b_r into `wb` for the coefficients
    /// `g` (length n) and the measured eigenvalue `lambda_m`.
    pub fn assemble(&self, g: &[f64], lambda_m: f64, ws: &mut [f64], wb: &mut [f64]) {
        let (m, n) = (self.m(), self.n);
        debug_assert!(g.len() == n && ws.len() == m * self.q && wb.len() == m);
        for (k, (&s, &w)) in self.rows.rows.iter().zip(&self.rows.weights).enumerate() {
            wb[k] = w * (lambda_m - self.lambda_rows[k]) * g[s];
        }
        for i in 0..self.q {
            for k in 0..m {
                let at = (i * m + k) * n;
                let mut beta = dot(&self.stiffness[at..at + n], g);
                if let Some(mass) = &self.mass {
                    beta -= lambda_m * dot(&mass[at..at + n], g);
                }
                ws[i * m + k] = self.rows.weights[k] * beta;
            }
        }
    }
}

fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

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
use crate::structure::Parameter;

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
        let blocks = |pick: &dyn Fn(&Parameter) -> &crate::structure::SparseSym| {
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
    /// `g` (length n) and the measured eigenvalue `lambda_m`. Linear in `g`, affine in
    /// `lambda_m`.
    #[inline]
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

/// Number of systems assembled together by [`ModeSystem::assemble_lanes`]: the lanes of the
/// random streams, [`crate::random::LANES`].
pub use crate::random::{LANES, Lanes};

impl ModeSystem {
    /// [`ModeSystem::assemble`] for `LANES` independent data sets at once: `g[t][l]` is g_t of
    /// set l, `ws[i * m + k][l]` and `wb[k][l]` receive its W S_r and W b_r. Each set follows
    /// the same operations in the same order as `assemble`, so the results are bitwise equal;
    /// the lane loops vectorise.
    #[inline(always)]
    pub fn assemble_lanes(
        &self,
        g: &[Lanes],
        lambda_m: &Lanes,
        ws: &mut [Lanes],
        wb: &mut [Lanes],
    ) {
        let m = self.m();
        for (k, (&s, &w)) in self.rows.rows.iter().zip(&self.rows.weights).enumerate() {
            for l in 0..LANES {
                wb[k][l] = w * (lambda_m[l] - self.lambda_rows[k]) * g[s][l];
            }
        }
        // Row r = i m + k of W S; its blocks are rows of `stiffness` (and `mass`), so the
        // dot products run four rows at a time (independent accumulators, each row's terms
        // in the order of the scalar `dot`), then two, then one.
        let rows = self.q * m;
        let mut r = 0;
        while r < rows {
            let len = if r + 4 <= rows {
                self.rows_lanes::<4>(r, g, lambda_m, ws)
            } else if r + 2 <= rows {
                self.rows_lanes::<2>(r, g, lambda_m, ws)
            } else {
                self.rows_lanes::<1>(r, g, lambda_m, ws)
            };
            r += len;
        }
    }

    /// Rows r0 .. r0 + B of W S for [`ModeSystem::assemble_lanes`]; returns B.
    #[inline(always)]
    fn rows_lanes<const B: usize>(
        &self,
        r0: usize,
        g: &[Lanes],
        lambda_m: &Lanes,
        ws: &mut [Lanes],
    ) -> usize {
        let (m, n) = (self.m(), self.n);
        let g = &g[..n];
        let mut beta = dots_lanes::<B>(&self.stiffness[r0 * n..(r0 + B) * n], g);
        if let Some(mass) = &self.mass {
            let d = dots_lanes::<B>(&mass[r0 * n..(r0 + B) * n], g);
            for b in 0..B {
                for l in 0..LANES {
                    beta[b][l] -= lambda_m[l] * d[b][l];
                }
            }
        }
        for b in 0..B {
            let w = self.rows.weights[(r0 + b) % m];
            for l in 0..LANES {
                ws[r0 + b][l] = w * beta[b][l];
            }
        }
        B
    }
}

/// The dot products of the B consecutive rows of length g.len() in `a` with g, per lane.
#[inline(always)]
fn dots_lanes<const B: usize>(a: &[f64], g: &[Lanes]) -> [Lanes; B] {
    let n = g.len();
    let mut out = [[0.0; LANES]; B];
    for (j, gl) in g.iter().enumerate() {
        for b in 0..B {
            let x = a[b * n + j];
            for l in 0..LANES {
                out[b][l] += x * gl[l];
            }
        }
    }
    out
}

#[inline]
fn dot(a: &[f64], b: &[f64]) -> f64 {
    let mut out = 0.0;
    for (x, y) in a.iter().zip(b) {
        out += x * y;
    }
    out
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::identify::{RetainedRows, Weighting};
    use crate::structure::{Parameter, Role, SparseSym};

    #[test]
    fn lanes_give_bitwise_the_single_assembly_with_and_without_mass() {
        let (n_dofs, n) = (6, 5);
        let y = Mat::from_fn(n_dofs, n, |i, j| {
            ((i * 7 + j * 3) % 5) as f64 - 1.5 + 0.1 * j as f64
        });
        let lambdas: Vec<f64> = (0..n).map(|i| (i * i) as f64 * 10.0).collect();
        let mut with_mass = SparseSym::zero();
        with_mass.add(1, 1, 0.25);
        let params = vec![
            Parameter {
                name: "a".into(),
                unit: "",
                value: 3.0,
                stiffness: SparseSym::spring(0, 2, 1.0),
                mass: SparseSym::zero(),
                role: Role::Identified,
            },
            Parameter {
                name: "b".into(),
                unit: "",
                value: 0.5,
                stiffness: SparseSym::spring(3, 4, 1.0),
                mass: with_mass,
                role: Role::Identified,
            },
        ];
        for params in [params[..1].to_vec(), params] {
            let q = params.len();
            let system = ModeSystem::new(
                &y,
                &lambdas,
                &params,
                RetainedRows::select(n, 1, 2, 3, Weighting::Inverse),
            );
            let m = system.m();
            let g: Vec<Lanes> = (0..n)
                .map(|t| std::array::from_fn(|l| (t as f64 + 1.0) * (l as f64 - 3.3)))
                .collect();
            let lambda: Lanes = std::array::from_fn(|l| 35.0 + l as f64);
            let (mut ws, mut wb) = (vec![[0.0; LANES]; m * q], vec![[0.0; LANES]; m]);
            system.assemble_lanes(&g, &lambda, &mut ws, &mut wb);
            for l in 0..LANES {
                let gl: Vec<f64> = g.iter().map(|x| x[l]).collect();
                let (mut s1, mut b1) = (vec![0.0; m * q], vec![0.0; m]);
                system.assemble(&gl, lambda[l], &mut s1, &mut b1);
                for r in 0..m * q {
                    assert_eq!(s1[r].to_bits(), ws[r][l].to_bits());
                }
                for r in 0..m {
                    assert_eq!(b1[r].to_bits(), wb[r][l].to_bits());
                }
            }
        }
    }
}

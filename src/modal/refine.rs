//! Refinement of approximate lowest eigenpairs with accurately computed products K y.
//!
//! Why: in the stiffness matrix of a finely meshed slender structure, the entries are of the
//! element scale EI / h^3 while K y for a low mode is of the scale lambda M y, smaller by up
//! to the condition number (about (L / h)^4 for a beam). K y computed in double precision
//! then carries a round-off of eps |K| |y| per entry, comparable to the signal from a few
//! thousand beam elements on, and so do the Cholesky factor of K - sigma M and every
//! eigenvalue sigma + 1/theta taken from it (scipy's `eigsh` loses the low modes the same
//! way). The stored matrix itself defines its low eigenpairs much better: what is lost is
//! mostly the arithmetic, up to the limit set by the rounding of the stored entries (module
//! docs of [`super::lanczos`], with measured numbers).
//!
//! Method: K y is accumulated in twice the working precision (error-free transformations:
//! Dekker's product and Knuth's sum, the "Dot2" of Ogita, Rump & Oishi, "Accurate sum and
//! dot product", SIAM J. Sci. Comput. 26 (2005)), so that the Rayleigh quotients
//! y^T K y of the stored K are exact to working precision, while the factorised K - sigma M
//! serves only as a preconditioner. One sweep of a block correction (Davidson's method):
//!
//! ```text
//!   R = K Y - M Y Lambda                       (accurate K Y)
//!   D = (K - sigma M)^-1 R, M-orthogonalised against Y
//!   Rayleigh-Ritz of (K, M) on span[Y, D]      (accurate K [Y, D])
//! ```
//!
//! A correction column whose M-norm is below [`NOISE_FLOOR`] may be round-off of the vector
//! itself and stays out of the Rayleigh-Ritz. When the pair's relative residual
//! ||K y - lambda M y|| / ||K y|| stands above [`FLOOR_FACTOR`] times its rounding floor
//! ([`super::residual`]) and still falls, the small correction is subtracted from its vector
//! instead ([`polished`]): on a 3D solid the Lanczos vectors' residuals of 1e-8 come from
//! errors of M-norm 1e-11 along the modes of the largest eigenvalues. Scaled up into the
//! Rayleigh-Ritz instead, those columns would put an eigenvalue of that scale into the
//! projected pencil, whose dense solution then carries an absolute error of eps times it: an
//! earlier version did so, and its low eigenvalues moved by 1e-7 from sweep to sweep, its
//! residuals stalled at 1e-8 or reached their floor by chance, depending on the rounding of
//! the Lanczos vectors. Subtracted, they take the residuals of the 540-DOF lap
//! (`tests/suite/sparse_solver.rs`) from 1e-8 to 1e-10 in one sweep. The refinement stops
//! when no column enters or the Ritz values stop moving.
//!
//! Dependence: the Rayleigh-Ritz gives one pair per M-independent direction of its basis
//! ([`super::pencil`]). Vectors to refine that are nearly dependent (Lanczos vectors of a
//! model whose default shift lies 1e150 beyond its low modes: rank 1 of 10) are an error,
//! [`ModalError::DependentVectors`]; corrections nearly dependent on each other drop out of
//! a sweep, and should the pencil on [Y, D] still have fewer directions than Y (it cannot,
//! Y being M-orthonormal and D M-orthogonal to it, unless the arithmetic broke down), the
//! pairs stay as they stand. An earlier version read p pairs regardless and panicked.
//!
//! Cost: K Y in twice the precision ([`super::accurate`]) is the bulk. Four vectors share one pass over K, the
//! error of each product comes from one fused multiply-add where the processor has it (the
//! same error term as Dekker's product: exact either way, so the same results), and the
//! blocks of columns, products and solves alike, run on rayon's pool.
//!
//! Memory: a sweep holds the pairs (Y, K Y, M Y), the corrections (D, K D, M D) and builds the
//! next pairs from them, nine N x p blocks at most: the Rayleigh-Ritz matrices are formed block
//! by block and the new vectors summed into place ([`Refined`] never joins [Y, D]), the
//! corrections are copied only when some are left out, the products are written
//! into their matrix, four columns of scratch per thread.

use faer::linalg::matmul::matmul;
use faer::sparse::SparseColMatRef;
use faer::{Accum, Mat, Par};

use rayon::prelude::*;

use super::accurate::accurate_block;
use super::pencil::dense_pencil;
use super::residual::{self, Residual};
use super::sparse_llt::SparseLlt;
use super::{ModalError, sparse_mul, sparse_mul_block};

/// Corrections of M-norm below this (for M-normalised vectors) are left out, unless the
/// pair's residual asks for them (see [`refine`]): their content may be the rounding of the
/// vector, whose Rayleigh quotient is of the element scale.
pub const NOISE_FLOOR: f64 = 1e-7;

/// Above this rounding floor the residual of a pair says nothing (a rigid-body mode, K y = 0
/// to round-off; a low mode of a finely meshed beam, whose K has a condition number past
/// 1 / eps): it is not corrected for its residual.
pub const RESOLVABLE: f64 = 1e-6;

/// A wanted pair is corrected while its relative residual exceeds this many times its rounding
/// floor ([`super::residual`]).
pub const FLOOR_FACTOR: f64 = 10.0;

/// A Q, the products accurate ([`super::accurate::accurate_mul`], four columns a pass, with || |A| |q_j| ||
/// of every column) or plain (no bounds), the blocks of four columns on rayon's threads, each
/// written straight into its columns of the product.
pub(super) fn mul_columns(
    a: SparseColMatRef<'_, usize, f64>,
    q: &Mat<f64>,
    accurate: bool,
) -> (Mat<f64>, Vec<f64>) {
    const W: usize = 4;
    let (n, p) = (q.nrows(), q.ncols());
    let col = |j: usize| q.col_as_slice(j);
    let mut product = Mat::<f64>::zeros(n, p);
    let columns: Vec<&mut [f64]> = product
        .as_mut()
        .col_iter_mut()
        .map(|c| {
            c.try_as_col_major_mut()
                .expect("a column of an owned matrix is contiguous")
                .as_slice_mut()
        })
        .collect();
    let mut chunks: Vec<Vec<&mut [f64]>> = Vec::new();
    let mut rest = columns.into_iter();
    loop {
        let chunk: Vec<&mut [f64]> = rest.by_ref().take(W).collect();
        if chunk.is_empty() {
            break;
        }
        chunks.push(chunk);
    }
    let bounds: Vec<Vec<f64>> = chunks
        .into_par_iter()
        .enumerate()
        .map(|(b, target)| {
            let first = b * W;
            let mut bounds = Vec::new();
            match (accurate, <[&mut [f64]; W]>::try_from(target)) {
                (true, Ok(block)) => {
                    let squares =
                        accurate_block::<W>(a, std::array::from_fn(|r| col(first + r)), block);
                    bounds.extend(squares.iter().map(|s| s.sqrt()));
                }
                (true, Err(rest)) => {
                    for (r, y) in rest.into_iter().enumerate() {
                        bounds.push(accurate_block::<1>(a, [col(first + r)], [y])[0].sqrt());
                    }
                }
                (false, Ok(block)) => {
                    sparse_mul_block::<W>(a, std::array::from_fn(|r| col(first + r)), block);
                }
                (false, Err(rest)) => {
                    for (r, y) in rest.into_iter().enumerate() {
                        sparse_mul(a, col(first + r), y);
                    }
                }
            }
            bounds
        })
        .collect();
    (product, bounds.into_iter().flatten().collect())
}

/// Refined pairs.
pub struct Refined {
    /// Ritz values of (K, M), ascending.
    pub values: Vec<f64>,
    /// Ritz vectors, M-orthonormal.
    pub vectors: Mat<f64>,
    /// K Y (accurate products) and M Y of the vectors.
    pub products: (Mat<f64>, Mat<f64>),
    /// An upper bound of || |K| |y| || for every vector (the rounding floor's scale,
    /// [`super::residual`]).
    pub bounds: Vec<f64>,
    /// Correction sweeps done (0: the first Rayleigh-Ritz with accurate products sufficed).
    pub sweeps: usize,
}

impl Refined {
    /// The residual of pair `j` (module docs of [`super::residual`]).
    pub fn residual(&self, j: usize) -> Residual {
        let (ky, my) = (
            self.products.0.col_as_slice(j),
            self.products.1.col_as_slice(j),
        );
        let r: Vec<f64> = ky
            .iter()
            .zip(my)
            .map(|(a, b)| a - self.values[j] * b)
            .collect();
        residual::of_products(ky, &r, self.bounds[j])
    }

    /// Rayleigh-Ritz of (K, M) on the columns of Q, given in blocks (Q_b, K Q_b, M Q_b) with
    /// the bounds of its columns: the lowest `p` pairs. The blocks are never joined: the
    /// Gram matrices are formed block by block and the Ritz vectors summed into their
    /// place (three N x (p + corrections) copies fewer at the refinement's peak).
    ///
    /// The pencil gives one pair per M-independent direction of Q ([`dense_pencil`]), so
    /// fewer than `p` when Q has fewer: then [`ModalError::DependentVectors`], and
    /// [`ModalError::NoConvergence`] when the dense solver fails.
    fn of_blocks(blocks: &[Block<'_>], bounds: &[f64], p: usize) -> Result<Self, ModalError> {
        let widths: Vec<usize> = blocks.iter().map(|b| b.0.ncols()).collect();
        let offsets: Vec<usize> = widths
            .iter()
            .scan(0, |at, w| {
                let o = *at;
                *at += w;
                Some(o)
            })
            .collect();
        let total: usize = widths.iter().sum();
        let (mut a, mut b) = (
            Mat::<f64>::zeros(total, total),
            Mat::<f64>::zeros(total, total),
        );
        // The lower blocks, mirrored: K and M are symmetric.
        for (i, (qi, _, _)) in blocks.iter().enumerate() {
            for (j, (_, kqj, mqj)) in blocks.iter().enumerate().take(i + 1) {
                let (oi, oj, wi, wj) = (offsets[i], offsets[j], widths[i], widths[j]);
                for (gram, product) in [(&mut a, kqj), (&mut b, mqj)] {
                    let block = qi.transpose() * *product;
                    gram.submatrix_mut(oi, oj, wi, wj).copy_from(&block);
                    gram.submatrix_mut(oj, oi, wj, wi)
                        .copy_from(block.transpose());
                }
            }
        }
        let (values, x) = dense_pencil(&a, &b).ok_or(ModalError::NoConvergence)?;
        if x.ncols() < p {
            return Err(ModalError::DependentVectors {
                independent: x.ncols(),
                requested: p,
            });
        }
        let n = blocks[0].0.nrows();
        // sum over the blocks of Q_b x_b, for Q, K Q and M Q.
        // 0: Q, 1: K Q, 2: M Q.
        let combine = |which: usize| {
            let mut out = Mat::<f64>::zeros(n, p);
            for (block, (&o, &w)) in blocks.iter().zip(offsets.iter().zip(&widths)) {
                let part = [block.0, block.1, block.2][which];
                matmul(
                    out.as_mut(),
                    Accum::Add,
                    part.as_ref(),
                    x.submatrix(o, 0, w, p),
                    1.0,
                    Par::Seq,
                );
            }
            out
        };
        // |K| |Q x| <= sum_i |x_i| |K| |q_i|, column by column.
        let bounds = (0..p)
            .map(|j| (0..total).map(|i| x[(i, j)].abs() * bounds[i]).sum())
            .collect();
        Ok(Refined {
            values: values[..p].to_vec(),
            vectors: combine(0),
            products: (combine(1), combine(2)),
            bounds,
            sweeps: 0,
        })
    }
}

/// A block of a basis: its columns Q_b, K Q_b and M Q_b.
type Block<'a> = (&'a Mat<f64>, &'a Mat<f64>, &'a Mat<f64>);

/// Refines the M-orthonormal columns of `y` (the `wanted` lowest first) by block corrections
/// with the factor of K - sigma M, at most `max_sweeps` sweeps. A correction enters the
/// Rayleigh-Ritz while its M-norm is above [`NOISE_FLOOR`]; below it, a wanted pair's
/// correction is subtracted from its vector ([`polished`]) while the pair's relative
/// residual ||K y - lambda M y|| / ||K y|| stands above [`FLOOR_FACTOR`] times its rounding
/// floor ([`super::residual`]), that floor is at most [`RESOLVABLE`], and the residual fell
/// at least twofold in the last sweep. Stops when no correction enters either way, when the
/// last sweep only polished and left every wanted pair at its floor, or when the Ritz values
/// move by less than `tol * (|lambda| + |sigma|)` and none was polished.
///
/// [`ModalError::DependentVectors`] when the columns of `y` are not M-independent (the
/// Rayleigh-Ritz on them cannot give as many pairs); when a sweep's corrections cannot
/// be added (the pencil on [Y, D] gives fewer pairs than Y has, or is not solved), the
/// pairs as they stand, for the caller to judge by their residuals.
#[allow(clippy::too_many_arguments)]
pub fn refine(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    llt: &SparseLlt,
    shift: f64,
    y: Mat<f64>,
    wanted: usize,
    tol: f64,
    max_sweeps: usize,
) -> Result<Refined, ModalError> {
    let p = y.ncols();
    let (ky, bounds) = mul_columns(k, &y, true);
    let (my, _) = mul_columns(m, &y, false);
    let mut block = Refined::of_blocks(&[(&y, &ky, &my)], &bounds, p)?;
    // The block holds its own vectors and products from here.
    drop((y, ky, my));
    let mut last_residual = vec![f64::INFINITY; wanted.min(p)];
    // Whether the last sweep only polished: the corrections of the pairs it left alone were
    // all below the noise floor and stay so.
    let mut only_polished = false;
    for sweep in 1..=max_sweeps {
        let residuals: Vec<Residual> = (0..last_residual.len())
            .map(|j| block.residual(j))
            .collect();
        if only_polished && residuals.iter().all(at_floor) {
            // The polished pairs are at their floor: a sweep would find nothing to do, at the
            // cost of a solve and an M product of every column (0.02 s on the 24k solid).
            return Ok(block);
        }
        let above_floor: Vec<bool> = residuals
            .iter()
            .zip(&last_residual)
            .map(|(r, &last)| !at_floor(r) && r.relative < 0.5 * last)
            .collect();
        for (last, r) in last_residual.iter_mut().zip(&residuals) {
            *last = r.relative;
        }
        let (d, md) = corrections(&block, m, llt);
        let (keep, polish) = chosen(&d, &md, &above_floor);
        if keep.is_empty() && polish.is_empty() {
            block.sweeps = sweep - 1;
            return Ok(block);
        }
        block.sweeps = sweep;
        polished(&mut block, k, (&d, &md), &polish);
        only_polished = keep.is_empty();
        if only_polished {
            continue;
        }
        let (dk, mdk) = selected((d, md), &keep);
        // Y is M-orthonormal and D M-orthogonal to it: the pencil on [Y, D] has Y's p
        // directions at least, unless the arithmetic broke down; then the pairs stay.
        let Ok(next) = extended(&block, k, (&dk, &mdk)) else {
            return Ok(block);
        };
        let moved = (0..p)
            .map(|j| {
                (next.values[j] - block.values[j]).abs() / (block.values[j].abs() + shift.abs())
            })
            .fold(0.0, f64::max);
        block = Refined {
            sweeps: sweep,
            ..next
        };
        if moved <= tol && polish.is_empty() {
            return Ok(block);
        }
    }
    Ok(block)
}

/// Whether a pair's residual is as small as its rounding lets it be, or says nothing (its
/// floor above [`RESOLVABLE`]).
fn at_floor(r: &Residual) -> bool {
    r.floor > RESOLVABLE || r.relative <= FLOOR_FACTOR * r.floor
}

/// D = (K - sigma M)^-1 (K Y - M Y Lambda), M-orthogonalised against Y (twice), and M D.
fn corrections(
    block: &Refined,
    m: SparseColMatRef<'_, usize, f64>,
    llt: &SparseLlt,
) -> (Mat<f64>, Mat<f64>) {
    let (y, (ky, my)) = (&block.vectors, &block.products);
    let mut d = Mat::<f64>::zeros(y.nrows(), y.ncols());
    for (j, &lambda) in block.values.iter().enumerate() {
        let (kc, mc) = (ky.col_as_slice(j), my.col_as_slice(j));
        for ((c, a), b) in d.col_as_slice_mut(j).iter_mut().zip(kc).zip(mc) {
            *c = a - lambda * b;
        }
    }
    llt.solve_columns_in_place(d.as_mut());
    for _ in 0..2 {
        let c = my.transpose() * &d;
        matmul(d.as_mut(), Accum::Add, y, &c, -1.0, Par::Seq);
    }
    let (md, _) = mul_columns(m, &d, false);
    (d, md)
}

/// The corrections that enter the Rayleigh-Ritz (M-norm above [`NOISE_FLOOR`]), and the
/// wanted pairs whose corrections are below it but whose residuals ask for them (`above_floor`):
/// those are subtracted from their vectors as they are ([`polished`]).
fn chosen(d: &Mat<f64>, md: &Mat<f64>, above_floor: &[bool]) -> (Vec<usize>, Vec<usize>) {
    let (mut keep, mut polish) = (Vec::new(), Vec::new());
    for j in 0..d.ncols() {
        let norm = residual::m_norm(d.col_as_slice(j), md.col_as_slice(j));
        if norm > NOISE_FLOOR {
            keep.push(j);
        } else if above_floor.get(j).copied().unwrap_or(false) && norm > 0.0 {
            polish.push(j);
        }
    }
    (keep, polish)
}

/// y_j - d_j for the pairs `which`, with K y_j (accurate) and M y_j updated and each pair's
/// Rayleigh quotient. Why not the Rayleigh-Ritz: such a correction is mostly the error of
/// y_j along the modes of the largest eigenvalues (the residual's share there is 1/lambda_k
/// of the error, the preconditioned correction takes it back whole); scaled up into the
/// projected pencil, it brings an eigenvalue of that scale, and the dense solver's absolute
/// error (eps times the largest eigenvalue) would then swamp the low ones. Subtracted as it
/// is, it removes that error to first order; d_j is M-orthogonal to every pair, so the pairs
/// stay M-orthonormal up to the square of its norm.
fn polished(
    block: &mut Refined,
    k: SparseColMatRef<'_, usize, f64>,
    (d, md): (&Mat<f64>, &Mat<f64>),
    which: &[usize],
) {
    if which.is_empty() {
        return;
    }
    let n = d.nrows();
    let columns = Mat::from_fn(n, which.len(), |i, c| d[(i, which[c])]);
    let (kd, bounds) = mul_columns(k, &columns, true);
    for (c, &j) in which.iter().enumerate() {
        let subtract = |target: &mut Mat<f64>, from: &[f64]| {
            for (t, v) in target.col_as_slice_mut(j).iter_mut().zip(from) {
                *t -= v;
            }
        };
        subtract(&mut block.vectors, columns.col_as_slice(c));
        subtract(&mut block.products.0, kd.col_as_slice(c));
        subtract(&mut block.products.1, md.col_as_slice(j));
        let y = block.vectors.col_as_slice(j);
        let dot = |a: &[f64]| y.iter().zip(a).map(|(u, v)| u * v).sum::<f64>();
        block.values[j] =
            dot(block.products.0.col_as_slice(j)) / dot(block.products.1.col_as_slice(j));
        block.bounds[j] += bounds[c];
    }
}

/// The chosen columns of D and M D; D and M D themselves when every column enters (no copy:
/// they are the largest blocks of a sweep).
fn selected((d, md): (Mat<f64>, Mat<f64>), keep: &[usize]) -> (Mat<f64>, Mat<f64>) {
    if keep.len() == d.ncols() {
        return (d, md);
    }
    let chosen = |a: &Mat<f64>| Mat::from_fn(a.nrows(), keep.len(), |i, c| a[(i, keep[c])]);
    (chosen(&d), chosen(&md))
}

/// Rayleigh-Ritz on [Y, D] (D the chosen corrections, M D their M products).
fn extended(
    block: &Refined,
    k: SparseColMatRef<'_, usize, f64>,
    (d, md): (&Mat<f64>, &Mat<f64>),
) -> Result<Refined, ModalError> {
    let (kd, bounds_d) = mul_columns(k, d, true);
    let bounds: Vec<f64> = block.bounds.iter().chain(&bounds_d).copied().collect();
    let (y, (ky, my)) = (&block.vectors, &block.products);
    Refined::of_blocks(&[(y, ky, my), (d, &kd, md)], &bounds, block.vectors.ncols())
}

#[cfg(test)]
mod tests {
    //! The refinement on the paper's chain (38 DOFs: small enough for the dense solution of
    //! [`crate::modal::ModalSolution`] to be the reference).
    use super::*;
    use crate::modal::ModalSolution;
    use crate::modal::lanczos::REFINE_SWEEPS;
    use crate::modal::shift::factor_shifted;
    use crate::model::fixtures::paper_model;

    /// Starting vectors that are not M-independent (the sixth repeats the fifth; the Lanczos
    /// vectors of a chain with a joint spring of 4.36e158 N m/rad had rank 1 of 10,
    /// `tests/suite/numerics_refused.rs`) are refused with their count. The Rayleigh-Ritz on them has five
    /// pairs; before, the refinement read a sixth and panicked (`col < self.ncols()`).
    #[test]
    fn dependent_starting_vectors_are_refused_not_indexed() {
        let mats = paper_model(1e7, 1e4).assemble();
        let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
        let dense = ModalSolution::solve(&mats).unwrap();
        let (shift, llt) = factor_shifted(k, m, None).unwrap();
        let mut y = dense.vectors().subcols(0, 6).to_owned();
        let fifth = y.col(4).to_owned();
        y.col_mut(5).copy_from(&fifth);
        let refused = refine(k, m, &llt, shift, y, 4, 1e-10, REFINE_SWEEPS).err();
        assert_eq!(
            refused,
            Some(ModalError::DependentVectors {
                independent: 5,
                requested: 6
            })
        );
    }

    /// The normal case: M-orthonormal starting vectors y_j = (v_j + e v_{j+6}) / sqrt(1 + e^2)
    /// (v the dense solution's vectors, e = 1e-4; their Rayleigh quotients are off by 2e-5 to
    /// 2e-4 times the first elastic eigenvalue lambda_3) are refined to the dense pairs: the
    /// elastic eigenvalues within 1e-9 relative (measured 7e-11 and 2e-11, the dense
    /// solution's own round-off), the rigid-body ones within 1e-10 lambda_3 of zero (measured
    /// 1e-12; the dense ones are 8e-10 lambda_3), Y^T M Y = E to 1e-12. Without the sweeps
    /// (`max_sweeps` = 0) they stay off by those 2e-5 to 2e-4.
    #[test]
    fn perturbed_pairs_are_refined_to_the_dense_solution() {
        let mats = paper_model(1e7, 1e4).assemble();
        let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
        let dense = ModalSolution::solve(&mats).unwrap();
        let (shift, llt) = factor_shifted(k, m, None).unwrap();
        let e = 1e-4;
        let v = dense.vectors();
        let y = Mat::from_fn(v.nrows(), 6, |i, j| {
            (v[(i, j)] + e * v[(i, j + 6)]) / (1.0 + e * e).sqrt()
        });
        let refined = refine(k, m, &llt, shift, y, 4, 1e-10, REFINE_SWEEPS)
            .expect("independent vectors are refined");
        assert_eq!(refined.values.len(), 6);
        let first = dense.values()[2];
        for j in 0..2 {
            let (r, d) = (refined.values[j], dense.values()[j]);
            assert!(r.abs() <= 1e-10 * first, "rigid pair {j}: {r} (dense {d})");
        }
        for j in 2..4 {
            let (r, d) = (refined.values[j], dense.values()[j]);
            assert!((r - d).abs() <= 1e-9 * d, "pair {j}: {r} vs {d}");
        }
        let gram = refined.vectors.transpose() * &refined.products.1;
        for i in 0..6 {
            for j in 0..6 {
                let want = if i == j { 1.0 } else { 0.0 };
                assert!((gram[(i, j)] - want).abs() < 1e-12, "Y^T M Y ({i},{j})");
            }
        }
    }
}

//! The reduction basis: built once on the nominal model, extended by blocks of vectors
//! (the static corrections at the start, the enrichment later).
//!
//! The basis of [`build`] holds
//! - the nominal model's lowest pairs Phi (rigid-body modes included);
//! - for every direction (dK, dM) in which the model will move (a joint parameter, a
//!   candidate effect's parameter), the static correction of every wanted elastic mode s,
//!   (K - sigma M)^-1 (dK - lambda_s dM) phi_s: the part of the mode's first derivative that
//!   the other modes of Phi do not carry (the derivative of a pair is Phi's modes plus this
//!   vector, to first order in the shift sigma). Every load is first relieved of what the
//!   nominal modes carry ([`relieve`]). Where a direction touches at most
//!   [`UNIT_SUPPORT`] DOFs (a sensor's mass, a point spring), the static response to a unit
//!   load at each of them instead: it carries the correction of every mode at once, and of
//!   any size of the effect.
//!
//! Why not the whole column space of every dK (residual flexibility, or fixed-interface
//! Craig-Bampton with the interface kept): the joint springs of the 3D laps act on every
//! node pair of the overlap, 861 of them per direction on the 212,562-DOF lap, which would
//! make thousands of basis vectors of N entries each (about 2,600 static solves and 4.4 GB for
//! three springs); the modes' own corrections are 3 x 10 vectors there, and what they miss at
//! parameters far from the nominal ones the residual check finds and the enrichment adds
//! (module docs of [`super`]).

use std::sync::Arc;

use faer::linalg::matmul::matmul;
use faer::{Accum, Mat, MatRef, Par, Side};

use super::super::shift::factor_shifted;
use super::super::sparse_llt::SparseLlt;
use super::super::{ModalError, ModalSolution, sparse_mul};
use crate::structure::columns::Columns;
use crate::structure::reduced::{Precondition, Reduced};
use crate::structure::{SparseSym, Structure};

/// A direction touching at most this many DOFs adds the static response to a unit load at
/// each of them in place of its per-mode corrections.
pub const UNIT_SUPPORT: usize = 48;

/// A new vector whose length, after the basis is taken out of it, is below this fraction of
/// its length before (in the mass norm) adds no direction and is left out.
pub const DEPENDENT: f64 = 1e-6;

/// The basis of the module docs for `structure` at its present parameter values: `nominal`
/// its lowest pairs, `directions` the (dK, dM) the model will move in, `modes` the pairs of
/// `nominal` whose corrections are added; residuals accepted up to `tolerance`. `factor`:
/// the factor of K - sigma M at the eigensolver's default shift of the structure's matrices
/// when the caller has it (the nominal solve's, [`ModalSolution::lowest_of_factored`]: the
/// same factor, not made again: 2.6 s of factorisation and 1 GB on the 212,562-DOF lap of
/// bench/), else made here.
pub fn build(
    structure: &Structure,
    nominal: &ModalSolution,
    factor: Option<Arc<SparseLlt>>,
    directions: &[(&SparseSym, &SparseSym)],
    modes: std::ops::Range<usize>,
    tolerance: f64,
) -> Result<Reduced, ModalError> {
    let n = structure.dof_count();
    let mats = structure.assemble();
    let llt = match factor {
        Some(llt) if llt.dof_count() == n => llt,
        Some(llt) => {
            return Err(ModalError::VectorLength {
                len: llt.dof_count(),
                dofs: n,
            });
        }
        None => Arc::new(factor_shifted(mats.k.as_faer(), mats.m.as_faer(), None)?.1),
    };
    let precondition = Precondition::new(move |x| llt.solve_block_in_place(x));
    let elastic = nominal.values().get(structure.rigid).copied();
    let mut reduced = Reduced {
        base: Arc::clone(&structure.base),
        parameter_count: structure.parameters.len(),
        basis: Columns::empty(n),
        k_basis: Columns::empty(n),
        m_basis: Columns::empty(n),
        k: Mat::zeros(0, 0),
        m: Mat::zeros(0, 0),
        parameters: vec![(Mat::zeros(0, 0), Mat::zeros(0, 0)); structure.parameters.len()],
        scale: elastic.unwrap_or(1.0).max(f64::MIN_POSITIVE),
        tolerance,
        precondition,
        enriched: 0,
    };
    extend(&mut reduced, structure, nominal.vectors().as_ref());
    let mut loads = corrections(nominal, directions, modes);
    relieve(&mut loads, nominal, &mats.m);
    reduced.precondition.apply(loads.as_mut());
    extend(&mut reduced, structure, loads.as_ref());
    Ok(reduced)
}

/// The loads whose static responses [`build`] adds: per direction, unit loads at its DOFs
/// or (dK - lambda_s dM) phi_s for every mode s of `modes`.
fn corrections(
    nominal: &ModalSolution,
    directions: &[(&SparseSym, &SparseSym)],
    modes: std::ops::Range<usize>,
) -> Mat<f64> {
    let n = nominal.dof_count();
    let mut columns: Vec<Vec<f64>> = Vec::new();
    let mut units: Vec<usize> = Vec::new();
    for (dk, dm) in directions {
        let mut touched: Vec<usize> = dk
            .entries()
            .iter()
            .chain(dm.entries())
            .map(|e| e.0)
            .collect();
        touched.sort_unstable();
        touched.dedup();
        if touched.len() <= UNIT_SUPPORT {
            units.extend(touched);
            continue;
        }
        for s in modes.clone().filter(|&s| s < nominal.len()) {
            let phi = nominal.vectors().col_as_slice(s);
            let lambda = nominal.values()[s];
            let (mut kv, mut mv) = (vec![0.0; n], vec![0.0; n]);
            dk.apply(phi, &mut kv);
            dm.apply(phi, &mut mv);
            columns.push(kv.iter().zip(&mv).map(|(k, m)| k - lambda * m).collect());
        }
    }
    units.sort_unstable();
    units.dedup();
    let unit_columns = units.iter().map(|&i| {
        let mut e = vec![0.0; n];
        e[i] = 1.0;
        e
    });
    let columns: Vec<Vec<f64>> = unit_columns.chain(columns).collect();
    Mat::from_fn(n, columns.len(), |i, j| columns[j][i])
}

/// Takes out of every load the part the nominal modes carry, f - M Phi Phi^T f (inertia
/// relief): what is left is balanced by no rigid-body motion and excites the modes above
/// Phi alone, so that its static response is not swamped by 1 / sigma times the rigid-body
/// modes (a unit load at one DOF has a resultant; the shift sigma lies just below zero).
fn relieve(loads: &mut Mat<f64>, nominal: &ModalSolution, m: &crate::structure::SymMatrix) {
    let phi = nominal.vectors();
    let m_phi = apply(m.as_faer(), phi);
    let mut c = Mat::<f64>::zeros(phi.ncols(), loads.ncols());
    matmul(
        c.as_mut(),
        Accum::Replace,
        phi.transpose(),
        loads.as_ref(),
        1.0,
        Par::Seq,
    );
    matmul(
        loads.as_mut(),
        Accum::Add,
        m_phi.as_ref(),
        c.as_ref(),
        -1.0,
        Par::Seq,
    );
}

/// Adds the directions of the columns of `w` that the basis lacks: each made M-orthogonal to
/// the basis (twice), the block M-orthonormalised on its independent directions
/// ([`DEPENDENT`]), the projections of the base matrices and of every parameter's derivative
/// matrices grown by them. Returns the number of columns added.
pub(super) fn extend(reduced: &mut Reduced, structure: &Structure, w: MatRef<'_, f64>) -> usize {
    if w.ncols() == 0 {
        return 0;
    }
    let (kb, mb) = (reduced.base.k.as_faer(), reduced.base.m.as_faer());
    let mut w = w.to_owned();
    let before = mass_norms(mb, &w);
    for _ in 0..2 {
        let c = reduced.m_basis.transpose_times(w.as_ref());
        reduced
            .basis
            .times_into(w.as_mut(), Accum::Add, c.as_ref(), -1.0);
    }
    let w = independent(mb, &w, &before);
    let added = w.ncols();
    if added == 0 {
        return 0;
    }
    let mw = apply(mb, &w);
    let kw = apply(kb, &w);
    let basis = reduced.basis.joined(w);
    let w = basis.last_block();
    let grow = |old: &Mat<f64>, bw: &Mat<f64>| {
        // [V W]^T B W: the new columns (and, by symmetry, rows) of the projection.
        grown(old, &basis.transpose_times(bw.as_ref()))
    };
    reduced.k = grow(&reduced.k, &kw);
    reduced.m = grow(&reduced.m, &mw);
    for (p, (dk, dm)) in structure.parameters.iter().zip(&mut reduced.parameters) {
        *dk = grown(dk, &project_columns(&p.stiffness, &basis, w));
        *dm = grown(dm, &project_columns(&p.mass, &basis, w));
    }
    reduced.k_basis = reduced.k_basis.joined(kw);
    reduced.m_basis = reduced.m_basis.joined(mw);
    reduced.basis = basis;
    added
}

/// sqrt(w_j^T M w_j) of every column.
fn mass_norms(m: faer::sparse::SparseColMatRef<'_, usize, f64>, w: &Mat<f64>) -> Vec<f64> {
    let mw = apply(m, w);
    (0..w.ncols())
        .map(|j| dot(w.col_as_slice(j), mw.col_as_slice(j)).max(0.0).sqrt())
        .collect()
}

/// The M-orthonormal block W T spanning the directions of `w` whose length is above
/// [`DEPENDENT`] of `before` (the columns' lengths before the basis was taken out): the Gram
/// matrix W^T M W scaled by those lengths, its eigenvectors of eigenvalue above DEPENDENT^2.
fn independent(
    m: faer::sparse::SparseColMatRef<'_, usize, f64>,
    w: &Mat<f64>,
    before: &[f64],
) -> Mat<f64> {
    let k = w.ncols();
    let d: Vec<f64> = before
        .iter()
        .map(|&b| {
            if b > 0.0 && b.is_finite() {
                1.0 / b
            } else {
                0.0
            }
        })
        .collect();
    let mw = apply(m, w);
    let gram = Mat::from_fn(k, k, |i, j| {
        let g = 0.5
            * (dot(w.col_as_slice(i), mw.col_as_slice(j))
                + dot(w.col_as_slice(j), mw.col_as_slice(i)));
        d[i] * g * d[j]
    });
    let Ok(evd) = gram.self_adjoint_eigen(Side::Lower) else {
        return Mat::zeros(w.nrows(), 0);
    };
    let kept: Vec<usize> = (0..k)
        .filter(|&i| evd.S()[i] > DEPENDENT * DEPENDENT)
        .collect();
    let t = Mat::from_fn(k, kept.len(), |i, c| {
        d[i] * evd.U()[(i, kept[c])] / evd.S()[kept[c]].sqrt()
    });
    let mut out = Mat::zeros(w.nrows(), kept.len());
    matmul(
        out.as_mut(),
        Accum::Replace,
        w.as_ref(),
        t.as_ref(),
        1.0,
        Par::Seq,
    );
    out
}

/// A x for every column of x (A sparse, both triangles stored).
pub(super) fn apply(a: faer::sparse::SparseColMatRef<'_, usize, f64>, x: &Mat<f64>) -> Mat<f64> {
    let mut out = Mat::zeros(x.nrows(), x.ncols());
    for j in 0..x.ncols() {
        let col = x.col_as_slice(j).to_vec();
        sparse_mul(a, &col, out.col_as_slice_mut(j));
    }
    out
}

/// [V W]^T S W for a derivative matrix S given by its entries.
fn project_columns(s: &SparseSym, basis: &Columns, w: &Mat<f64>) -> Mat<f64> {
    let mut out = Mat::<f64>::zeros(basis.ncols(), w.ncols());
    let mut row = vec![0.0; basis.ncols()];
    for &(i, j, v) in s.entries() {
        let mut read = false;
        for c in 0..w.ncols() {
            let t = v * w[(j, c)];
            if t != 0.0 {
                if !read {
                    basis.row_into(i, &mut row);
                    read = true;
                }
                for (q, b) in row.iter().enumerate() {
                    out[(q, c)] += b * t;
                }
            }
        }
    }
    out
}

/// The symmetric (r + k) x (r + k) matrix with `old` (r x r) in its leading block and `cols`
/// ((r + k) x k) as its last columns and, transposed, its last rows.
fn grown(old: &Mat<f64>, cols: &Mat<f64>) -> Mat<f64> {
    let (r, k) = (old.nrows(), cols.ncols());
    Mat::from_fn(r + k, r + k, |i, j| match (i < r, j < r) {
        (true, true) => old[(i, j)],
        (_, false) => cols[(i, j - r)],
        (false, true) => cols[(j, i - r)],
    })
}

pub(super) fn dot(a: &[f64], b: &[f64]) -> f64 {
    a.iter().zip(b).map(|(x, y)| x * y).sum()
}

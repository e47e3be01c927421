//! The lowest eigenpairs of a large sparse problem K y = lambda M y: shift-invert Lanczos with
//! thick restarts (Krylov-Schur), for models past the reach of the dense solver in
//! [`super`].
//!
//! K is symmetric positive semidefinite (singular for a free-free structure: its rigid-body
//! modes have lambda = 0), M symmetric positive definite; both are given with both triangles
//! stored.
//!
//! Method (Ericsson & Ruhe, "The spectral transformation Lanczos method for the numerical
//! solution of large sparse generalized symmetric eigenvalue problems", Math. Comp. 35 (1980);
//! Stewart, "A Krylov-Schur algorithm for large eigenproblems", SIAM J. Matrix Anal. Appl. 23
//! (2001); Wu & Simon, "Thick-restart Lanczos method for large symmetric eigenvalue problems",
//! SIAM J. Matrix Anal. Appl. 22 (2000)):
//!
//! 1. Shift. sigma < 0, so that K - sigma M is positive definite and is factorised by sparse
//!    Cholesky (faer's supernodal or simplicial factor, under the ordering of the two,
//!    approximate minimum degree or the DOF order, whose factor has fewer entries:
//!    [`super::sparse_llt`]). The default rule:
//!    `sigma = -1e-4 * mean_i(K_ii / M_ii) / N^2`, a unit-free fraction of the stiffness/mass
//!    scale of the mesh (see [`LanczosSettings::shift`] for its reasons and limits); if the factorisation meets a
//!    non-positive pivot (round-off on a near-singular K), |sigma| is multiplied by 100 and the
//!    factorisation repeated, at most [`SHIFT_ATTEMPTS`] times. M is checked positive
//!    definite by its own factorisation. Repeated solves of one structure share what does
//!    not change ([`super::memo`]): the symbolic analyses of a pattern, and the check of an M
//!    already found definite.
//! 2. Lanczos on OP = (K - sigma M)^-1 M, which is self-adjoint in the M-inner product
//!    <a, b> = a^T M b and has the eigenvalues theta = 1 / (lambda - sigma) > 0: the lowest
//!    lambda are the largest theta, well separated. Every new vector is M-orthogonalised
//!    by classical Gram-Schmidt, first against the vectors the recurrence couples it to, then
//!    against the whole basis (a third pass when the second removed more than it left), so
//!    that the basis stays M-orthonormal to round-off; the products M v are kept beside the
//!    basis.
//! 3. Thick restart: when the basis holds `basis_size` vectors, the Ritz pairs of the
//!    projected matrix H = V^T M OP V are computed, the best `keep` Ritz vectors kept, and
//!    the expansion continues from the residual vector (the Krylov-Schur form).
//! 4. A Ritz pair (theta, x) has the shift-invert residual ||OP x - theta x||_M =
//!    |beta * s_last|; when the `count` largest theta all satisfy
//!    ||OP x - theta x||_M <= tol * theta, the Ritz vectors (and [`REFINE_EXTRA`] more) are
//!    refined on the original pencil by [`super::refine`]: Rayleigh-Ritz with K y accumulated
//!    in twice the working precision, corrections preconditioned by the factor of
//!    K - sigma M. The eigenvalues are then Rayleigh quotients of the stored K and M, not
//!    sigma + 1/theta, whose round-off grows with the condition number of K (see below). Each
//!    pair is accepted when its backward error
//!
//!    ```text
//!      eta = ||K y - lambda M y||_2 / ((||K||_1 + |lambda| ||M||_1) ||y||_2) <= tol
//!    ```
//!
//!    (Higham & Higham, "Structured backward error and condition of generalized eigenvalue
//!    problems", SIAM J. Matrix Anal. Appl. 20 (1998); ||.||_1 is the largest column sum, an
//!    upper bound of ||.||_2 for a symmetric matrix), or, when the rounding of the vector
//!    alone leaves more, at most [`FLOOR_FACTOR`] times that (an unreachable tolerance is
//!    not asked for). The refinement corrects each wanted pair until its relative residual
//!    ||K y - lambda M y|| / ||K y|| stands at its rounding floor ([`super::residual`]), which
//!    it reports: on the 3D lap of 2.4e4 DOFs, 1e-4 from the Lanczos vectors, 1e-9 after
//!    one sweep.
//! 5. Stop. Once the Krylov space has converged, a restart would hand the refinement the
//!    same vectors: a pair the refinement cannot accept is an error at once
//!    ([`ModalError::NotConverged`], naming how many pairs converged and the first three
//!    others with their backward error), as is a Krylov space still short of the tolerance
//!    after `max_restarts` restarts (with their shift-invert residual). Before, a
//!    model of 2.3e5 DOFs restarted without end, each restart's refinement accepting 7 of 12
//!    pairs.
//!
//! What limits the accuracy. A small backward error does not make a low eigenvalue accurate:
//! the condition number of a beam's K grows like (L / h)^4, and round-off of the size
//! eps ||K|| moves the lowest eigenvalue by eps lambda_max. Without the refinement, the first
//! elastic frequency of the paper's chain at 2 x 2000 elements (N = 8004) comes out
//! 149.690 Hz instead of 150.0539 (scipy's `eigsh` fails the same way, worse on a cantilever
//! of 1e5 DOFs: docs/benchmarks.md, "Large models"); with it, 150.053849 (1.1e-8 relative). What is left
//! is the rounding of the stored entries of K themselves (each element matrix stored in
//! double precision no longer has the rigid-body motions in its null space exactly): no
//! solver working on the stored K can do better. Measured on that chain, relative error of the
//! first elastic frequency against the continuum: 2e-9 at N = 2004, 4e-9 at 4004, 1.1e-8 at
//! 8004 (elements of 0.1 and 0.15 mm), then 2e-5 at 12004 and 4e-5 at 20004, where the
//! rigid-body pair shows the same rounding as a spurious 0.88 Hz; the result is then the
//! same for every shift from -1e6 to -5e10. On the clamped-free cantilever (no rigid-body
//! modes) the error stays at 1.2e-6 at N = 1e5 (elements of 0.02 mm). The remedy would be
//! an assembly in a deformation basis (K = B^T D B with the element strains B u computed
//! from the DOFs), which the sparse-matrix interface of a structure does not carry.
//!
//! Memory is linear in N: the basis V and M V (N x (basis_size + 1) each) while Lanczos runs,
//! let go before the refinement; the Cholesky factor of the banded or sparse K - sigma M; the
//! refinement's blocks of p = count + REFINE_EXTRA columns: at its peak the pairs and their K,
//! M products (3 N x p), the corrections and their products (3 N x p) and the next pairs (3 N x p)
//! (module docs of [`super::refine`]). On the cantilever of 1e5 DOFs, 20 modes: 241 MB peak for
//! the whole process, 500 MB before these blocks were counted (docs/benchmarks.md).
//!
//! Threads: where `RAYON_NUM_THREADS` allows two, the check of M runs on a thread of its own
//! beside the factorisation of K - sigma M; the refinement's block solves and products with
//! K and M run on rayon's pool; the Lanczos recurrence itself is sequential. The results are
//! the same bits on any number of threads: every block of columns is the same whatever
//! thread runs it. A block Lanczos
//! (four vectors a step, one pass over the factor for the four) was tried and left out: per
//! column a block solve costs a quarter, but the blocks needed 80 operator applications
//! where single vectors need 50, and the block Gram-Schmidt cost more than it saved (the
//! 24k solid 0.51-0.56 s against 0.49-0.50; the 212k lap 11.4 s against 11.9).
//! [`LowestModes::timings`] says where the time went.
//!
//! A limit shared with every single-vector Krylov method: an eigenvalue of exact multiplicity
//! m > 1 shows its further copies only through round-off, after some delay. The rigid-body
//! pair of a free-free structure is found this way (its two eigenvalues are split by
//! round-off); an exactly repeated elastic eigenvalue of a symmetric structure may need a
//! larger `basis_size`.

use std::time::Instant;

use faer::Mat;
use faer::sparse::SparseColMatRef;

use super::krylov::{Krylov, dot};
use super::memo::CHECKED_MASS;
use super::refine::{FLOOR_FACTOR, Refined, refine};
use super::residual::Residual;
pub use super::shift::{SHIFT_ATTEMPTS, default_shift};
use super::shift::{factor_shifted, lower_sum};
use super::sparse_llt::{Ordering, SparseLlt};
use super::{ModalError, beside, fix_sign};

/// Ritz vectors beyond the wanted ones that enter the refinement.
pub const REFINE_EXTRA: usize = 4;

/// Most refinement sweeps.
pub const REFINE_SWEEPS: usize = 10;

/// Settings of [`lowest_modes`].
#[derive(Debug, Clone, PartialEq)]
pub struct LanczosSettings {
    /// The shift sigma (rad^2/s^2), below every wanted eigenvalue and < 0 so that K - sigma M
    /// is positive definite for a semidefinite K. Default `None`: the rule
    /// `sigma = -1e-4 * mean_i(K_ii / M_ii) / N^2`. For a mesh of a continuum, K_ii / M_ii is
    /// the eigenvalue scale of one element, (c / h)^2 (h the element size, c a wave speed),
    /// and the lowest elastic eigenvalue is of order (c / L)^2 = (c / h)^2 / N^(2/d) (d the
    /// number of refined dimensions), so that |sigma| stays below it. For a finely meshed beam
    /// (bending: K_ii / M_ii grows like 1/h^4) the rule gives a |sigma| above the first
    /// elastic eigenvalue (-4.7e10 against 8.9e5 at N = 20004); the refined results do not
    /// depend on it there (module docs), only the number of restarts does. If the
    /// factorisation meets a non-positive pivot, |sigma| grows 100-fold, at most
    /// [`SHIFT_ATTEMPTS`] times. Range: finite, < 0.
    pub shift: Option<f64>,
    /// Convergence tolerance tol of the module docs: the shift-invert residual relative to
    /// theta and the backward error eta. Default 1e-10; range [1e-15, 1e-2].
    pub tolerance: f64,
    /// Most thick restarts before [`ModalError::NotConverged`]. Default 300; at least 1.
    pub max_restarts: usize,
    /// Vectors in the Krylov basis. Default `None`: max(2 count + 1, count + 20), at most N.
    /// Range: count + 1 ..= N (count + 2 at least when N allows).
    pub basis_size: Option<usize>,
}

impl Default for LanczosSettings {
    fn default() -> Self {
        LanczosSettings {
            shift: None,
            tolerance: 1e-10,
            max_restarts: 300,
            basis_size: None,
        }
    }
}

/// The converged pairs and how they were obtained.
#[derive(Debug, Clone)]
pub struct LowestModes {
    /// Eigenvalues lambda, ascending, rad^2/s^2.
    pub values: Vec<f64>,
    /// Eigenvectors as columns (N x count), M-normalised, sign fixed (module docs of
    /// [`super`]).
    pub vectors: Mat<f64>,
    /// Backward error eta of every pair (module docs).
    pub backward_errors: Vec<f64>,
    /// Relative residual ||K y - lambda M y|| / ||K y|| of every pair and its rounding floor
    /// ([`super::residual`]).
    pub residuals: Vec<Residual>,
    /// The shift sigma that was factorised.
    pub shift: f64,
    /// Thick restarts used.
    pub restarts: usize,
    /// Applications of OP (one sparse triangular solve pair each).
    pub operator_applications: usize,
    /// Refinement sweeps ([`super::refine`]).
    pub refinement_sweeps: usize,
    /// Where the time went.
    pub timings: Timings,
}

/// Wall time of the solver's phases, seconds (a report: nothing depends on it).
#[derive(Debug, Clone, Copy, Default, PartialEq)]
pub struct Timings {
    /// The factorisations of M (its check) and of K - sigma M.
    pub factorisation: f64,
    /// The applications of OP: M v and the triangular solves.
    pub solves: f64,
    /// The M-orthogonalisation of the Krylov basis.
    pub orthogonalisation: f64,
    /// The refinement ([`super::refine`]) and the residuals.
    pub refinement: f64,
    /// Everything.
    pub total: f64,
}

/// The `count` lowest eigenpairs of K y = lambda M y (module docs).
pub fn lowest_modes(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    count: usize,
    settings: &LanczosSettings,
) -> Result<LowestModes, ModalError> {
    lowest_modes_factored(k, m, count, settings).map(|(modes, _)| modes)
}

/// As [`lowest_modes`], with the factor of K - sigma M it made (sigma: [`LowestModes::shift`]),
/// for a caller that needs the same factor after the solve (the reduced model's basis,
/// [`super::reduced::basis`]): kept, it is not made twice (on the 212,562-DOF lap of bench/,
/// 1.3e8 entries).
pub fn lowest_modes_factored(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    count: usize,
    settings: &LanczosSettings,
) -> Result<(LowestModes, SparseLlt), ModalError> {
    let started = Instant::now();
    let n = check_problem(k, m, count)?;
    let size = check_settings(settings, count, n)?;
    // The check of M under minimum degree, not the fewest-entries rule of K - sigma M: on
    // the lap of 212,562 DOFs the DOF order fills less (3.3e7 entries against 6.2e7) but
    // factorises 13 times slower (9.5 s against 0.7 s), likely because a solid's consistent
    // M couples each direction only with itself and the three interleave, so that adjacent
    // columns seldom share a pattern. On K - sigma M the DOF order was the faster (2.6 s
    // against 7.5 s). The check runs beside the factorisation of K - sigma M on a second
    // thread (1.0 s of that lap's 4.8 s of factorisations); with one thread, before it.
    let (mass_definite, shifted) = beside(
        || {
            CHECKED_MASS.is_definite(m, || {
                lower_sum(m, None)
                    .and_then(|lower| SparseLlt::from_lower(lower.as_ref(), Ordering::Amd))
                    .is_some()
            })
        },
        || factor_shifted(k, m, settings.shift),
    );
    if !mass_definite {
        return Err(ModalError::MassNotPositiveDefinite);
    }
    let (shift, llt) = shifted?;
    let factorisation = started.elapsed().as_secs_f64();
    let norms = (norm_1(k), norm_1(m));
    let mut krylov = Krylov::new(n, size, m, llt);
    // The Ritz vectors kept by a restart: half the room above the wanted pairs. A basis of N
    // vectors (count = N among them) spans the space and is never restarted.
    let keep = (count + (size - count) / 2).min(size - 1);
    let tol = settings.tolerance;
    for restart in 0..=settings.max_restarts {
        krylov.expand();
        let (theta, s) = krylov.ritz();
        let beta = krylov.beta;
        let shift_invert: Vec<f64> = (0..count)
            .map(|i| (beta * s[(size - 1, i)]).abs() / theta[i])
            .collect();
        let converged = shift_invert.iter().filter(|&&r| r <= tol).count();
        if converged == count || krylov.full() {
            // Rayleigh-Ritz with accurately computed K y (see [`super::refine`]) on the
            // wanted Ritz vectors and a few more, which absorb the next pairs' components.
            // The Krylov space has converged: a restart would hand the refinement the same
            // vectors, so what it cannot accept is an error.
            let refining = Instant::now();
            let extra = (count + REFINE_EXTRA).min(size);
            let start = krylov.basis(&s, extra);
            let (applications, solves, orthogonalisation) =
                (krylov.applications, krylov.solves, krylov.orthogonalisation);
            let llt = krylov.into_factor();
            let refined = refine(k, m, &llt, shift, start, count, tol, REFINE_SWEEPS)?;
            let pairs = ritz_pairs(shift, &refined, count, norms);
            let unconverged: Vec<(usize, f64)> = (0..count)
                .filter(|&j| pairs.backward_errors[j] > acceptance(tol, &pairs, j))
                .map(|j| (j + 1, pairs.backward_errors[j]))
                .collect();
            if unconverged.is_empty() {
                let modes = LowestModes {
                    restarts: restart,
                    operator_applications: applications,
                    refinement_sweeps: refined.sweeps,
                    timings: Timings {
                        factorisation,
                        solves: solves.as_secs_f64(),
                        orthogonalisation: orthogonalisation.as_secs_f64(),
                        refinement: refining.elapsed().as_secs_f64(),
                        total: started.elapsed().as_secs_f64(),
                    },
                    ..pairs
                };
                return Ok((modes, llt));
            }
            return Err(ModalError::NotConverged {
                converged: count - unconverged.len(),
                requested: count,
                restarts: restart,
                stage: "backward error",
                unconverged,
                tolerance: tol,
            });
        }
        if restart == settings.max_restarts {
            return Err(ModalError::NotConverged {
                converged,
                requested: count,
                restarts: restart,
                stage: "residual",
                unconverged: (0..count)
                    .filter(|&j| shift_invert[j] > tol)
                    .map(|j| (j + 1, shift_invert[j]))
                    .collect(),
                tolerance: tol,
            });
        }
        krylov.restart(&theta, &s, keep);
    }
    unreachable!("the loop returns on its last pass")
}

/// The largest backward error pair `j` may have: the tolerance, or [`FLOOR_FACTOR`] times what
/// the rounding of its vector alone leaves (module docs of [`super::residual`]) when that is
/// larger.
fn acceptance(tol: f64, pairs: &LowestModes, j: usize) -> f64 {
    let r = pairs.residuals[j];
    let floor = if r.relative > 0.0 {
        pairs.backward_errors[j] * r.floor / r.relative
    } else {
        0.0
    };
    tol.max(FLOOR_FACTOR * floor)
}

fn check_problem(
    k: SparseColMatRef<'_, usize, f64>,
    m: SparseColMatRef<'_, usize, f64>,
    count: usize,
) -> Result<usize, ModalError> {
    let n = k.nrows();
    if k.ncols() != n || m.nrows() != n || m.ncols() != n {
        return Err(ModalError::ShapeMismatch {
            k: (k.nrows(), k.ncols()),
            m: (m.nrows(), m.ncols()),
        });
    }
    if count == 0 || count > n {
        return Err(ModalError::CountOutOfRange { count, dofs: n });
    }
    if !k.val().iter().chain(m.val()).all(|v| v.is_finite()) {
        return Err(ModalError::NonFinite);
    }
    Ok(n)
}

fn check_settings(s: &LanczosSettings, count: usize, n: usize) -> Result<usize, ModalError> {
    let bad = |name: &'static str, value: f64, allowed: String| ModalError::InvalidSetting {
        name,
        value,
        allowed,
    };
    if let Some(sigma) = s.shift
        && !(sigma.is_finite() && sigma < 0.0)
    {
        return Err(bad("shift", sigma, "finite and < 0 (rad^2/s^2)".into()));
    }
    if !(1e-15..=1e-2).contains(&s.tolerance) {
        return Err(bad("tolerance", s.tolerance, "1e-15 ..= 1e-2".into()));
    }
    if s.max_restarts == 0 {
        return Err(bad("max_restarts", 0.0, "at least 1".into()));
    }
    let smallest = (count + 2).min(n);
    let size = s
        .basis_size
        .unwrap_or((2 * count + 1).max(count + 20))
        .min(n);
    if s.basis_size.is_some_and(|b| b < smallest || b > n) {
        return Err(bad(
            "basis_size",
            size as f64,
            format!("{smallest} ..= {n} (count + 2 ..= N)"),
        ));
    }
    Ok(size.max(smallest))
}

/// ||A||_1, the largest absolute column sum.
fn norm_1(a: SparseColMatRef<'_, usize, f64>) -> f64 {
    (0..a.ncols())
        .map(|j| a.val_of_col(j).iter().map(|v| v.abs()).sum::<f64>())
        .fold(0.0, f64::max)
}

/// The `count` lowest refined pairs (values ascending, vectors M-normalised) with signs
/// fixed, their backward errors and residuals (from the refinement's accurate products).
fn ritz_pairs(
    shift: f64,
    refined: &Refined,
    count: usize,
    (norm_k, norm_m): (f64, f64),
) -> LowestModes {
    let values = refined.values[..count].to_vec();
    let mut vectors = refined.vectors.subcols(0, count).to_owned();
    let residuals: Vec<Residual> = (0..count).map(|j| refined.residual(j)).collect();
    let mut backward_errors = Vec::with_capacity(count);
    for (j, &lambda) in values.iter().enumerate() {
        fix_sign(&mut vectors, j);
        let y = vectors.col_as_slice(j);
        let (ky, my) = (
            refined.products.0.col_as_slice(j),
            refined.products.1.col_as_slice(j),
        );
        let r = ky
            .iter()
            .zip(my)
            .map(|(a, b)| (a - lambda * b).powi(2))
            .sum::<f64>()
            .sqrt();
        backward_errors.push(r / ((norm_k + lambda.abs() * norm_m) * dot(y, y).sqrt()));
    }
    LowestModes {
        values,
        vectors,
        backward_errors,
        residuals,
        shift,
        restarts: 0,
        operator_applications: 0,
        refinement_sweeps: 0,
        timings: Timings::default(),
    }
}

#[cfg(test)]
mod tests {
    //! Refusals of bad input, and the pairs of a problem small enough to be checked against
    //! the dense solver of [`super::super`] (a different method: Cholesky reduction).
    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::fixtures::paper_model;
    use crate::structure::SymMatrix;

    #[test]
    fn lowest_pairs_of_the_paper_model_match_the_dense_solution() {
        let mats = paper_model(1e7, 1e4).assemble();
        let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
        let sparse = lowest_modes(k, m, 8, &LanczosSettings::default()).unwrap();
        let dense = ModalSolution::solve(&mats).unwrap();
        // The dense eigenvalues carry a round-off of a few eps lambda_max; measured difference
        // 7.3e-11 relative on pair 2.
        let lambda_max = dense.values()[dense.len() - 1];
        for i in 2..8 {
            let (s, d) = (sparse.values[i], dense.values()[i]);
            assert!(
                (s - d).abs() < 1e-10 * d.max(1e-4 * lambda_max),
                "pair {i}: {s} vs {d}"
            );
        }
        assert!(sparse.backward_errors.iter().all(|&e| e <= 1e-10));
        assert!(sparse.shift < 0.0);
    }

    #[test]
    fn every_pair_of_the_model_is_answered() {
        // count = N: the Krylov space is the whole space after one expansion (this panicked
        // in the choice of the restart's kept vectors before).
        let mats = paper_model(1e7, 1e4).assemble();
        let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
        let n = mats.size();
        let sparse = lowest_modes(k, m, n, &LanczosSettings::default()).unwrap();
        let dense = ModalSolution::solve(&mats).unwrap();
        assert_eq!(sparse.values.len(), n);
        let lambda_max = dense.values()[n - 1];
        for i in 2..n {
            let (s, d) = (sparse.values[i], dense.values()[i]);
            assert!(
                (s - d).abs() < 1e-10 * d.max(1e-4 * lambda_max),
                "pair {i}: {s} vs {d}"
            );
        }
    }

    #[test]
    fn bad_input_is_refused_with_the_reason() {
        let mats = paper_model(1e7, 1e4).assemble();
        let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
        let n = mats.size();
        let with = |s: LanczosSettings| lowest_modes(k, m, 4, &s).unwrap_err();
        assert!(matches!(
            with(LanczosSettings {
                shift: Some(1.0),
                ..Default::default()
            }),
            ModalError::InvalidSetting { name: "shift", .. }
        ));
        assert!(matches!(
            with(LanczosSettings {
                tolerance: 0.5,
                ..Default::default()
            }),
            ModalError::InvalidSetting {
                name: "tolerance",
                ..
            }
        ));
        assert!(matches!(
            with(LanczosSettings {
                basis_size: Some(5),
                ..Default::default()
            }),
            ModalError::InvalidSetting {
                name: "basis_size",
                ..
            }
        ));
        assert_eq!(
            lowest_modes(k, m, n + 1, &LanczosSettings::default()).unwrap_err(),
            ModalError::CountOutOfRange {
                count: n + 1,
                dofs: n
            }
        );
        let small = SymMatrix::from_entries(2, &[(0, 0, 1.0), (1, 1, 1.0)]);
        assert!(matches!(
            lowest_modes(k, small.as_faer(), 1, &LanczosSettings::default()).unwrap_err(),
            ModalError::ShapeMismatch { .. }
        ));
        let massless = SymMatrix::from_entries(2, &[(0, 0, 1.0), (1, 1, 0.0)]);
        assert_eq!(
            lowest_modes(
                small.as_faer(),
                massless.as_faer(),
                1,
                &LanczosSettings::default()
            )
            .unwrap_err(),
            ModalError::MassNotPositiveDefinite
        );
        let nan = SymMatrix::from_entries(2, &[(0, 0, f64::NAN), (1, 1, 1.0)]);
        assert_eq!(
            lowest_modes(
                nan.as_faer(),
                small.as_faer(),
                1,
                &LanczosSettings::default()
            )
            .unwrap_err(),
            ModalError::NonFinite
        );
    }
}

//! Whether a modal solution is that of an elastic structure: the first deformable eigenvalue
//! must stand above the solver's zero, else the structure is a mechanism (it moves without
//! deforming more ways than its rigid-body count says) or so ill scaled (stiffness-to-mass
//! ratios spanning many orders of magnitude, values that overflow) that double precision
//! cannot resolve its modes. Either way no frequency of zero and no NaN leaves the solver.

use super::{DENSE_MAX_DOFS, ModalSolution};
use crate::structure::Matrices;

/// A structure whose first deformable eigenvalue is zero to round-off (or not a number): it
/// moves without deforming more ways than its rigid-body count says, or it is ill scaled.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
#[error("{}", self.describe())]
pub struct Mechanism {
    /// The deformable mode (1-based).
    pub mode: usize,
    /// Its computed frequency, Hz (NaN when the solution is not finite).
    pub frequency_hz: f64,
    /// How many times the largest stiffness-to-mass ratio K_ii / M_ii exceeds the smallest
    /// (infinite when K or M overflow).
    pub spread: f64,
}

/// Above this spread of K_ii / M_ii a zero deformable eigenvalue is blamed on the scaling:
/// a mechanism in a well-scaled model spreads by a few orders of magnitude at most.
pub const ILL_SCALED_SPREAD: f64 = 1e6;

impl Mechanism {
    fn describe(&self) -> String {
        if !self.frequency_hz.is_finite() || !self.spread.is_finite() {
            return format!(
                "deformable mode {} has no finite frequency: the model is ill scaled (a stiffness or mass so large or so small that the matrices or their eigenvalues overflow double precision); check the values and their units",
                self.mode
            );
        }
        if self.spread > ILL_SCALED_SPREAD {
            return format!(
                "deformable mode {} has frequency {:.3e} Hz, at the round-off level of zero, and the model's stiffness-to-mass ratios K_ii/M_ii span a factor {:.1e}: the model is ill scaled (a value off by orders of magnitude, such as a Young's modulus in the wrong unit), and double precision cannot resolve its modes; check the values and their units",
                self.mode, self.frequency_hz, self.spread
            );
        }
        format!(
            "deformable mode {} has frequency {:.3e} Hz, at the round-off level of zero: the structure is a mechanism (a joint or support stiffness too small for the rest of the model, or all stiffness removed somewhere)",
            self.mode, self.frequency_hz
        )
    }
}

/// The largest K_ii / M_ii over the smallest, over the DOFs with positive stiffness and mass
/// (infinite when K or M holds a value that is not finite).
fn spread(matrices: &Matrices) -> f64 {
    if !matrices.k.is_finite() || !matrices.m.is_finite() {
        return f64::INFINITY;
    }
    let ratios = matrices
        .k
        .diagonal()
        .into_iter()
        .zip(matrices.m.diagonal())
        .filter(|(k, m)| *k > 0.0 && *m > 0.0)
        .map(|(k, m)| k / m);
    let (lo, hi) = ratios.fold((f64::INFINITY, 0.0_f64), |(lo, hi), r| {
        (lo.min(r), hi.max(r))
    });
    if hi > 0.0 { hi / lo } else { 1.0 }
}

/// How far above the computed rigid-body eigenvalues (the sparse solver's zero) the first
/// deformable one must stand.
const RIGID_MARGIN: f64 = 1e2;

/// Checks that the first deformable eigenvalue of `modal` (the solution of `matrices`, with
/// `rigid` rigid-body modes first) stands above the solver's zero: for the dense solve of a
/// small model, the round-off level [`Matrices::zero_eigenvalue_level`]; for the sparse
/// solver of a large one, whose low eigenvalues are accurate relative to themselves,
/// `RIGID_MARGIN` times the largest computed rigid-body eigenvalue. Never at or below 0.
pub fn check_elastic(
    matrices: &Matrices,
    modal: &ModalSolution,
    rigid: usize,
) -> Result<(), Mechanism> {
    let zero = if matrices.size() <= DENSE_MAX_DOFS {
        matrices.zero_eigenvalue_level()
    } else {
        RIGID_MARGIN
            * modal.values()[..rigid.min(modal.len())]
                .iter()
                .fold(0.0, |a: f64, l| a.max(l.abs()))
    };
    let vectors = modal.vectors();
    let finite = zero.is_finite()
        && modal.values().iter().all(|l| l.is_finite())
        && (0..vectors.ncols()).all(|j| (0..vectors.nrows()).all(|i| vectors[(i, j)].is_finite()));
    let above_zero = |lambda: f64| lambda > zero;
    match modal.values().get(rigid) {
        Some(&lambda) if !finite || !above_zero(lambda) => Err(Mechanism {
            mode: 1,
            frequency_hz: if finite {
                modal.frequency_hz(rigid)
            } else {
                f64::NAN
            },
            spread: spread(matrices),
        }),
        _ => Ok(()),
    }
}

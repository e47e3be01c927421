//! Derivatives of eigenpairs with respect to a parameter, by modal expansion over all N pairs
//! (exact for the full basis; Fox & Kapoor, AIAA J. 6 (1968); Nelson's normalisation term):
//!
//! ```text
//!   d lambda_s = y_s^T (dK - lambda_s dM) y_s
//!   d y_s      = sum_{t != s} y_t [y_t^T (dK - lambda_s dM) y_s] / (lambda_s - lambda_t)
//!                - 1/2 y_s (y_s^T dM y_s)
//! ```
//! for M-normalised vectors and a simple eigenvalue lambda_s.
//!
//! [`ModeDerivatives`] is what the fits use: every pair of a small model computed, the
//! expansion above is exact; on the lowest pairs of a large model, the deflated conjugate
//! gradients of [`crate::modal::deflated`] give the part beyond them from the factor of
//! K - sigma M, one factor for every mode; where they fail, Nelson's method
//! ([`crate::modal::nelson`], one LU per mode), and the expansion over the computed pairs last
//! (a repeated eigenvalue, where neither applies). Pairs solved on a reduced model take the
//! reduced model's exact derivatives ([`crate::modal::reduced::derivative`]): no factor, no
//! full matrices. A fit needs the vector derivatives only where its sensors read them:
//! [`ModeDerivatives::read`] takes them through the sensors' functionals, by one adjoint solve
//! per sensor instead of one per parameter where a mode has fewer sensors than parameters.

use std::sync::Arc;

use crate::modal::ModalSolution;
use crate::modal::deflated::{DeflatedModes, Reading};
use crate::modal::nelson::{EigenDerivative, NelsonMode};
use crate::modal::reduced::derivative::derivative;
use crate::modal::sparse_llt::SparseLlt;
use crate::structure::{Matrices, SparseSym};

/// The derivatives of the computed modes with respect to any parameters (module docs).
pub struct ModeDerivatives<'a> {
    mats: Option<&'a Matrices>,
    modal: &'a ModalSolution,
    deflated: Option<DeflatedModes<'a>>,
}

/// d lambda_s and d y_s.
pub type Derivative = (f64, Vec<f64>);

impl<'a> ModeDerivatives<'a> {
    /// The pairs `modal` of `mats`: one sparse Cholesky factorisation when `modal` holds
    /// only the lowest pairs.
    pub fn new(mats: &'a Matrices, modal: &'a ModalSolution) -> Self {
        Self::with(mats, modal, |k, m| DeflatedModes::new(k, m, modal))
    }

    /// As [`ModeDerivatives::new`] for pairs that may have been solved on a reduced model:
    /// `mats` (K and M of the model) is needed only when they were not (the caller assembles
    /// them only then: [`ModeDerivatives::needs_matrices`]).
    pub fn of_solution(mats: Option<&'a Matrices>, modal: &'a ModalSolution) -> Self {
        match mats {
            Some(mats) if modal.reduced().is_none() => Self::new(mats, modal),
            _ => Self {
                mats,
                modal,
                deflated: None,
            },
        }
    }

    /// Whether the derivatives of `modal`'s pairs need the model's full matrices: not for
    /// pairs solved on a reduced model.
    pub fn needs_matrices(modal: &ModalSolution) -> bool {
        modal.reduced().is_none()
    }

    /// As [`ModeDerivatives::of_solution`], with the factor `shared` of
    /// [`ModeDerivatives::factor`] of a model of the same DOFs that differs in its joint as
    /// the preconditioner: no factorisation (a fresh one without `shared`).
    pub fn sharing(
        mats: Option<&'a Matrices>,
        modal: &'a ModalSolution,
        shared: Option<Arc<SparseLlt>>,
    ) -> Self {
        match (mats, shared) {
            (Some(mats), Some(llt)) if modal.reduced().is_none() => {
                Self::with(mats, modal, |k, m| DeflatedModes::sharing(k, m, modal, llt))
            }
            _ => Self::of_solution(mats, modal),
        }
    }

    /// The factor of K - sigma M (none where every pair is computed), for
    /// [`ModeDerivatives::sharing`].
    pub fn factor(&self) -> Option<Arc<SparseLlt>> {
        self.deflated.as_ref().map(DeflatedModes::factor)
    }

    fn with(
        mats: &'a Matrices,
        modal: &'a ModalSolution,
        deflate: impl FnOnce(
            faer::sparse::SparseColMatRef<'a, usize, f64>,
            faer::sparse::SparseColMatRef<'a, usize, f64>,
        ) -> Result<DeflatedModes<'a>, crate::modal::ModalError>,
    ) -> Self {
        let deflated = (modal.len() < modal.dof_count())
            .then(|| deflate(mats.k.as_faer(), mats.m.as_faer()).ok())
            .flatten();
        Self {
            mats: Some(mats),
            modal,
            deflated,
        }
    }

    /// The derivatives of the modes `modes` for each parameter's derivative matrices
    /// (dK, dM): `[mode][parameter]`.
    pub fn of(&self, modes: &[usize], params: &[(&SparseSym, &SparseSym)]) -> Vec<Vec<Derivative>> {
        if let Some(reduced) = self.modal.reduced() {
            return modes
                .iter()
                .map(|&s| {
                    params
                        .iter()
                        .map(|(dk, dm)| {
                            derivative(self.modal, reduced, s, dk, dm)
                                .unwrap_or_else(|_| eigen_derivative(self.modal, s, dk, dm))
                        })
                        .collect()
                })
                .collect();
        }
        let pairs = |d: Vec<EigenDerivative>| d.into_iter().map(|d| (d.value, d.vector)).collect();
        match self.deflated.as_ref().map(|d| d.derivatives(modes, params)) {
            Some(Ok(all)) => all.into_iter().map(pairs).collect(),
            _ => modes.iter().map(|&s| self.of_one(s, params)).collect(),
        }
    }

    /// As [`ModeDerivatives::of`], each vector derivative read through the linear functionals
    /// of its mode (`reads[k]`: the nonzero terms of every c of mode `modes[k]`):
    /// `[mode][parameter]` = (d lambda, c^T d y for every c). By the adjoint solve of
    /// [`DeflatedModes::readings`] where the functionals of every mode are fewer than the
    /// parameters, else from the whole vectors of [`ModeDerivatives::of`].
    pub fn read(
        &self,
        modes: &[usize],
        params: &[(&SparseSym, &SparseSym)],
        reads: &[Vec<&[(usize, f64)]>],
    ) -> Vec<Vec<Reading>> {
        let fewer = reads.iter().all(|r| r.len() < params.len());
        if let Some(Ok(read)) = self
            .deflated
            .as_ref()
            .filter(|_| fewer)
            .map(|d| d.readings(modes, params, reads))
        {
            return read;
        }
        let dot = |c: &[(usize, f64)], v: &[f64]| c.iter().map(|&(d, x)| x * v[d]).sum::<f64>();
        self.of(modes, params)
            .into_iter()
            .zip(reads)
            .map(|(of_mode, r)| {
                of_mode
                    .into_iter()
                    .map(|(value, dy)| (value, r.iter().map(|c| dot(c, &dy)).collect()))
                    .collect()
            })
            .collect()
    }

    /// Mode `s` alone, where the modes together failed: the deflated factor, Nelson's
    /// method, the expansion.
    fn of_one(&self, s: usize, params: &[(&SparseSym, &SparseSym)]) -> Vec<Derivative> {
        if let Some(Ok(mut d)) = self.deflated.as_ref().map(|d| d.derivatives(&[s], params)) {
            return d
                .remove(0)
                .into_iter()
                .map(|d| (d.value, d.vector))
                .collect();
        }
        let nelson = self.deflated.as_ref().zip(self.mats).and_then(|(_, mats)| {
            let y: Vec<f64> = self.modal.vectors().col(s).iter().copied().collect();
            let (k, m) = (mats.k.as_faer(), mats.m.as_faer());
            NelsonMode::new(k, m, self.modal.values()[s], &y).ok()
        });
        params
            .iter()
            .map(
                |(dk, dm)| match nelson.as_ref().map(|n| n.derivative(dk, dm)) {
                    Some(Ok(d)) => (d.value, d.vector),
                    _ => eigen_derivative(self.modal, s, dk, dm),
                },
            )
            .collect()
    }
}

/// d lambda_s and d y_s for the derivative matrices `dk`, `dm` of one parameter.
pub fn eigen_derivative(
    modal: &ModalSolution,
    s: usize,
    dk: &SparseSym,
    dm: &SparseSym,
) -> (f64, Vec<f64>) {
    let y = modal.vectors();
    let n = y.nrows();
    let lambda = modal.values()[s];
    let ys: Vec<f64> = (0..n).map(|i| y[(i, s)]).collect();
    let (mut kv, mut mv) = (vec![0.0; n], vec![0.0; n]);
    dk.apply(&ys, &mut kv);
    dm.apply(&ys, &mut mv);
    let v: Vec<f64> = kv.iter().zip(&mv).map(|(k, m)| k - lambda * m).collect();
    let coefficient = |t: usize| (0..n).map(|i| y[(i, t)] * v[i]).sum::<f64>();
    let d_lambda = coefficient(s);
    let self_term = -0.5 * ys.iter().zip(&mv).map(|(a, b)| a * b).sum::<f64>();
    let mut dy: Vec<f64> = ys.iter().map(|v| self_term * v).collect();
    for t in (0..modal.len()).filter(|&t| t != s) {
        let a = coefficient(t) / (lambda - modal.values()[t]);
        for (i, d) in dy.iter_mut().enumerate() {
            *d += a * y[(i, t)];
        }
    }
    (d_lambda, dy)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::effects::{Configured, EffectContext, by_name};
    use crate::model::fixtures::paper_model;

    /// Against central differences of the eigensolution, for a stiffness parameter (k2 of the
    /// joint) and a mass parameter (the joint mass), at a point with both present. The step is
    /// 1e-3 relative: eigenvalues are accurate to about eps * lambda_max in absolute terms.
    #[test]
    fn eigen_derivatives_match_central_differences() {
        let model = paper_model(1e7, 1e4);
        let nominal = ModalSolution::solve(&model.assemble()).unwrap();
        let ctx = std::sync::Arc::new(EffectContext::new(
            model.clone(),
            &[],
            nominal.frequency_hz(2),
        ));
        let joint_mass = by_name("joint_mass").unwrap();
        let at = |k2: f64, m: f64| {
            let configured = Configured {
                ctx: ctx.clone(),
                structure: paper_model(1e7, k2),
                effects: vec![(joint_mass.clone(), vec![m])],
            };
            ModalSolution::solve(&configured.assemble()).unwrap()
        };
        let (k2, m) = (1.3e4, 0.4);
        let base = at(k2, m);
        let configured = Configured {
            ctx: ctx.clone(),
            structure: paper_model(1e7, k2),
            effects: vec![(joint_mass.clone(), vec![m])],
        };
        let k2_param = &configured.structure.identified()[1];
        let mass_param = &configured.effect_parameters()[0];
        for (param, (plus, minus), h) in [
            (
                k2_param,
                (at(k2 * (1.0 + 1e-3), m), at(k2 * (1.0 - 1e-3), m)),
                k2 * 1e-3,
            ),
            (
                mass_param,
                (at(k2, m * (1.0 + 1e-3)), at(k2, m * (1.0 - 1e-3))),
                m * 1e-3,
            ),
        ] {
            for s in [2, 3, 5] {
                let (dl, dy) = eigen_derivative(&base, s, &param.stiffness, &param.mass);
                let fd_l = (plus.values()[s] - minus.values()[s]) / (2.0 * h);
                assert!(
                    (dl - fd_l).abs() < 1e-5 * dl.abs(),
                    "{}: mode {s}: {dl} vs {fd_l}",
                    param.name
                );
                let scale = dy.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
                for (i, dyi) in dy.iter().enumerate() {
                    let fd = (plus.vectors()[(i, s)] - minus.vectors()[(i, s)]) / (2.0 * h);
                    assert!(
                        (dyi - fd).abs() < 1e-4 * scale,
                        "{}: mode {s}, dof {i}: {dyi} vs {fd}",
                        param.name
                    );
                }
            }
        }
    }

    /// On a model solved sparsely (the 604-DOF chain, 12 pairs), the adjoint readings of
    /// [`ModeDerivatives::read`] (two functionals, three parameters) are the whole vector
    /// derivatives of [`ModeDerivatives::of`] read through the same functionals; with more
    /// functionals than parameters it reads the whole vectors, the same numbers.
    #[test]
    fn readings_are_the_whole_derivatives_read() {
        use crate::model::fixtures::{free_two_bars, k2_and_point_mass};
        let structure = free_two_bars(150);
        let (dk2, point_mass) = k2_and_point_mass(&structure);
        let zero = SparseSym::zero();
        let mats = structure.assemble();
        let modal = ModalSolution::lowest_of(&mats, 12).unwrap();
        assert!(modal.len() < modal.dof_count());
        let derivatives = ModeDerivatives::of_solution(Some(&mats), &modal);
        let params = [(&dk2, &zero), (&zero, &point_mass), (&dk2, &point_mass)];
        let a: Vec<(usize, f64)> = vec![(100, 1.0)];
        let b: Vec<(usize, f64)> = vec![(300, 0.7), (301, 0.01)];
        let modes = [3, 6, 9];
        let whole = derivatives.of(&modes, &params);
        for reads in [vec![&a[..], &b[..]], vec![&a[..], &b[..], &a[..], &b[..]]] {
            let all: Vec<Vec<&[(usize, f64)]>> = modes.iter().map(|_| reads.clone()).collect();
            let got = derivatives.read(&modes, &params, &all);
            for (of_mode, want_mode) in got.iter().zip(&whole) {
                for ((value, read), (want, dy)) in of_mode.iter().zip(want_mode) {
                    assert!((value - want).abs() <= 1e-12 * want.abs());
                    let scale = dy.iter().fold(0.0_f64, |m, v| m.max(v.abs()));
                    for (r, c) in read.iter().zip(&reads) {
                        let w: f64 = c.iter().map(|&(d, x)| x * dy[d]).sum();
                        // Both solves stop at 1e-11 of their right-hand side (measured: 7e-15).
                        assert!((r - w).abs() < 1e-11 * scale, "{r} vs {w}");
                    }
                }
            }
        }
    }
}

//! The range of a joint parameter and the limits it may run to: a limit is an answer (a glued
//! interface is rigid, a monolithic bar's "joint" is rigid), never a refusal.
//!
//! **Range.** A fit keeps every identified parameter p in [FREE s_p, RIGID s_p], s_p the
//! parameter's structural scale: the value at which its stiffness on the DOFs it touches
//! equals the structure's own there, min over those DOFs of K0_ii / |dK/dp_ii| (K0 the
//! structure without its parameters; the mass matrices for a mass parameter). At the rigid end
//! the parameter is [`RIGID`] times stiffer than the stiffest element it joins: its compliance
//! is 1e-3 of one element's, far below what any frequency can show, while K stays within three
//! orders of its own entries (a penalty of 1e20 would ruin the eigenvalues). At the free end it
//! carries [`FREE`] of them: a hinge, a gap. The unknown x = ln(p / p0) is held in that
//! interval by the solver's bounds ([`crate::optim::Bounds::with_interval`]).
//!
//! **Limit.** Where the fitted x has a standard error above [`EXAMINED_SE`] (a factor 1.65),
//! or lies on an end of its range, chi^2 is evaluated with the parameter at each end of the
//! range, every other unknown held but the shape scales (re-solved: they are linear): when
//! an end raises chi^2 by less than 1, the data cannot tell the parameter from that end (the
//! rigid end first). The bound reported is where chi^2 rises by [`BOUND_CHI2`] (3.84: a
//! one-sided 95% bound) above the end's value, found by bisection of ln p between the fit and
//! the other end (the other end itself when chi^2 never rises so far: the data bound nothing).
//! Holding the other unknowns makes the rise at least the profile likelihood's: the bound is
//! on the safe side of the profile's.

use super::{Limit, LimitKind, Problem, chi2, initial_scales};
use crate::diagnose::pairing::Pairing;
use crate::structure::{Parameter, SparseSym, Structure};

/// The rigid end of a parameter's range, in units of its structural scale.
pub const RIGID: f64 = 1e3;
/// The free end of a parameter's range, in units of its structural scale.
pub const FREE: f64 = 1e-8;
/// Standard error of ln p above which a parameter's limits are examined.
pub const EXAMINED_SE: f64 = 0.5;
/// Rise of chi^2 from a limit that sets the one-sided 95% bound.
pub const BOUND_CHI2: f64 = 3.84;
/// Bisection steps of the bound on ln p (a range of 25 to 0.006: the bound to 0.6%).
const BISECTIONS: usize = 12;

/// The structural scale s_p of `parameter` on `structure` (module docs); 1 when it touches
/// nothing the structure stiffens or weighs.
pub fn structural_scale(structure: &Structure, parameter: &Parameter) -> f64 {
    let (own, base) = if parameter.stiffness.is_zero() {
        (&parameter.mass, structure.base.m.diagonal())
    } else {
        (&parameter.stiffness, structure.base.k.diagonal())
    };
    let fallback = base.iter().fold(0.0_f64, |a, b| a.max(b.abs()));
    let scale = diagonal_ratio(own, &base).unwrap_or_else(|| {
        let largest = own.entries().iter().fold(0.0_f64, |a, e| a.max(e.2.abs()));
        if largest > 0.0 {
            fallback / largest
        } else {
            0.0
        }
    });
    if scale.is_finite() && scale > 0.0 {
        scale
    } else {
        1.0
    }
}

/// min over the diagonal entries of `own` of base_ii / |own_ii|, among those where both are
/// nonzero; None when there is none.
fn diagonal_ratio(own: &SparseSym, base: &[f64]) -> Option<f64> {
    let mut diagonal = vec![0.0; base.len()];
    for &(i, j, v) in own.entries() {
        if i == j && i < diagonal.len() {
            diagonal[i] += v;
        }
    }
    diagonal
        .iter()
        .zip(base)
        .filter(|(d, b)| **d != 0.0 && **b != 0.0)
        .map(|(d, b)| (b / d).abs())
        .min_by(f64::total_cmp)
}

/// The interval of x = ln(p / p0) of every identified parameter of `structure`, p0 its value
/// there: [ln(FREE s_p / p0), ln(RIGID s_p / p0)], widened to hold 0 (the start).
pub fn ranges(structure: &Structure) -> Vec<(f64, f64)> {
    structure
        .identified()
        .iter()
        .map(|p| {
            let s = structural_scale(structure, p);
            let p0 = p.value.abs().max(f64::MIN_POSITIVE);
            (
                (FREE * s / p0).ln().min(0.0),
                (RIGID * s / p0).ln().max(0.0),
            )
        })
        .collect()
}

/// The limit of joint unknown `j` at the optimum `x` (chi^2 `at`, standard error `se` of
/// ln p), if the data cannot tell it from one (module docs).
pub(super) fn limit(
    problem: &Problem,
    x: &[f64],
    pairing: &Pairing,
    j: usize,
    at: f64,
    se: f64,
) -> Option<Limit> {
    let (lo, hi) = problem.ranges[j];
    let on_end = x[j] >= hi - 1e-9 || x[j] <= lo + 1e-9;
    if !(se > EXAMINED_SE || on_end) {
        return None;
    }
    let cost = |v: f64| moved(problem, x, pairing, j, v).unwrap_or(f64::INFINITY);
    for (end, other, kind) in [(hi, lo, LimitKind::Rigid), (lo, hi, LimitKind::Free)] {
        let at_end = cost(end);
        if at_end - at.min(at_end) >= 1.0 {
            continue;
        }
        let floor = at.min(at_end);
        // The bound: the x between the fit (or the end) and the other end where chi^2 rises
        // by BOUND_CHI2 above the floor.
        let (mut near, mut far) = (x[j].clamp(lo, hi), other);
        if cost(far) - floor < BOUND_CHI2 {
            near = far;
        } else {
            for _ in 0..BISECTIONS {
                let mid = 0.5 * (near + far);
                if cost(mid) - floor < BOUND_CHI2 {
                    near = mid;
                } else {
                    far = mid;
                }
            }
        }
        return Some(Limit {
            kind,
            bound: problem.joint_p0[j] * near.exp(),
        });
    }
    None
}

/// chi^2 with joint unknown `j` moved to `v`, every other held but the shape scales
/// (re-solved); None when the model has no eigensolution there.
fn moved(problem: &Problem, x: &[f64], pairing: &Pairing, j: usize, v: f64) -> Option<f64> {
    let mut y = x.to_vec();
    y[j] = v;
    let mut configured = problem.configured(&y);
    let modal = problem.modes(&mut configured).ok()?;
    initial_scales(problem, &modal, pairing, &mut y);
    Some(chi2(&problem.evaluate(&y, pairing).ok()?.residual))
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::diagnose::fit::{Calibration, Noise, fit_from, with_limits};
    use crate::diagnose::pairing::PairingRule;
    use crate::modal::ModalSolution;
    use crate::model::effects::EffectContext;
    use crate::model::fixtures::paper_model;
    use crate::optim::Silent;
    use crate::simulate::{Errors, simulate};
    use crate::structure::Observation;
    use crate::study::NoiseKind;
    use std::sync::Arc;

    /// A spring's structural scale is the stiffest diagonal entry of the structure on the DOFs
    /// it joins over its own: the joint's k1 against the beams' translational entries.
    #[test]
    fn the_structural_scale_is_the_structures_own_stiffness_on_the_joints_dofs() {
        let model = paper_model(1e7, 1e4);
        let params = model.identified();
        let k1 = &params[0];
        let base = model.base.k.diagonal();
        let (mut expected, mut found) = (f64::INFINITY, false);
        for &(i, j, v) in k1.stiffness.entries() {
            if i == j && v != 0.0 && base[i] != 0.0 {
                expected = expected.min((base[i] / v).abs());
                found = true;
            }
        }
        assert!(found);
        assert_eq!(structural_scale(&model, k1), expected);
        // The range holds the nominal value and spans free to rigid.
        let ranges = ranges(&model);
        for ((lo, hi), p) in ranges.iter().zip(&params) {
            assert!(*lo < 0.0 && *hi > 0.0, "{lo} {hi}");
            let s = structural_scale(&model, p);
            assert!(((p.value * hi.exp()) / (RIGID * s) - 1.0).abs() < 1e-12);
            assert!(((p.value * lo.exp()) / (FREE * s) - 1.0).abs() < 1e-12);
        }
    }

    /// Data of a rigid joint (k1, k2 1e6 times the nominal), fitted from 1e3 times the nominal
    /// (where the modes pair): the fit runs stiff and stays in its range, and both parameters
    /// are reported at their rigid limit with a finite lower bound below where the fit
    /// stopped; data of the nominal joint, fitted from the nominal, mark no limit.
    #[test]
    fn a_rigid_joint_is_reported_at_its_limit_not_refused() {
        let nominal = paper_model(1e7, 1e4);
        let dofs: Vec<Observation> = (0..38)
            .step_by(2)
            .map(|d| Observation::dof(&nominal.dofs, d))
            .collect();
        let errors = Errors {
            shape: 0.01,
            frequency: 0.001,
            kind: NoiseKind::Gaussian,
            seed: 5,
        };
        let first = ModalSolution::solve(&nominal.assemble())
            .unwrap()
            .frequency_hz(2);
        let ctx = Arc::new(EffectContext::new(nominal.clone(), &dofs, first));
        let calibration = Calibration {
            noise: Noise {
                frequency: 0.001,
                shape: 0.01,
            },
            discrepancy: Default::default(),
            pairing: PairingRule {
                window: 10.0,
                given: Vec::new(),
            },
            shape_floor: 0.02,
            measured_std: false,
        };
        for (truth, rigid, start) in [
            (paper_model(1e13, 1e10), true, 1e3_f64.ln()),
            (nominal.clone(), false, 0.0),
        ] {
            let measured = simulate(&truth, &[], &[1, 2, 3, 4], &dofs, errors).unwrap();
            let fitted = fit_from(
                &ctx,
                &measured,
                &calibration,
                &[],
                &[start, start],
                &mut Silent,
            )
            .unwrap();
            let fitted = with_limits(fitted, &measured, &calibration);
            for ((e, p), (_, hi)) in fitted
                .estimates
                .iter()
                .zip(nominal.identified())
                .zip(ranges(&nominal))
            {
                assert!(
                    e.value > 0.0 && e.value <= p.value * hi.exp() * (1.0 + 1e-9),
                    "{e:?}"
                );
                match (rigid, e.limit) {
                    (true, Some(limit)) => {
                        assert_eq!(limit.kind, LimitKind::Rigid, "{e:?}");
                        assert!(limit.bound > 0.0 && limit.bound < e.value, "{e:?}");
                    }
                    (false, None) => {}
                    _ => panic!("rigid {rigid}: {e:?}"),
                }
            }
        }
    }
}

//! The spread of one mode's corrections for one sensor layout and one set of settings (n, m,
//! W): the measurement noise propagated to first order through the library's own per-mode
//! estimator, eq. (5)-(13) ([`crate::identify::propagation`]).
//!
//! The layout reads the nominal mode (the plan assumes the model is right: the spread of a
//! first-order estimator does not depend on the size of the correction). The noise is the
//! study's: every shape component multiplied by (1 + e) with var(e) = v_s
//! ([`crate::random::NoiseKind::shape_variance`]), the frequency by (1 + eps), std(eps) =
//! sigma_f, so that lambda moves by 2 lambda eps. With J_y = dZ/dy~ and J_l = dZ/dlambda
//! (Z = Delta p / p), the covariance of the relative corrections is
//!
//! ```text
//!   C = J_y diag(v_s y~_j^2) J_y^T + 4 lambda^2 sigma_f^2 J_l J_l^T,
//! ```
//!
//! whose diagonal is the square of what a study's `predicted_std` column divides by p_i.
//! A mode is determinate when the projection exists, its basis vector is in the sub-basis,
//! every parameter's resolution in W S_r reaches [`MIN_RESOLUTION`] (the level below which
//! `identify --select auto` holds a parameter) and every column of W S_r is at least
//! [`UNSEEN`] of the largest. The columns are in relative units (p_i dK/dp_i), so a column
//! that much smaller is a parameter the mode does not see: a symmetric bending mode of a
//! joint at the middle of a symmetric beam does not move it transversally, and its k1 column
//! is round-off (1e-13 of k2's), which the resolution, a measure of angle, does not reveal.

use faer::{Mat, Side};
use serde::Serialize;

use crate::identify::propagation::jacobian;
use crate::identify::{MIN_RESOLUTION, ModeSystem, Projector, condition_number, identifiability};

/// A column of W S_r below this fraction of the largest is a parameter the mode does not see.
pub const UNSEEN: f64 = 1e-6;

/// Why a mode's corrections are not determined by a layout.
#[derive(Debug, Clone, Copy, PartialEq, Eq, Serialize)]
#[serde(rename_all = "snake_case")]
pub enum Status {
    /// Every parameter is determined.
    Determinate,
    /// Fewer sensors than the smallest basis the method allows (rigid-body modes + q).
    TooFewSensors,
    /// The mode's own basis vector is beyond n (n must exceed r + rigid-body modes - 1).
    BeyondBasis,
    /// The basis vectors read at the sensors are dependent: g of eq. (15) is not determined.
    Unprojectable,
    /// W S_r of eq. (13) is rank deficient (a parameter's resolution below the threshold).
    RankDeficient,
}

/// The first-order spread of one determinate mode.
#[derive(Debug, Clone, PartialEq)]
pub struct Propagated {
    /// Covariance of the relative corrections Z_r (q x q, row-major).
    pub covariance: Vec<f64>,
    /// Standard deviation of each Z_r(i) = Delta p_i / p_i.
    pub relative_std: Vec<f64>,
    /// cond(W S_r) at the noise-free point.
    pub condition: f64,
    /// Resolution of every parameter in W S_r.
    pub resolution: Vec<f64>,
}

/// The noise a plan expects, in variances.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Noise {
    /// var(e) of the relative shape error of every component.
    pub shape_variance: f64,
    /// var(eps) of the relative frequency error.
    pub frequency_variance: f64,
}

/// The spread of the mode whose `system` and projector are given, read as `shape` (the mode at
/// the sensors) with eigenvalue `lambda`; the status when it is not determinate.
pub fn propagate(
    projector: &Projector,
    system: &ModeSystem,
    shape: &[f64],
    lambda: f64,
    noise: Noise,
) -> Result<Propagated, Status> {
    let (m, q, n) = (system.m(), system.q(), projector.column(0).len());
    let mut g = vec![0.0; n];
    projector.project(shape, &mut g);
    let (mut ws, mut wb) = (vec![0.0; m * q], vec![0.0; m]);
    system.assemble(&g, lambda, &mut ws, &mut wb);
    let all: Vec<usize> = (0..q).collect();
    let resolution = identifiability::resolution(&ws, m, &all);
    let norms: Vec<f64> = (0..q)
        .map(|i| {
            ws[i * m..(i + 1) * m]
                .iter()
                .map(|x| x * x)
                .sum::<f64>()
                .sqrt()
        })
        .collect();
    let largest = norms.iter().copied().fold(0.0, f64::max);
    if resolution.iter().any(|&r| r < MIN_RESOLUTION) || norms.iter().any(|&n| n < UNSEEN * largest)
    {
        return Err(Status::RankDeficient);
    }
    let jac = jacobian(projector, system, shape, lambda).ok_or(Status::RankDeficient)?;
    let frequency = 4.0 * lambda * lambda * noise.frequency_variance;
    let mut covariance = vec![0.0; q * q];
    for i in 0..q {
        for k in 0..=i {
            let s: f64 = shape
                .iter()
                .enumerate()
                .map(|(j, y)| jac.shape[(i, j)] * jac.shape[(k, j)] * y * y)
                .sum();
            let c = s * noise.shape_variance + frequency * jac.lambda[i] * jac.lambda[k];
            covariance[i * q + k] = c;
            covariance[k * q + i] = c;
        }
    }
    Ok(Propagated {
        relative_std: (0..q).map(|i| covariance[i * q + i].sqrt()).collect(),
        covariance,
        condition: condition_number(&ws, m, q),
        resolution,
    })
}

/// ln det of a symmetric positive definite `q x q` matrix (row-major); -inf when singular.
pub fn log_det(a: &[f64], q: usize) -> f64 {
    let mat = Mat::from_fn(q, q, |i, j| a[i * q + j]);
    match mat.llt(Side::Lower) {
        Ok(llt) => {
            let l = llt.L();
            (0..q).map(|i| 2.0 * l[(i, i)].ln()).sum()
        }
        Err(_) => f64::NEG_INFINITY,
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::identify::{Identifier, Settings, Weighting};
    use crate::modal::ModalSolution;
    use crate::model::fixtures::paper_model;

    /// The propagated standard deviations against central differences of the library's own
    /// estimator (`Identifier::identify`), one perturbed measurement at a time: the two are
    /// independent routes to J Sigma J^T.
    #[test]
    fn propagated_spread_matches_differences_of_the_estimator() {
        use crate::measured::MeasuredMode;
        use crate::structure::Observation;
        let model = paper_model(1e7, 1e4);
        let modal = ModalSolution::solve(&model.assemble()).unwrap();
        let settings = Settings {
            n: 7,
            m: 3,
            weighting: Weighting::Inverse,
        };
        let id = Identifier::for_structure(&model, &modal, settings).unwrap();
        let dofs: Vec<usize> = (0..38).step_by(4).map(|d| d & !1).collect();
        let mut seen: Vec<usize> = Vec::new();
        for &d in &dofs {
            if !seen.contains(&d) {
                seen.push(d);
            }
        }
        let points: Vec<Observation> = seen
            .iter()
            .map(|&d| Observation::dof(&model.dofs, d))
            .collect();
        let yt = Mat::from_fn(seen.len(), 7, |i, j| id.basis()[(seen[i], j)]);
        let projector = Projector::new(&yt).unwrap();
        let noise = Noise {
            shape_variance: 1e-4,
            frequency_variance: 4e-6,
        };
        for mode in 1..=3 {
            let s_r = mode + 1;
            let shape: Vec<f64> = seen.iter().map(|&d| modal.vectors()[(d, s_r)]).collect();
            let lambda = modal.values()[s_r];
            let system = id.mode_system(s_r);
            let got = propagate(&projector, &system, &shape, lambda, noise).unwrap();
            let z = |shape: &[f64], f_scale: f64| {
                let measured = MeasuredMode::new(
                    mode,
                    crate::modal::lambda_to_hz(lambda) * f_scale,
                    points.clone(),
                    shape.to_vec(),
                );
                id.identify(&measured).unwrap().relative.unwrap()
            };
            // Variance of Z_i: the squared difference quotients times each variance.
            let mut var = [0.0; 2];
            let mut add = |a: &[f64], b: &[f64], step: f64, variance: f64| {
                for (v, (x, y)) in var.iter_mut().zip(a.iter().zip(b)) {
                    *v += ((x - y) / (2.0 * step)).powi(2) * variance;
                }
            };
            for j in 0..shape.len() {
                let h = 1e-6 * shape[j].abs().max(1e-12);
                let (mut up, mut down) = (shape.clone(), shape.clone());
                up[j] += h;
                down[j] -= h;
                add(&z(&up, 1.0), &z(&down, 1.0), h, 1e-4 * shape[j] * shape[j]);
            }
            add(&z(&shape, 1.0 + 1e-7), &z(&shape, 1.0 - 1e-7), 1e-7, 4e-6);
            for (i, v) in var.iter().enumerate() {
                let want = v.sqrt();
                let rel = (got.relative_std[i] - want).abs() / want;
                assert!(
                    rel < 1e-4,
                    "mode {mode} p{i}: {} vs {want}",
                    got.relative_std[i]
                );
            }
        }
    }

    #[test]
    fn log_det_of_a_known_matrix() {
        let a = [4.0, 2.0, 2.0, 3.0];
        assert!((log_det(&a, 2) - 8f64.ln()).abs() < 1e-14);
        assert_eq!(log_det(&[1.0, 1.0, 1.0, 1.0], 2), f64::NEG_INFINITY);
    }
}

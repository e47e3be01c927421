//! `support_flexibility`: a clamp or a pin is never rigid. Each motion a rigid support holds
//! (w, theta) gets a compliance c >= 0: the support becomes a grounded spring of stiffness
//! 1 / c on that motion, c = 0 the rigid support of the model.
//!
//! The builder removed the held DOFs, so a compliance cannot be an added spring on the model's
//! DOFs. Instead the held motions u_h follow the free ones statically, which is exact at
//! c = 0 and in statics, and a Rayleigh-Ritz (Guyan) reduction in dynamics whose error is of
//! order (omega / omega_e)^2 of the effect, omega_e the frequencies of the elements at the
//! support. With K_hh, M_hh the beam's stiffness and mass among the held motions, B_K, B_M
//! theirs with the free DOFs, and C = diag(c):
//!
//! ```text
//!   G = (I + C K_hh)^-1 C          (= (K_hh + C^-1)^-1 where C is invertible)
//!   S = -G B_K                      (u_h = S u_f)
//!   dK = -B_K^T G B_K               dM = B_M^T S + S^T B_M + S^T M_hh S
//!   dG/dc_i = (I + C K_hh)^-1 E_i (I - K_hh G)      (E_i = e_i e_i^T)
//! ```
//!
//! all smooth at c = 0, where dK = dM = 0. Masses and springs attached at the support itself
//! are left out (a rigid support holds them still; a flexible one moves them by S u_f, whose
//! energy is of second order in S). A support at a joint holds both joint nodes and stays
//! rigid. Size: the mean of the compliances relative to the beam's, c EI / L for a rotation
//! and c EI / L^3 for a translation (L the chain's length, EI at the support).

use faer::Mat;
use faer::linalg::solvers::Solve;

use super::{Effect, EffectContext, EffectParameter, Tier, per_site_name};
use crate::structure::{Direction, HeldCoupling, SparseSym};

/// See the module docs.
#[derive(Debug, Clone, Copy)]
pub struct SupportFlexibility;

/// Relative compliance of the fit's scale.
const SCALE: f64 = 0.01;

/// The compliance of each held motion that is relative compliance 1 (module docs).
fn unit_compliances(ctx: &EffectContext) -> Vec<f64> {
    let sites = &ctx.structure.sites;
    let length = match (sites.elements.first(), sites.elements.last()) {
        (Some(a), Some(b)) => b.line.x[1] - a.line.x[0],
        _ => return Vec::new(),
    };
    sites
        .supports
        .iter()
        .flat_map(|s| {
            let ei = s.section.bending_stiffness();
            s.held.iter().map(move |d| match d {
                Direction::Theta => length / ei,
                _ => length.powi(3) / ei,
            })
        })
        .collect()
}

/// The held motions' own block and their coupling with the free DOFs as dense matrices
/// (n_h x n_h, n_h x n_f) over `free` (the DOFs any held motion couples with, in order).
fn dense(coupling: &HeldCoupling, free: &[usize]) -> (Mat<f64>, Mat<f64>) {
    let n = coupling.own.len();
    let own = Mat::from_fn(n, n, |i, j| coupling.own[i][j]);
    let mut b = Mat::zeros(n, free.len());
    for (h, row) in coupling.free.iter().enumerate() {
        for &(d, v) in row {
            let col = free.binary_search(&d).expect("listed DOF");
            b[(h, col)] += v;
        }
    }
    (own, b)
}

/// The blocks of the module docs at compliances `c`.
struct Reduction {
    /// DOFs of the structure the effect touches.
    free: Vec<usize>,
    k_hh: Mat<f64>,
    m_hh: Mat<f64>,
    b_k: Mat<f64>,
    b_m: Mat<f64>,
    /// I + C K_hh, factored.
    h: faer::linalg::solvers::PartialPivLu<f64>,
    g: Mat<f64>,
    s: Mat<f64>,
}

impl Reduction {
    fn new(ctx: &EffectContext, c: &[f64]) -> Self {
        let held = &ctx.structure.sites.held;
        let mut free: Vec<usize> = held
            .stiffness
            .free
            .iter()
            .chain(&held.mass.free)
            .flatten()
            .map(|&(d, _)| d)
            .collect();
        free.sort_unstable();
        free.dedup();
        let (k_hh, b_k) = dense(&held.stiffness, &free);
        let (m_hh, b_m) = dense(&held.mass, &free);
        let n = c.len();
        let compliance = Mat::from_fn(n, n, |i, j| if i == j { c[i] } else { 0.0 });
        let h = (Mat::<f64>::identity(n, n) + &compliance * &k_hh).partial_piv_lu();
        let g = h.solve(&compliance);
        let s = -(&g * &b_k);
        Self {
            free,
            k_hh,
            m_hh,
            b_k,
            b_m,
            h,
            g,
            s,
        }
    }

    /// dK and dM on the structure's DOFs from dense n_f x n_f blocks.
    fn sparse(&self, k: &Mat<f64>, m: &Mat<f64>) -> (SparseSym, SparseSym) {
        let (mut ks, mut ms) = (SparseSym::zero(), SparseSym::zero());
        for (i, &a) in self.free.iter().enumerate() {
            for (j, &b) in self.free.iter().enumerate() {
                if k[(i, j)] != 0.0 {
                    ks.push(a, b, k[(i, j)]);
                }
                if m[(i, j)] != 0.0 {
                    ms.push(a, b, m[(i, j)]);
                }
            }
        }
        (ks, ms)
    }

    /// K(c) - K(0), M(c) - M(0).
    fn contribution(&self) -> (SparseSym, SparseSym) {
        let dk = -(self.b_k.transpose() * &self.g * &self.b_k);
        let bm_s = self.b_m.transpose() * &self.s;
        let dm = &bm_s + bm_s.transpose() + self.s.transpose() * &self.m_hh * &self.s;
        self.sparse(&dk, &dm)
    }

    /// dK/dc_i, dM/dc_i.
    fn derivative(&self, i: usize) -> (SparseSym, SparseSym) {
        let n = self.g.nrows();
        let mut e = Mat::<f64>::zeros(n, n);
        e[(i, i)] = 1.0;
        let dg = self
            .h
            .solve(&e * (Mat::<f64>::identity(n, n) - &self.k_hh * &self.g));
        let dk = -(self.b_k.transpose() * &dg * &self.b_k);
        let ds = -(&dg * &self.b_k);
        let bm_ds = self.b_m.transpose() * &ds;
        let ds_m_s = ds.transpose() * &self.m_hh * &self.s;
        let dm = &bm_ds + bm_ds.transpose() + &ds_m_s + ds_m_s.transpose();
        self.sparse(&dk, &dm)
    }
}

impl Effect for SupportFlexibility {
    fn name(&self) -> &'static str {
        "support_flexibility"
    }

    fn tier(&self) -> Tier {
        Tier::Default
    }

    fn describe(&self) -> &'static str {
        "compliance c of every motion a rigid support holds (the support becomes a spring of stiffness 1 / c); size = mean of c EI / L (rotation) and c EI / L^3 (translation), L the chain's length"
    }

    fn parameters(&self, ctx: &EffectContext) -> Vec<EffectParameter> {
        let supports = &ctx.structure.sites.supports;
        let mut unit = unit_compliances(ctx).into_iter();
        let mut out = Vec::new();
        for (i, s) in supports.iter().enumerate() {
            for d in &s.held {
                let (suffix, unit_name) = match d {
                    Direction::Theta => ("c_theta", "rad/(N m)"),
                    _ => ("c_w", "m/N"),
                };
                out.push(EffectParameter {
                    name: per_site_name(self.name(), "support", i, supports.len(), suffix),
                    unit: unit_name,
                    scale: SCALE * unit.next().expect("one per held motion"),
                    non_negative: true,
                });
            }
        }
        out
    }

    fn contribution(&self, ctx: &EffectContext, theta: &[f64]) -> (SparseSym, SparseSym) {
        Reduction::new(ctx, theta).contribution()
    }

    fn derivatives(&self, ctx: &EffectContext, theta: &[f64]) -> Vec<(SparseSym, SparseSym)> {
        let r = Reduction::new(ctx, theta);
        (0..theta.len()).map(|i| r.derivative(i)).collect()
    }

    fn theta_of_size(&self, ctx: &EffectContext, size: f64) -> Vec<f64> {
        unit_compliances(ctx).iter().map(|u| size * u).collect()
    }

    fn size_of_theta(&self, ctx: &EffectContext, theta: &[f64]) -> f64 {
        let unit = unit_compliances(ctx);
        theta.iter().zip(&unit).map(|(c, u)| c / u).sum::<f64>() / unit.len().max(1) as f64
    }
}

#[cfg(test)]
mod tests {
    use std::path::Path;
    use std::sync::Arc;

    use super::*;
    use crate::modal::ModalSolution;
    use crate::model::effects::Configured;
    use crate::model::effects::tests::{assert_central_differences, context_of as context, dense};
    use crate::structure::Structure;

    const STEEL: &str =
        "youngs_modulus = 2.1e11\ndensity = 7850.0\narea = 2.4e-3\nsecond_moment = 3.2e-7\n";
    /// EI of [`STEEL`], N m^2.
    const EI: f64 = 2.1e11 * 3.2e-7;

    fn build(text: &str) -> Structure {
        crate::model::from_toml(text, Path::new("test.toml")).unwrap()
    }

    /// The lowest `count` elastic frequencies of `ctx`'s structure with the effect at `theta`.
    fn frequencies(ctx: &EffectContext, theta: Vec<f64>, count: usize) -> Vec<f64> {
        let configured = Configured {
            ctx: Arc::new(ctx.clone()),
            structure: ctx.structure.clone(),
            effects: vec![(Arc::new(SupportFlexibility), theta)],
        };
        let modal = ModalSolution::solve(&configured.assemble()).unwrap();
        let rigid = ctx.structure.rigid;
        (0..count).map(|i| modal.frequency_hz(rigid + i)).collect()
    }

    /// Two beams joined, clamped at 0 and pinned at 0.36 m.
    fn clamped_and_pinned(supports: &str) -> String {
        format!(
            "[[beam]]\nlength = 0.2\nelements = 10\n{STEEL}\n[[beam]]\nlength = 0.3\nelements = 15\n{STEEL}\n[[joint]]\nk1 = 1e7\nk2 = 1e4\n{supports}"
        )
    }

    const RIGID: &str =
        "[[support]]\nx = 0.0\nkind = \"clamped\"\n[[support]]\nx = 0.36\nkind = \"pinned\"\n";

    #[test]
    fn the_builder_records_the_held_motions_of_rigid_supports_away_from_joints() {
        let s = build(&clamped_and_pinned(RIGID));
        let sites = &s.sites;
        assert_eq!(sites.supports.len(), 2);
        assert_eq!(sites.supports[0].held, vec![Direction::W, Direction::Theta]);
        assert_eq!(sites.supports[1].held, vec![Direction::W]);
        let held = &sites.held.stiffness;
        assert_eq!(held.own.len(), 3);
        // The clamped end's block is the first element's: 12 EI / l^3 on w, 4 EI / l on theta.
        let l: f64 = 0.02;
        assert!((held.own[0][0] - 12.0 * EI / l.powi(3)).abs() < 1e-9 * held.own[0][0]);
        assert!((held.own[1][1] - 4.0 * EI / l).abs() < 1e-9 * held.own[1][1]);
        // The pinned node is interior: two elements, 24 EI / l^3.
        assert!((held.own[2][2] - 24.0 * EI / l.powi(3)).abs() < 1e-9 * held.own[2][2]);
        // Couplings with the free DOFs: the clamp's with its neighbour's w, theta; the pin's
        // with its own theta and both neighbours' w, theta.
        assert_eq!(held.free[0].len(), 2);
        assert_eq!(held.free[2].len(), 5);
        // A support at the joint holds both joint nodes: no site.
        let at_joint = build(&clamped_and_pinned(
            "[[support]]\nx = 0.2\nkind = \"pinned\"\n",
        ));
        assert!(at_joint.sites.supports.is_empty());
        assert!(!SupportFlexibility.applies(&context(at_joint)));
    }

    #[test]
    fn vanishes_at_zero_round_trips_its_size_and_its_derivatives_match_central_differences() {
        let ctx = context(build(&clamped_and_pinned(RIGID)));
        let e = SupportFlexibility;
        assert_eq!(e.parameters(&ctx).len(), 3);
        let (k0, m0) = dense(ctx.structure.dof_count(), &e.contribution(&ctx, &[0.0; 3]));
        assert_eq!((k0.norm_max(), m0.norm_max()), (0.0, 0.0));
        let back = e.size_of_theta(&ctx, &e.theta_of_size(&ctx, 0.07));
        assert!((back - 0.07).abs() < 1e-12, "{back}");
        // At zero (where the derivative is the first-order effect) and away from it, unequal.
        let mut away = e.theta_of_size(&ctx, 0.3);
        away[1] *= 2.0;
        for theta in [vec![0.0; 3], away] {
            for i in 0..theta.len() {
                // The compliance is strongly nonlinear on the scale of an element's (1/156 of
                // the scale here): at zero a step of 1e-7 scales keeps the O(h^2) error below
                // 1e-9; away from it, where dK/dc falls as 1/c^2, 1e-4 c keeps the rounding
                // of K small beside the step.
                let h = 1e-7 * e.parameters(&ctx)[i].scale + 1e-4 * theta[i];
                let (ka, ma) = assert_central_differences(&e, &ctx, &theta, i, h);
                assert!(ka.norm_max() > 0.0 && ma.norm_max() > 0.0, "c{i}");
            }
        }
    }

    /// Root beta L of 1 + cos cosh + kappa (cos sinh - sin cosh) = 0 (a cantilever on a
    /// rotational spring k at its root, kappa = EI beta / k; divided by cosh) in (a, b).
    fn spring_cantilever_root(kappa_per_beta_l: f64, a: f64, b: f64) -> f64 {
        let g = |x: f64| {
            1.0 / x.cosh() + x.cos() + kappa_per_beta_l * x * (x.cos() * x.tanh() - x.sin())
        };
        let (mut lo, mut hi) = (a, b);
        assert!(g(lo) * g(hi) < 0.0, "no sign change in ({a}, {b})");
        for _ in 0..200 {
            let mid = 0.5 * (lo + hi);
            if g(lo) * g(mid) <= 0.0 {
                hi = mid;
            } else {
                lo = mid;
            }
        }
        0.5 * (lo + hi)
    }

    /// Independent check: the analytic frequencies of an Euler-Bernoulli cantilever whose
    /// root is a rotational spring (derived from w(0) = 0, EI w''(0) = k w'(0) and a free tip)
    /// against the clamped model with a rotational compliance 1 / k at the clamp.
    #[test]
    fn a_rotational_compliance_at_a_clamp_gives_the_analytic_spring_cantilever() {
        let length: f64 = 0.5;
        let ctx = context(build(&format!(
            "[[beam]]\nlength = {length}\nelements = 100\n{STEEL}\n[[support]]\nx = 0.0\nkind = \"clamped\"\n"
        )));
        // kappa = 0.1 at the first mode's beta L = 1.875.
        let k = EI * 1.875 / length / 0.1;
        let fe = frequencies(&ctx, vec![0.0, 1.0 / k], 4);
        let scale = (EI / (7850.0 * 2.4e-3 * length.powi(4))).sqrt() / (2.0 * std::f64::consts::PI);
        // Roots between those of the pinned-free (k = 0) and the clamped-free (k = inf) beam.
        let brackets = [
            (1e-6, 1.8751),
            (3.9266, 4.6941),
            (7.0686, 7.8548),
            (10.2102, 10.9956),
        ];
        for (i, (a, b)) in brackets.into_iter().enumerate() {
            let x = spring_cantilever_root(EI / (length * k), a, b);
            let analytic = x * x * scale;
            let err = (fe[i] - analytic).abs() / analytic;
            // Measured: 1e-7 and below (100 elements).
            assert!(
                err < 1e-6,
                "mode {}: {} Hz against {analytic} Hz ({err:.1e})",
                i + 1,
                fe[i]
            );
        }
        // The spring matters: mode 1 is well below the clamped beam's.
        let clamped = 1.8751_f64.powi(2) * scale;
        assert!(fe[0] < 0.95 * clamped);
    }

    /// Independent check: the builder's spring supports keep their DOFs (no reduction); the
    /// clamped-and-pinned model with the same compliances reduced statically gives the same
    /// frequencies to the reduction's error.
    #[test]
    fn compliances_match_spring_supports_that_keep_their_dofs() {
        let (kw, kt, kp) = (2e8, 2e5, 5e7);
        let springs = build(&clamped_and_pinned(&format!(
            "[[support]]\nx = 0.0\nkind = \"spring\"\ntranslational = {kw}\nrotational = {kt}\n[[support]]\nx = 0.36\nkind = \"spring\"\ntranslational = {kp}\n"
        )));
        let exact = ModalSolution::solve(&springs.assemble()).unwrap();
        let ctx = context(build(&clamped_and_pinned(RIGID)));
        let reduced = frequencies(&ctx, vec![1.0 / kw, 1.0 / kt, 1.0 / kp], 5);
        let rigid = frequencies(&ctx, vec![0.0; 3], 5);
        for (i, f) in reduced.iter().enumerate() {
            let e = exact.frequency_hz(i);
            let err = (f - e).abs() / e;
            // The reduction's error, of order (omega / omega_e)^2 of the effect: measured
            // 2e-10 (mode 1) to 4e-5 (mode 4) for supports that move the modes by 60-160%.
            assert!(
                err < 1e-4,
                "mode {}: {f} Hz against {e} Hz ({err:.1e})",
                i + 1
            );
            // ... and the supports' flexibility is no small part of it.
            assert!(
                (rigid[i] - e).abs() > 100.0 * (f - e).abs(),
                "mode {}",
                i + 1
            );
        }
    }
}

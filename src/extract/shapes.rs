//! From a complex mode shape (a residue vector) to a real normal mode and its complexity.
//!
//! - Best real direction: the points v_o = x_o + i y_o of the shape in the complex plane are
//!   fitted by a line through the origin (total least squares): the principal axis of
//!   S = [[x.x, x.y], [x.y, y.y]], at angle theta = atan2(2 x.y, x.x - y.y) / 2. The real
//!   shape is Re(v e^{-i theta}) = x cos(theta) + y sin(theta), signed and scaled to a largest
//!   component of +1. It maximises the norm of the real part of the rotated shape (the
//!   criterion of Ahmadian, Gladwell, Ismail, "Extracting real modes from complex measured
//!   modes", IMAC 1995).
//! - MPC, modal phase collinearity (Pappa, Elliott, Schenk, "Consistent-mode indicator for the
//!   eigensystem realization algorithm", J. Guidance, Control and Dynamics 16, 1993), in the
//!   eigenvalue form ((l1 - l2) / (l1 + l2))^2 of S's eigenvalues l1 >= l2 (as in Reynders,
//!   Houbrechts, De Roeck, "Fully automated (operational) modal analysis", MSSP 29, 2012):
//!   1 for a real (collinear) mode, 0 for components spread evenly in phase.
//! - MPD, mean phase deviation (Reynders et al. 2012): the angle between each component and the
//!   principal axis, in [0, 90] degrees, averaged with the components' magnitudes as weights.
//!   0 for a real mode.

use faer::c64;

/// The real normal mode of a complex shape and the complexity of the shape.
#[derive(Debug, Clone, PartialEq)]
pub struct RealMode {
    /// Real shape, largest component +1.
    pub shape: Vec<f64>,
    /// Modal phase collinearity, in [0, 1].
    pub mpc: f64,
    /// Mean phase deviation (degrees), in [0, 90].
    pub mpd_deg: f64,
    /// The angle of the principal axis (radians).
    pub angle: f64,
}

/// The largest |re| or |im| of `v` as a power of two 2^e, when it lies outside
/// 2^-60..2^60, where the sums of squares and their squares below would overflow or
/// underflow; None inside (no rescaling: the results stay the bits they always were).
fn far_scale(v: &[c64]) -> Option<f64> {
    let peak = v
        .iter()
        .map(|z| z.re.abs().max(z.im.abs()))
        .fold(0.0_f64, f64::max);
    let far = peak.is_finite() && peak > 0.0 && !(2f64.powi(-60)..=2f64.powi(60)).contains(&peak);
    far.then(|| 2f64.powi((peak.log2().round() as i32).clamp(-1000, 1000)))
}

/// `v` divided by its [`far_scale`] (exact: a power of two), when it has one.
fn rescaled(v: &[c64]) -> Option<Vec<c64>> {
    far_scale(v).map(|s| v.iter().map(|z| z / s).collect())
}

/// MAC of two complex vectors: |a^H b|^2 / (a^H a b^H b); 0 when either is zero. Scale-free:
/// vectors of any magnitude a double holds give the same MAC.
pub fn mac(a: &[c64], b: &[c64]) -> f64 {
    if let Some(a) = rescaled(a) {
        return mac(&a, b);
    }
    if let Some(b) = rescaled(b) {
        return mac(a, &b);
    }
    let ab: c64 = a.iter().zip(b).map(|(x, y)| x.conj() * y).sum();
    let aa: f64 = a.iter().map(|x| x.norm_sqr()).sum();
    let bb: f64 = b.iter().map(|x| x.norm_sqr()).sum();
    if aa > 0.0 && bb > 0.0 {
        (ab.norm_sqr() / (aa * bb)).min(1.0)
    } else {
        0.0
    }
}

/// MAC of two real vectors.
pub fn mac_real(a: &[f64], b: &[f64]) -> f64 {
    let ab: f64 = a.iter().zip(b).map(|(x, y)| x * y).sum();
    let aa: f64 = a.iter().map(|x| x * x).sum();
    let bb: f64 = b.iter().map(|x| x * x).sum();
    if aa > 0.0 && bb > 0.0 {
        (ab * ab / (aa * bb)).min(1.0)
    } else {
        0.0
    }
}

/// Scales a vector so that its component of largest magnitude is +1 (the first on a tie); a
/// zero vector stays zero.
pub fn unit_peak(v: &mut [f64]) {
    let mut peak = 0.0_f64;
    for &x in v.iter() {
        if x.abs() > peak.abs() {
            peak = x;
        }
    }
    if peak != 0.0 {
        for x in v.iter_mut() {
            *x /= peak;
        }
    }
}

/// The complex shape scaled so that its component of largest magnitude is 1 + 0i.
pub fn complex_unit_peak(v: &[c64]) -> Vec<c64> {
    let peak = v.iter().copied().fold(
        c64::new(0.0, 0.0),
        |a, x| if x.norm() > a.norm() { x } else { a },
    );
    if peak.norm() > 0.0 {
        v.iter().map(|x| x / peak).collect()
    } else {
        v.to_vec()
    }
}

/// The second moments (x.x, y.y, x.y) of the points v_o = x_o + i y_o.
fn moments(v: &[c64]) -> (f64, f64, f64) {
    let sxx: f64 = v.iter().map(|z| z.re * z.re).sum();
    let syy: f64 = v.iter().map(|z| z.im * z.im).sum();
    let sxy: f64 = v.iter().map(|z| z.re * z.im).sum();
    (sxx, syy, sxy)
}

/// Re(v e^{-i angle}) per component.
fn rotated(v: &[c64], angle: f64) -> Vec<f64> {
    let (c, s) = (angle.cos(), angle.sin());
    v.iter().map(|z| z.re * c + z.im * s).collect()
}

/// The real shape of `v` (its principal axis, as in [`real_mode`]) scaled so that component
/// `peak` is +1: [`real_mode`]'s shape when `peak` is its largest component, a smooth function
/// of `v` near it (the standard errors differentiate it with the peak held).
pub fn real_shape_scaled_at(v: &[c64], peak: usize) -> Vec<f64> {
    if let Some(v) = rescaled(v) {
        return real_shape_scaled_at(&v, peak);
    }
    let (sxx, syy, sxy) = moments(v);
    let shape = rotated(v, 0.5 * (2.0 * sxy).atan2(sxx - syy));
    let at = shape[peak];
    shape.iter().map(|x| x / at).collect()
}

/// The real normal mode and complexity of a complex shape (see the module docs). Scale-free:
/// a shape of any magnitude a double holds gives the same mode, MPC and MPD.
pub fn real_mode(v: &[c64]) -> RealMode {
    if let Some(v) = rescaled(v) {
        return real_mode(&v);
    }
    let (sxx, syy, sxy) = moments(v);
    let angle = 0.5 * (2.0 * sxy).atan2(sxx - syy);
    let (c, s) = (angle.cos(), angle.sin());
    let mut shape = rotated(v, angle);
    unit_peak(&mut shape);
    let trace = sxx + syy;
    let half_gap = (0.25 * (sxx - syy).powi(2) + sxy * sxy).sqrt();
    let mpc = if trace > 0.0 {
        (2.0 * half_gap / trace).powi(2).min(1.0)
    } else {
        1.0
    };
    let total: f64 = v.iter().map(|z| z.norm()).sum();
    let mpd_deg = if total > 0.0 {
        v.iter()
            .map(|z| {
                let along = (z.re * c + z.im * s).abs();
                let r = z.norm();
                if r > 0.0 {
                    r * (along / r).clamp(0.0, 1.0).acos()
                } else {
                    0.0
                }
            })
            .sum::<f64>()
            / total
            * 180.0
            / std::f64::consts::PI
    } else {
        0.0
    };
    RealMode {
        shape,
        mpc,
        mpd_deg,
        angle,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn a_rotated_real_shape_is_real_with_full_collinearity() {
        let phi = [0.3, -1.0, 0.5, 0.8];
        let rot = c64::from_polar(2.5, 1.1);
        let v: Vec<c64> = phi.iter().map(|&x| rot * x).collect();
        let m = real_mode(&v);
        // Largest component is -1.0 in phi: scaled to +1 the shape is -phi.
        for (a, b) in m.shape.iter().zip(phi) {
            assert!((a + b).abs() < 1e-14, "{:?}", m.shape);
        }
        assert!((m.mpc - 1.0).abs() < 1e-14);
        assert!(m.mpd_deg.abs() < 1e-6);
    }

    #[test]
    fn the_mode_and_its_complexity_do_not_depend_on_the_scale() {
        let phi: f64 = 0.4;
        let v = [
            c64::new(1.0, 0.0),
            c64::from_polar(1.0, phi),
            c64::new(-0.3, 0.1),
        ];
        let m = real_mode(&v);
        for scale in [1e-300, 1e-150, 1e-80, 1e80, 1e150, 1e300] {
            let w: Vec<c64> = v.iter().map(|z| z * scale).collect();
            let s = real_mode(&w);
            assert!(
                (s.mpc - m.mpc).abs() < 1e-12,
                "{scale}: {} vs {}",
                s.mpc,
                m.mpc
            );
            assert!((s.mpd_deg - m.mpd_deg).abs() < 1e-9, "{scale}");
            for (a, b) in s.shape.iter().zip(&m.shape) {
                assert!((a - b).abs() < 1e-12, "{scale}");
            }
            assert!((mac(&w, &v) - mac(&v, &v)).abs() < 1e-12, "{scale}");
        }
    }

    #[test]
    fn evenly_spread_phases_have_zero_collinearity() {
        // Four components at 0, 45, 90, 135 degrees, equal magnitude: S = 2 I.
        let v: Vec<c64> = (0..4)
            .map(|k| c64::from_polar(1.0, k as f64 * std::f64::consts::FRAC_PI_4))
            .collect();
        let m = real_mode(&v);
        assert!(m.mpc.abs() < 1e-14, "{}", m.mpc);
    }

    /// MPC against the closed form for two components: v = (1, e^{i phi}) gives
    /// S = [[1 + c^2, c s], [c s, s^2]], eigenvalues 1 +- |cos phi|, MPC = cos^2 phi.
    /// MPD: both components deviate by phi/2 from the bisecting axis.
    #[test]
    fn two_components_closed_form() {
        let phi: f64 = 0.4;
        let v = [c64::new(1.0, 0.0), c64::from_polar(1.0, phi)];
        let m = real_mode(&v);
        assert!((m.mpc - phi.cos().powi(2)).abs() < 1e-14, "{}", m.mpc);
        assert!(
            (m.mpd_deg - (phi / 2.0).to_degrees()).abs() < 1e-12,
            "{}",
            m.mpd_deg
        );
        assert!((m.angle - phi / 2.0).abs() < 1e-14);
    }

    #[test]
    fn mac_of_scaled_vectors_is_one_and_of_orthogonal_zero() {
        let a = [c64::new(1.0, 2.0), c64::new(-0.5, 0.1)];
        let b: Vec<c64> = a.iter().map(|x| x * c64::new(0.3, -4.0)).collect();
        assert!((mac(&a, &b) - 1.0).abs() < 1e-14);
        assert_eq!(mac_real(&[1.0, 0.0], &[0.0, 2.0]), 0.0);
        assert_eq!(mac(&a, &[c64::new(0.0, 0.0); 2]), 0.0);
    }
}

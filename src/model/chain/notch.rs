//! The root of a lap's layer: where a beam of height h continues as a thinner layer of height
//! h_l, the other layer ends against it in a free face, a notch of depth a = h - h_l cut into
//! the beam. Plane sections miss the notch: near it the beam's fibres below the layer carry
//! no stress, and the section rotates more than the beam and the layer on either side. Its
//! local compliance is that of an edge crack of the same depth in pure bending (linear
//! elastic fracture mechanics; H. Tada, P. C. Paris, G. R. Irwin, "The Stress Analysis of
//! Cracks Handbook", the single-edge-notched strip in bending, accurate to 0.5% for any
//! depth):
//!
//! ```text
//!   K_I = sigma sqrt(pi a) F(s),  sigma = 6 M / (b h^2),  s = a / h
//!   F(s) = sqrt(2 / (pi s) tan(pi s / 2)) (0.923 + 0.199 (1 - sin(pi s / 2))^4) / cos(pi s / 2)
//!   c = 2 / M^2 * integral_0^a K_I^2 / E b da = 72 pi / (E b h^2) integral_0^(a/h) s F(s)^2 ds
//! ```
//!
//! (energy release rate K_I^2 / E in plane stress, the crack's energy c M^2 / 2). Its stiffness
//! 1 / c is the bonded limit of the root (an interface that does not slip makes the layers one
//! beam, cracked at the overlap's ends); a compliant interface lets part of the moment pass
//! into the layer before the notch, so the root of a real lap is stiffer (the layered lap fits
//! it from this start). b and h are the rectangle's of the section: h = sqrt(12 I / A).

use crate::structure::Section;

/// Notches shallower than this fraction of the height are none.
const SHALLOWEST: f64 = 1e-6;
/// Simpson intervals of the integral (the integrand is smooth on [0, s] for s < 1).
const INTERVALS: usize = 400;

/// Height of the rectangle of `section`'s area and second moment, m.
pub fn height(section: &Section) -> f64 {
    (12.0 * section.second_moment / section.area).sqrt()
}

/// Tada's geometry factor of an edge crack of relative depth `s` in pure bending.
fn geometry_factor(s: f64) -> f64 {
    let t = 0.5 * std::f64::consts::PI * s;
    (2.0 / (std::f64::consts::PI * s) * t.tan()).sqrt() * (0.923 + 0.199 * (1.0 - t.sin()).powi(4))
        / t.cos()
}

/// integral_0^s t F(t)^2 dt by Simpson's rule (t F(t)^2 -> 0 as t -> 0).
fn energy_integral(s: f64) -> f64 {
    let h = s / INTERVALS as f64;
    let f = |t: f64| {
        if t == 0.0 {
            0.0
        } else {
            t * geometry_factor(t).powi(2)
        }
    };
    let inner: f64 = (1..INTERVALS)
        .map(|i| (if i % 2 == 1 { 4.0 } else { 2.0 }) * f(i as f64 * h))
        .sum();
    h / 3.0 * (f(0.0) + inner + f(s))
}

/// The rotational stiffness (N m/rad) of a notch of depth `depth` in a beam of section
/// `beam` (see the module docs), or `None` when the depth is not a notch (at most
/// [`SHALLOWEST`] of the height, or not shallower than the beam).
pub fn stiffness(beam: &Section, depth: f64) -> Option<f64> {
    let h = height(beam);
    let s = depth / h;
    if !(s > SHALLOWEST && s < 1.0) {
        return None;
    }
    let b = beam.area / h;
    let c = 72.0 * std::f64::consts::PI / (beam.youngs_modulus * b * h * h) * energy_integral(s);
    Some(1.0 / c)
}

#[cfg(test)]
mod tests {
    use super::*;

    fn bar(b: f64, h: f64) -> Section {
        Section {
            youngs_modulus: 7.0e10,
            density: 2700.0,
            area: b * h,
            second_moment: b * h * h * h / 12.0,
            shear: None,
        }
    }

    #[test]
    fn a_shallow_notch_is_the_edge_crack_of_a_half_plane() {
        // F -> 1.122 as s -> 0 (the half plane's 1.12 of the exact solution; the handbook's
        // fit gives sqrt(1) (0.923 + 0.199) = 1.122), so c -> 72 pi 1.122^2 s^2 / 2 / (E b h^2).
        let s = 1e-5;
        let section = bar(0.025, 0.006);
        let k = stiffness(&section, s * 0.006).unwrap();
        let c = 72.0 * std::f64::consts::PI * 1.122f64.powi(2) * s * s
            / 2.0
            / (7.0e10 * 0.025 * 0.006 * 0.006);
        assert!((1.0 / k / c - 1.0).abs() < 1e-4, "{} vs {c}", 1.0 / k);
    }

    #[test]
    fn the_integral_converges_and_the_compliance_grows_with_the_depth() {
        // Simpson against a 4x finer rule at the half depth of a half-lap splice.
        let coarse = energy_integral(0.5);
        let h = 0.5 / (4 * INTERVALS) as f64;
        let fine: f64 = (0..4 * INTERVALS)
            .map(|i| {
                let (a, b) = (i as f64 * h, (i + 1) as f64 * h);
                let g = |t: f64| {
                    if t == 0.0 {
                        0.0
                    } else {
                        t * geometry_factor(t).powi(2)
                    }
                };
                (b - a) / 6.0 * (g(a) + 4.0 * g(0.5 * (a + b)) + g(b))
            })
            .sum();
        assert!((coarse / fine - 1.0).abs() < 1e-9, "{coarse} vs {fine}");
        let section = bar(0.025, 0.006);
        let depths = [0.1, 0.3, 0.5, 0.7].map(|s| stiffness(&section, s * 0.006).unwrap());
        assert!(depths.windows(2).all(|w| w[1] < w[0]), "{depths:?}");
        // k scales with E b h^2 at a given relative depth.
        let twice = stiffness(&bar(0.05, 0.012), 0.006).unwrap();
        assert!((twice / (8.0 * depths[2]) - 1.0).abs() < 1e-12);
    }

    #[test]
    fn no_notch_where_the_layer_is_the_beam() {
        let section = bar(0.025, 0.006);
        assert_eq!(stiffness(&section, 0.0), None);
        assert_eq!(stiffness(&section, -1e-3), None);
        assert_eq!(stiffness(&section, 0.006), None);
    }
}

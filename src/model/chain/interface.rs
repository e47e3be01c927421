//! Element matrices of a layered lap ([`super::layered`]): the layers' axial bar elements and
//! the zero-thickness interface elements between two layers, integrated with the layers' own
//! shape functions by 4-point Gauss-Legendre quadrature (exact: the integrands are
//! polynomials of degree 6 at most).
//!
//! On an element of length l, xi = (x - x_1) / l:
//! - bending, (w_1, theta_1, w_2, theta_2): the Hermite cubics N(xi) of [`super::beam`],
//!   theta = dw/dx = N'(xi) / l;
//! - axial, (u_1, u_2, u_m): the quadratic Lagrange functions of the end and middle nodes.
//!   Quadratic u matches the quadratic theta of the cubic w, so that a slip-free interface
//!   (u_1 - u_2 = -r theta) is representable and the stiff interface does not lock.
//!
//! Interface, per unit length (sign convention: w upwards, theta = dw/dx, the axial
//! displacement at height z in a layer with centroid z_c is u - (z - z_c) theta; the upper
//! layer's centroid is d_1 above the interface, the lower layer's d_2 below it):
//!
//! ```text
//!   gap   g = w_1 - w_2
//!   slip  s = (u_1 + d_1 theta_1) - (u_2 - d_2 theta_2)
//!   energy  1/2 integral (k_n g^2 + k_s s^2) dx
//! ```

/// Gauss-Legendre points and weights on [0, 1].
const GAUSS: [(f64, f64); 4] = [
    (0.069_431_844_202_973_71, 0.173_927_422_568_726_93),
    (0.330_009_478_207_571_87, 0.326_072_577_431_273_07),
    (0.669_990_521_792_428_1, 0.326_072_577_431_273_07),
    (0.930_568_155_797_026_3, 0.173_927_422_568_726_93),
];

/// Hermite cubics for w at xi on an element of length `l`.
fn hermite(xi: f64, l: f64) -> [f64; 4] {
    let (x2, x3) = (xi * xi, xi * xi * xi);
    [
        1.0 - 3.0 * x2 + 2.0 * x3,
        l * (xi - 2.0 * x2 + x3),
        3.0 * x2 - 2.0 * x3,
        l * (-x2 + x3),
    ]
}

/// dN/dx of the Hermite cubics: theta at xi.
fn hermite_slope(xi: f64, l: f64) -> [f64; 4] {
    let x2 = xi * xi;
    [
        (-6.0 * xi + 6.0 * x2) / l,
        1.0 - 4.0 * xi + 3.0 * x2,
        (6.0 * xi - 6.0 * x2) / l,
        -2.0 * xi + 3.0 * x2,
    ]
}

/// Quadratic Lagrange functions of (end 1, end 2, middle).
fn quadratic(xi: f64) -> [f64; 3] {
    [
        (1.0 - xi) * (1.0 - 2.0 * xi),
        xi * (2.0 * xi - 1.0),
        4.0 * xi * (1.0 - xi),
    ]
}

/// d/dx of [`quadratic`] on an element of length `l`.
fn quadratic_slope(xi: f64, l: f64) -> [f64; 3] {
    [
        (4.0 * xi - 3.0) / l,
        (4.0 * xi - 1.0) / l,
        (4.0 - 8.0 * xi) / l,
    ]
}

/// l times the quadrature of `f(xi) f(xi)^T`.
fn gram<const N: usize>(l: f64, f: impl Fn(f64) -> [f64; N]) -> [[f64; N]; N] {
    let mut out = [[0.0; N]; N];
    for (xi, w) in GAUSS {
        let v = f(xi);
        for i in 0..N {
            for j in 0..N {
                out[i][j] += w * l * v[i] * v[j];
            }
        }
    }
    out
}

/// Axial stiffness of a quadratic bar element, EA integral u'^2: DOFs (u_1, u_2, u_m).
pub fn bar_stiffness(ea: f64, l: f64) -> [[f64; 3]; 3] {
    gram(l, |xi| quadratic_slope(xi, l).map(|v| v * ea.sqrt()))
}

/// Consistent axial mass of a quadratic bar element, rho A integral u^2.
pub fn bar_mass(rho_a: f64, l: f64) -> [[f64; 3]; 3] {
    gram(l, |xi| quadratic(xi).map(|v| v * rho_a.sqrt()))
}

/// Stiffness of a two-node (linear) bar element, EA / l [[1, -1], [-1, 1]].
pub fn linear_bar_stiffness(ea: f64, l: f64) -> [[f64; 2]; 2] {
    let k = ea / l;
    [[k, -k], [-k, k]]
}

/// Consistent mass of a two-node bar element, rho A l / 6 [[2, 1], [1, 2]].
pub fn linear_bar_mass(rho_a: f64, l: f64) -> [[f64; 2]; 2] {
    let m = rho_a * l / 6.0;
    [[2.0 * m, m], [m, 2.0 * m]]
}

/// The gap's matrix per unit k_n, integral g^2: DOFs (w, theta of the upper layer's two
/// nodes, then the lower layer's).
pub fn normal(l: f64) -> [[f64; 8]; 8] {
    gram(l, |xi| {
        let n = hermite(xi, l);
        [n[0], n[1], n[2], n[3], -n[0], -n[1], -n[2], -n[3]]
    })
}

/// The slip's matrix per unit k_s, integral s^2: DOFs (w, theta of the upper layer's two
/// nodes, then the lower layer's; u_1, u_2, u_m of the upper layer, then the lower layer's);
/// `d` the distances of the upper and lower centroids from the interface.
pub fn shear(l: f64, d: [f64; 2]) -> [[f64; 14]; 14] {
    gram(l, |xi| {
        let t = hermite_slope(xi, l);
        let u = quadratic(xi);
        let mut s = [0.0; 14];
        for k in 0..4 {
            s[k] = d[0] * t[k];
            s[4 + k] = d[1] * t[k];
        }
        for k in 0..3 {
            s[8 + k] = u[k];
            s[11 + k] = -u[k];
        }
        s
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::chain::beam::element_mass;
    use crate::structure::Section;

    /// The textbook quadratic bar: EA / (3 l) [[7, 1, -8], [1, 7, -8], [-8, -8, 16]] and
    /// rho A l / 30 [[4, -1, 2], [-1, 4, 2], [2, 2, 16]].
    #[test]
    fn the_bar_matrices_are_the_textbook_ones() {
        let (ea, rho_a, l) = (3.0, 30.0, 0.5);
        let k = bar_stiffness(ea, l);
        let m = bar_mass(rho_a, l);
        let k_ref = [[7.0, 1.0, -8.0], [1.0, 7.0, -8.0], [-8.0, -8.0, 16.0]];
        let m_ref = [[4.0, -1.0, 2.0], [-1.0, 4.0, 2.0], [2.0, 2.0, 16.0]];
        for i in 0..3 {
            for j in 0..3 {
                assert!((k[i][j] - ea / (3.0 * l) * k_ref[i][j]).abs() < 1e-12);
                assert!((m[i][j] - rho_a * l / 30.0 * m_ref[i][j]).abs() < 1e-12);
            }
        }
    }

    /// The gap matrix is the consistent-mass pattern of the beam element (integral N N^T) in
    /// blocks [[A, -A], [-A, A]].
    #[test]
    fn the_gap_matrix_is_the_mass_pattern_in_blocks() {
        let l = 0.013;
        let unit = Section {
            youngs_modulus: 1.0,
            density: 1.0,
            area: 1.0,
            second_moment: 1.0,
            shear: None,
        };
        let a = element_mass(&unit, l);
        let g = normal(l);
        for i in 0..4 {
            for j in 0..4 {
                for (bi, bj, sign) in [(0, 0, 1.0), (0, 4, -1.0), (4, 0, -1.0), (4, 4, 1.0)] {
                    assert!((g[bi + i][bj + j] - sign * a[i][j]).abs() < 1e-15);
                }
            }
        }
    }

    /// A slip-free motion of a bonded pair (u_1 = -d_1 theta, u_2 = d_2 theta under a uniform
    /// curvature, w shared) stores no shear energy; a uniform slip u_1 = 1 stores l.
    #[test]
    fn slip_free_motions_store_nothing_and_a_uniform_slip_its_length() {
        let (l, d) = (0.02, [0.003, 0.005]);
        let s = shear(l, d);
        let kappa = 2.0;
        // w = kappa x^2 / 2 on [0, l], theta = kappa x; the axial fields at the nodes and middle.
        let w = |x: f64| 0.5 * kappa * x * x;
        let th = |x: f64| kappa * x;
        let q = [w(0.0), th(0.0), w(l), th(l)];
        let mut v = [0.0; 14];
        v[..4].copy_from_slice(&q);
        v[4..8].copy_from_slice(&q);
        for (k, x) in [0.0, l, 0.5 * l].into_iter().enumerate() {
            v[8 + k] = -d[0] * th(x);
            v[11 + k] = d[1] * th(x);
        }
        let energy: f64 = (0..14)
            .flat_map(|i| (0..14).map(move |j| (i, j)))
            .map(|(i, j)| v[i] * s[i][j] * v[j])
            .sum();
        assert!(energy.abs() < 1e-15, "{energy}");
        let mut u = [0.0; 14];
        u[8..11].copy_from_slice(&[1.0; 3]);
        let energy: f64 = (0..14)
            .flat_map(|i| (0..14).map(move |j| (i, j)))
            .map(|(i, j)| u[i] * s[i][j] * u[j])
            .sum();
        assert!((energy - l).abs() < 1e-15, "{energy}");
    }
}

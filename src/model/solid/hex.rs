//! The 8-node trilinear hexahedron of an isotropic elastic solid: its stiffness with
//! incompatible modes (Wilson, Taylor, Beresford and Zienkiewicz 1973, in Taylor's form that
//! passes the patch test on any shape: Taylor, Beresford, Wilson, "A non-conforming element
//! for stress analysis", IJNME 10, 1976) and its consistent mass.
//!
//! Why incompatible modes: the plain trilinear brick locks in bending (a parasitic shear
//! strain appears when its faces bend), so a bar meshed with a few bricks through the thickness
//! is far too stiff, the more so the longer the bricks. The three bubble modes
//! P_i = 1 - xi_i^2 per displacement component (nine internal DOFs) let the element bend; they
//! are condensed out per element (K = K_uu - K_ua K_aa^-1 K_au). Their derivatives are taken
//! with the Jacobian at the element's centre and weighted with its determinant there, so
//! that int B_a dV = 0 and a uniform strain field is reproduced exactly (the patch test,
//! `tests/suite/solid.rs`). On a rectangular brick the element then bends exactly in pure
//! bending, and the mesh needs no more than two elements through a layer.
//!
//! Node order: the four corners of the face zeta = -1 counter-clockwise from
//! (xi, eta) = (-1, -1), then those of zeta = +1. DOFs: 3 per node, (u_x, u_y, u_z), node-major.
//! Strains in Voigt order (e_xx, e_yy, e_zz, g_xy, g_yz, g_zx). Integration: 2 x 2 x 2 Gauss
//! points, exact for the mass of a parallelepiped.
//!
//! May import: nothing of the crate (pure numerics).

/// Natural coordinates of the eight nodes.
pub const CORNERS: [[f64; 3]; 8] = [
    [-1.0, -1.0, -1.0],
    [1.0, -1.0, -1.0],
    [1.0, 1.0, -1.0],
    [-1.0, 1.0, -1.0],
    [-1.0, -1.0, 1.0],
    [1.0, -1.0, 1.0],
    [1.0, 1.0, 1.0],
    [-1.0, 1.0, 1.0],
];

/// An isotropic linear elastic material.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Material {
    /// Young's modulus, Pa.
    pub youngs_modulus: f64,
    /// Poisson's ratio, from 0 to below 0.5.
    pub poisson_ratio: f64,
    /// Density, kg/m^3.
    pub density: f64,
}

impl Material {
    /// The 6 x 6 elasticity matrix D (Voigt order of the module docs, engineering shear).
    pub fn elasticity(&self) -> [[f64; 6]; 6] {
        let (e, nu) = (self.youngs_modulus, self.poisson_ratio);
        let lambda = e * nu / ((1.0 + nu) * (1.0 - 2.0 * nu));
        let mu = e / (2.0 * (1.0 + nu));
        let mut d = [[0.0; 6]; 6];
        for i in 0..3 {
            d[i][..3].fill(lambda);
            d[i][i] = lambda + 2.0 * mu;
            d[i + 3][i + 3] = mu;
        }
        d
    }
}

/// The element's matrices: stiffness (24 x 24) and mass (24 x 24), row-major.
pub struct HexMatrices {
    /// Stiffness, incompatible modes condensed out.
    pub k: Vec<f64>,
    /// Consistent mass.
    pub m: Vec<f64>,
}

/// The shape functions' derivatives with respect to (xi, eta, zeta) at a point.
fn natural_gradients(p: [f64; 3]) -> [[f64; 3]; 8] {
    std::array::from_fn(|a| {
        let c = CORNERS[a];
        let f = |i: usize| 1.0 + c[i] * p[i];
        [
            0.125 * c[0] * f(1) * f(2),
            0.125 * c[1] * f(0) * f(2),
            0.125 * c[2] * f(0) * f(1),
        ]
    })
}

/// The shape functions at a point.
fn shape(p: [f64; 3]) -> [f64; 8] {
    std::array::from_fn(|a| {
        let c = CORNERS[a];
        0.125 * (1.0 + c[0] * p[0]) * (1.0 + c[1] * p[1]) * (1.0 + c[2] * p[2])
    })
}

/// The Jacobian J_ij = d x_j / d xi_i at a point, its inverse and determinant.
fn jacobian(x: &[[f64; 3]; 8], p: [f64; 3]) -> ([[f64; 3]; 3], f64) {
    let g = natural_gradients(p);
    let mut j = [[0.0; 3]; 3];
    for (ga, xa) in g.iter().zip(x) {
        for r in 0..3 {
            for c in 0..3 {
                j[r][c] += ga[r] * xa[c];
            }
        }
    }
    invert3(&j)
}

/// The inverse and determinant of a 3 x 3 matrix.
fn invert3(a: &[[f64; 3]; 3]) -> ([[f64; 3]; 3], f64) {
    let cof = |r: usize, c: usize| {
        let (r1, r2) = ((r + 1) % 3, (r + 2) % 3);
        let (c1, c2) = ((c + 1) % 3, (c + 2) % 3);
        a[r1][c1] * a[r2][c2] - a[r1][c2] * a[r2][c1]
    };
    let det = a[0][0] * cof(0, 0) + a[0][1] * cof(0, 1) + a[0][2] * cof(0, 2);
    let inv = std::array::from_fn(|i| std::array::from_fn(|j| cof(j, i) / det));
    (inv, det)
}

/// Physical gradient of a function whose natural gradient is `g`: J^-1 g.
fn physical(inv: &[[f64; 3]; 3], g: [f64; 3]) -> [f64; 3] {
    std::array::from_fn(|i| inv[i][0] * g[0] + inv[i][1] * g[1] + inv[i][2] * g[2])
}

/// The 6 x 3 strain block of a function with physical gradient `d` (columns u_x, u_y, u_z).
fn strain_block(d: [f64; 3]) -> [[f64; 3]; 6] {
    [
        [d[0], 0.0, 0.0],
        [0.0, d[1], 0.0],
        [0.0, 0.0, d[2]],
        [d[1], d[0], 0.0],
        [0.0, d[2], d[1]],
        [d[2], 0.0, d[0]],
    ]
}

/// Gauss points of the 2 x 2 x 2 rule (weights 1).
fn gauss_points() -> [[f64; 3]; 8] {
    let g = 1.0 / 3f64.sqrt();
    CORNERS.map(|c| c.map(|s| s * g))
}

/// Adds w B1^T D B2 to `out` (`rows` x `cols`, row-major), B given as column blocks of 3.
fn add_btdb(
    out: &mut [f64],
    cols: usize,
    b1: &[[f64; 6]],
    b2: &[[f64; 6]],
    d: &[[f64; 6]; 6],
    w: f64,
) {
    for (r, br) in b1.iter().enumerate() {
        let mut db = [0.0; 6];
        for (i, dbi) in db.iter_mut().enumerate() {
            *dbi = (0..6).map(|k| d[i][k] * br[k]).sum::<f64>() * w;
        }
        for (c, bc) in b2.iter().enumerate() {
            out[r * cols + c] += (0..6).map(|k| db[k] * bc[k]).sum::<f64>();
        }
    }
}

/// The columns of B (each a 6-vector of strains) for the 24 nodal DOFs at a point.
fn columns(blocks: impl Iterator<Item = [[f64; 3]; 6]>) -> Vec<[f64; 6]> {
    let mut cols = Vec::new();
    for b in blocks {
        cols.extend((0..3).map(|dir| std::array::from_fn(|s| b[s][dir])));
    }
    cols
}

/// The stiffness (incompatible modes condensed out) and consistent mass of the brick with
/// nodes `x` (m, the order of the module docs) of `material`. `None` when the element is
/// inverted or degenerate (det J <= 0 at a Gauss point).
///
/// The integration sees neither the size of the modulus, of the density nor the unit of
/// length: it runs on the nodes relative to the first, divided by h, the power of two nearest
/// their largest coordinate, with the modulus and the density divided by the powers of two
/// nearest them; K is then that times those powers of E and h, M times rho's and h^3 (exact
/// scalings, all powers of two). Whether a brick is degenerate is thereby a
/// matter of its shape alone, and a modulus or a size near the ends of the floating-point
/// range shows as an infinite or zero entry of the result, which the caller checks
/// ([`super::Solid::generate`]), never as a failed integration.
pub fn hex8(x: &[[f64; 3]; 8], material: &Material) -> Option<HexMatrices> {
    let extent = x
        .iter()
        .flat_map(|p| (0..3).map(move |i| (p[i] - x[0][i]).abs()))
        .fold(0.0_f64, f64::max);
    if !(extent.is_finite() && extent > 0.0) {
        return None;
    }
    let h = 2f64.powi((extent.log2().round() as i32).clamp(-1022, 1023));
    let unit_x: [[f64; 3]; 8] =
        std::array::from_fn(|a| std::array::from_fn(|i| (x[a][i] - x[0][i]) / h));
    // Powers of two too: the integration at E / 2^a and rho / 2^b rounds exactly as at E and
    // rho would, had the products not left a double's range.
    let two = |v: f64| 2f64.powi((v.log2().round() as i32).clamp(-1022, 1023));
    let (e_unit, rho_unit) = (two(material.youngs_modulus), two(material.density));
    let unit = Material {
        youngs_modulus: material.youngs_modulus / e_unit,
        poisson_ratio: material.poisson_ratio,
        density: material.density / rho_unit,
    };
    let mut e = hex8_unit(&unit_x, &unit)?;
    let (k_scale, m_scale) = (e_unit * h, rho_unit * h * h * h);
    e.k.iter_mut().for_each(|v| *v *= k_scale);
    e.m.iter_mut().for_each(|v| *v *= m_scale);
    Some(e)
}

/// [`hex8`] on nodes of any scale, as given.
fn hex8_unit(x: &[[f64; 3]; 8], material: &Material) -> Option<HexMatrices> {
    let d = material.elasticity();
    let (inv0, det0) = jacobian(x, [0.0; 3]);
    if det0.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
        return None;
    }
    let mut kuu = vec![0.0; 24 * 24];
    let mut kua = vec![0.0; 24 * 9];
    let mut kaa = vec![0.0; 81];
    let mut m = vec![0.0; 24 * 24];
    for p in gauss_points() {
        let (inv, det) = jacobian(x, p);
        if det.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let grads = natural_gradients(p);
        let b = columns(grads.iter().map(|&g| strain_block(physical(&inv, g))));
        // The bubbles' natural gradients, mapped with the centre's Jacobian (Taylor).
        let bubbles = (0..3).map(|i| {
            let mut g = [0.0; 3];
            g[i] = -2.0 * p[i];
            strain_block(physical(&inv0, g))
        });
        let ba = columns(bubbles);
        add_btdb(&mut kuu, 24, &b, &b, &d, det);
        add_btdb(&mut kua, 9, &b, &ba, &d, det0);
        add_btdb(&mut kaa, 9, &ba, &ba, &d, det0 * det0 / det);
        let n = shape(p);
        for a in 0..8 {
            for c in 0..8 {
                let v = material.density * n[a] * n[c] * det;
                for dir in 0..3 {
                    m[(3 * a + dir) * 24 + 3 * c + dir] += v;
                }
            }
        }
    }
    condense(&mut kuu, &kua, &mut kaa)?;
    Some(HexMatrices { k: kuu, m })
}

/// K_uu -= K_ua K_aa^-1 K_au, by a Cholesky factor of K_aa (9 x 9, positive definite for a
/// valid element); `None` when it is not.
fn condense(kuu: &mut [f64], kua: &[f64], kaa: &mut [f64]) -> Option<()> {
    const N: usize = 9;
    for j in 0..N {
        let mut s = kaa[j * N + j];
        for k in 0..j {
            s -= kaa[j * N + k] * kaa[j * N + k];
        }
        if s.partial_cmp(&0.0) != Some(std::cmp::Ordering::Greater) {
            return None;
        }
        let l = s.sqrt();
        kaa[j * N + j] = l;
        for i in j + 1..N {
            let mut s = kaa[i * N + j];
            for k in 0..j {
                s -= kaa[i * N + k] * kaa[j * N + k];
            }
            kaa[i * N + j] = s / l;
        }
    }
    // W = L^-1 K_au (9 x 24); then K_uu -= W^T W.
    let mut w = vec![0.0; N * 24];
    for c in 0..24 {
        for i in 0..N {
            let mut s = kua[c * N + i];
            for k in 0..i {
                s -= kaa[i * N + k] * w[k * 24 + c];
            }
            w[i * 24 + c] = s / kaa[i * N + i];
        }
    }
    for r in 0..24 {
        for c in 0..24 {
            kuu[r * 24 + c] -= (0..N).map(|i| w[i * 24 + r] * w[i * 24 + c]).sum::<f64>();
        }
    }
    Some(())
}

#[cfg(test)]
mod tests {
    use super::*;

    const STEEL: Material = Material {
        youngs_modulus: 210e9,
        poisson_ratio: 0.3,
        density: 7850.0,
    };

    /// A distorted brick: the unit cube with its nodes moved.
    fn distorted() -> [[f64; 3]; 8] {
        let shift = [
            [0.0, 0.0, 0.0],
            [0.1, -0.05, 0.02],
            [-0.07, 0.12, 0.0],
            [0.05, 0.03, -0.04],
            [0.02, 0.0, 0.1],
            [-0.1, 0.05, 0.0],
            [0.08, 0.1, -0.06],
            [0.0, -0.08, 0.05],
        ];
        std::array::from_fn(|a| {
            std::array::from_fn(|i| 0.5 * (CORNERS[a][i] + 1.0) * [2.0, 1.0, 0.5][i] + shift[a][i])
        })
    }

    #[test]
    fn rigid_motions_have_no_stiffness_and_the_mass_is_the_volume_times_density() {
        let x = distorted();
        let e = hex8(&x, &STEEL).unwrap();
        let scale = e.k.iter().fold(0.0_f64, |a, v| a.max(v.abs()));
        for motion in 0..6 {
            let u: Vec<f64> = (0..24)
                .map(|d| {
                    let (a, dir) = (d / 3, d % 3);
                    if motion < 3 {
                        f64::from(u8::from(dir == motion))
                    } else {
                        // Rotation about axis motion - 3: omega x r.
                        let mut w = [0.0; 3];
                        w[motion - 3] = 1.0;
                        let r = x[a];
                        [
                            w[1] * r[2] - w[2] * r[1],
                            w[2] * r[0] - w[0] * r[2],
                            w[0] * r[1] - w[1] * r[0],
                        ][dir]
                    }
                })
                .collect();
            for r in 0..24 {
                let f: f64 = (0..24).map(|c| e.k[r * 24 + c] * u[c]).sum();
                assert!(f.abs() < 1e-12 * scale, "motion {motion}, row {r}: {f}");
            }
        }
        // Total mass in each direction: u^T M u with u a unit translation.
        assert!(jacobian(&x, [0.0; 3]).1 > 0.0);
        for dir in 0..3 {
            let total: f64 = (0..8)
                .flat_map(|a| (0..8).map(move |c| (a, c)))
                .map(|(a, c)| e.m[(3 * a + dir) * 24 + 3 * c + dir])
                .sum();
            let volume: f64 = gauss_points().iter().map(|&p| jacobian(&x, p).1).sum();
            assert!((total - STEEL.density * volume).abs() < 1e-12 * total);
        }
    }

    #[test]
    fn stiffness_is_symmetric_and_an_inverted_element_is_refused() {
        let e = hex8(&distorted(), &STEEL).unwrap();
        for r in 0..24 {
            for c in 0..24 {
                let (a, b) = (e.k[r * 24 + c], e.k[c * 24 + r]);
                assert!((a - b).abs() <= 1e-12 * a.abs().max(b.abs()).max(1.0));
            }
        }
        let mut x = distorted();
        x.swap(0, 4);
        x.swap(1, 5);
        x.swap(2, 6);
        x.swap(3, 7);
        assert!(hex8(&x, &STEEL).is_none());
    }
}

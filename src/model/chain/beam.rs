//! Beam elements: Euler-Bernoulli (Hermite cubic shape functions, consistent mass), or
//! Timoshenko where the section declares its shear (shear deformation and rotary inertia).
//!
//! Element DOFs are `(w_1, theta_1, w_2, theta_2)`: transverse displacement then rotation at
//! each end (of the cross-section, for a Timoshenko element). The Euler-Bernoulli matrices are
//! the textbook forms (e.g. Przemieniecki, *Theory of Matrix Structural Analysis*, ch. 5 and
//! 11):
//!
//! ```text
//!            EI  [ 12    6l   -12    6l  ]            rho A l [ 156   22l    54   -13l ]
//!   k_e  =  ---  [ 6l   4l^2  -6l   2l^2 ]    m_e  =  ------- [ 22l   4l^2   13l  -3l^2 ]
//!           l^3  [-12   -6l    12   -6l  ]              420   [ 54    13l   156   -22l ]
//!                [ 6l   2l^2  -6l   4l^2 ]                    [-13l  -3l^2  -22l   4l^2 ]
//! ```
//!
//! The Timoshenko element interpolates w and the rotation with the polynomials that solve the
//! static equations exactly (interdependent interpolation), with phi = 12 EI / (kappa G A l^2):
//!
//! ```text
//!               EI       [ 12    6l           -12    6l         ]
//!   k_e  =  ----------   [ 6l   (4 + phi)l^2  -6l   (2 - phi)l^2 ]
//!           (1+phi) l^3  [-12   -6l            12   -6l          ]
//!                        [ 6l   (2 - phi)l^2  -6l   (4 + phi)l^2 ]
//!
//!   m_e = rho A l / (1+phi)^2 [t] + rho I / ((1+phi)^2 l) [r], symmetric, with
//!     t11 = t33 = 13/35 + 7 phi/10 + phi^2/3        t13 = 9/70 + 3 phi/10 + phi^2/6
//!     t12 = -t34 = (11/210 + 11 phi/120 + phi^2/24) l
//!     t23 = -t14 = (13/420 + 3 phi/40 + phi^2/24) l
//!     t22 = t44 = (1/105 + phi/60 + phi^2/120) l^2  t24 = -(1/140 + phi/60 + phi^2/120) l^2
//!     r11 = r33 = -r13 = 6/5                        r12 = r14 = -r23 = -r34 = (1/10 - phi/2) l
//!     r22 = r44 = (2/15 + phi/6 + phi^2/3) l^2      r24 = (-1/30 - phi/6 + phi^2/6) l^2
//! ```
//!
//! (the consistent mass of those shape functions: Friedman and Kosmatka, *Computers &
//! Structures* 47, 1993). At phi = 0, k_e and t are the Euler-Bernoulli forms and r the
//! rotary inertia of a Rayleigh beam.

/// A 4x4 element matrix, row-major.
pub type ElementMatrix = [[f64; 4]; 4];

pub use crate::structure::{Section, Shear};

/// A length of a beam with another section (a stepped beam: a lap region, a reinforcement).
#[derive(Debug, Clone, PartialEq)]
pub struct Segment {
    /// Start, m from the beam's start.
    pub from: f64,
    /// End, m from the beam's start.
    pub to: f64,
    /// Its section.
    pub section: Section,
}

/// A beam of the chain, in SI units; validated by [`super::config`]. Its section is uniform
/// but for its [`Segment`]s.
#[derive(Debug, Clone, PartialEq)]
pub struct Beam {
    /// Length, m.
    pub length: f64,
    /// Number of finite elements when the beam has no segment, support, attachment or sensor
    /// inside it; with such break points, every interval between them gets elements of about
    /// `length / elements` (at least one).
    pub elements: usize,
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Density rho, kg/m^3.
    pub density: f64,
    /// Cross-section area A, m^2.
    pub area: f64,
    /// Second moment of area I, m^4.
    pub second_moment: f64,
    /// Shear deformation and rotary inertia (a Timoshenko beam); `None`: Euler-Bernoulli.
    pub shear: Option<Shear>,
    /// Stepped lengths, ascending, not overlapping.
    pub segments: Vec<Segment>,
}

impl Beam {
    /// A uniform beam.
    pub fn uniform(length: f64, elements: usize, section: Section) -> Self {
        Self {
            length,
            elements,
            youngs_modulus: section.youngs_modulus,
            density: section.density,
            area: section.area,
            second_moment: section.second_moment,
            shear: section.shear,
            segments: Vec::new(),
        }
    }

    /// The beam's own section (outside its segments).
    pub fn section(&self) -> Section {
        Section {
            youngs_modulus: self.youngs_modulus,
            density: self.density,
            area: self.area,
            second_moment: self.second_moment,
            shear: self.shear,
        }
    }

    /// The section at `s` m from the beam's start.
    pub fn section_at(&self, s: f64) -> Section {
        self.segments
            .iter()
            .find(|g| s >= g.from && s <= g.to)
            .map_or_else(|| self.section(), |g| g.section)
    }

    /// Length of one element of the uniform mesh, m.
    pub fn element_length(&self) -> f64 {
        self.length / self.elements as f64
    }

    /// Bending stiffness EI of the beam's own section, N m^2.
    pub fn bending_stiffness(&self) -> f64 {
        self.youngs_modulus * self.second_moment
    }

    /// Mass per unit length rho A of the beam's own section, kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.density * self.area
    }

    /// Total mass, segments included, kg.
    pub fn mass(&self) -> f64 {
        let own = self.mass_per_length() * self.length;
        self.segments.iter().fold(own, |m, g| {
            m + (g.section.mass_per_length() - self.mass_per_length()) * (g.to - g.from)
        })
    }

    /// Element stiffness matrix of the uniform mesh (see the module docs).
    pub fn element_stiffness(&self) -> ElementMatrix {
        element_stiffness(&self.section(), self.element_length())
    }

    /// Element consistent mass matrix of the uniform mesh (see the module docs).
    pub fn element_mass(&self) -> ElementMatrix {
        element_mass(&self.section(), self.element_length())
    }
}

/// phi = 12 EI / (kappa G A l^2) of an element of length `l`: 0 for Euler-Bernoulli.
pub fn shear_ratio(section: &Section, l: f64) -> f64 {
    section
        .shear_rigidity()
        .map_or(0.0, |ga| 12.0 * section.bending_stiffness() / (ga * l * l))
}

/// Stiffness matrix of an element of length `l` (see the module docs).
pub fn element_stiffness(section: &Section, l: f64) -> ElementMatrix {
    timoshenko_stiffness(section, l, shear_ratio(section, l)).0
}

/// Consistent mass matrix of an element of length `l` (see the module docs).
pub fn element_mass(section: &Section, l: f64) -> ElementMatrix {
    if section.shear.is_none() {
        let c = section.mass_per_length() * l / 420.0;
        return scale(
            [
                [156.0, 22.0 * l, 54.0, -13.0 * l],
                [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
                [54.0, 13.0 * l, 156.0, -22.0 * l],
                [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
            ],
            c,
        );
    }
    timoshenko_mass(section, l, shear_ratio(section, l)).0
}

/// The Timoshenko element's stiffness at `phi` in place of the section's, and its derivative
/// in phi: c (S0 + phi S1) / (1 + phi) and c (S1 - S0) / (1 + phi)^2, c = EI / l^3.
pub fn timoshenko_stiffness(section: &Section, l: f64, phi: f64) -> (ElementMatrix, ElementMatrix) {
    let c = section.bending_stiffness() / (l * l * l);
    let l2 = l * l;
    let s0 = [
        [12.0, 6.0 * l, -12.0, 6.0 * l],
        [6.0 * l, 4.0 * l2, -6.0 * l, 2.0 * l2],
        [-12.0, -6.0 * l, 12.0, -6.0 * l],
        [6.0 * l, 2.0 * l2, -6.0 * l, 4.0 * l2],
    ];
    let s1 = [
        [0.0, 0.0, 0.0, 0.0],
        [0.0, l2, 0.0, -l2],
        [0.0, 0.0, 0.0, 0.0],
        [0.0, -l2, 0.0, l2],
    ];
    let value = from_fn(|i, j| c * (s0[i][j] + phi * s1[i][j]) / (1.0 + phi));
    let slope = from_fn(|i, j| c * (s1[i][j] - s0[i][j]) / ((1.0 + phi) * (1.0 + phi)));
    (value, slope)
}

/// The Timoshenko element's consistent mass at `phi` in place of the section's, and its
/// derivative in phi (the module docs' t and r, each a quadratic in phi over (1 + phi)^2).
pub fn timoshenko_mass(section: &Section, l: f64, phi: f64) -> (ElementMatrix, ElementMatrix) {
    let l2 = l * l;
    // [constant, linear, quadratic] coefficients of each distinct entry.
    let t11 = [13.0 / 35.0, 7.0 / 10.0, 1.0 / 3.0];
    let t13 = [9.0 / 70.0, 3.0 / 10.0, 1.0 / 6.0];
    let t12 = [11.0 / 210.0, 11.0 / 120.0, 1.0 / 24.0].map(|x| x * l);
    let t23 = [13.0 / 420.0, 3.0 / 40.0, 1.0 / 24.0].map(|x| x * l);
    let t22 = [1.0 / 105.0, 1.0 / 60.0, 1.0 / 120.0].map(|x| x * l2);
    let t24 = [-1.0 / 140.0, -1.0 / 60.0, -1.0 / 120.0].map(|x| x * l2);
    let n23 = t23.map(|x| -x);
    let n12 = t12.map(|x| -x);
    let translation = [
        [t11, t12, t13, n23],
        [t12, t22, t23, t24],
        [t13, t23, t11, n12],
        [n23, t24, n12, t22],
    ];
    let r11 = [1.2, 0.0, 0.0];
    let r12 = [0.1 * l, -0.5 * l, 0.0];
    let r22 = [2.0 / 15.0, 1.0 / 6.0, 1.0 / 3.0].map(|x| x * l2);
    let r24 = [-1.0 / 30.0, -1.0 / 6.0, 1.0 / 6.0].map(|x| x * l2);
    let (n11, m12) = (r11.map(|x| -x), r12.map(|x| -x));
    let rotation = [
        [r11, r12, n11, r12],
        [r12, r22, m12, r24],
        [n11, m12, r11, m12],
        [r12, r24, m12, r22],
    ];
    let ct = section.mass_per_length() * l;
    let cr = section.density * section.second_moment / l;
    // q(phi) / (1 + phi)^2 and its derivative (q' (1 + phi) - 2 q) / (1 + phi)^3.
    let over = |q: [f64; 3]| {
        let v = q[0] + phi * (q[1] + phi * q[2]);
        let d = q[1] + 2.0 * phi * q[2];
        let p1 = 1.0 + phi;
        (v / (p1 * p1), (d * p1 - 2.0 * v) / (p1 * p1 * p1))
    };
    let entry = |i: usize, j: usize| {
        let (t, dt) = over(translation[i][j]);
        let (r, dr) = over(rotation[i][j]);
        (ct * t + cr * r, ct * dt + cr * dr)
    };
    (from_fn(|i, j| entry(i, j).0), from_fn(|i, j| entry(i, j).1))
}

fn from_fn(f: impl Fn(usize, usize) -> f64) -> ElementMatrix {
    std::array::from_fn(|i| std::array::from_fn(|j| f(i, j)))
}

fn scale(mut a: ElementMatrix, c: f64) -> ElementMatrix {
    for row in &mut a {
        for x in row {
            *x *= c;
        }
    }
    a
}

#[cfg(test)]
mod tests {
    use super::*;

    fn unit_beam() -> Beam {
        // One element of length 2 with EI = 8 and rho A = 420 / 2 so that the prefactors are 1.
        Beam {
            length: 2.0,
            elements: 1,
            youngs_modulus: 8.0,
            density: 210.0,
            area: 1.0,
            second_moment: 1.0,
            shear: None,
            segments: Vec::new(),
        }
    }

    #[test]
    fn element_matrices_match_the_textbook_forms_entry_by_entry() {
        let b = unit_beam();
        let k = b.element_stiffness();
        let m = b.element_mass();
        // EI/l^3 = 1 and rho A l / 420 = 1, l = 2.
        let k_ref = [
            [12.0, 12.0, -12.0, 12.0],
            [12.0, 16.0, -12.0, 8.0],
            [-12.0, -12.0, 12.0, -12.0],
            [12.0, 8.0, -12.0, 16.0],
        ];
        let m_ref = [
            [156.0, 44.0, 54.0, -26.0],
            [44.0, 16.0, 26.0, -12.0],
            [54.0, 26.0, 156.0, -44.0],
            [-26.0, -12.0, -44.0, 16.0],
        ];
        assert_eq!(k, k_ref);
        assert_eq!(m, m_ref);
    }

    #[test]
    fn element_mass_carries_the_element_mass_in_translation() {
        // A rigid translation w = 1 has kinetic energy 1/2 * m_total: u^T m u = rho A l.
        let b = Beam {
            length: 0.3,
            elements: 3,
            ..unit_beam()
        };
        let m = b.element_mass();
        let u = [1.0, 0.0, 1.0, 0.0];
        let mut e = 0.0;
        for i in 0..4 {
            for j in 0..4 {
                e += u[i] * m[i][j] * u[j];
            }
        }
        let expected = b.mass_per_length() * b.element_length();
        assert!((e - expected).abs() < 1e-12 * expected, "{e} vs {expected}");
    }

    #[test]
    fn element_stiffness_is_zero_on_rigid_motions() {
        let b = Beam {
            length: 0.7,
            elements: 5,
            ..unit_beam()
        };
        let k = b.element_stiffness();
        let l = b.element_length();
        // translation and rotation about the first node
        for u in [[1.0, 0.0, 1.0, 0.0], [0.0, 1.0, l, 1.0]] {
            for row in &k {
                let f: f64 = row.iter().zip(&u).map(|(a, b)| a * b).sum();
                assert!(f.abs() < 1e-12 * k[0][0], "{f}");
            }
        }
    }

    /// A Timoshenko section with phi = `phi` on elements of length `l` (EI = 8, GA from phi).
    fn timoshenko(phi: f64, l: f64) -> Section {
        let ei = 8.0;
        Section {
            youngs_modulus: 8.0,
            density: 210.0,
            area: 1.0,
            second_moment: 1.0,
            shear: Some(Shear {
                factor: 1.0,
                modulus: 12.0 * ei / (phi * l * l),
            }),
        }
    }

    fn quadratic(a: &ElementMatrix, u: &[f64; 4]) -> f64 {
        (0..4)
            .map(|i| (0..4).map(|j| u[i] * a[i][j] * u[j]).sum::<f64>())
            .sum()
    }

    #[test]
    fn a_timoshenko_element_is_stiffness_free_on_rigid_motions_and_carries_its_mass() {
        let l = 0.2;
        for phi in [1e-3, 0.3, 4.0] {
            let s = timoshenko(phi, l);
            assert!((shear_ratio(&s, l) - phi).abs() < 1e-12 * phi);
            let k = element_stiffness(&s, l);
            for u in [[1.0, 0.0, 1.0, 0.0], [0.0, 1.0, l, 1.0]] {
                for row in &k {
                    let f: f64 = row.iter().zip(&u).map(|(a, b)| a * b).sum();
                    assert!(f.abs() < 1e-12 * k[1][1], "phi {phi}: {f}");
                }
            }
            // A translation moves the element's mass rho A l and turns no section.
            let m = element_mass(&s, l);
            let e = quadratic(&m, &[1.0, 0.0, 1.0, 0.0]);
            let expected = s.mass_per_length() * l;
            assert!((e - expected).abs() < 1e-12 * expected, "phi {phi}: {e}");
            // A rigid rotation about the first node: the translation's inertia about it,
            // rho A l^3 / 3, plus the sections' rotary inertia rho I l.
            let e = quadratic(&m, &[0.0, 1.0, l, 1.0]);
            let expected = s.mass_per_length() * l.powi(3) / 3.0 + s.density * s.second_moment * l;
            assert!((e - expected).abs() < 1e-12 * expected, "phi {phi}: {e}");
        }
    }

    #[test]
    fn without_shear_flexibility_the_timoshenko_element_is_the_rayleigh_beam() {
        // phi -> 0: the Euler-Bernoulli stiffness, and the Euler-Bernoulli mass plus the
        // rotary inertia rho I / (30 l) [36, 3l, -36, 3l; ...].
        let l = 0.2;
        let s = timoshenko(1e-12, l);
        let eb = s.euler_bernoulli();
        let (k, k0) = (element_stiffness(&s, l), element_stiffness(&eb, l));
        let (m, m0) = (element_mass(&s, l), element_mass(&eb, l));
        let c = s.density * s.second_moment / (30.0 * l);
        let rotary = [
            [36.0, 3.0 * l, -36.0, 3.0 * l],
            [3.0 * l, 4.0 * l * l, -3.0 * l, -l * l],
            [-36.0, -3.0 * l, 36.0, -3.0 * l],
            [3.0 * l, -l * l, -3.0 * l, 4.0 * l * l],
        ];
        for i in 0..4 {
            for j in 0..4 {
                assert!((k[i][j] - k0[i][j]).abs() < 1e-9 * k0[1][1], "k {i} {j}");
                let want = m0[i][j] + c * rotary[i][j];
                assert!((m[i][j] - want).abs() < 1e-9 * m0[0][0], "m {i} {j}");
            }
        }
    }

    #[test]
    fn the_phi_derivatives_match_central_differences() {
        let l = 0.2;
        let s = timoshenko(0.5, l);
        for phi in [0.0, 0.5, 3.0] {
            let h = 1e-6;
            for f in [timoshenko_stiffness, timoshenko_mass] {
                let (_, d) = f(&s, l, phi);
                let (up, down) = (f(&s, l, phi + h).0, f(&s, l, phi - h).0);
                let big = d.iter().flatten().fold(0.0f64, |a, x| a.max(x.abs()));
                for i in 0..4 {
                    for j in 0..4 {
                        let fd = (up[i][j] - down[i][j]) / (2.0 * h);
                        assert!(
                            (fd - d[i][j]).abs() < 1e-6 * big,
                            "phi {phi} {i} {j}: {fd} vs {}",
                            d[i][j]
                        );
                    }
                }
            }
        }
    }
}

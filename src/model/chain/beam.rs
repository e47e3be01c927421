//! Euler-Bernoulli beam elements: Hermite cubic shape functions, consistent mass.
//!
//! Element DOFs are `(w_1, theta_1, w_2, theta_2)`: transverse displacement then rotation at
//! each end. The matrices are the textbook forms (e.g. Przemieniecki, *Theory of Matrix
//! Structural Analysis*, ch. 5 and 11):
//!
//! ```text
//!            EI  [ 12    6l   -12    6l  ]            rho A l [ 156   22l    54   -13l ]
//!   k_e  =  ---  [ 6l   4l^2  -6l   2l^2 ]    m_e  =  ------- [ 22l   4l^2   13l  -3l^2 ]
//!           l^3  [-12   -6l    12   -6l  ]              420   [ 54    13l   156   -22l ]
//!                [ 6l   2l^2  -6l   4l^2 ]                    [-13l  -3l^2  -22l   4l^2 ]
//! ```

/// A 4x4 element matrix, row-major.
pub type ElementMatrix = [[f64; 4]; 4];

pub use crate::structure::Section;

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

/// Stiffness matrix of an element of length `l` (see the module docs).
pub fn element_stiffness(section: &Section, l: f64) -> ElementMatrix {
    let c = section.bending_stiffness() / (l * l * l);
    scale(
        [
            [12.0, 6.0 * l, -12.0, 6.0 * l],
            [6.0 * l, 4.0 * l * l, -6.0 * l, 2.0 * l * l],
            [-12.0, -6.0 * l, 12.0, -6.0 * l],
            [6.0 * l, 2.0 * l * l, -6.0 * l, 4.0 * l * l],
        ],
        c,
    )
}

/// Consistent mass matrix of an element of length `l` (see the module docs).
pub fn element_mass(section: &Section, l: f64) -> ElementMatrix {
    let c = section.mass_per_length() * l / 420.0;
    scale(
        [
            [156.0, 22.0 * l, 54.0, -13.0 * l],
            [22.0 * l, 4.0 * l * l, 13.0 * l, -3.0 * l * l],
            [54.0, 13.0 * l, 156.0, -22.0 * l],
            [-13.0 * l, -3.0 * l * l, -22.0 * l, 4.0 * l * l],
        ],
        c,
    )
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
}

//! Where a structure can carry the effects a model may lack (`crate::model::effects`): its
//! joints, its beam elements with their sections, its free ends, and its total mass. A builder
//! fills what it knows; an external model may know none of it, and the effects that need a
//! site then do not apply.

use super::dofs::{Direction, LineElement};

/// The section of a beam element, SI units.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Section {
    /// Young's modulus E, Pa.
    pub youngs_modulus: f64,
    /// Density rho, kg/m^3.
    pub density: f64,
    /// Area A, m^2.
    pub area: f64,
    /// Second moment of area I, m^4.
    pub second_moment: f64,
    /// Shear deformation and rotary inertia (a Timoshenko beam); `None`: Euler-Bernoulli.
    pub shear: Option<Shear>,
}

/// The shear properties of a Timoshenko section.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Shear {
    /// Shear correction factor kappa (5/6 for a solid rectangle).
    pub factor: f64,
    /// Shear modulus G, Pa.
    pub modulus: f64,
}

impl Section {
    /// Bending stiffness EI, N m^2.
    pub fn bending_stiffness(&self) -> f64 {
        self.youngs_modulus * self.second_moment
    }

    /// Mass per unit length rho A, kg/m.
    pub fn mass_per_length(&self) -> f64 {
        self.density * self.area
    }

    /// Squared radius of gyration I / A, m^2.
    pub fn gyration_squared(&self) -> f64 {
        self.second_moment / self.area
    }

    /// Shear rigidity kappa G A, N; `None` for an Euler-Bernoulli section.
    pub fn shear_rigidity(&self) -> Option<f64> {
        self.shear.map(|s| s.factor * s.modulus * self.area)
    }

    /// The same section without shear deformation or rotary inertia.
    pub fn euler_bernoulli(&self) -> Self {
        Self {
            shear: None,
            ..*self
        }
    }
}

/// A joint between two beam ends.
#[derive(Debug, Clone, PartialEq)]
pub struct JointSite {
    /// Abscissa, m.
    pub x: f64,
    /// w DOFs of its two nodes (`None` where a support removed it).
    pub w: [Option<usize>; 2],
    /// theta DOFs of its two nodes.
    pub theta: [Option<usize>; 2],
    /// Sections of the two beam ends it joins.
    pub sections: [Section; 2],
    /// Indices of its k1 and k2 (of a layered lap: k_n and k_s) in the structure's
    /// parameters.
    pub parameters: [usize; 2],
    /// Whether it is a layered lap (a distributed interface over an overlap).
    pub lap: bool,
    /// Of a layered lap with notched roots: the index of their k_r in the structure's
    /// parameters.
    pub root: Option<usize>,
}

/// A beam element.
#[derive(Debug, Clone, PartialEq)]
pub struct ElementSite {
    /// Beam of the chain, 0-based.
    pub beam: usize,
    /// Position and DOFs.
    pub line: LineElement,
    /// Section.
    pub section: Section,
}

impl ElementSite {
    /// Length, m.
    pub fn length(&self) -> f64 {
        self.line.x[1] - self.line.x[0]
    }
}

/// A free end of the chain (no support there).
#[derive(Debug, Clone, PartialEq)]
pub struct EndSite {
    /// Abscissa, m.
    pub x: f64,
    /// Its w DOF.
    pub w: usize,
    /// Its theta DOF.
    pub theta: usize,
}

/// A support that holds motions of the chain rigidly (clamped, pinned, guided): the builder
/// removed their DOFs.
#[derive(Debug, Clone, PartialEq)]
pub struct SupportSite {
    /// Abscissa, m.
    pub x: f64,
    /// Section of the beam there.
    pub section: Section,
    /// The motions it holds (w before theta), in [`HeldMotions`] order.
    pub held: Vec<Direction>,
}

/// The beam's stiffness or mass on the motions the rigid supports hold: what their removed
/// DOFs would carry were the supports not rigid.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HeldCoupling {
    /// Among the held motions, n_h x n_h (row by row).
    pub own: Vec<Vec<f64>>,
    /// Of each held motion with the DOFs of the structure: (DOF, value), one entry per DOF.
    pub free: Vec<Vec<(usize, f64)>>,
}

/// The motions held by the rigid supports, in support order (w before theta at each), with
/// the beam's stiffness and mass on them.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct HeldMotions {
    /// Stiffness.
    pub stiffness: HeldCoupling,
    /// Mass.
    pub mass: HeldCoupling,
}

/// The sites of a structure.
#[derive(Debug, Clone, Default, PartialEq)]
pub struct Sites {
    /// Mass of all beams (attachments excluded), kg: the scale of effect sizes.
    pub beam_mass: f64,
    /// Number of beams (0 for a model without beams).
    pub beams: usize,
    /// Joints, in chain order.
    pub joints: Vec<JointSite>,
    /// Beam elements, in chain order.
    pub elements: Vec<ElementSite>,
    /// Free ends.
    pub free_ends: Vec<EndSite>,
    /// Rigid supports away from joints (a support at a joint holds both joint nodes and stays
    /// rigid).
    pub supports: Vec<SupportSite>,
    /// The motions those supports hold.
    pub held: HeldMotions,
}

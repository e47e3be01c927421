//! How a beam chain is held and what is attached to it in a test: supports, point masses
//! (with rotary inertia, rigidly attached or hanging on a spring) and sensors.

use crate::structure::Direction;

/// A support of the chain at abscissa `x`. It acts on every node at `x` (both nodes of a joint).
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// Abscissa along the chain, m.
    pub x: f64,
    /// What it holds.
    pub kind: SupportKind,
    /// For a spring support: whether its translational and rotational stiffnesses are
    /// identified parameters (otherwise part of the model).
    pub identify: [bool; 2],
}

/// What a support holds.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum SupportKind {
    /// w and theta held (the DOFs are removed).
    Clamped,
    /// w held, theta free.
    Pinned,
    /// theta held, w free (a sliding clamp).
    Guided,
    /// Grounded springs on w (N/m) and theta (N m/rad); either may be zero.
    Spring {
        /// Translational stiffness, N/m.
        translational: f64,
        /// Rotational stiffness, N m/rad.
        rotational: f64,
    },
}

impl SupportKind {
    /// The name in the model file.
    pub fn name(&self) -> &'static str {
        match self {
            SupportKind::Clamped => "clamped",
            SupportKind::Pinned => "pinned",
            SupportKind::Guided => "guided",
            SupportKind::Spring { .. } => "spring",
        }
    }

    /// Whether the support removes the DOF of `direction`.
    pub fn removes(&self, direction: Direction) -> bool {
        matches!(
            (self, direction),
            (SupportKind::Clamped, _)
                | (SupportKind::Pinned, Direction::W)
                | (SupportKind::Guided, Direction::Theta)
        )
    }

    /// Whether it restrains translation and rotation (removed or sprung), for the count of
    /// rigid-body modes.
    pub fn restrains(&self) -> (bool, bool) {
        match *self {
            SupportKind::Spring {
                translational,
                rotational,
            } => (translational > 0.0, rotational > 0.0),
            _ => (self.removes(Direction::W), self.removes(Direction::Theta)),
        }
    }
}

/// A point mass at abscissa `x` (a stinger, an accelerometer, a bolt head).
#[derive(Debug, Clone, PartialEq)]
pub struct PointMass {
    /// Abscissa, m.
    pub x: f64,
    /// Mass, kg.
    pub mass: f64,
    /// Rotary inertia about the bending axis, kg m^2 (rigidly attached masses only).
    pub rotary_inertia: f64,
    /// `Some(k)`: the mass hangs on a translational spring of stiffness k (N/m) and moves on
    /// its own DOF; `None`: rigidly attached.
    pub spring: Option<f64>,
    /// Whether the mass is an identified parameter (its rotary inertia scales with it).
    pub identify: bool,
}

/// A sensor declared in the model: a node is placed at it, `simulate` can read it, and its
/// mass, if given, is part of the model.
#[derive(Debug, Clone, PartialEq)]
pub struct Sensor {
    /// Abscissa, m.
    pub x: f64,
    /// What it measures: w or theta.
    pub direction: Direction,
    /// Label in measured files, if any.
    pub label: Option<String>,
    /// Mass, kg (0: not modelled).
    pub mass: f64,
}

/// Number of rigid-body modes of a planar chain held by `supports`: the rigid motions
/// w = a + b x, theta = b, less the independent constraints the supports put on (a, b)
/// (a restrained translation at x: a + b x = 0; a restrained rotation: b = 0).
pub fn rigid_body_modes(supports: &[Support]) -> usize {
    let mut rows: Vec<[f64; 2]> = Vec::new();
    for s in supports {
        let (translation, rotation) = s.kind.restrains();
        if translation {
            rows.push([1.0, s.x]);
        }
        if rotation {
            rows.push([0.0, 1.0]);
        }
    }
    let rank = if rows.is_empty() {
        0
    } else if rows
        .iter()
        .any(|r| (r[0] * rows[0][1] - r[1] * rows[0][0]) != 0.0)
    {
        2
    } else {
        1
    };
    2 - rank
}

#[cfg(test)]
mod tests {
    use super::*;

    fn at(x: f64, kind: SupportKind) -> Support {
        Support {
            x,
            kind,
            identify: [false; 2],
        }
    }

    #[test]
    fn rigid_body_modes_follow_the_constraints() {
        assert_eq!(rigid_body_modes(&[]), 2);
        assert_eq!(rigid_body_modes(&[at(0.0, SupportKind::Clamped)]), 0);
        assert_eq!(rigid_body_modes(&[at(0.3, SupportKind::Pinned)]), 1);
        assert_eq!(
            rigid_body_modes(&[at(0.0, SupportKind::Pinned), at(0.5, SupportKind::Pinned)]),
            0
        );
        assert_eq!(rigid_body_modes(&[at(0.2, SupportKind::Guided)]), 1);
        let soft = SupportKind::Spring {
            translational: 10.0,
            rotational: 0.0,
        };
        assert_eq!(rigid_body_modes(&[at(0.0, soft), at(0.0, soft)]), 1);
        assert_eq!(rigid_body_modes(&[at(0.0, soft), at(0.4, soft)]), 0);
    }
}

//! Supports of a beam chain, every kind in this file: what a kind holds, its grounded springs,
//! its name and identifiable parameters, its `[[support]]` table in the model file, and the
//! count of rigid-body modes the supports leave.
//!
//! The kinds and their fields in the model file (any other field is refused by serde):
//!
//! | kind      | holds     | fields                                             |
//! |-----------|-----------|----------------------------------------------------|
//! | `clamped` | w, theta  | `x`                                                |
//! | `pinned`  | w         | `x`                                                |
//! | `guided`  | theta     | `x` (a sliding clamp)                              |
//! | `spring`  | -         | `x`, `translational` (N/m) and/or `rotational` (N m/rad) |
//!
//! Every kind accepts `identify`, the list of its identifiable parameters (a spring's
//! stiffnesses that are > 0). Adding a kind: a variant of [`SupportKind`] and of the raw
//! table, and the compiler points at every match to extend, all in this file ([`SupportKind::name`],
//! [`SupportKind::holds`], [`SupportKind::springs`], the raw table's validation); what it
//! restrains and may identify follow from what it holds and its springs.
//!
//! May import: the structure's directions and the input checks.

use serde::Deserialize;

use crate::input::{FieldCheck, InputError, TaggedTable};
use crate::structure::Direction;

/// A support of the chain at abscissa `x`. It acts on every node at `x` (both nodes of a joint).
#[derive(Debug, Clone, PartialEq)]
pub struct Support {
    /// Abscissa along the chain, m.
    pub x: f64,
    /// What it holds.
    pub kind: SupportKind,
    /// Whether its parameters of w and theta ([`SupportKind::identifiable`]) are identified
    /// parameters (otherwise part of the model).
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

/// The names of a support's grounded springs on w and theta, as the model file and the
/// parameter names (`support1.rotational`) write them.
pub const SPRING_NAMES: [&str; 2] = ["translational", "rotational"];

/// The units of a support's grounded springs on w and theta.
pub const SPRING_UNITS: [&str; 2] = ["N/m", "N m/rad"];

/// The slot of a chain's motion in the `[w, theta]` pairs below; `None` for the directions of
/// external models, which a chain has not.
pub fn motion_slot(direction: Direction) -> Option<usize> {
    match direction {
        Direction::W => Some(0),
        Direction::Theta => Some(1),
        Direction::X
        | Direction::Y
        | Direction::Z
        | Direction::Rx
        | Direction::Ry
        | Direction::Rz => None,
    }
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

    /// Whether it holds w and theta rigidly (the DOFs are removed).
    pub fn holds(&self) -> [bool; 2] {
        match self {
            SupportKind::Clamped => [true, true],
            SupportKind::Pinned => [true, false],
            SupportKind::Guided => [false, true],
            SupportKind::Spring { .. } => [false, false],
        }
    }

    /// Whether it holds a motion of its node (clamped, pinned, guided: a rigid support), not
    /// only springs.
    pub fn holds_a_motion(&self) -> bool {
        self.holds().contains(&true)
    }

    /// Its grounded springs on w (N/m) and theta (N m/rad); 0 where it has none.
    pub fn springs(&self) -> [f64; 2] {
        match *self {
            SupportKind::Clamped | SupportKind::Pinned | SupportKind::Guided => [0.0, 0.0],
            SupportKind::Spring {
                translational,
                rotational,
            } => [translational, rotational],
        }
    }

    /// Whether the support removes the DOF of `direction`.
    pub fn removes(&self, direction: Direction) -> bool {
        motion_slot(direction).is_some_and(|slot| self.holds()[slot])
    }

    /// Whether it restrains translation and rotation (held or sprung), for the count of
    /// rigid-body modes.
    pub fn restrains(&self) -> (bool, bool) {
        let (held, springs) = (self.holds(), self.springs());
        (held[0] || springs[0] > 0.0, held[1] || springs[1] > 0.0)
    }

    /// The parameters of w and theta that `identify` may list: its springs that are > 0.
    pub fn identifiable(&self) -> [Option<&'static str>; 2] {
        let springs = self.springs();
        std::array::from_fn(|slot| (springs[slot] > 0.0).then_some(SPRING_NAMES[slot]))
    }
}

/// A `[[support]]` table as written, one variant per kind with its own fields (parsed from a
/// [`TaggedTable`] by its `kind`).
#[derive(Debug, Deserialize)]
#[serde(rename_all = "lowercase", deny_unknown_fields)]
enum RawSupport {
    Clamped {
        x: f64,
        #[serde(default)]
        identify: Vec<String>,
    },
    Pinned {
        x: f64,
        #[serde(default)]
        identify: Vec<String>,
    },
    Guided {
        x: f64,
        #[serde(default)]
        identify: Vec<String>,
    },
    Spring {
        x: f64,
        translational: Option<f64>,
        rotational: Option<f64>,
        #[serde(default)]
        identify: Vec<String>,
    },
}

/// Where the supports of a model file are checked: the file's text (for the lines of errors),
/// the checks of its values, and what an abscissa must be.
pub(crate) struct SupportCheck<'a> {
    /// The model file's text.
    pub text: &'a str,
    /// The checks of its values.
    pub check: &'a FieldCheck<'a>,
    /// Checks an abscissa on the chain (field path, value).
    pub position: &'a dyn Fn(String, f64) -> Result<f64, InputError>,
}

impl SupportCheck<'_> {
    /// The `i`-th `[[support]]` table, validated; `earlier` are the supports before it (one
    /// support per position).
    pub(crate) fn support(
        &self,
        table: TaggedTable,
        i: usize,
        earlier: &[Support],
    ) -> Result<Support, InputError> {
        let p = |field: &str| format!("support[{i}].{field}");
        let raw: RawSupport =
            table.parse("kind", &format!("support[{i}]"), self.check.file, self.text)?;
        let (x, identify, kind) = match raw {
            RawSupport::Clamped { x, identify } => (x, identify, Ok(SupportKind::Clamped)),
            RawSupport::Pinned { x, identify } => (x, identify, Ok(SupportKind::Pinned)),
            RawSupport::Guided { x, identify } => (x, identify, Ok(SupportKind::Guided)),
            RawSupport::Spring {
                x,
                translational,
                rotational,
                identify,
            } => (x, identify, self.spring(translational, rotational, &p)),
        };
        let x = (self.position)(p("x"), x)?;
        if let Some(other) = earlier.iter().position(|o| o.x == x) {
            return Err(self.check.invalid(
                p("x"),
                x,
                format!("support[{other}] is already there: one support per position"),
            ));
        }
        let kind = kind?;
        let identifiable = kind.identifiable();
        let mut flags = [false; 2];
        for (k, name) in identify.iter().enumerate() {
            let Some(slot) = identifiable.iter().position(|n| *n == Some(name.as_str())) else {
                return Err(self.check.invalid(
                    p(&format!("identify[{k}]")),
                    format!("\"{name}\""),
                    "a spring support identifies its \"translational\" and/or \"rotational\" stiffness, when that stiffness is given and > 0",
                ));
            };
            flags[slot] = true;
        }
        Ok(Support {
            x,
            kind,
            identify: flags,
        })
    }

    fn spring(
        &self,
        translational: Option<f64>,
        rotational: Option<f64>,
        p: &dyn Fn(&str) -> String,
    ) -> Result<SupportKind, InputError> {
        if translational.is_none() && rotational.is_none() {
            return Err(self.check.invalid(
                p("kind"),
                "\"spring\"",
                "a spring support needs translational (N/m) and/or rotational (N m/rad)",
            ));
        }
        let stiffness = |slot: usize, value: Option<f64>| {
            self.check.non_negative(
                p(SPRING_NAMES[slot]),
                value.unwrap_or(0.0),
                SPRING_UNITS[slot],
            )
        };
        Ok(SupportKind::Spring {
            translational: stiffness(0, translational)?,
            rotational: stiffness(1, rotational)?,
        })
    }
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

    /// What each kind holds, springs, restrains and may identify, kind by kind.
    #[test]
    fn each_kind_states_its_motions() {
        let spring = SupportKind::Spring {
            translational: 0.0,
            rotational: 4.0,
        };
        let cases = [
            (SupportKind::Clamped, "clamped", [true, true], (true, true)),
            (SupportKind::Pinned, "pinned", [true, false], (true, false)),
            (SupportKind::Guided, "guided", [false, true], (false, true)),
            (spring, "spring", [false, false], (false, true)),
        ];
        for (kind, name, holds, restrains) in cases {
            assert_eq!(kind.name(), name);
            assert_eq!(
                [Direction::W, Direction::Theta].map(|d| kind.removes(d)),
                holds,
                "{name}"
            );
            assert!(!kind.removes(Direction::X), "{name}");
            assert_eq!(kind.restrains(), restrains, "{name}");
        }
        assert_eq!(spring.springs(), [0.0, 4.0]);
        assert_eq!(spring.identifiable(), [None, Some("rotational")]);
        assert_eq!(SupportKind::Clamped.identifiable(), [None, None]);
    }
}

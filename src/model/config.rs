//! The model file (TOML, SI units), parsed in two stages: raw serde structs that reject
//! unknown keys, then a validated [`Model`].
//!
//! ```toml
//! [[beam]]
//! length = 0.20            # m
//! elements = 7
//! youngs_modulus = 2.1e11  # Pa
//! density = 7850.0         # kg/m^3
//! area = 2.4e-3            # m^2
//! second_moment = 3.2e-7   # m^4
//!
//! [[joint]]
//! k1 = 1.0e7               # N/m
//! k2 = 1.0e4               # N m/rad
//! ```

use std::path::Path;

use serde::Deserialize;

use super::{Beam, Joint, Model};
use crate::input::{FieldCheck, InputError, parse_toml, read_file};

/// Largest number of beams: the identification takes at most
/// [`crate::identify::wls::MAX_Q`] parameters, two per joint.
pub const MAX_BEAMS: usize = crate::identify::wls::MAX_Q / 2 + 1;

/// Largest number of elements per beam: the modal solution is dense, O(N^3).
pub const MAX_ELEMENTS_PER_BEAM: i64 = 2000;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawModel {
    beam: Vec<RawBeam>,
    #[serde(default)]
    joint: Vec<RawJoint>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBeam {
    length: f64,
    elements: i64,
    youngs_modulus: f64,
    density: f64,
    area: f64,
    second_moment: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    k1: f64,
    k2: f64,
}

impl Model {
    /// Reads and validates a model file.
    pub fn from_path(path: &Path) -> Result<Model, InputError> {
        Model::from_toml(&read_file(path)?, path)
    }

    /// Parses and validates model TOML text; `file` names it in errors.
    pub fn from_toml(text: &str, file: &Path) -> Result<Model, InputError> {
        let raw: RawModel = parse_toml(text, file)?;
        let check = FieldCheck { file };
        if raw.beam.is_empty() || raw.beam.len() > MAX_BEAMS {
            return Err(check.invalid(
                "beam",
                format!("{} beam(s)", raw.beam.len()),
                format!("a chain has 1 to {MAX_BEAMS} [[beam]] tables"),
            ));
        }
        let beams = raw
            .beam
            .iter()
            .enumerate()
            .map(|(i, b)| {
                let p = |field: &str| format!("beam[{i}].{field}");
                Ok(Beam {
                    length: check.positive(p("length"), b.length, "m")?,
                    elements: check.int_range(
                        p("elements"),
                        b.elements,
                        1,
                        MAX_ELEMENTS_PER_BEAM,
                    )?,
                    youngs_modulus: check.positive(p("youngs_modulus"), b.youngs_modulus, "Pa")?,
                    density: check.positive(p("density"), b.density, "kg/m^3")?,
                    area: check.positive(p("area"), b.area, "m^2")?,
                    second_moment: check.positive(p("second_moment"), b.second_moment, "m^4")?,
                })
            })
            .collect::<Result<Vec<_>, InputError>>()?;
        if raw.joint.len() + 1 != beams.len() {
            return Err(check.invalid(
                "joint",
                format!("{} joint(s)", raw.joint.len()),
                format!(
                    "a chain of {} beam(s) needs exactly {} [[joint]] table(s), joint i connecting beam i to beam i+1",
                    beams.len(),
                    beams.len() - 1
                ),
            ));
        }
        let joints = raw
            .joint
            .iter()
            .enumerate()
            .map(|(i, j)| {
                Ok(Joint {
                    k1: check.positive(format!("joint[{i}].k1"), j.k1, "N/m")?,
                    k2: check.positive(format!("joint[{i}].k2"), j.k2, "N m/rad")?,
                })
            })
            .collect::<Result<Vec<_>, InputError>>()?;
        Ok(Model::new(beams, joints))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    const GOOD: &str = r#"
[[beam]]
length = 0.20
elements = 7
youngs_modulus = 2.1e11
density = 7850.0
area = 2.4e-3
second_moment = 3.2e-7

[[beam]]
length = 0.30
elements = 10
youngs_modulus = 2.1e11
density = 7850.0
area = 2.4e-3
second_moment = 3.2e-7

[[joint]]
k1 = 1.0e7
k2 = 1.0e4
"#;

    fn error_of(text: &str) -> String {
        Model::from_toml(text, Path::new("m.toml"))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn reads_the_paper_layout() {
        let model = Model::from_toml(GOOD, Path::new("m.toml")).unwrap();
        assert_eq!(model.beams().len(), 2);
        assert_eq!(model.dof_count(), 38);
        assert_eq!(
            model.joints()[0],
            Joint {
                k1: 1.0e7,
                k2: 1.0e4
            }
        );
    }

    #[test]
    fn negative_length_names_file_path_value_and_range() {
        let text = GOOD.replacen("length = 0.30", "length = -0.3", 1);
        assert_eq!(
            error_of(&text),
            "m.toml: beam[1].length = -0.3 is invalid: it must be finite and > 0 (m)"
        );
    }

    #[test]
    fn non_finite_and_zero_values_are_rejected() {
        let text = GOOD.replacen("density = 7850.0", "density = nan", 1);
        assert!(error_of(&text).starts_with("m.toml: beam[0].density = NaN is invalid"));
        let text = GOOD.replacen("k2 = 1.0e4", "k2 = 0.0", 1);
        assert_eq!(
            error_of(&text),
            "m.toml: joint[0].k2 = 0 is invalid: it must be finite and > 0 (N m/rad)"
        );
        let text = GOOD.replacen("elements = 7", "elements = 0", 1);
        assert_eq!(
            error_of(&text),
            "m.toml: beam[0].elements = 0 is invalid: it must be an integer from 1 to 2000"
        );
    }

    #[test]
    fn unknown_missing_and_mistyped_keys_name_the_path_and_line() {
        let text = GOOD.replacen("area = 2.4e-3", "aera = 2.4e-3", 1);
        let e = error_of(&text);
        assert!(
            e.starts_with("m.toml:7: beam[0].aera: unknown field `aera`, expected one of `length`"),
            "{e}"
        );
        let text = GOOD.replacen("elements = 10", "elements = \"ten\"", 1);
        let e = error_of(&text);
        assert!(
            e.starts_with(
                "m.toml:12: beam[1].elements: invalid type: string \"ten\", expected i64"
            ),
            "{e}"
        );
        let text = GOOD.replacen("k1 = 1.0e7\n", "", 1);
        let e = error_of(&text);
        assert!(e.contains("joint[0]: missing field `k1`"), "{e}");
    }

    #[test]
    fn joint_count_must_be_beams_minus_one() {
        let text = GOOD.replacen("[[joint]]\nk1 = 1.0e7\nk2 = 1.0e4\n", "", 1);
        let e = error_of(&text);
        assert!(
            e.starts_with(
                "m.toml: joint = 0 joint(s) is invalid: a chain of 2 beam(s) needs exactly 1"
            ),
            "{e}"
        );
    }
}

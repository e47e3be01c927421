//! The model file of an external model (TOML), parsed in two stages: raw serde structs that
//! reject unknown keys, then a validated [`MatricesFile`] with the paths resolved against the
//! TOML file's folder.
//!
//! ```toml
//! kind = "matrices"
//! stiffness = "K.mtx"          # K without the parameters' terms (Matrix Market)
//! mass = "M.mtx"               # M without the parameters' terms
//! dofs = "dofs.csv"            # dof,label,x,y,z,direction
//! rigid_body_modes = 2         # optional: checked against the model
//! sensor_tolerance = 0.005     # optional, m: sensors by x,y,z within it of a DOF
//!
//! [[parameter]]
//! name = "k1"
//! unit = "N/m"                 # optional
//! value = 1.0e7                # nominal p_i, > 0
//! dk = "dK_k1.mtx"             # dK/dp_i (required)
//! dm = "dM_k1.mtx"             # dM/dp_i (optional)
//! role = "identified"          # or "fixed"
//! ```
//!
//! The model's matrices at the parameter values are K = K_file + sum_i p_i dK/dp_i and the
//! same for M (eq. (8) is exact for them).

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::input::{FieldCheck, InputError};
use crate::structure::Role;

/// The units a parameter may declare (those of the builders' parameters).
pub const UNITS: [&str; 8] = ["N/m", "N m/rad", "N/rad", "N/m^2", "kg", "kg m^2", "-", ""];

/// The raw file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawMatrices {
    kind: String,
    stiffness: String,
    mass: String,
    dofs: String,
    rigid_body_modes: Option<i64>,
    sensor_tolerance: Option<f64>,
    #[serde(default)]
    parameter: Vec<RawParameter>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawParameter {
    name: String,
    unit: Option<String>,
    value: f64,
    dk: Option<String>,
    dm: Option<String>,
    role: Option<String>,
}

/// A validated model file: what to read and the parameters' settings.
#[derive(Debug, Clone, PartialEq)]
pub struct MatricesFile {
    /// The TOML file (errors name it).
    pub file: PathBuf,
    /// K without the parameters' terms.
    pub stiffness: PathBuf,
    /// M without the parameters' terms.
    pub mass: PathBuf,
    /// The DOF table.
    pub dofs: PathBuf,
    /// The declared number of rigid-body modes, if any.
    pub rigid_body_modes: Option<usize>,
    /// How far a sensor given by coordinates may lie from its nearest DOF, m (default: see
    /// [`crate::structure::nearest`]).
    pub sensor_tolerance: Option<f64>,
    /// The parameters, in file order.
    pub parameters: Vec<ParameterFile>,
}

/// One parameter of the file.
#[derive(Debug, Clone, PartialEq)]
pub struct ParameterFile {
    /// Name in output files.
    pub name: String,
    /// Unit, one of [`UNITS`].
    pub unit: &'static str,
    /// Nominal value p_i.
    pub value: f64,
    /// dK/dp_i.
    pub dk: PathBuf,
    /// dM/dp_i, if the parameter changes the mass.
    pub dm: Option<PathBuf>,
    /// Identified or fixed.
    pub role: Role,
}

impl RawMatrices {
    /// Validates the file; `file` is the TOML file, whose folder relative paths start from.
    pub(crate) fn validate(self, file: &Path) -> Result<MatricesFile, InputError> {
        let check = FieldCheck { file };
        if self.kind != "matrices" {
            return Err(check.invalid(
                "kind",
                format!("\"{}\"", self.kind),
                "this reader takes kind = \"matrices\"",
            ));
        }
        let folder = file.parent().unwrap_or(Path::new(""));
        let resolve = |path: &str, field: String| {
            if path.trim().is_empty() {
                Err(check.invalid(
                    field,
                    "\"\"",
                    "it must name a file (relative to the model file)",
                ))
            } else {
                Ok(folder.join(path))
            }
        };
        let rigid_body_modes = self
            .rigid_body_modes
            .map(|r| check.int_range("rigid_body_modes", r, 0, i64::from(u32::MAX)))
            .transpose()?;
        let sensor_tolerance = self
            .sensor_tolerance
            .map(|t| check.positive("sensor_tolerance", t, "m"))
            .transpose()?;
        if self.parameter.is_empty() {
            return Err(check.invalid(
                "parameter",
                "[]",
                "a model needs at least one [[parameter]] with its dK/dp",
            ));
        }
        let mut parameters: Vec<ParameterFile> = Vec::with_capacity(self.parameter.len());
        for (i, p) in self.parameter.into_iter().enumerate() {
            let at = |field: &str| format!("parameter[{i}].{field}");
            if p.name.trim().is_empty() || p.name.contains([',', ' ', '"']) {
                return Err(check.invalid(
                    at("name"),
                    format!("\"{}\"", p.name),
                    "a name is not empty and has no comma, space or quote (it is a CSV field)",
                ));
            }
            if let Some(first) = parameters.iter().position(|q| q.name == p.name) {
                return Err(check.invalid(
                    at("name"),
                    format!("\"{}\"", p.name),
                    format!("names must be unique (parameter[{first}] has it)"),
                ));
            }
            let unit = match p.unit.as_deref() {
                None => "",
                Some(u) => UNITS.into_iter().find(|k| *k == u).ok_or_else(|| {
                    check.invalid(
                        at("unit"),
                        format!("\"{u}\""),
                        format!("it must be one of \"{}\"", UNITS.join("\", \"")),
                    )
                })?,
            };
            let value = check.positive(at("value"), p.value, unit)?;
            let Some(dk) = p.dk else {
                return Err(check.invalid(
                    at("dk"),
                    "(missing)",
                    "every parameter needs dk, the Matrix Market file of dK/dp",
                ));
            };
            let dk = resolve(&dk, at("dk"))?;
            let dm = p.dm.map(|d| resolve(&d, at("dm"))).transpose()?;
            let role = match p.role.as_deref() {
                None | Some("identified") => Role::Identified,
                Some("fixed") => Role::Fixed,
                Some(other) => {
                    return Err(check.invalid(
                        at("role"),
                        format!("\"{other}\""),
                        "it must be \"identified\" or \"fixed\"",
                    ));
                }
            };
            parameters.push(ParameterFile {
                name: p.name,
                unit,
                value,
                dk,
                dm,
                role,
            });
        }
        Ok(MatricesFile {
            file: file.to_path_buf(),
            stiffness: resolve(&self.stiffness, "stiffness".into())?,
            mass: resolve(&self.mass, "mass".into())?,
            dofs: resolve(&self.dofs, "dofs".into())?,
            rigid_body_modes,
            sensor_tolerance,
            parameters,
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::input::parse_toml;

    fn validate(text: &str) -> Result<MatricesFile, String> {
        let file = Path::new("models/x/model.toml");
        parse_toml::<RawMatrices>(text, file)
            .and_then(|raw| raw.validate(file))
            .map_err(|e| e.to_string())
    }

    const HEAD: &str =
        "kind = \"matrices\"\nstiffness = \"K.mtx\"\nmass = \"M.mtx\"\ndofs = \"dofs.csv\"\n";

    #[test]
    fn paths_are_relative_to_the_model_file() {
        let f = validate(&format!(
            "{HEAD}[[parameter]]\nname = \"k\"\nvalue = 2.0\ndk = \"sub/dK.mtx\"\nrole = \"fixed\"\n"
        ))
        .unwrap();
        assert_eq!(f.stiffness, Path::new("models/x/K.mtx"));
        assert_eq!(f.parameters[0].dk, Path::new("models/x/sub/dK.mtx"));
        assert_eq!(f.parameters[0].role, Role::Fixed);
        assert_eq!(f.parameters[0].unit, "");
        assert_eq!(f.rigid_body_modes, None);
    }

    #[test]
    fn bad_fields_are_named_with_the_value_and_what_is_allowed() {
        let cases = [
            (
                format!("{HEAD}[[parameter]]\nname = \"k\"\nvalue = 2.0\n"),
                "models/x/model.toml: parameter[0].dk = (missing) is invalid: every parameter needs dk, the Matrix Market file of dK/dp",
            ),
            (
                format!("{HEAD}[[parameter]]\nname = \"k\"\nvalue = -2.0\ndk = \"d\"\n"),
                "models/x/model.toml: parameter[0].value = -2 is invalid: it must be finite and > 0 ()",
            ),
            (
                format!(
                    "{HEAD}[[parameter]]\nname = \"k\"\nvalue = 2.0\ndk = \"d\"\nrole = \"free\"\n"
                ),
                "models/x/model.toml: parameter[0].role = \"free\" is invalid: it must be \"identified\" or \"fixed\"",
            ),
            (
                format!(
                    "{HEAD}[[parameter]]\nname = \"k\"\nvalue = 2.0\ndk = \"d\"\n[[parameter]]\nname = \"k\"\nvalue = 2.0\ndk = \"d\"\n"
                ),
                "models/x/model.toml: parameter[1].name = \"k\" is invalid: names must be unique (parameter[0] has it)",
            ),
            (
                format!(
                    "{HEAD}[[parameter]]\nname = \"k\"\nunit = \"psi\"\nvalue = 2.0\ndk = \"d\"\n"
                ),
                "models/x/model.toml: parameter[0].unit = \"psi\" is invalid: it must be one of \"N/m\", \"N m/rad\", \"N/rad\", \"N/m^2\", \"kg\", \"kg m^2\", \"-\", \"\"",
            ),
            (
                HEAD.to_string(),
                "models/x/model.toml: parameter = [] is invalid: a model needs at least one [[parameter]] with its dK/dp",
            ),
        ];
        for (text, message) in cases {
            assert_eq!(validate(&text).unwrap_err(), message);
        }
    }
}

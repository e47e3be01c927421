//! The levels file of an amplitude fit (TOML; docs/formats.md, "Levels"): the model, and per
//! excitation level the measured-modes file of that level and where its response amplitude
//! comes from. Parsed in two stages: raw serde structs ([`RawLevels`], unknown keys refused),
//! then the validated [`Levels`] ([`Levels::from_str`]), whose errors name the file, the field
//! path, the value and what is allowed.
//!
//! ```toml
//! model = "models/unesp-bert.toml"   # the model the modes' points are read against
//! reference = 1                      # FRF response node whose peak gives the amplitude
//! excitation_unit = "V"              # the unit of `excitation` (labels only)
//! random_band_hz = 110.0             # a flat random excitation of this band, RMS = level
//! reference_x = 0.5                  # optional: the reference sensor in the modes files
//! reference_dof = "w"                # (x, dof): --joint then uses the joint's deformation
//!
//! [[level]]
//! excitation = 0.05                  # > 0, each level once
//! modes = "modes_0p05V.csv"          # measured modes with damping ratios
//! frf = "frf_0p05V.uff"              # amplitude = excitation x |H_reference(f_r)| ...
//! # acceleration = [0.21, 0.04]      # ... or given: m/s^2 per mode, at the reference sensor
//! ```
//!
//! Relative paths are relative to the levels file's folder.
//!
//! Imports: [`crate::input`].

use std::path::{Path, PathBuf};

use serde::Deserialize;

use crate::input::{FieldCheck, InputError, Number, parse_toml, read_file};

/// The most levels a levels file may hold. A test measures a handful to a few dozen levels
/// (UNESP-BERT: six); 200 fit in under a second, while the fit's time grows faster than the
/// count (5000 levels took minutes).
pub const MAX_LEVELS: usize = 200;

/// The levels file as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLevels {
    /// The model file.
    pub model: String,
    /// Response node of the FRFs whose peak gives the amplitude.
    pub reference: Option<u64>,
    /// Unit of the excitation (labels only).
    pub excitation_unit: Option<String>,
    /// Bandwidth (Hz) of a flat random excitation whose RMS is `excitation`.
    pub random_band_hz: Option<f64>,
    /// The reference sensor's point in the modes files: its abscissa (m) ...
    pub reference_x: Option<f64>,
    /// ... and direction (`w` by default).
    pub reference_dof: Option<String>,
    /// The levels.
    #[serde(default)]
    pub level: Vec<RawLevel>,
}

/// One level as written.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub struct RawLevel {
    /// Excitation level.
    pub excitation: f64,
    /// Measured-modes file.
    pub modes: String,
    /// FRF file (universal file, dataset 58).
    pub frf: Option<String>,
    /// Acceleration amplitude per mode (m/s^2).
    pub acceleration: Option<Vec<f64>>,
}

/// Where a level's response amplitude comes from.
#[derive(Debug, Clone, PartialEq)]
pub enum Source {
    /// The FRFs of the level: the amplitude is the excitation times the FRF's magnitude at
    /// the mode's frequency, at the reference node.
    Frf(PathBuf),
    /// Given acceleration amplitudes (m/s^2), one per mode in the order of the modes file.
    Acceleration(Vec<f64>),
}

/// One validated level.
#[derive(Debug, Clone, PartialEq)]
pub struct Level {
    /// Excitation level (> 0).
    pub excitation: f64,
    /// Measured-modes file.
    pub modes: PathBuf,
    /// Amplitude source.
    pub source: Source,
}

/// A validated levels file.
#[derive(Debug, Clone, PartialEq)]
pub struct Levels {
    /// The levels file.
    pub file: PathBuf,
    /// The model file.
    pub model: PathBuf,
    /// Reference response node (required with FRFs).
    pub reference: Option<u64>,
    /// Unit of the excitation ("" when not given).
    pub excitation_unit: String,
    /// Bandwidth (Hz) of a flat random excitation whose RMS is the level (None: harmonic
    /// excitation of amplitude the level).
    pub random_band_hz: Option<f64>,
    /// The reference sensor among the modes files' points (abscissa, direction): with it, the
    /// joint's fit (`--joint`) takes the joint's own deformation amplitude.
    pub reference_point: Option<(f64, String)>,
    /// The levels, in the file's order (at least two, distinct excitations).
    pub levels: Vec<Level>,
}

impl Levels {
    /// Reads and validates the levels file at `path`.
    pub fn from_path(path: &Path) -> Result<Self, InputError> {
        Self::from_str(&read_file(path)?, path)
    }

    /// Parses and validates levels TOML text; `file` names it in errors and its folder is
    /// where relative paths start.
    pub fn from_str(text: &str, file: &Path) -> Result<Self, InputError> {
        let raw: RawLevels = parse_toml(text, file)?;
        Self::validate(raw, file)
    }

    fn validate(raw: RawLevels, file: &Path) -> Result<Self, InputError> {
        let check = FieldCheck { file };
        let folder = file.parent().unwrap_or(Path::new(""));
        if raw.level.len() < 2 {
            return Err(check.invalid(
                "level",
                format!("{} level(s)", raw.level.len()),
                "an amplitude fit needs at least two [[level]] tables, each with its own \
                 excitation",
            ));
        }
        if raw.level.len() > MAX_LEVELS {
            return Err(check.invalid(
                "level",
                format!("{} levels", raw.level.len()),
                format!("an amplitude fit takes at most {MAX_LEVELS} [[level]] tables"),
            ));
        }
        let random_band_hz = match raw.random_band_hz {
            Some(b) => Some(check.positive("random_band_hz", b, "Hz")?),
            None => None,
        };
        let reference_point = match (raw.reference_x, raw.reference_dof) {
            (Some(x), dof) => {
                if !x.is_finite() {
                    return Err(check.invalid("reference_x", Number(x), "it must be finite (m)"));
                }
                let dof = dof.unwrap_or_else(|| "w".into());
                if dof != "w" && dof != "theta" {
                    return Err(check.invalid(
                        "reference_dof",
                        format!("\"{dof}\""),
                        "it must be \"w\" or \"theta\"",
                    ));
                }
                Some((x, dof))
            }
            (None, Some(dof)) => {
                return Err(check.invalid(
                    "reference_dof",
                    format!("\"{dof}\""),
                    "it needs `reference_x`, the reference sensor's abscissa in the modes files",
                ));
            }
            (None, None) => None,
        };
        let mut levels: Vec<Level> = Vec::with_capacity(raw.level.len());
        for (i, l) in raw.level.into_iter().enumerate() {
            let excitation = check.positive(
                format!("level[{i}].excitation"),
                l.excitation,
                "the excitation's unit",
            )?;
            if let Some(j) = levels.iter().position(|p| p.excitation == excitation) {
                return Err(check.invalid(
                    format!("level[{i}].excitation"),
                    Number(excitation),
                    format!("it must differ from level[{j}].excitation: each level once"),
                ));
            }
            let source = match (l.frf, l.acceleration) {
                (Some(frf), None) => {
                    if raw.reference.is_none() {
                        return Err(check.invalid(
                            "reference",
                            "(absent)",
                            format!(
                                "level[{i}].frf needs `reference`, the response node of the \
                                 FRFs whose peak gives the amplitude"
                            ),
                        ));
                    }
                    Source::Frf(folder.join(frf))
                }
                (None, Some(values)) => {
                    for (k, &v) in values.iter().enumerate() {
                        check.positive(format!("level[{i}].acceleration[{k}]"), v, "m/s^2")?;
                    }
                    Source::Acceleration(values)
                }
                (None, None) => {
                    return Err(check.invalid(
                        format!("level[{i}]"),
                        "no amplitude",
                        "give `frf` (the level's FRFs: amplitude = excitation x the FRF's \
                         magnitude at the mode's frequency, at `reference`) or `acceleration` \
                         (m/s^2, one per mode)",
                    ));
                }
                (Some(_), Some(_)) => {
                    return Err(check.invalid(
                        format!("level[{i}]"),
                        "both `frf` and `acceleration`",
                        "give one source of the amplitude, not both",
                    ));
                }
            };
            levels.push(Level {
                excitation,
                modes: folder.join(l.modes),
                source,
            });
        }
        Ok(Self {
            file: file.to_path_buf(),
            model: folder.join(raw.model),
            reference: raw.reference,
            excitation_unit: raw.excitation_unit.unwrap_or_default(),
            random_band_hz,
            reference_point,
            levels,
        })
    }

    /// Every file the levels file names (model, modes, FRFs): with the files the model names
    /// (`output::guard::model_inputs`), the inputs an output must not overwrite.
    pub fn inputs(&self) -> Vec<PathBuf> {
        let mut files = vec![self.file.clone(), self.model.clone()];
        for l in &self.levels {
            files.push(l.modes.clone());
            if let Source::Frf(f) = &l.source {
                files.push(f.clone());
            }
        }
        files
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn read(text: &str) -> Result<Levels, String> {
        Levels::from_str(text, Path::new("dir/levels.toml")).map_err(|e| e.to_string())
    }

    #[test]
    fn more_levels_than_the_bound_are_refused_naming_the_count() {
        let level = |i: usize| {
            format!(
                "[[level]]\nexcitation = {}\nmodes = \"a.csv\"\nacceleration = [1.0]\n",
                i + 1
            )
        };
        let file = |n: usize| {
            format!(
                "model = \"m.toml\"\n{}",
                (0..n).map(level).collect::<String>()
            )
        };
        assert_eq!(read(&file(MAX_LEVELS)).unwrap().levels.len(), MAX_LEVELS);
        assert_eq!(
            read(&file(MAX_LEVELS + 1)).unwrap_err(),
            "dir/levels.toml: level = 201 levels is invalid: an amplitude fit takes at most 200 \
             [[level]] tables"
        );
    }

    #[test]
    fn paths_are_relative_to_the_levels_file() {
        let l = read(
            "model = \"m.toml\"\nreference = 1\n[[level]]\nexcitation = 0.1\nmodes = \"a.csv\"\n\
             frf = \"a.uff\"\n[[level]]\nexcitation = 0.2\nmodes = \"b.csv\"\n\
             acceleration = [1.0, 2.0]\n",
        )
        .unwrap();
        assert_eq!(l.model, PathBuf::from("dir/m.toml"));
        assert_eq!(l.levels[0].source, Source::Frf(PathBuf::from("dir/a.uff")));
        assert_eq!(l.levels[1].source, Source::Acceleration(vec![1.0, 2.0]));
    }
}

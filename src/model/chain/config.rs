//! The chain's model file (TOML, SI units), parsed in two stages: raw serde structs that
//! reject unknown keys, then a validated [`Chain`]. A `[[support]]` table is parsed by its
//! kind in [`super::support`].
//!
//! ```toml
//! [mesh]                     # optional
//! element_length = 0.01      # m: beams without `elements` get elements of at most this
//! nodes_at = [0.176]         # m: extra node positions
//!
//! [[beam]]
//! length = 0.20              # m
//! elements = 7               # or leave it out and set mesh.element_length
//! youngs_modulus = 2.1e11    # Pa
//! density = 7850.0           # kg/m^3
//! area = 2.4e-3              # m^2
//! second_moment = 3.2e-7     # m^4
//! # shear_factor = 0.8333    # optional: a Timoshenko beam (shear deformation and rotary
//! #                          # inertia), kappa; then shear_modulus (G, Pa) or poisson (nu,
//! #                          # G = E / (2 (1 + nu))); segments keep the beam's
//! [[beam.segment]]           # a stepped length of this beam (m from its start)
//! from = 0.16
//! to = 0.20
//! area = 4.8e-3              # and/or youngs_modulus, density, second_moment
//!
//! [[joint]]
//! k1 = 1.0e7                 # N/m
//! k2 = 1.0e4                 # N m/rad
//! fixed = ["k1"]             # optional: held at its value, not identified
//!
//! [[support]]                # optional, any number; none: free-free
//! x = 0.0                    # m along the chain
//! kind = "clamped"           # clamped | pinned | guided | spring: each kind its own fields
//! # translational = 1e5      # spring only: N/m
//! # rotational = 10.0        # spring only: N m/rad (one of the two at least)
//! # identify = ["rotational"] # spring: stiffnesses identified beside the joints
//!
//! [[mass]]                   # a point mass
//! x = 0.085
//! mass = 0.02                # kg
//! rotary_inertia = 1e-6      # kg m^2, optional
//! # spring = 5e4             # N/m: the mass hangs on a spring (its own DOF)
//! # identify = true          # the mass is identified beside the joints
//!
//! [[sensor]]                 # a sensor position: a node goes there
//! x = 0.5
//! dof = "w"                  # w (default) or theta
//! label = "acc1"             # optional
//! mass = 0.003               # kg, optional: then part of the model
//! ```

use std::path::Path;

use serde::Deserialize;

use super::Chain;
use super::beam::{Beam, Section, Segment, Shear};
use super::calibration::{BeamCalibration, Factor};
use super::joint::Joint;
use super::lap::{ROOT_PARAMETER, RawLap, lap};
use super::setup::{PointMass, Sensor};
use super::support::{Support, SupportCheck};
use crate::input::{FieldCheck, InputError, Number, TaggedTable};
use crate::structure::{Direction, Role};

/// Largest number of beams: the identification takes at most
/// [`crate::structure::MAX_IDENTIFIED`] parameters, two per joint.
pub const MAX_BEAMS: usize = crate::structure::MAX_IDENTIFIED / 2 + 1;

/// Largest number of elements per beam (above 120 DOFs the lowest modes come from the sparse
/// solver; beyond about 2 x 2000 elements the rounding of K itself limits the low modes).
pub const MAX_ELEMENTS_PER_BEAM: i64 = 2000;

/// The chain's model file.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawChain {
    #[serde(default)]
    kind: Option<String>,
    #[serde(default)]
    mesh: Option<RawMesh>,
    #[serde(default)]
    beam: Vec<RawBeam>,
    #[serde(default)]
    joint: Vec<RawJoint>,
    #[serde(default)]
    support: Vec<TaggedTable>,
    #[serde(default)]
    mass: Vec<RawMass>,
    #[serde(default)]
    sensor: Vec<RawSensor>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMesh {
    element_length: Option<f64>,
    #[serde(default)]
    nodes_at: Vec<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBeam {
    length: f64,
    elements: Option<i64>,
    youngs_modulus: f64,
    density: f64,
    area: f64,
    second_moment: f64,
    shear_factor: Option<f64>,
    shear_modulus: Option<f64>,
    poisson: Option<f64>,
    #[serde(default)]
    segment: Vec<RawSegment>,
    calibrated: Option<RawCalibrated>,
}

/// `[beam.calibrated]`: written by `jointid calibrate` (module
/// [`super::calibration`]).
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawCalibrated {
    stiffness_factor: Option<f64>,
    stiffness_factor_se: Option<f64>,
    density_factor: Option<f64>,
    density_factor_se: Option<f64>,
    reference: Option<String>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSegment {
    from: f64,
    to: f64,
    youngs_modulus: Option<f64>,
    density: Option<f64>,
    area: Option<f64>,
    second_moment: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawJoint {
    kind: Option<String>,
    k1: Option<f64>,
    k2: Option<f64>,
    #[serde(default)]
    fixed: Vec<String>,
    lap: Option<RawLap>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMass {
    x: f64,
    mass: f64,
    rotary_inertia: Option<f64>,
    spring: Option<f64>,
    #[serde(default)]
    identify: bool,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawSensor {
    x: f64,
    dof: Option<String>,
    label: Option<String>,
    mass: Option<f64>,
}

impl RawChain {
    /// Validates the raw file into a chain; `file` names it in errors, `text` is its text
    /// (for the lines of errors in its supports).
    pub(crate) fn validate(self, file: &Path, text: &str) -> Result<Chain, InputError> {
        let check = FieldCheck { file };
        if let Some(kind) = self.kind.as_deref().filter(|k| *k != "chain") {
            return Err(check.invalid(
                "kind",
                format!("\"{kind}\""),
                "a beam-chain model has kind = \"chain\" (or no kind)",
            ));
        }
        if self.beam.is_empty() || self.beam.len() > MAX_BEAMS {
            return Err(check.invalid(
                "beam",
                format!("{} beam(s)", self.beam.len()),
                format!("a chain has 1 to {MAX_BEAMS} [[beam]] tables"),
            ));
        }
        let element_length = self
            .mesh
            .as_ref()
            .and_then(|m| m.element_length)
            .map(|h| check.positive("mesh.element_length", h, "m"))
            .transpose()?;
        let beams = self
            .beam
            .iter()
            .enumerate()
            .map(|(i, b)| beam(b, i, element_length, &check))
            .collect::<Result<Vec<_>, InputError>>()?;
        let calibration = self
            .beam
            .iter()
            .enumerate()
            .filter_map(|(i, b)| Some(calibrated(b.calibrated.as_ref()?, i, &check)))
            .collect::<Result<Vec<_>, InputError>>()?;
        if self.joint.len() + 1 != beams.len() {
            return Err(check.invalid(
                "joint",
                format!("{} joint(s)", self.joint.len()),
                format!(
                    "a chain of {} beam(s) needs exactly {} [[joint]] table(s), joint i connecting beam i to beam i+1",
                    beams.len(),
                    beams.len() - 1
                ),
            ));
        }
        let joints = self
            .joint
            .iter()
            .enumerate()
            .map(|(i, j)| joint(j, i, &beams, &check))
            .collect::<Result<Vec<_>, InputError>>()?;
        super::layered::check_overlaps(&beams, &joints, &check)?;
        let length: f64 = beams.iter().map(|b| b.length).sum();
        let position = |path: String, x: f64| {
            if x.is_finite() && (0.0..=length).contains(&x) {
                Ok(x)
            } else {
                Err(check.invalid(
                    path,
                    x,
                    format!("it must lie on the chain, from 0 to {length} m"),
                ))
            }
        };
        let supports_check = SupportCheck {
            text,
            check: &check,
            position: &position,
        };
        let mut supports: Vec<Support> = Vec::with_capacity(self.support.len());
        for (i, table) in self.support.into_iter().enumerate() {
            let support = supports_check.support(table, i, &supports)?;
            supports.push(support);
        }
        super::layered::check_supports(&beams, &joints, &supports, &check)?;
        let masses = self
            .mass
            .iter()
            .enumerate()
            .map(|(i, m)| point_mass(m, i, &check, &position))
            .collect::<Result<Vec<_>, InputError>>()?;
        let sensors = sensors(&self.sensor, &check, &position)?;
        masses_within_bound(&beams, &masses, &sensors, &check)?;
        sensors_on_motions(&sensors, &supports, length, &check)?;
        identified_within_limit(&joints, &supports, &masses, &check)?;
        let nodes_at = self
            .mesh
            .map(|m| m.nodes_at)
            .unwrap_or_default()
            .into_iter()
            .enumerate()
            .map(|(i, x)| position(format!("mesh.nodes_at[{i}]"), x))
            .collect::<Result<Vec<_>, InputError>>()?;
        let chain = Chain {
            beams,
            joints,
            supports,
            masses,
            sensors,
            nodes_at,
            calibration,
        };
        if let Some((i, other, near)) = super::mesh::crowded_support(&chain) {
            let x = chain.supports[i].x;
            return Err(check.invalid(
                format!("support[{i}].x"),
                x,
                format!(
                    "it lies {:.3e} m from another node of the mesh at x = {other} m (a joint, a \
                     beam's end, a segment's or an overlap's end, a support, a mass on a spring \
                     or a requested node), closer than {near:.3e} m (5% of the element length): \
                     the element between them would be thousands of times stiffer than its \
                     neighbours, and a rigid support holds a node; put it at x = {other}, or \
                     {near:.3e} m or more from it",
                    (x - other).abs()
                ),
            ));
        }
        Ok(chain)
    }
}

/// `position(path, x)`: x checked to lie on the chain.
type Position<'a> = dyn Fn(String, f64) -> Result<f64, InputError> + 'a;

/// `[[mass]]` table `i`.
fn point_mass(
    m: &RawMass,
    i: usize,
    check: &FieldCheck,
    position: &Position,
) -> Result<PointMass, InputError> {
    let p = |field: &str| format!("mass[{i}].{field}");
    if m.spring.is_some() && m.rotary_inertia.is_some() {
        return Err(check.invalid(
            p("rotary_inertia"),
            m.rotary_inertia.unwrap_or(0.0),
            "a mass on a spring moves in translation only: leave rotary_inertia out",
        ));
    }
    Ok(PointMass {
        x: position(p("x"), m.x)?,
        mass: check.positive(p("mass"), m.mass, "kg")?,
        rotary_inertia: m
            .rotary_inertia
            .map(|j| check.non_negative(p("rotary_inertia"), j, "kg m^2"))
            .transpose()?
            .unwrap_or(0.0),
        spring: m
            .spring
            .map(|k| check.positive(p("spring"), k, "N/m"))
            .transpose()?,
        identify: m.identify,
    })
}

/// The largest point mass (a `[[mass]]`, a sensor's), relative to the beams' own mass; the
/// largest rotary inertia likewise relative to the beams' mass times the chain's length
/// squared. A shaker's armature or a clamp is tens of times a test beam's mass; a million
/// times leaves the beams a rounding error of the mass matrix (issue 42: masses of 1e60 kg
/// were accepted).
pub const MAX_MASS_RATIO: f64 = 1e6;

/// Refuses a point mass or rotary inertia beyond [`MAX_MASS_RATIO`] of the beams'.
fn masses_within_bound(
    beams: &[Beam],
    masses: &[PointMass],
    sensors: &[Sensor],
    check: &FieldCheck,
) -> Result<(), InputError> {
    let own: f64 = beams.iter().map(|b| b.density * b.area * b.length).sum();
    let length: f64 = beams.iter().map(|b| b.length).sum();
    let (most, most_inertia) = (MAX_MASS_RATIO * own, MAX_MASS_RATIO * own * length * length);
    let over = |path: String, value: f64, bound: f64, unit: &str| {
        check.invalid(
            path,
            Number(value),
            format!(
                "it must be at most {} {unit}, a million times the beams' mass {} kg",
                Number(bound),
                Number(own)
            ),
        )
    };
    for (i, m) in masses.iter().enumerate() {
        if m.mass > most {
            return Err(over(format!("mass[{i}].mass"), m.mass, most, "kg"));
        }
        if m.rotary_inertia > most_inertia {
            let path = format!("mass[{i}].rotary_inertia");
            return Err(over(path, m.rotary_inertia, most_inertia, "kg m^2"));
        }
    }
    match sensors.iter().position(|s| s.mass > most) {
        Some(i) => Err(over(
            format!("sensor[{i}].mass"),
            sensors[i].mass,
            most,
            "kg",
        )),
        None => Ok(()),
    }
}

/// The `[[sensor]]` tables: direction, a unique label, position, mass.
fn sensors(
    raw: &[RawSensor],
    check: &FieldCheck,
    position: &Position,
) -> Result<Vec<Sensor>, InputError> {
    let mut sensors: Vec<Sensor> = Vec::with_capacity(raw.len());
    for (i, s) in raw.iter().enumerate() {
        let p = |field: &str| format!("sensor[{i}].{field}");
        let direction = match s.dof.as_deref() {
            None | Some("w") => Direction::W,
            Some("theta") => Direction::Theta,
            Some(other) => {
                return Err(check.invalid(
                    p("dof"),
                    format!("\"{other}\""),
                    "it must be \"w\" or \"theta\"",
                ));
            }
        };
        if let Some(label) = &s.label {
            if label.is_empty() || label.contains(',') || label.contains(':') {
                return Err(check.invalid(
                    p("label"),
                    format!("\"{label}\""),
                    "a label is non-empty text without commas or colons",
                ));
            }
            if let Some(other) = sensors.iter().position(|o| o.label.as_ref() == Some(label)) {
                return Err(check.invalid(
                    p("label"),
                    format!("\"{label}\""),
                    format!("sensor[{other}] has this label already"),
                ));
            }
        }
        sensors.push(Sensor {
            x: position(p("x"), s.x)?,
            direction,
            label: s.label.clone(),
            mass: s
                .mass
                .map(|m| check.non_negative(p("mass"), m, "kg"))
                .transpose()?
                .unwrap_or(0.0),
        });
    }
    Ok(sensors)
}

/// Refuses a sensor on a motion a support holds.
fn sensors_on_motions(
    sensors: &[Sensor],
    supports: &[Support],
    length: f64,
    check: &FieldCheck,
) -> Result<(), InputError> {
    let tol = 1e-9 * length;
    for (i, sensor) in sensors.iter().enumerate() {
        if let Some((k, support)) = supports
            .iter()
            .enumerate()
            .find(|(_, s)| (s.x - sensor.x).abs() <= tol && s.kind.removes(sensor.direction))
        {
            return Err(check.invalid(
                format!("sensor[{i}].x"),
                sensor.x,
                format!(
                    "support[{k}] ({}) holds {} there: a sensor reads a motion that exists",
                    support.kind.name(),
                    sensor.direction
                ),
            ));
        }
    }
    Ok(())
}

/// Refuses more identified parameters (joints', supports', masses') than the method solves for.
fn identified_within_limit(
    joints: &[Joint],
    supports: &[Support],
    masses: &[PointMass],
    check: &FieldCheck,
) -> Result<(), InputError> {
    let identified = joints
        .iter()
        .flat_map(|j| j.roles)
        .filter(|r| *r == Role::Identified)
        .count()
        + supports
            .iter()
            .flat_map(|s| s.identify)
            .filter(|&b| b)
            .count()
        + masses.iter().filter(|m| m.identify).count();
    if identified > crate::structure::MAX_IDENTIFIED {
        return Err(check.invalid(
            "joint",
            format!("{identified} identified parameters"),
            format!(
                "at most {} parameters can be identified: hold some fixed (`fixed = [...]`)",
                crate::structure::MAX_IDENTIFIED
            ),
        ));
    }
    Ok(())
}

fn beam(
    b: &RawBeam,
    i: usize,
    element_length: Option<f64>,
    check: &FieldCheck,
) -> Result<Beam, InputError> {
    let p = |field: &str| format!("beam[{i}].{field}");
    let length = check.positive(p("length"), b.length, "m")?;
    let elements = match (b.elements, element_length) {
        (Some(e), _) => check.int_range(p("elements"), e, 1, MAX_ELEMENTS_PER_BEAM)?,
        (None, Some(h)) => {
            let count = (length / h).ceil();
            if count > MAX_ELEMENTS_PER_BEAM as f64 {
                return Err(check.invalid(
                    "mesh.element_length",
                    Number(h),
                    format!(
                        "beam[{i}] ({} m) would need {} elements, above {MAX_ELEMENTS_PER_BEAM}",
                        Number(length),
                        Number(count)
                    ),
                ));
            }
            count as usize
        }
        (None, None) => {
            return Err(check.invalid(
                p("elements"),
                "missing",
                "give the beam's number of elements, or [mesh].element_length",
            ));
        }
    };
    let youngs_modulus = check.positive(p("youngs_modulus"), b.youngs_modulus, "Pa")?;
    let shear = shear(b, i, check)?;
    let own = Section {
        youngs_modulus,
        density: check.positive(p("density"), b.density, "kg/m^3")?,
        area: check.positive(p("area"), b.area, "m^2")?,
        second_moment: check.positive(p("second_moment"), b.second_moment, "m^4")?,
        shear: shear.map(|s| s.at(youngs_modulus)),
    };
    let mut segments: Vec<Segment> = Vec::with_capacity(b.segment.len());
    for (k, g) in b.segment.iter().enumerate() {
        let q = |field: &str| format!("beam[{i}].segment[{k}].{field}");
        let from = check.non_negative(q("from"), g.from, "m from the beam's start")?;
        if !(g.to.is_finite() && g.to > from && g.to <= length) {
            return Err(check.invalid(
                q("to"),
                g.to,
                format!(
                    "it must lie after from = {from} and at most at the beam's length {length} m"
                ),
            ));
        }
        if let Some(prev) = segments.iter().position(|s| from < s.to && g.to > s.from) {
            return Err(check.invalid(
                q("from"),
                from,
                format!("the segment overlaps beam[{i}].segment[{prev}]"),
            ));
        }
        let or = |v: Option<f64>, field: &str, own: f64, unit: &str| {
            v.map_or(Ok(own), |v| check.positive(q(field), v, unit))
        };
        let youngs_modulus = or(g.youngs_modulus, "youngs_modulus", own.youngs_modulus, "Pa")?;
        segments.push(Segment {
            from,
            to: g.to,
            section: Section {
                youngs_modulus,
                density: or(g.density, "density", own.density, "kg/m^3")?,
                area: or(g.area, "area", own.area, "m^2")?,
                second_moment: or(g.second_moment, "second_moment", own.second_moment, "m^4")?,
                shear: shear.map(|s| s.at(youngs_modulus)),
            },
        });
    }
    let h = length / elements as f64;
    section_terms(check, &format!("beam[{i}]"), &own, h)?;
    for (k, g) in segments.iter().enumerate() {
        // The elements of a segment are never longer than the beam's.
        section_terms(
            check,
            &format!("beam[{i}].segment[{k}]"),
            &g.section,
            h.min(g.to - g.from),
        )?;
    }
    segments.sort_by(|a, b| a.from.total_cmp(&b.from));
    let mut beam = Beam::uniform(length, elements, own);
    beam.segments = segments;
    Ok(beam)
}

/// A beam's declared shear: kappa, and G given or from Poisson's ratio and each section's E.
#[derive(Debug, Clone, Copy)]
enum DeclaredShear {
    Modulus { factor: f64, modulus: f64 },
    Poisson { factor: f64, poisson: f64 },
}

impl DeclaredShear {
    /// The shear of a section of Young's modulus `e`.
    fn at(self, e: f64) -> Shear {
        match self {
            Self::Modulus { factor, modulus } => Shear { factor, modulus },
            Self::Poisson { factor, poisson } => Shear {
                factor,
                modulus: e / (2.0 * (1.0 + poisson)),
            },
        }
    }
}

/// Beam `i`'s declared shear, `None` for an Euler-Bernoulli beam.
/// `beam[i].calibrated`: each factor > 0 with a standard error >= 0 (an error needs its
/// factor), at least one factor.
fn calibrated(
    c: &RawCalibrated,
    i: usize,
    check: &FieldCheck,
) -> Result<BeamCalibration, InputError> {
    let p = |field: &str| format!("beam[{i}].calibrated.{field}");
    let factor = |name: &str, value: Option<f64>, se: Option<f64>| match (value, se) {
        (None, None) => Ok(None),
        (None, Some(se)) => Err(check.invalid(
            p(&format!("{name}_se")),
            Number(se),
            format!("a standard error needs its factor: give {name} too"),
        )),
        (Some(v), se) => Ok(Some(Factor {
            value: check.positive(p(name), v, "the factor of the typed value")?,
            se: check.non_negative(p(&format!("{name}_se")), se.unwrap_or(0.0), "-")?,
        })),
    };
    let stiffness = factor(
        "stiffness_factor",
        c.stiffness_factor,
        c.stiffness_factor_se,
    )?;
    let density = factor("density_factor", c.density_factor, c.density_factor_se)?;
    if stiffness.is_none() && density.is_none() {
        return Err(check.invalid(
            format!("beam[{i}].calibrated"),
            "no factor",
            "give stiffness_factor or density_factor (or leave the table out)",
        ));
    }
    Ok(BeamCalibration {
        beam: i,
        stiffness,
        density,
        reference: c.reference.clone(),
    })
}

fn shear(b: &RawBeam, i: usize, check: &FieldCheck) -> Result<Option<DeclaredShear>, InputError> {
    let p = |field: &str| format!("beam[{i}].{field}");
    let Some(factor) = b.shear_factor else {
        for (field, value) in [("shear_modulus", b.shear_modulus), ("poisson", b.poisson)] {
            if let Some(v) = value {
                return Err(check.invalid(
                    p(field),
                    Number(v),
                    "it needs shear_factor (kappa), which makes the beam a Timoshenko beam",
                ));
            }
        }
        return Ok(None);
    };
    let factor = check.positive(
        p("shear_factor"),
        factor,
        "kappa, 5/6 for a solid rectangle",
    )?;
    match (b.shear_modulus, b.poisson) {
        (Some(g), None) => Ok(Some(DeclaredShear::Modulus {
            factor,
            modulus: check.positive(p("shear_modulus"), g, "Pa")?,
        })),
        (None, Some(poisson)) if poisson > -1.0 && poisson < 0.5 => {
            Ok(Some(DeclaredShear::Poisson { factor, poisson }))
        }
        (None, Some(nu)) => Err(check.invalid(
            p("poisson"),
            Number(nu),
            "Poisson's ratio must lie in (-1, 0.5)",
        )),
        (Some(g), Some(_)) => Err(check.invalid(
            p("shear_modulus"),
            Number(g),
            "give shear_modulus or poisson, not both",
        )),
        (None, None) => Err(check.invalid(
            p("shear_factor"),
            Number(factor),
            "a Timoshenko beam needs shear_modulus (G, Pa) or poisson (nu, G = E / (2 (1 + nu)))",
        )),
    }
}

/// Refuses a section whose element terms on elements of length `h` (mass rho A h, bending
/// stiffness E I / h^3, axial stiffness E A / h) are not finite, nonzero numbers: each field
/// may be in range and their product still overflow (an area of 1e308 m^2).
fn section_terms(check: &FieldCheck, at: &str, s: &Section, h: f64) -> Result<(), InputError> {
    let terms = [
        (
            "density x area x element length",
            s.density * s.area * h,
            "kg",
        ),
        (
            "youngs_modulus x second_moment / element length^3",
            s.youngs_modulus * s.second_moment / h.powi(3),
            "N/m",
        ),
        (
            "youngs_modulus x area / element length",
            s.youngs_modulus * s.area / h,
            "N/m",
        ),
        (
            "shear_factor x shear modulus x area / element length",
            s.shear_rigidity().map_or(1.0, |ga| ga / h),
            "N/m",
        ),
    ];
    for (name, value, unit) in terms {
        if !value.is_normal() {
            return Err(check.invalid(
                at.to_string(),
                format!("{name} = {}", Number(value)),
                format!("the section's element terms must be finite and nonzero ({unit}): check the units and magnitudes of its fields"),
            ));
        }
    }
    Ok(())
}

fn joint(j: &RawJoint, i: usize, beams: &[Beam], check: &FieldCheck) -> Result<Joint, InputError> {
    let active = match j.kind.as_deref() {
        None | Some("point") => false,
        Some("lap") => true,
        Some(other) => {
            return Err(check.invalid(
                format!("joint[{i}].kind"),
                format!("\"{other}\""),
                "it must be \"point\" (k1, k2: eq. (17), the default) or \"lap\" (the layered lap of [joint.lap])",
            ));
        }
    };
    let names: &[&str] = if active {
        &["k_n", "k_s", ROOT_PARAMETER]
    } else {
        &["k1", "k2"]
    };
    let mut roles = [Role::Identified; 2];
    let mut root_role = Role::Identified;
    for (k, name) in j.fixed.iter().enumerate() {
        match names.iter().position(|n| n == name) {
            Some(2) => root_role = Role::Fixed,
            Some(slot) => roles[slot] = Role::Fixed,
            None => {
                return Err(check.invalid(
                    format!("joint[{i}].fixed[{k}]"),
                    format!("\"{name}\""),
                    format!(
                        "a joint's parameters are \"{}\" and \"{}\"",
                        names[..names.len() - 1].join("\", \""),
                        names[names.len() - 1]
                    ),
                ));
            }
        }
    }
    let lap = match (&j.lap, active) {
        (Some(raw), _) => {
            let lap_roles = if active {
                (roles, root_role)
            } else {
                ([Role::Identified; 2], Role::Identified)
            };
            Some(lap(raw, i, active, lap_roles, beams, check)?)
        }
        (None, true) => {
            return Err(check.invalid(
                format!("joint[{i}].lap"),
                "missing",
                "a joint of kind = \"lap\" needs its [joint.lap] table (length, layers, k_n, k_s)",
            ));
        }
        (None, false) => None,
    };
    if let Some(k) = j.fixed.iter().position(|n| n == ROOT_PARAMETER)
        && lap.is_some_and(|l| l.k_r.is_none())
    {
        return Err(check.invalid(
            format!("joint[{i}].fixed[{k}]"),
            "\"k_r\"",
            "the lap's roots are rigid (no joint.lap.k_r given): there is no k_r to hold",
        ));
    }
    if active {
        if let Some((name, value)) = [("k1", j.k1), ("k2", j.k2)]
            .into_iter()
            .find_map(|(n, v)| v.map(|v| (n, v)))
        {
            return Err(check.invalid(
                format!("joint[{i}].{name}"),
                value,
                "a joint of kind = \"lap\" has k_n, k_s in [joint.lap] in place of k1, k2: leave it out",
            ));
        }
        return Ok(Joint {
            k1: 0.0,
            k2: 0.0,
            roles,
            lap,
        });
    }
    let given = |name: &str, v: Option<f64>, unit: &str| match v {
        Some(v) => check.positive(format!("joint[{i}].{name}"), v, unit),
        None => Err(InputError::Format {
            file: check.file.to_path_buf(),
            line: None,
            path: format!("joint[{i}]"),
            message: format!("missing field `{name}`"),
        }),
    };
    Ok(Joint {
        k1: given("k1", j.k1, "N/m")?,
        k2: given("k2", j.k2, "N m/rad")?,
        roles,
        lap,
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::model::chain::SupportKind;

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

    fn chain(text: &str) -> Result<Chain, String> {
        crate::model::chain_from_toml(text, Path::new("m.toml")).map_err(|e| e.to_string())
    }

    fn error_of(text: &str) -> String {
        chain(text).unwrap_err()
    }

    #[test]
    fn reads_the_paper_layout() {
        let chain = chain(GOOD).unwrap();
        assert_eq!(chain.beams.len(), 2);
        assert_eq!(chain.build().dof_count(), 38);
        assert_eq!(chain.joints[0], Joint::identified(1.0e7, 1.0e4));
    }

    #[test]
    fn negative_length_names_file_path_value_and_range() {
        let text = GOOD.replacen("length = 0.30", "length = -0.3", 1);
        assert_eq!(
            error_of(&text),
            "m.toml: beam[1].length = -0.3 is invalid: it must be finite and > 0 (m)"
        );
    }

    /// Fields each in range whose product overflows are refused with the section named.
    #[test]
    fn sections_whose_element_terms_overflow_are_rejected() {
        let text = GOOD.replacen("area = 2.4e-3", "area = 1e308", 1);
        let err = error_of(&text);
        assert!(
            err.starts_with("m.toml: beam[0] = density x area x element length = ")
                && err.contains("must be finite and nonzero (kg)"),
            "{err}"
        );
        let text = GOOD.replacen("second_moment = 3.2e-7", "second_moment = 1e300", 1);
        let err = error_of(&text);
        assert!(
            err.contains("youngs_modulus x second_moment / element length^3"),
            "{err}"
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

    #[test]
    fn set_up_tables_are_read_and_checked() {
        let text = format!(
            "{GOOD}\n[[support]]\nx = 0.0\nkind = \"clamped\"\nidentify = []\n[[support]]\nx = 0.5\nkind = \"spring\"\ntranslational = 1e5\nidentify = [\"translational\"]\n[[mass]]\nx = 0.085\nmass = 0.02\nrotary_inertia = 1e-6\n[[sensor]]\nx = 0.176\nlabel = \"acc3\"\nmass = 0.003\n"
        );
        let c = chain(&text).unwrap();
        assert_eq!(c.supports[0].kind, SupportKind::Clamped);
        assert_eq!(
            c.supports[1].kind,
            SupportKind::Spring {
                translational: 1e5,
                rotational: 0.0
            }
        );
        assert_eq!(c.supports[1].identify, [true, false]);
        assert_eq!(c.masses[0].rotary_inertia, 1e-6);
        assert_eq!(c.sensors[0].label.as_deref(), Some("acc3"));
        let cases = [
            (
                "[[support]]\nx = 0.7\nkind = \"clamped\"\n",
                "m.toml: support[0].x = 0.7 is invalid: it must lie on the chain, from 0 to 0.5 m",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"welded\"\n",
                "m.toml:24: support[0].kind: unknown variant `welded`, expected one of `clamped`, `pinned`, `guided`, `spring`",
            ),
            (
                "[[support]]\nx = 0.1\n",
                "m.toml:22: support[0]: missing field `kind`",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"spring\"\n",
                "m.toml: support[0].kind = \"spring\" is invalid: a spring support needs translational (N/m) and/or rotational (N m/rad)",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"pinned\"\nrotational = 3.0\n",
                "m.toml:25: support[0].rotational: unknown field `rotational`, expected `x` or `identify` (kind = \"pinned\")",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"clamped\"\n[[support]]\nx = 0.2\nkind = \"spring\"\nrotational = \"stiff\"\n",
                "m.toml:28: support[1].rotational: invalid type: string \"stiff\", expected f64 (kind = \"spring\")",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"spring\"\nidentify = [\"rotational\", 3]\n",
                "m.toml:25: support[0].identify[1]: invalid type: integer `3`, expected a string (kind = \"spring\")",
            ),
            (
                "[[support]]\nkind = \"guided\"\n",
                "m.toml:22: support[0]: missing field `x` (kind = \"guided\")",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"spring\"\nrotational = -3.0\n",
                "m.toml: support[0].rotational = -3 is invalid: it must be finite and >= 0 (N m/rad)",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"spring\"\ntranslational = 1e5\nidentify = [\"rotational\"]\n",
                "m.toml: support[0].identify[0] = \"rotational\" is invalid: a spring support identifies its \"translational\" and/or \"rotational\" stiffness, when that stiffness is given and > 0",
            ),
            (
                "[[support]]\nx = 0.1\nkind = \"clamped\"\nidentify = [\"translational\"]\n",
                "m.toml: support[0].identify[0] = \"translational\" is invalid: a spring support identifies its \"translational\" and/or \"rotational\" stiffness, when that stiffness is given and > 0",
            ),
            (
                "[[mass]]\nx = 0.1\nmass = -0.01\n",
                "m.toml: mass[0].mass = -0.01 is invalid: it must be finite and > 0 (kg)",
            ),
            (
                "[[mass]]\nx = 0.1\nmass = 1e60\n",
                "m.toml: mass[0].mass = 1e60 is invalid: it must be at most 9420000 kg, a million times the beams' mass 9.42 kg",
            ),
            (
                "[[sensor]]\nx = 0.1\nmass = 1e100\n",
                "m.toml: sensor[0].mass = 1e100 is invalid: it must be at most 9420000 kg, a million times the beams' mass 9.42 kg",
            ),
            (
                "[[mass]]\nx = 0.1\nmass = 1\nrotary_inertia = 1e70\n",
                "m.toml: mass[0].rotary_inertia = 1e70 is invalid: it must be at most 2355000 kg m^2, a million times the beams' mass 9.42 kg",
            ),
            (
                "[[sensor]]\nx = 0.1\ndof = \"u\"\n",
                "m.toml: sensor[0].dof = \"u\" is invalid: it must be \"w\" or \"theta\"",
            ),
        ];
        for (extra, message) in cases {
            assert_eq!(error_of(&format!("{GOOD}\n{extra}")), message, "{extra}");
        }
        let fixed = GOOD.replacen("k2 = 1.0e4\n", "k2 = 1.0e4\nfixed = [\"k3\"]\n", 1);
        assert_eq!(
            error_of(&fixed),
            "m.toml: joint[0].fixed[0] = \"k3\" is invalid: a joint's parameters are \"k1\" and \"k2\""
        );
    }

    #[test]
    fn segments_must_lie_on_their_beam_without_overlap() {
        let seg = |from: f64, to: f64| {
            GOOD.replacen(
                "second_moment = 3.2e-7\n\n[[beam]]",
                &format!("second_moment = 3.2e-7\n[[beam.segment]]\nfrom = {from}\nto = {to}\narea = 4.8e-3\n\n[[beam]]"),
                1,
            )
        };
        let c = chain(&seg(0.15, 0.2)).unwrap();
        assert_eq!(c.beams[0].segments[0].section.area, 4.8e-3);
        assert_eq!(c.beams[0].segments[0].section.second_moment, 3.2e-7);
        assert_eq!(
            error_of(&seg(0.15, 0.25)),
            "m.toml: beam[0].segment[0].to = 0.25 is invalid: it must lie after from = 0.15 and at most at the beam's length 0.2 m"
        );
    }

    #[test]
    fn elements_come_from_the_beam_or_the_mesh_size() {
        let no_count = GOOD.replacen("elements = 7\n", "", 1);
        assert_eq!(
            error_of(&no_count),
            "m.toml: beam[0].elements = missing is invalid: give the beam's number of elements, or [mesh].element_length"
        );
        let meshed = format!("[mesh]\nelement_length = 0.03\n{no_count}");
        assert_eq!(chain(&meshed).unwrap().beams[0].elements, 7);
    }

    #[test]
    fn a_timoshenko_beam_takes_kappa_with_g_or_poisson_and_its_segments_keep_them() {
        let with = |fields: &str| {
            GOOD.replacen(
                "second_moment = 3.2e-7\n\n[[beam]]",
                &format!("second_moment = 3.2e-7\n{fields}\n[[beam.segment]]\nfrom = 0.15\nto = 0.2\nyoungs_modulus = 1.3e11\n\n[[beam]]"),
                1,
            )
        };
        let c = chain(&with("shear_factor = 0.8\npoisson = 0.3")).unwrap();
        let own = c.beams[0].section().shear.unwrap();
        assert_eq!(own.factor, 0.8);
        assert!((own.modulus - 2.1e11 / 2.6).abs() < 1.0);
        // A segment of its own E: G from the same Poisson's ratio.
        let seg = c.beams[0].segments[0].section.shear.unwrap();
        assert!((seg.modulus - 1.3e11 / 2.6).abs() < 1.0);
        assert!(c.beams[1].section().shear.is_none());
        let c = chain(&with("shear_factor = 0.8\nshear_modulus = 8e10")).unwrap();
        assert_eq!(c.beams[0].segments[0].section.shear.unwrap().modulus, 8e10);
        for (fields, message) in [
            (
                "shear_factor = 0.0\npoisson = 0.3",
                "beam[0].shear_factor = 0 is invalid",
            ),
            (
                "shear_factor = -1.0\npoisson = 0.3",
                "beam[0].shear_factor = -1 is invalid",
            ),
            (
                "shear_factor = 0.8\nshear_modulus = 0.0",
                "beam[0].shear_modulus = 0 is invalid",
            ),
            (
                "shear_factor = 0.8\nshear_modulus = -8e10",
                "beam[0].shear_modulus = -8e10 is invalid",
            ),
            (
                "shear_factor = 0.8\npoisson = 0.5",
                "beam[0].poisson = 0.5 is invalid: Poisson's ratio must lie in (-1, 0.5)",
            ),
            (
                "shear_factor = 0.8",
                "beam[0].shear_factor = 0.8 is invalid: a Timoshenko beam needs shear_modulus",
            ),
            (
                "shear_factor = 0.8\npoisson = 0.3\nshear_modulus = 8e10",
                "give shear_modulus or poisson, not both",
            ),
            (
                "poisson = 0.3",
                "beam[0].poisson = 0.3 is invalid: it needs shear_factor",
            ),
            (
                "shear_modulus = 8e10",
                "beam[0].shear_modulus = 8e10 is invalid: it needs shear_factor",
            ),
        ] {
            let err = error_of(&with(fields));
            assert!(err.contains(message), "{fields}: {err}");
        }
    }
}

#[cfg(test)]
mod lap_height {
    /// A fuzzing find: a lapped beam of area 1e-308 m^2 (height sqrt(12 I / A) ~ 2e151 m)
    /// assembled matrices past double precision; it is refused where the layers are made.
    #[test]
    fn a_lapped_beam_higher_than_long_is_refused_naming_it() {
        let beam = |area: &str| {
            format!(
                "[[beam]]\nlength = 0.3\nelements = 10\nyoungs_modulus = 2e11\ndensity = 7850\narea = {area}\nsecond_moment = 4.3e-9\n"
            )
        };
        let text = |area: &str| {
            format!(
                "{}{}[[joint]]\nk1 = 1e9\nk2 = 1e5\n[joint.lap]\nlength = 0.1\n",
                beam("3.2e-4"),
                beam(area)
            )
        };
        let file = std::path::Path::new("m.toml");
        assert!(crate::model::chain_from_toml(&text("3.2e-4"), file).is_ok());
        let e = crate::model::chain_from_toml(&text("1e-308"), file)
            .unwrap_err()
            .to_string();
        assert!(
            e.contains("beam[1]") && e.contains("no higher than it is long"),
            "{e}"
        );
        assert!(e.len() < 200, "{e}");
    }
}

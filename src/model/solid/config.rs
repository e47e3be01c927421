//! The configuration of a lap specimen (TOML), parsed in two stages: raw serde structs that
//! reject unknown keys, then a validated [`SolidConfig`]; every error names the file, the field
//! path, the value and what is allowed.
//!
//! ```toml
//! width = 0.025                # m, the bars' width (y)
//! overlap = 0.05               # m, the lap's length (x)
//!
//! [material]
//! youngs_modulus = 2.1e11      # Pa
//! poisson_ratio = 0.3          # from -1 to below 0.5
//! density = 7850.0             # kg/m^3
//!
//! [[bar]]                      # exactly two: the lower bar (from x = 0), then the upper one
//! length = 0.3                 # m, >= overlap
//! thickness = 0.01             # m (z)
//!
//! [[bar]]
//! length = 0.3
//! thickness = 0.01
//!
//! [interface]                  # stiffness per area of the lap, N/m^3
//! normal = 1e13                # z
//! shear_x = 2e12               # x
//! shear_y = 2e12               # y
//!
//! [[interface.bolt]]           # optional: a stiffer patch (a bolt's clamped area)
//! x = 0.275                    # m, centre, inside the lap
//! y = 0.0125
//! radius = 0.005               # m
//! factor = 10.0                # the stiffness per area inside it, times the interface's
//!
//! [mesh]
//! size = 0.005                 # m, the target edge of a brick in x and y
//! layers = 2                   # bricks through each bar's thickness (default 2)
//! ```
//!
//! May import: the shared input checks, the element's material.

use std::path::Path;

use serde::Deserialize;

use super::hex::Material;
use crate::input::{FieldCheck, InputError, Number};

/// The most DOFs a generated model may have (that of the external-model reader).
pub const MAX_DOFS: usize = crate::model::matrices::build::MAX_DOFS;

/// The number of elements of a length at the target element size (at least 1), as a float:
/// exact up to 2^53, and never wrapping for any positive lengths (infinite at worst).
fn division_count(length: f64, size: f64) -> f64 {
    ((length / size) * (1.0 - 1e-12)).ceil().max(1.0)
}

/// The number of elements of a length at the target element size (at least 1). Only for a
/// validated configuration, whose counts are bounded by [`MAX_DOFS`].
pub fn divisions(length: f64, size: f64) -> usize {
    division_count(length, size) as usize
}

/// The most bricks through a bar's thickness.
pub const MAX_LAYERS: i64 = 64;

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawSolid {
    width: f64,
    overlap: f64,
    material: RawMaterial,
    bar: Vec<RawBar>,
    interface: RawInterface,
    mesh: RawMesh,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMaterial {
    youngs_modulus: f64,
    poisson_ratio: f64,
    density: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBar {
    length: f64,
    thickness: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawInterface {
    normal: f64,
    shear_x: f64,
    shear_y: f64,
    #[serde(default)]
    bolt: Vec<RawBolt>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawBolt {
    x: f64,
    y: f64,
    radius: f64,
    factor: f64,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawMesh {
    size: f64,
    layers: Option<i64>,
}

/// A bar: length (x) and thickness (z), m.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct BarSize {
    /// Length, m.
    pub length: f64,
    /// Thickness, m.
    pub thickness: f64,
}

/// A stiffer patch of the interface around a bolt.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Bolt {
    /// Centre (x, y), m.
    pub centre: [f64; 2],
    /// Radius, m.
    pub radius: f64,
    /// The stiffness per area inside it, relative to the interface's.
    pub factor: f64,
}

impl Bolt {
    /// Whether (x, y) lies in the patch.
    pub fn contains(&self, x: f64, y: f64) -> bool {
        (x - self.centre[0]).hypot(y - self.centre[1]) <= self.radius
    }
}

/// The interface's stiffnesses per area, N/m^3, and its bolt patches.
#[derive(Debug, Clone, PartialEq)]
pub struct Interface {
    /// Normal (z).
    pub normal: f64,
    /// Shear along x.
    pub shear_x: f64,
    /// Shear along y.
    pub shear_y: f64,
    /// Stiffer patches.
    pub bolts: Vec<Bolt>,
}

/// The mesh density.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MeshSize {
    /// Target edge in x and y, m.
    pub size: f64,
    /// Bricks through each bar's thickness.
    pub layers: usize,
}

/// A validated lap specimen.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidConfig {
    /// Width of both bars (y), m.
    pub width: f64,
    /// Length of the lap (x), m.
    pub overlap: f64,
    /// The material of both bars.
    pub material: Material,
    /// The lower bar, then the upper one.
    pub bars: [BarSize; 2],
    /// The interface.
    pub interface: Interface,
    /// The mesh.
    pub mesh: MeshSize,
}

impl SolidConfig {
    /// Parses and validates TOML text; `file` names it in errors. The check that every bolt
    /// patch holds an interface node needs the mesh: [`super::SolidConfig::from_toml`].
    pub(crate) fn parse(text: &str, file: &Path) -> Result<SolidConfig, InputError> {
        crate::input::parse_toml::<RawSolid>(text, file)?.validate(file)
    }

    /// The number of DOFs of the mesh: 3 per node. Counted in floating point, so that any
    /// lengths and mesh size give a count (exact up to 2^53, infinite at worst), never a
    /// wrapped one.
    pub fn dof_count(&self) -> f64 {
        let size = self.mesh.size;
        let ny = division_count(self.width, size) + 1.0;
        let nz = self.mesh.layers as f64 + 1.0;
        // The stations of each bar: its part off the lap, then the lap (as the mesh does).
        let part = |length: f64| {
            if length > self.overlap {
                division_count(length - self.overlap, size)
            } else {
                0.0
            }
        };
        let lap = division_count(self.overlap, size);
        let lower = part(self.bars[0].length) + lap + 1.0;
        let upper = part(self.bars[1].length) + lap + 1.0;
        3.0 * ny * nz * (lower + upper)
    }

    /// The longest of the lengths the mesh divides (the one with most elements): its field
    /// path and value.
    fn longest(&self) -> (&'static str, f64) {
        [
            ("width", self.width),
            ("bar[0].length", self.bars[0].length),
            ("bar[1].length", self.bars[1].length),
        ]
        .into_iter()
        .fold(
            ("overlap", self.overlap),
            |a, b| if b.1 > a.1 { b } else { a },
        )
    }
}

/// The stiffest interface per area, bolt patches included, relative to the thinner bar's own
/// stiffness per area through its thickness, E / t. An interface a million times stiffer than
/// the bar is rigid to any test; beyond it the matrices lose the bars' stiffness to rounding
/// and the model `solid` writes is refused by its own reader (extra rigid-body modes, a
/// failed factorisation: issue 42, a normal stiffness of 1e308 or a modulus of 1e-300).
pub const MAX_INTERFACE_RATIO: f64 = 1e6;

/// The softest interface per area relative to the thicker bar's E / t: softer, the two bars
/// part to rounding and the model has 12 rigid-body modes, not 6.
pub const MIN_INTERFACE_RATIO: f64 = 1e-9;

/// Refuses an interface stiffer than [`MAX_INTERFACE_RATIO`] times the bars, or softer than
/// [`MIN_INTERFACE_RATIO`] times them.
fn interface_within_bars(
    interface: &Interface,
    material: &Material,
    bars: &[BarSize; 2],
    check: &FieldCheck,
) -> Result<(), InputError> {
    let stiffest = (0..interface.bolts.len()).max_by(|&a, &b| {
        interface.bolts[a]
            .factor
            .total_cmp(&interface.bolts[b].factor)
    });
    let factor = stiffest.map_or(1.0, |i| interface.bolts[i].factor.max(1.0));
    let thinner = bars[0].thickness.min(bars[1].thickness);
    let most = MAX_INTERFACE_RATIO * material.youngs_modulus / thinner;
    let thicker = bars[0].thickness.max(bars[1].thickness);
    let least = MIN_INTERFACE_RATIO * material.youngs_modulus / thicker;
    for (field, value) in [
        ("interface.normal", interface.normal),
        ("interface.shear_x", interface.shear_x),
        ("interface.shear_y", interface.shear_y),
    ] {
        let soft = value < least || value.is_nan();
        if soft {
            return Err(check.invalid(
                field,
                Number(value),
                format!(
                    "it must be at least {} N/m^3, 1e-9 E / t of the thicker bar",
                    Number(least)
                ),
            ));
        }
        let within = value * factor <= most;
        if within {
            continue;
        }
        // The bolt's factor is named when the interface alone is within the bound.
        let (field, shown) = match stiffest.filter(|_| value <= most) {
            Some(i) => (format!("interface.bolt[{i}].factor"), factor),
            None => (field.to_string(), value),
        };
        return Err(check.invalid(
            field,
            Number(shown),
            format!(
                "{} x the bolt factor {} must be at most {} N/m^3, 1e6 E / t of the thinner bar",
                Number(value),
                Number(factor),
                Number(most)
            ),
        ));
    }
    Ok(())
}

impl RawSolid {
    pub(crate) fn validate(self, file: &Path) -> Result<SolidConfig, InputError> {
        let check = FieldCheck { file };
        let width = check.positive("width", self.width, "m")?;
        let overlap = check.positive("overlap", self.overlap, "m")?;
        let m = &self.material;
        let material = Material {
            youngs_modulus: check.positive("material.youngs_modulus", m.youngs_modulus, "Pa")?,
            poisson_ratio: if m.poisson_ratio.is_finite()
                && m.poisson_ratio > -1.0
                && m.poisson_ratio < 0.5
            {
                m.poisson_ratio
            } else {
                return Err(check.invalid(
                    "material.poisson_ratio",
                    Number(m.poisson_ratio),
                    "it must be above -1 and below 0.5",
                ));
            },
            density: check.positive("material.density", m.density, "kg/m^3")?,
        };
        let [lower, upper] = self.bar.as_slice() else {
            return Err(check.invalid(
                "bar",
                format!("{} bar(s)", self.bar.len()),
                "a lap specimen has exactly two [[bar]]: the lower one, then the upper one",
            ));
        };
        let mut bars = [BarSize {
            length: 0.0,
            thickness: 0.0,
        }; 2];
        for (i, (raw, bar)) in [lower, upper].into_iter().zip(&mut bars).enumerate() {
            bar.thickness = check.positive(format!("bar[{i}].thickness"), raw.thickness, "m")?;
            bar.length = check.positive(format!("bar[{i}].length"), raw.length, "m")?;
            if bar.thickness > bar.length {
                return Err(check.invalid(
                    format!("bar[{i}].thickness"),
                    Number(bar.thickness),
                    format!(
                        "a bar is at most as thick as long, {} m",
                        Number(bar.length)
                    ),
                ));
            }
            if bar.length < overlap {
                return Err(check.invalid(
                    format!("bar[{i}].length"),
                    Number(bar.length),
                    format!("it must be at least the overlap, {} m", Number(overlap)),
                ));
            }
        }
        let raw = &self.interface;
        let per_area = "N/m^3, stiffness per area of the lap";
        let mut interface = Interface {
            normal: check.positive("interface.normal", raw.normal, per_area)?,
            shear_x: check.positive("interface.shear_x", raw.shear_x, per_area)?,
            shear_y: check.positive("interface.shear_y", raw.shear_y, per_area)?,
            bolts: Vec::new(),
        };
        let lap_start = bars[0].length - overlap;
        for (i, b) in raw.bolt.iter().enumerate() {
            let at = |f: &str| format!("interface.bolt[{i}].{f}");
            let inside = |v: f64, lo: f64, hi: f64, field: &str| {
                if v.is_finite() && v >= lo && v <= hi {
                    Ok(v)
                } else {
                    Err(check.invalid(
                        at(field),
                        Number(v),
                        format!(
                            "the centre must lie on the lap: from {} to {} m",
                            Number(lo),
                            Number(hi)
                        ),
                    ))
                }
            };
            interface.bolts.push(Bolt {
                centre: [
                    inside(b.x, lap_start, bars[0].length, "x")?,
                    inside(b.y, 0.0, width, "y")?,
                ],
                radius: check.positive(at("radius"), b.radius, "m")?,
                factor: check.positive(
                    at("factor"),
                    b.factor,
                    "the patch's stiffness per area over the interface's",
                )?,
            });
        }
        interface_within_bars(&interface, &material, &bars, &check)?;
        let size = check.positive("mesh.size", self.mesh.size, "m")?;
        let layers =
            check.int_range("mesh.layers", self.mesh.layers.unwrap_or(2), 1, MAX_LAYERS)?;
        let config = SolidConfig {
            width,
            overlap,
            material,
            bars,
            interface,
            mesh: MeshSize { size, layers },
        };
        let dofs = config.dof_count();
        if dofs > MAX_DOFS as f64 {
            let count = if dofs.is_finite() {
                Number(dofs).to_string()
            } else {
                "over 1e308".to_string()
            };
            let (field, length) = config.longest();
            return Err(check.invalid(
                "mesh.size",
                Number(size),
                format!("with {field} = {} m the mesh would have {count} DOFs, above the {MAX_DOFS} an external model may have: give a larger size or a smaller specimen", Number(length)),
            ));
        }
        Ok(config)
    }
}

#[cfg(test)]
pub(crate) mod tests {
    use super::*;

    /// The text of a small specimen (36 bricks a bar... a few hundred DOFs).
    pub(crate) const SMALL: &str = "width = 0.02\noverlap = 0.04\n\
        [material]\nyoungs_modulus = 2.1e11\npoisson_ratio = 0.3\ndensity = 7850.0\n\
        [[bar]]\nlength = 0.12\nthickness = 0.01\n[[bar]]\nlength = 0.1\nthickness = 0.008\n\
        [interface]\nnormal = 1e13\nshear_x = 2e12\nshear_y = 3e12\n\
        [mesh]\nsize = 0.01\nlayers = 1\n";

    pub(crate) fn small() -> SolidConfig {
        SolidConfig::from_toml(SMALL, Path::new("lap.toml")).unwrap()
    }

    fn error(text: &str) -> String {
        SolidConfig::from_toml(text, Path::new("lap.toml"))
            .unwrap_err()
            .to_string()
    }

    #[test]
    fn a_valid_file_reads_and_counts_its_dofs() {
        let c = small();
        assert_eq!(c.mesh.layers, 1);
        assert_eq!(c.bars[1].thickness, 0.008);
        // 13 + 11 stations, 3 across, 2 up.
        assert_eq!(c.dof_count(), (3 * 3 * 2 * 24) as f64);
    }

    /// Sizes whose element counts do not fit in a machine word (a mesh size of 1e-21 m, a
    /// width of 1e308 m, a bar of 1e99 m) are refused by the DOF limit, with the count said
    /// in floating point, not wrapped to a small one that passes it.
    #[test]
    fn counts_beyond_a_machine_word_are_refused_not_wrapped() {
        let cases = [
            (
                "size = 0.01",
                "size = 1e-21",
                "mesh.size = 1e-21",
                "bar[0].length = 0.12 m",
            ),
            (
                "width = 0.02",
                "width = 1e308",
                "mesh.size = 0.01",
                "width = 1e308 m",
            ),
            (
                "length = 0.12",
                "length = 1e99",
                "mesh.size = 0.01",
                "bar[0].length = 1e99 m",
            ),
        ];
        for (from, to, field, longest) in cases {
            let text = SMALL.replacen(from, to, 1);
            assert_ne!(text, SMALL, "{from}");
            let message = error(&text);
            assert!(
                message.starts_with(&format!(
                    "lap.toml: {field} is invalid: with {longest} the mesh would have "
                )),
                "{message}"
            );
            assert!(
                message.contains("DOFs, above the 1000000 an external model may have"),
                "{message}"
            );
        }
        let message = error(&SMALL.replacen("width = 0.02", "width = 1e308", 1));
        assert!(message.contains("would have over 1e308 DOFs"), "{message}");
    }

    #[test]
    fn bad_fields_are_named_with_the_value_and_what_is_allowed() {
        let cases = [
            (
                "width = 0.02",
                "width = -1",
                "lap.toml: width = -1 is invalid: it must be finite and > 0 (m)",
            ),
            (
                "poisson_ratio = 0.3",
                "poisson_ratio = 0.5",
                "lap.toml: material.poisson_ratio = 0.5 is invalid: it must be above -1 and below 0.5",
            ),
            (
                "length = 0.1\n",
                "length = 0.03\n",
                "lap.toml: bar[1].length = 0.03 is invalid: it must be at least the overlap, 0.04 m",
            ),
            (
                "layers = 1",
                "layers = 0",
                "lap.toml: mesh.layers = 0 is invalid: it must be an integer from 1 to 64",
            ),
            (
                "size = 0.01",
                "size = 1e-5",
                "lap.toml: mesh.size = 1e-5 is invalid: with bar[0].length = 0.12 m the mesh would have 264156012 DOFs, above the 1000000 an external model may have: give a larger size or a smaller specimen",
            ),
            (
                "normal = 1e13",
                "normal = 0",
                "lap.toml: interface.normal = 0 is invalid: it must be finite and > 0 (N/m^3, stiffness per area of the lap)",
            ),
            (
                "normal = 1e13",
                "normal = 1e308",
                "lap.toml: interface.normal = 1e308 is invalid: 1e308 x the bolt factor 1 must be at most 2.625e19 N/m^3, 1e6 E / t of the thinner bar",
            ),
            (
                "youngs_modulus = 2.1e11",
                "youngs_modulus = 1e-300",
                "lap.toml: interface.normal = 1e13 is invalid: 1e13 x the bolt factor 1 must be at most 1.25e-292 N/m^3, 1e6 E / t of the thinner bar",
            ),
            (
                "[mesh]",
                "[[interface.bolt]]\nx = 0.01\ny = 0.01\nradius = 0.001\nfactor = 5\n[mesh]",
                "lap.toml: interface.bolt[0].x = 0.01 is invalid: the centre must lie on the lap: from 0.08 to 0.12 m",
            ),
            (
                "[mesh]",
                "[[interface.bolt]]\nx = 0.095\ny = 0.005\nradius = 0.001\nfactor = 5\n[mesh]",
                "lap.toml: interface.bolt[0].radius = 0.001 is invalid: no interface node lies within it at mesh.size = 0.01 m: give a larger radius or a smaller mesh.size",
            ),
        ];
        for (from, to, message) in cases {
            let text = SMALL.replacen(from, to, 1);
            assert_ne!(text, SMALL, "{from}");
            assert_eq!(error(&text), message);
        }
        let one_bar = SMALL.replacen("[[bar]]\nlength = 0.1\nthickness = 0.008\n", "", 1);
        assert_eq!(
            error(&one_bar),
            "lap.toml: bar = 1 bar(s) is invalid: a lap specimen has exactly two [[bar]]: the lower one, then the upper one"
        );
        assert!(error(&format!("{SMALL}colour = 1\n")).contains("colour"));
    }
}

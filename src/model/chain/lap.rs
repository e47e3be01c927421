//! A joint's overlap: the two beams as two layers over a finite length, joined by a distributed
//! interface of normal stiffness k_n and shear stiffness k_s per unit length (N/m per m). Its
//! description and its table in the model file; the assembly is [`super::layered`].
//!
//! Geometry. The overlap is centred on the joint's abscissa x_j: it spans
//! [x_j - length / 2, x_j + length / 2]. Over it the left beam (beam j) continues as the upper
//! layer to x_j + length / 2, where it ends free; the right beam (beam j + 1) begins as the
//! lower layer at x_j - length / 2. Each layer has its own section and two heights: `offset`,
//! its centroid's height above its own beam's axis, and `to_interface`, the distance from its
//! centroid to the interface (below the upper layer's centroid, above the lower layer's).
//!
//! ```toml
//! [[joint]]
//! k1 = 1.0e7               # a point joint, as always ...
//! k2 = 1.0e4
//! [joint.lap]              # ... whose overlap is known: diagnose tries the layered lap
//! length = 0.1             # m, > 0, at most twice the shorter of the two beams
//! layers = "half"          # "half" (half-lap splice, the default) or "full" (plain overlap)
//! # [joint.lap.upper]      # or each layer given: area, second_moment, offset, to_interface
//! # k_n = 1e12            # N/m per m: start values (optional for a point joint)
//! # k_s = 1e10
//! # k_r = 4e3             # N m/rad: the layers' notched roots (see super::notch; a point
//! #                       # joint's default: the notch's closed form; kind = "lap": rigid)
//! ```
//!
//! A joint with `kind = "lap"` is the layered lap itself (no k1, k2; `k_n`, `k_s` required,
//! `k_r` optional, `fixed` names any of "k_n", "k_s", "k_r").
//!
//! `layers = "half"`: each beam cut to half its height h = sqrt(12 I / A) over the overlap: area
//! A / 2, second moment I / 8, offsets +h/4 (upper) and -h/4 (lower), h/4 to the interface.
//! `layers = "full"`: each beam at its full section, one on the other: offsets 0, h/2 to the
//! interface. E and rho are the beams'.

use serde::Deserialize;

use super::beam::{Beam, Section};
use super::notch;
use crate::input::{FieldCheck, InputError, Number};
use crate::structure::Role;

/// One layer of an overlap.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Layer {
    /// Its section.
    pub section: Section,
    /// Height of its centroid above its own beam's axis, m.
    pub offset: f64,
    /// Distance from its centroid to the interface, m (> 0).
    pub to_interface: f64,
}

/// A joint's overlap (see the module docs).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lap {
    /// Length of the overlap, m, centred on the joint.
    pub length: f64,
    /// The upper layer (the left beam's end) and the lower layer (the right beam's start).
    pub layers: [Layer; 2],
    /// Normal stiffness of the interface per unit length, N/m per m.
    pub k_n: f64,
    /// Shear (slip) stiffness of the interface per unit length, N/m per m.
    pub k_s: f64,
    /// Whether k_n, k_s are identified or held fixed.
    pub roles: [Role; 2],
    /// The notch stiffness of each layer's root (the upper layer's at the overlap's start, the
    /// lower's at its end; [`super::notch`]), `None` where the layer is its beam's full height.
    pub notches: [Option<f64>; 2],
    /// The rotational stiffness of every notched root, N m/rad: `None`, the roots are rigid
    /// (plane sections through them).
    pub k_r: Option<f64>,
    /// Whether k_r is identified or held fixed.
    pub root_role: Role,
    /// `true`: the joint is this layered lap; `false`: a point joint whose overlap this is.
    pub active: bool,
}

/// The names and the unit of a lap's parameters, in parameter order.
pub const LAP_PARAMETERS: [&str; 2] = ["k_n", "k_s"];
/// The unit of k_n and k_s.
pub const LAP_UNIT: &str = "N/m^2";
/// The name of the roots' rotational stiffness.
pub const ROOT_PARAMETER: &str = "k_r";
/// Its unit.
pub const ROOT_UNIT: &str = "N m/rad";

impl Lap {
    /// The overlap's ends for a joint at `x`, m.
    pub fn span(&self, x: f64) -> (f64, f64) {
        (x - 0.5 * self.length, x + 0.5 * self.length)
    }

    /// The shear stiffness at which the interface's slip decays over the overlap's length:
    /// 1 / (L^2 (1 / EA_1 + 1 / EA_2 + r^2 / (EI_1 + EI_2))), r the distance between the
    /// layers' centroids (the partial-interaction parameter alpha L = 1, Newmark et al. 1951).
    pub fn shear_scale(&self) -> f64 {
        let [a, b] = self.layers;
        let ea = |l: &Layer| l.section.youngs_modulus * l.section.area;
        let r = a.to_interface + b.to_interface;
        let ei = a.section.bending_stiffness() + b.section.bending_stiffness();
        1.0 / (self.length.powi(2) * (1.0 / ea(&a) + 1.0 / ea(&b) + r * r / ei))
    }

    /// The normal stiffness at which the layers' relative deflection decays over the overlap:
    /// 4 EI_r / L^4 with EI_r = EI_1 EI_2 / (EI_1 + EI_2) (a beam on an elastic foundation,
    /// lambda L = 1).
    pub fn normal_scale(&self) -> f64 {
        let [a, b] = self.layers.map(|l| l.section.bending_stiffness());
        4.0 * (a * b / (a + b)) / self.length.powi(4)
    }
}

/// The `[joint.lap]` table.
#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
pub(crate) struct RawLap {
    length: f64,
    layers: Option<String>,
    upper: Option<RawLayer>,
    lower: Option<RawLayer>,
    k_n: Option<f64>,
    k_s: Option<f64>,
    k_r: Option<f64>,
}

#[derive(Debug, Deserialize)]
#[serde(deny_unknown_fields)]
struct RawLayer {
    area: f64,
    second_moment: f64,
    offset: f64,
    to_interface: f64,
}

/// The lap of joint `j` (between `beams[j]` and `beams[j + 1]`), the joint itself when
/// `active`, its roles `roles` (k_n, k_s) and `root_role` (k_r).
pub(crate) fn lap(
    raw: &RawLap,
    j: usize,
    active: bool,
    (roles, root_role): ([Role; 2], Role),
    beams: &[Beam],
    check: &FieldCheck,
) -> Result<Lap, InputError> {
    let p = |field: &str| format!("joint[{j}].lap.{field}");
    let length = check.positive(p("length"), raw.length, "m")?;
    let (left, right) = (&beams[j], &beams[j + 1]);
    let reach = 2.0 * left.length.min(right.length);
    if length > reach * (1.0 + 1e-12) {
        return Err(check.invalid(
            p("length"),
            Number(length),
            format!(
                "a centred overlap reaches half its length into each beam: at most twice the shorter of beam[{j}] ({} m) and beam[{}] ({} m), {} m",
                Number(left.length),
                j + 1,
                Number(right.length),
                Number(reach)
            ),
        ));
    }
    // The mesh tells abscissae apart to a fraction of the chain's length, and break points to
    // a fraction of a beam's: an overlap whose halves are not well above that has its ends
    // merged into the joint's node, and its layers would have no element. Twice the fraction
    // per half keeps the ends apart whatever the rounding.
    let fraction = super::mesh::SAME_X.max(super::mesh::MERGE);
    let chain_length: f64 = beams.iter().map(|b| b.length).sum();
    let least = 4.0 * fraction * chain_length;
    if length <= least {
        return Err(check.invalid(
            p("length"),
            Number(length),
            format!(
                "the mesh tells abscissae apart to {} of the chain's length ({} m): the overlap must be longer than {} m",
                Number(fraction),
                Number(chain_length),
                Number(least)
            ),
        ));
    }
    let sections = [left.section_at(left.length), right.section_at(0.0)];
    lapped_heights(&[left, right], &sections, j, check)?;
    let layers = match (raw.layers.as_deref(), &raw.upper, &raw.lower) {
        (_, Some(u), Some(l)) if raw.layers.is_none() => [
            layer(u, sections[0], &p("upper"), check)?,
            layer(l, sections[1], &p("lower"), check)?,
        ],
        (None | Some("half"), None, None) => [half(sections[0], 1.0), half(sections[1], -1.0)],
        (Some("full"), None, None) => sections.map(full),
        (Some(other), None, None) => {
            return Err(check.invalid(
                p("layers"),
                format!("\"{other}\""),
                "it must be \"half\" (half-lap splice) or \"full\" (plain overlap), or leave it out and give both [joint.lap.upper] and [joint.lap.lower]",
            ));
        }
        _ => {
            return Err(check.invalid(
                p("layers"),
                raw.layers.as_deref().unwrap_or("(none)"),
                "give either `layers` or both tables [joint.lap.upper] and [joint.lap.lower]",
            ));
        }
    };
    let notches = [0, 1].map(|r| {
        let depth = notch::height(&sections[r]) - notch::height(&layers[r].section);
        notch::stiffness(&sections[r], depth)
    });
    let nominal: Vec<f64> = notches.iter().flatten().copied().collect();
    let k_r = match raw.k_r {
        Some(v) if nominal.is_empty() => {
            return Err(check.invalid(
                p("k_r"),
                v,
                "neither layer's root is a notch (each layer is its beam's full height): leave k_r out",
            ));
        }
        Some(v) => Some(check.positive(p("k_r"), v, "N m/rad")?),
        None if active || nominal.is_empty() => None,
        None => Some(nominal.iter().sum::<f64>() / nominal.len() as f64),
    };
    let mut lap = Lap {
        length,
        layers,
        k_n: 0.0,
        k_s: 0.0,
        roles,
        notches,
        k_r,
        root_role,
        active,
    };
    let value = |v: Option<f64>, name: &str, scale: f64| match v {
        Some(v) => check.positive(p(name), v, "N/m per m"),
        None if active => Err(check.invalid(
            p(name),
            "missing",
            format!("a joint of kind = \"lap\" needs the interface's {name} (N/m per m)"),
        )),
        None => Ok(scale),
    };
    lap.k_n = value(raw.k_n, "k_n", 1e4 * lap.normal_scale())?;
    lap.k_s = value(raw.k_s, "k_s", lap.shear_scale())?;
    Ok(lap)
}

/// The beams `beams` of joint `j` (left, right) at their overlap ends, `sections`, checked to be
/// beams: a section higher (sqrt(12 I / A)) than its beam is long (an area of 1e-308 m^2
/// against its second moment) would put the layers' centroids off the axis by more than any
/// structure spans, and their matrices past double precision.
fn lapped_heights(
    beams: &[&Beam; 2],
    sections: &[Section; 2],
    j: usize,
    check: &FieldCheck,
) -> Result<(), InputError> {
    for (k, (beam, section)) in beams.iter().zip(sections).enumerate() {
        let h = notch::height(section);
        if !(h.is_finite() && h <= beam.length) {
            return Err(check.invalid(
                format!("beam[{}]", j + k),
                format!("height sqrt(12 I / A) = {} m", Number(h)),
                format!(
                    "a lapped beam is no higher than it is long ({} m): check area and second_moment",
                    Number(beam.length)
                ),
            ));
        }
    }
    Ok(())
}

/// Half of a rectangle-equivalent section (height sqrt(12 I / A)), its centroid `sign` h/4
/// from the beam's axis (+1: the upper half).
fn half(s: Section, sign: f64) -> Layer {
    let h = notch::height(&s);
    Layer {
        section: Section {
            area: 0.5 * s.area,
            second_moment: s.second_moment / 8.0,
            ..s
        },
        offset: sign * 0.25 * h,
        to_interface: 0.25 * h,
    }
}

/// A beam's full section as a layer, its centroid on the beam's axis.
fn full(s: Section) -> Layer {
    let h = notch::height(&s);
    Layer {
        section: s,
        offset: 0.0,
        to_interface: 0.5 * h,
    }
}

fn layer(r: &RawLayer, beam: Section, at: &str, check: &FieldCheck) -> Result<Layer, InputError> {
    let q = |field: &str| format!("{at}.{field}");
    if !r.offset.is_finite() {
        return Err(check.invalid(q("offset"), r.offset, "it must be finite (m)"));
    }
    Ok(Layer {
        section: Section {
            area: check.positive(q("area"), r.area, "m^2")?,
            second_moment: check.positive(q("second_moment"), r.second_moment, "m^4")?,
            ..beam
        },
        offset: r.offset,
        to_interface: check.positive(q("to_interface"), r.to_interface, "m")?,
    })
}

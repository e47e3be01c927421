//! Point resolution, shared by every format: a measured point named by node and DOF, by
//! position along a chain and DOF, by coordinates in space and direction (the nearest DOF of
//! a model without beam elements, [`crate::structure::nearest`]) or by label (a DOF label or
//! a declared sensor's), resolved into an [`Observation`] of the structure.
//!
//! May import: the structure.

use crate::structure::{Direction, Observation, Structure};

/// How a file locates its measured points: the three forms a measured point may be named in.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Location {
    /// `node,dof`.
    Node,
    /// `x,dof`.
    Position,
    /// `label`.
    Label,
    /// `x,y,z,dof`: coordinates in space and a direction.
    Space,
}

impl Location {
    /// The names of the fields that locate a point in this form (the CSV's columns).
    pub fn fields(self) -> &'static [&'static str] {
        match self {
            Location::Node => &["node", "dof"],
            Location::Position => &["x", "dof"],
            Location::Label => &["label"],
            Location::Space => &["x", "y", "z", "dof"],
        }
    }
}

/// The observation that `fields` name in the form `location` (the texts of
/// [`Location::fields`], in that order), or what is wrong and what is allowed, for the format
/// to put at its position (a CSV's line).
pub fn locate(
    location: Location,
    fields: &[&str],
    structure: &Structure,
) -> Result<Observation, String> {
    let dofs = &structure.dofs;
    let direction = |text: &str| {
        Direction::parse(text).ok_or_else(|| {
            format!("dof = `{text}` is invalid: it must be `w` or `theta` (or x, y, z, rx, ry, rz for an external model)")
        })
    };
    match location {
        Location::Node => {
            let nodes = dofs
                .dofs()
                .iter()
                .filter_map(|d| d.node)
                .max()
                .map_or(0, |n| n + 1);
            let node: usize = fields[0].parse().ok().filter(|&n| n < nodes).ok_or_else(|| {
                if nodes == 0 {
                    format!("node = `{}` is invalid: this model has no numbered nodes; give points by label", fields[0])
                } else {
                    format!("node = `{}` is invalid: the model has nodes 0 to {}", fields[0], nodes - 1)
                }
            })?;
            let d = direction(fields[1])?;
            let label = crate::structure::DofMap::node_label(node, d);
            match dofs.index(&label) {
                Some(i) => Ok(Observation::dof(dofs, i)),
                None => Err(match dofs.constrained_by(&label) {
                    Some(by) => format!(
                        "node {node}, dof {d} is held by {by}: it is always zero; leave the row out"
                    ),
                    None => format!("node {node} has no dof {d}"),
                }),
            }
        }
        Location::Position => {
            let x: f64 = fields[0]
                .parse()
                .ok()
                .filter(|x: &f64| x.is_finite())
                .ok_or_else(|| {
                    format!("x = `{}` is invalid: it must be a number (m)", fields[0])
                })?;
            dofs.at_x(x, direction(fields[1])?)
                .map_err(|e| e.to_string())
        }
        Location::Space => {
            if !dofs.lines().is_empty() {
                return Err("rows by x,y,z apply to models without beam elements (external models): on a beam chain give `x,dof` (read along the elements) or `node,dof`".to_string());
            }
            let mut point = [0.0; 3];
            for ((p, text), name) in point.iter_mut().zip(fields).zip(["x", "y", "z"]) {
                *p = text
                    .parse()
                    .ok()
                    .filter(|v: &f64| v.is_finite())
                    .ok_or_else(|| {
                        format!("{name} = `{text}` is invalid: it must be a number (m)")
                    })?;
            }
            dofs.nearest(point, direction(fields[3])?)
                .map_err(|e| e.to_string())
        }
        Location::Label => {
            let label = fields[0];
            if let Some(i) = dofs.index(label) {
                return Ok(Observation::dof(dofs, i));
            }
            if let Some(s) = structure.sensors.iter().find(|s| s.label == label) {
                return Ok(s.clone());
            }
            Err(match dofs.constrained_by(label) {
                Some(by) => format!(
                    "label = `{label}` is held by {by}: it is always zero; leave the row out"
                ),
                None => format!(
                    "label = `{label}` is invalid: it is neither a DOF of the model nor a declared sensor"
                ),
            })
        }
    }
}

//! A 3D solid model of a bolted lap specimen, made with this module's own brick element and
//! written as an external model (`kind = "matrices"`): two bars of rectangular section, one
//! on top of the other over the lap, tied by interface springs whose stiffnesses are the
//! model's parameters. Free-free: six rigid-body modes. It is independent of the beam chain
//! (no code of [`crate::model::chain`] is used), so it serves as independent test data for
//! external models, sensors in space and large models (`jointid solid`).
//!
//! - [`config`]: the specimen's TOML;
//! - [`hex`]: the 8-node brick with incompatible modes, and its consistent mass;
//! - [`mesh`]: nodes, bricks and the lap's node pairs;
//! - [`triplets`]: sparse assembly of the lower triangle in bounded memory;
//! - [`files`]: the external model's files, written as a stream.
//!
//! The interface: at every pair of coincident nodes of the lap (the lower bar's top face, the
//! upper bar's bottom face) three springs, normal (z) and shear (x, y), each the stiffness per
//! area times the pair's tributary area (times a bolt patch's factor where the pair lies in
//! one): the lumped form of a zero-thickness interface layer. The parameter of each direction
//! is the sum of its springs over the lap, N/m (`k_normal`, `k_shear_x`, `k_shear_y`), so
//! dK/dp holds the springs' pattern with the pairs' shares of the total weight.
//!
//! May import: the shared input checks, the external model's limits and the Matrix Market
//! writer ([`crate::model::matrices`], [`crate::model::matrix_market`]); never the chain.

pub mod config;
pub mod files;
pub mod hex;
pub mod mesh;
pub mod triplets;

use std::collections::HashMap;

use crate::input::Number;
pub use config::SolidConfig;
use hex::{HexMatrices, hex8};
use mesh::Mesh;
use triplets::{Lower, Triplets};

impl SolidConfig {
    /// Reads and validates the file at `path`.
    pub fn from_path(path: &std::path::Path) -> Result<SolidConfig, crate::input::InputError> {
        Self::from_toml(&crate::input::read_file(path)?, path)
    }

    /// Parses and validates TOML text (every field, then every bolt patch against the mesh);
    /// `file` names it in errors.
    pub fn from_toml(
        text: &str,
        file: &std::path::Path,
    ) -> Result<SolidConfig, crate::input::InputError> {
        let config = SolidConfig::parse(text, file)?;
        mesh::check_bolts(&config, file)?;
        Ok(config)
    }
}

/// The names of the interface parameters, in the order of the directions x, y, z.
pub const PARAMETERS: [&str; 3] = ["k_shear_x", "k_shear_y", "k_normal"];

/// An interface parameter: its value and dK/dp.
#[derive(Debug, Clone, PartialEq)]
pub struct SolidParameter {
    /// Name (one of [`PARAMETERS`]).
    pub name: &'static str,
    /// The sum of the springs of its direction over the lap, N/m.
    pub value: f64,
    /// dK/dp: each pair's spring pattern times its share of the weight.
    pub dk: Lower,
}

/// A generated model: the mesh, K and M without the interface, and the interface parameters.
#[derive(Debug, Clone)]
pub struct Solid {
    /// The configuration it was made from.
    pub config: SolidConfig,
    /// The mesh (3 DOFs per node, DOF 3 n + d for direction d of node n).
    pub mesh: Mesh,
    /// K of the two bars alone.
    pub k: Lower,
    /// M.
    pub m: Lower,
    /// The interface's parameters, in the order of [`PARAMETERS`].
    pub parameters: Vec<SolidParameter>,
}

/// Why a validated configuration gives no model.
#[derive(Debug, thiserror::Error)]
pub enum SolidError {
    /// A brick that cannot be integrated (a validated configuration never gives one).
    #[error(
        "cannot make the model: brick {brick} (nodes {nodes:?}) is inverted or degenerate: det J <= 0 at a Gauss point"
    )]
    DegenerateBrick {
        /// The brick, 0-based.
        brick: usize,
        /// Its nodes, 0-based.
        nodes: [usize; 8],
    },
    /// A computed value (an entry of K or M, a parameter) outside the range of a double
    /// (infinite, or below the smallest normal number, whose reciprocal is infinite), and
    /// the input field it comes from.
    #[error("{field} = {value} is invalid: {reason}")]
    OutOfRange {
        /// The field's path in the configuration.
        field: String,
        /// Its value.
        value: String,
        /// What it gives and why that is refused.
        reason: String,
    },
}

/// The range of a double every computed value must lie in (by magnitude): the normal numbers,
/// whose reciprocals are finite too.
const RANGE: &str = "outside a double's range (2.2e-308 to 1.8e308)";

/// Whether `v` is finite and, when `positive`, at least the smallest normal number.
fn in_range(v: f64, positive: bool) -> bool {
    v.is_finite() && (!positive || v >= f64::MIN_POSITIVE)
}

impl SolidError {
    fn out_of_range(field: impl Into<String>, value: f64, reason: String) -> Self {
        SolidError::OutOfRange {
            field: field.into(),
            value: Number(value).to_string(),
            reason,
        }
    }
}

/// The first entry of `a` outside [`RANGE`] (any entry infinite or NaN, a diagonal entry not
/// positive and normal, or absent: underflowed to 0): its DOF (1-based) and value.
fn first_out_of_range(a: &Lower) -> Option<(usize, f64)> {
    let mut diagonal = vec![false; a.size()];
    for (r, c, v) in a.iter() {
        if !in_range(v, r == c) {
            return Some((r + 1, v));
        }
        diagonal[r] |= r == c;
    }
    diagonal.iter().position(|&d| !d).map(|r| (r + 1, 0.0))
}

impl Solid {
    /// The model of `config`. Every computed value is checked: an entry of K or M, or an
    /// interface parameter, outside the range of a double is refused naming the field it
    /// comes from (the modulus, the density, a stiffness per area, a bolt's factor, the lap's
    /// size).
    pub fn generate(config: &SolidConfig) -> Result<Solid, SolidError> {
        let mesh = Mesh::of(config);
        let (k, m) = assemble(&mesh, &config.material)?;
        let material = &config.material;
        let size = Number(config.mesh.size);
        if let Some((dof, v)) = first_out_of_range(&k) {
            return Err(SolidError::out_of_range(
                "material.youngs_modulus",
                material.youngs_modulus,
                format!(
                    "K (E x brick size {size} m) has {} at DOF {dof}, {RANGE}",
                    Number(v)
                ),
            ));
        }
        if let Some((dof, v)) = first_out_of_range(&m) {
            return Err(SolidError::out_of_range(
                "material.density",
                material.density,
                format!(
                    "M (density x brick size {size} m, cubed) has {} at DOF {dof}, {RANGE}",
                    Number(v)
                ),
            ));
        }
        let n = 3 * mesh.nodes.len();
        let total: f64 = mesh.pairs.iter().map(|p| p.2).sum();
        let area = config.width * config.overlap;
        if !in_range(area, true) {
            return Err(SolidError::out_of_range(
                "overlap",
                config.overlap,
                format!(
                    "the lap's area, width x overlap, is {} m^2, {RANGE}",
                    Number(area)
                ),
            ));
        }
        // Beyond the lap's area, only the bolts' factors weigh the springs: the bolt of the
        // largest factor is named for a value too large, that of the smallest for one too small.
        let bolt = |high: bool| {
            let bolts = config.interface.bolts.iter().enumerate();
            let by_factor = |a: &(usize, &config::Bolt), b: &(usize, &config::Bolt)| {
                a.1.factor.total_cmp(&b.1.factor)
            };
            let chosen = if high {
                bolts.max_by(by_factor)
            } else {
                bolts.min_by(by_factor)
            };
            chosen.map(|(i, b)| (format!("interface.bolt[{i}].factor"), b.factor))
        };
        if !in_range(total, true) {
            let (field, input) = bolt(total > 1.0).unwrap_or(("overlap".into(), config.overlap));
            return Err(SolidError::out_of_range(
                field,
                input,
                format!(
                    "the spring weights (area x bolt factor) sum to {} m^2, {RANGE}",
                    Number(total)
                ),
            ));
        }
        let per_area = [
            ("interface.shear_x", config.interface.shear_x),
            ("interface.shear_y", config.interface.shear_y),
            ("interface.normal", config.interface.normal),
        ];
        let mut parameters = Vec::with_capacity(PARAMETERS.len());
        for (d, (&name, (field, per_area))) in PARAMETERS.iter().zip(per_area).enumerate() {
            let value = per_area * total;
            if !in_range(value, true) {
                let (field, input) = bolt(value > 1.0)
                    .filter(|_| in_range(per_area * area, true))
                    .unwrap_or((field.to_string(), per_area));
                return Err(SolidError::out_of_range(
                    field,
                    input,
                    format!(
                        "{name} (stiffness per area x lap area) is {} N/m, {RANGE}",
                        Number(value)
                    ),
                ));
            }
            let mut dk = Triplets::new(n);
            for &(a, b, w) in &mesh.pairs {
                let (i, j, s) = (3 * a + d, 3 * b + d, w / total);
                dk.add(i, i, s);
                dk.add(j, j, s);
                dk.add(i, j, -s);
            }
            parameters.push(SolidParameter {
                name,
                value,
                dk: dk.finish(),
            });
        }
        Ok(Solid {
            config: config.clone(),
            mesh,
            k,
            m,
            parameters,
        })
    }

    /// The number of DOFs.
    pub fn dof_count(&self) -> usize {
        3 * self.mesh.nodes.len()
    }
}

/// K and M of the bricks of `mesh`. Bricks of the same shape (the same node offsets, bit for
/// bit) share one integration: a structured mesh has a handful of shapes.
pub fn assemble(mesh: &Mesh, material: &hex::Material) -> Result<(Lower, Lower), SolidError> {
    let n = 3 * mesh.nodes.len();
    let (mut k, mut m) = (Triplets::new(n), Triplets::new(n));
    let mut shapes: HashMap<[u64; 24], HexMatrices> = HashMap::new();
    let mut dofs = [0usize; 24];
    for (e, brick) in mesh.bricks.iter().enumerate() {
        let origin = mesh.nodes[brick[0]];
        let x: [[f64; 3]; 8] =
            std::array::from_fn(|a| std::array::from_fn(|i| mesh.nodes[brick[a]][i] - origin[i]));
        let key: [u64; 24] = std::array::from_fn(|i| x[i / 3][i % 3].to_bits());
        let element = match shapes.entry(key) {
            std::collections::hash_map::Entry::Occupied(o) => o.into_mut(),
            std::collections::hash_map::Entry::Vacant(v) => {
                v.insert(hex8(&x, material).ok_or(SolidError::DegenerateBrick {
                    brick: e,
                    nodes: *brick,
                })?)
            }
        };
        for (a, &node) in brick.iter().enumerate() {
            for d in 0..3 {
                dofs[3 * a + d] = 3 * node + d;
            }
        }
        k.add_block(&dofs, &element.k);
        m.add_block(&dofs, &element.m);
    }
    Ok((k.finish(), m.finish()))
}

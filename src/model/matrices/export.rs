//! Any structure written as an external model: K.mtx and M.mtx (the base matrices, without the
//! parameters' terms), `dK_<name>.mtx` (and `dM_<name>.mtx` where the mass depends on it) per
//! parameter, dofs.csv and a model.toml of kind "matrices" that reads back into the same
//! structure.
//!
//! Exact round trip: values are written in shortest round-trip form and every matrix keeps
//! the entries of each position in their order, so the matrices read back are bitwise those
//! of the structure, and so are K(p) and M(p) assembled from them (the same sums in the same
//! order, see [`crate::structure::SymMatrix::from_entries`]). A derivative is read back as the
//! list of its entries in file order, an off-diagonal one as (j, i) then (i, j)
//! ([`crate::model::matrix_market::LowerEntries::both_triangles`]): the order the chain
//! builder lists a spring in, so sums over the entries (the sensitivities y_s^T dK/dp y) are
//! the same bits too. A derivative listed in another order reads back as the same matrix, and
//! a note says that such sums may then differ in the last bit. What an external model cannot
//! hold is listed in [`Export::notes`] as well: declared sensors, the beam elements along
//! which positions are read, the sites of the effects.

use crate::model::matrix_market;
use crate::structure::{SparseSym, Structure, SymMatrix};

use super::config::UNITS;
use super::dof_table;

/// The files of an exported model, in memory: `(file name, bytes)`, model.toml first.
#[derive(Debug, Clone)]
pub struct Export {
    /// The files.
    pub files: Vec<(String, Vec<u8>)>,
    /// What the exported model does not carry, one sentence each.
    pub notes: Vec<String>,
}

/// A structure that cannot be exported.
#[derive(Debug, thiserror::Error)]
pub enum ExportError {
    /// A matrix whose two triangles differ (a builder's bug, never a user's input).
    #[error(
        "{matrix} is not symmetric entry by entry: it cannot be written as a symmetric Matrix Market file"
    )]
    NotSymmetric {
        /// Which matrix.
        matrix: String,
    },
    /// A parameter unit the reader would refuse.
    #[error("parameter {name} has unit \"{unit}\", which a matrices model cannot declare (allowed: \"{}\")", UNITS.join("\", \""))]
    Unit {
        /// The parameter.
        name: String,
        /// Its unit.
        unit: String,
    },
}

/// The files of `structure` as a model of kind "matrices"; `source` (the exported model file)
/// is named in their comments.
pub fn export(structure: &Structure, source: &str) -> Result<Export, ExportError> {
    let n = structure.dof_count();
    let mut files: Vec<(String, Vec<u8>)> = Vec::new();
    let comment = |what: &str| vec![format!("{what}, exported by jointid from {source}")];
    let mtx = |lower: &[(usize, usize, f64)], comments: Vec<String>| {
        let mut bytes = Vec::new();
        matrix_market::write(&mut bytes, n, lower, &comments).expect("writing to memory");
        bytes
    };
    files.push((
        "K.mtx".into(),
        mtx(
            &base_lower(&structure.base.k, "K")?,
            comment("K without the parameters' terms"),
        ),
    ));
    files.push((
        "M.mtx".into(),
        mtx(
            &base_lower(&structure.base.m, "M")?,
            comment("M without the parameters' terms"),
        ),
    ));
    let mut toml = format!(
        "# Exported by `jointid export` from {source}.\n\
         # K(p) = K + sum_i p_i dK/dp_i, M(p) = M + sum_i p_i dM/dp_i.\n\
         kind = \"matrices\"\n\
         stiffness = \"K.mtx\"\n\
         mass = \"M.mtx\"\n\
         dofs = \"dofs.csv\"\n\
         rigid_body_modes = {}\n",
        structure.rigid
    );
    if let Some(t) = structure.dofs.sensor_tolerance_set() {
        toml.push_str(&format!("sensor_tolerance = {t:e}\n"));
    }
    let mut reordered = false;
    for p in &structure.parameters {
        if !UNITS.contains(&p.unit) {
            return Err(ExportError::Unit {
                name: p.name.clone(),
                unit: p.unit.to_string(),
            });
        }
        let stem = unique_stem(&p.name, &files);
        let quoted = |s: &str| toml::Value::String(s.to_string()).to_string();
        toml.push_str(&format!(
            "\n[[parameter]]\nname = {}\nunit = {}\nvalue = {:e}\n",
            quoted(&p.name),
            quoted(p.unit),
            p.value
        ));
        let dk = format!("dK_{stem}.mtx");
        let lower = derivative_lower(&p.stiffness, &format!("dK/d{}", p.name))?;
        reordered |= !same_order(&p.stiffness, &lower, n);
        files.push((
            dk.clone(),
            mtx(&lower, comment(&format!("dK/d{} ({})", p.name, p.unit))),
        ));
        toml.push_str(&format!("dk = {}\n", quoted(&dk)));
        if !p.mass.is_zero() {
            let dm = format!("dM_{stem}.mtx");
            let lower = derivative_lower(&p.mass, &format!("dM/d{}", p.name))?;
            reordered |= !same_order(&p.mass, &lower, n);
            files.push((
                dm.clone(),
                mtx(&lower, comment(&format!("dM/d{} ({})", p.name, p.unit))),
            ));
            toml.push_str(&format!("dm = {}\n", quoted(&dm)));
        }
        let role = match p.role {
            crate::structure::Role::Identified => "identified",
            crate::structure::Role::Fixed => "fixed",
        };
        toml.push_str(&format!("role = \"{role}\"\n"));
    }
    let mut dofs = Vec::new();
    dof_table::write(&mut dofs, structure.dofs.dofs()).expect("writing to memory");
    files.push(("dofs.csv".into(), dofs));
    files.insert(0, ("model.toml".into(), toml.into_bytes()));
    let mut notes = notes(structure);
    if reordered {
        notes.push("a derivative lists its entries in another order than the file keeps: the exported model has the same matrices, but sums over their entries may differ in the last bit".to_string());
    }
    Ok(Export { files, notes })
}

/// The lower triangle of a base matrix, column by column, after the symmetry check.
fn base_lower(a: &SymMatrix, name: &str) -> Result<Vec<(usize, usize, f64)>, ExportError> {
    if a.asymmetry() != 0.0 {
        return Err(ExportError::NotSymmetric {
            matrix: name.to_string(),
        });
    }
    Ok(a.entries().into_iter().filter(|e| e.0 >= e.1).collect())
}

/// The entries of a derivative on and below the diagonal, in listed order, after checking
/// that above the diagonal lies the same sequence of values at every mirrored position.
fn derivative_lower(s: &SparseSym, name: &str) -> Result<Vec<(usize, usize, f64)>, ExportError> {
    let mut below: Vec<(usize, usize, u64)> = Vec::new();
    let mut above: Vec<(usize, usize, u64)> = Vec::new();
    for &(i, j, v) in s.entries() {
        if i > j {
            below.push((i, j, v.to_bits()));
        } else if i < j {
            above.push((j, i, v.to_bits()));
        }
    }
    // Stable: the order within a position is kept.
    below.sort_by_key(|e| (e.0, e.1));
    above.sort_by_key(|e| (e.0, e.1));
    if below != above {
        return Err(ExportError::NotSymmetric {
            matrix: name.to_string(),
        });
    }
    Ok(s.entries().iter().copied().filter(|e| e.0 >= e.1).collect())
}

/// Whether reading `lower` back gives the entries of `s` in their order.
fn same_order(s: &SparseSym, lower: &[(usize, usize, f64)], n: usize) -> bool {
    let back = matrix_market::LowerEntries {
        size: n,
        entries: lower.to_vec(),
    }
    .both_triangles();
    back.len() == s.entries().len()
        && back
            .iter()
            .zip(s.entries())
            .all(|(a, b)| a.0 == b.0 && a.1 == b.1 && a.2.to_bits() == b.2.to_bits())
}

/// `name` with every character outside [A-Za-z0-9._-] replaced by `_`, made unique among the
/// files so far.
fn unique_stem(name: &str, files: &[(String, Vec<u8>)]) -> String {
    let clean: String = name
        .chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || matches!(c, '.' | '_' | '-') {
                c
            } else {
                '_'
            }
        })
        .collect();
    let taken = |stem: &str| files.iter().any(|f| f.0 == format!("dK_{stem}.mtx"));
    let mut stem = clean.clone();
    let mut k = 2;
    while taken(&stem) {
        stem = format!("{clean}_{k}");
        k += 1;
    }
    stem
}

fn notes(structure: &Structure) -> Vec<String> {
    let mut notes = Vec::new();
    if !structure.sensors.is_empty() {
        notes.push(format!(
            "the model declares {} sensor(s): their masses are in M, but their labels and positions are not exported; measured files for the exported model name DOFs by label",
            structure.sensors.len()
        ));
    }
    if !structure.dofs.lines().is_empty() {
        notes.push("the exported model has no beam elements: measured rows by `x` or by `node` do not apply to it; name DOFs by label (`7:w`)".to_string());
    }
    let sites = &structure.sites;
    if !(sites.joints.is_empty() && sites.elements.is_empty() && sites.free_ends.is_empty()) {
        notes.push("the diagnosis effects that act on joints, beam elements or free ends do not apply to the exported model".to_string());
    }
    notes
}

/// Whether two structures are the same model bit for bit: base matrices, parameters (name,
/// unit, value, role, derivative entries), DOFs (labels, positions, directions) and the
/// rigid-body count. `Err` says the first difference.
pub fn identical(a: &Structure, b: &Structure) -> Result<(), String> {
    let bits = |e: Vec<(usize, usize, f64)>| -> Vec<(usize, usize, u64)> {
        e.into_iter().map(|(i, j, v)| (i, j, v.to_bits())).collect()
    };
    let sorted = |s: &SparseSym| {
        let mut e: Vec<(usize, usize, u64)> = s
            .entries()
            .iter()
            .map(|&(i, j, v)| (i, j, v.to_bits()))
            .collect();
        e.sort_by_key(|x| (x.0, x.1));
        e
    };
    if bits(a.base.k.entries()) != bits(b.base.k.entries()) {
        return Err("K differs".into());
    }
    if bits(a.base.m.entries()) != bits(b.base.m.entries()) {
        return Err("M differs".into());
    }
    if a.parameters.len() != b.parameters.len() {
        return Err("the number of parameters differs".into());
    }
    for (p, q) in a.parameters.iter().zip(&b.parameters) {
        let same = p.name == q.name
            && p.unit == q.unit
            && p.value.to_bits() == q.value.to_bits()
            && p.role == q.role
            && sorted(&p.stiffness) == sorted(&q.stiffness)
            && sorted(&p.mass) == sorted(&q.mass);
        if !same {
            return Err(format!("parameter {} differs", p.name));
        }
    }
    let dof = |s: &Structure| -> Vec<(String, [u64; 3], crate::structure::Direction)> {
        s.dofs
            .dofs()
            .iter()
            .map(|d| (d.label.clone(), d.position.map(f64::to_bits), d.direction))
            .collect()
    };
    if dof(a) != dof(b) {
        return Err("the DOF table differs".into());
    }
    let tolerance = |s: &Structure| s.dofs.sensor_tolerance_set().map(f64::to_bits);
    if tolerance(a) != tolerance(b) {
        return Err("the sensor tolerance differs".into());
    }
    if a.rigid != b.rigid {
        return Err(format!(
            "the rigid-body count differs ({} and {})",
            a.rigid, b.rigid
        ));
    }
    Ok(())
}

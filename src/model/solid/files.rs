//! The files of a generated solid as an external model (`kind = "matrices"`, see
//! docs/formats.md): `model.toml`, `K.mtx`, `M.mtx` (the bars without the interface),
//! `dK_<parameter>.mtx` per interface parameter and `dofs.csv` (labels `<node>:<direction>`,
//! nodes numbered from 1, directions x, y, z). Each file is written as a stream from the
//! assembled matrices, never held whole in memory.
//!
//! May import: the Matrix Market writer and the DOF table's writer.

use std::io::{self, Write};

use super::Solid;
use crate::input::Number;
use crate::model::matrices::dof_table;
use crate::model::matrix_market::write_entries;
use crate::structure::{Direction, DofInfo};

/// The directions of a node's three DOFs, in DOF order.
pub const DIRECTIONS: [Direction; 3] = [Direction::X, Direction::Y, Direction::Z];

impl Solid {
    /// The names of the files, model.toml first.
    pub fn file_names(&self) -> Vec<String> {
        let mut names = vec!["model.toml".to_string(), "K.mtx".into(), "M.mtx".into()];
        names.extend(self.parameters.iter().map(|p| format!("dK_{}.mtx", p.name)));
        names.push("dofs.csv".into());
        names
    }

    /// Writes the file `name` (one of [`Solid::file_names`]) into `out`; `source` (the
    /// configuration file) is named in the comments.
    pub fn write_file(&self, name: &str, source: &str, out: &mut dyn Write) -> io::Result<()> {
        let n = self.dof_count();
        let note = |what: &str| vec![format!("{what}, made by `jointid solid` from {source}")];
        match name {
            "model.toml" => out.write_all(self.model_toml(source).as_bytes()),
            "K.mtx" => write_entries(
                out,
                n,
                self.k.len(),
                self.k.iter(),
                &note("K of the two bars without the interface"),
            ),
            "M.mtx" => write_entries(
                out,
                n,
                self.m.len(),
                self.m.iter(),
                &note("consistent M of the two bars"),
            ),
            "dofs.csv" => dof_table::write_iter(
                out,
                self.mesh
                    .nodes
                    .iter()
                    .enumerate()
                    .flat_map(|(node, &position)| {
                        DIRECTIONS.into_iter().map(move |direction| DofInfo {
                            label: format!("{}:{direction}", node + 1),
                            position,
                            direction,
                            node: None,
                        })
                    }),
            ),
            other => match self
                .parameters
                .iter()
                .find(|p| format!("dK_{}.mtx", p.name) == other)
            {
                Some(p) => write_entries(
                    out,
                    n,
                    p.dk.len(),
                    p.dk.iter(),
                    &note(&format!("dK/d{} (N/m)", p.name)),
                ),
                None => Err(io::Error::new(
                    io::ErrorKind::InvalidInput,
                    format!("{other} is not a file of the model"),
                )),
            },
        }
    }

    /// The model file: the matrices, the DOF table, six rigid-body modes and the interface
    /// parameters at their values.
    fn model_toml(&self, source: &str) -> String {
        let c = &self.config;
        let mut t = format!(
            "# A lap specimen of {} bricks made by `jointid solid` from {source}: width {} m,\n\
             # overlap {} m, bars {} x {} m and {} x {} m (length x thickness), {} DOFs.\n\
             # K(p) = K + sum_i p_i dK/dp_i: p_i is the sum of the interface springs of one\n\
             # direction over the lap, N/m ({} N/m^3 normal, {} and {} N/m^3 shear, per area).\n\
             kind = \"matrices\"\n\
             stiffness = \"K.mtx\"\n\
             mass = \"M.mtx\"\n\
             dofs = \"dofs.csv\"\n\
             rigid_body_modes = 6\n",
            self.mesh.bricks.len(),
            Number(c.width),
            Number(c.overlap),
            Number(c.bars[0].length),
            Number(c.bars[0].thickness),
            Number(c.bars[1].length),
            Number(c.bars[1].thickness),
            self.dof_count(),
            Number(c.interface.normal),
            Number(c.interface.shear_x),
            Number(c.interface.shear_y),
        );
        for p in &self.parameters {
            t.push_str(&format!(
                "\n[[parameter]]\nname = \"{0}\"\nunit = \"N/m\"\nvalue = {1:e}\ndk = \"dK_{0}.mtx\"\nrole = \"identified\"\n",
                p.name, p.value
            ));
        }
        t
    }
}

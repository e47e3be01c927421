//! `jointid solid`: a 3D brick model of a bolted lap specimen from its TOML, written as an
//! external model (`kind = "matrices"`) into a new folder, through the same staging folder
//! as `jointid export`: on any error nothing is left, and no file is ever overwritten.

use std::io::{BufWriter, Write};

use anyhow::Context;

use super::export::{ensure_new_folder, fill_new_folder, write_staged};
use crate::cli::SolidArgs;
use jointid::model::solid::{Solid, SolidConfig};

pub fn run(args: &SolidArgs) -> anyhow::Result<()> {
    let config = SolidConfig::from_path(&args.config)?;
    ensure_new_folder(&args.out, "solid")?;
    let solid = Solid::generate(&config).with_context(|| args.config.display().to_string())?;
    let source = args.config.display().to_string();
    let names = solid.file_names();
    fill_new_folder(&args.out, |tmp| {
        for name in &names {
            write_staged(&tmp.join(name), |f| {
                let mut w = BufWriter::new(f);
                solid.write_file(name, &source, &mut w)?;
                w.flush()
            })?;
        }
        Ok(())
    })?;
    super::to_stdout(|w| {
        writeln!(
            w,
            "{}: {} ({} DOFs, {} bricks, {} interface node pairs, {} parameters, 6 rigid-body modes)",
            args.out.display(),
            names.join(", "),
            solid.dof_count(),
            solid.mesh.bricks.len(),
            solid.mesh.pairs.len(),
            solid.parameters.len()
        )
    })
}

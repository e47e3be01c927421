//! `jointid export`: a model written as an external model (`kind = "matrices"`) into a new
//! folder. The files go into a temporary folder beside it, are read back and compared with
//! the model bit for bit, and the folder is renamed into place: on any error nothing is left.
//! The target must not exist or be empty, so no file (the model's inputs among them) is ever
//! overwritten. The temporary folder is created exclusively under an unpredictable name
//! ([`staging_folder`]): the run removes only what it created.

use jointid::output::atomic::{commit_folder, create_staged_file, staging_folder, untrack};
use std::io::Write;
use std::path::Path;

use anyhow::{Context, bail};

use crate::cli::ExportArgs;
use jointid::model::matrices::{export, export::identical};

pub fn run(args: &ExportArgs) -> anyhow::Result<()> {
    let model = super::read_model(&args.model)?;
    let out = &args.out;
    ensure_new_folder(out, "export")?;
    let exported = export(&model, &args.model.display().to_string())
        .with_context(|| format!("{}: cannot export", args.model.display()))?;
    fill_new_folder(out, |tmp| {
        for (name, bytes) in &exported.files {
            write_staged(&tmp.join(name), |f| f.write_all(bytes))?;
        }
        let back = jointid::model::from_path(&tmp.join("model.toml"))
            .context("the exported model does not read back")?;
        identical(&model, &back).map_err(|why| {
            anyhow::anyhow!("the exported model reads back different from the model: {why}")
        })
    })?;
    let mut err = std::io::stderr().lock();
    for note in &exported.notes {
        writeln!(err, "note: {note}")?;
    }
    let names: Vec<&str> = exported.files.iter().map(|f| f.0.as_str()).collect();
    super::to_stdout(|w| {
        writeln!(
            w,
            "{}: {} ({} DOFs, {} parameters, {} rigid-body modes)",
            out.display(),
            names.join(", "),
            model.dof_count(),
            model.parameters.len(),
            model.rigid
        )
    })
}

/// Refuses an `--out` folder that exists and is not empty (`command` writes into a new
/// folder and never overwrites files).
pub(crate) fn ensure_new_folder(out: &Path, command: &str) -> anyhow::Result<()> {
    if out.exists() {
        let empty = out.is_dir()
            && std::fs::read_dir(out)
                .with_context(|| format!("{}: cannot read the folder", out.display()))?
                .next()
                .is_none();
        if !empty {
            bail!(
                "--out {} exists and is not an empty folder: {command} writes into a new folder and never overwrites files (the model's inputs among them); remove it or choose another",
                out.display()
            );
        }
    }
    Ok(())
}

/// Fills a temporary folder beside `out` with `fill` and renames it into place; on any
/// error the temporary folder is removed and nothing is left.
pub(crate) fn fill_new_folder(
    out: &Path,
    fill: impl FnOnce(&Path) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    if out.file_name().is_none() {
        bail!("--out {} is not a folder name", out.display());
    }
    let tmp = staging_folder(out).with_context(|| {
        format!(
            "{}: cannot create a temporary folder beside it",
            out.display()
        )
    })?;
    let result = fill(&tmp).and_then(|()| {
        commit_folder(&tmp, out).with_context(|| {
            format!(
                "{}: cannot move the exported folder into place",
                out.display()
            )
        })
    });
    if result.is_err() {
        let _ = std::fs::remove_dir_all(&tmp);
    }
    untrack(&tmp);
    result
}

/// Creates the new file `path` in a staging folder, writes it with `write` and syncs it.
pub(crate) fn write_staged(
    path: &Path,
    write: impl FnOnce(&mut std::fs::File) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let mut f =
        create_staged_file(path).with_context(|| format!("{}: cannot create", path.display()))?;
    write(&mut f)
        .and_then(|()| f.sync_all())
        .with_context(|| format!("{}: cannot write", path.display()))
}

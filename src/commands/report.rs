//! `jointid report`: SVG figures and index.html of a study CSV.

use anyhow::Context;

use crate::cli::ReportArgs;
use std::path::{Path, PathBuf};

use jointid::output::atomic::stage_folder;
use jointid::output::study_report::{Figure, index_html, study_figures};
use jointid::output::{Staged, check_outputs, commit_all, stage};
use jointid::report::StudyResults;

pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
    check_outputs(&[&args.out.join("index.html")], &[&args.results])?;
    let results = StudyResults::from_path(&args.results)?;
    let title = args.title.clone().unwrap_or_else(|| {
        args.results
            .file_stem()
            .map_or_else(|| "study".into(), |s| s.to_string_lossy().into_owned())
    });
    let figures = study_figures(&results, &title)?;
    let page = index_html(
        &title,
        &args.results.display().to_string(),
        &results,
        &figures,
    );
    let staged = stage_page(&args.out, &figures, &page, &[&args.results])?;
    commit_all(staged)?;
    super::to_stdout(|w| {
        writeln!(
            w,
            "{}: {} figure(s) and index.html",
            args.out.display(),
            figures.len()
        )
    })
}

/// The figures and the page, staged in `dir`, to be committed with the run's other outputs.
/// An existing `dir` gets each file staged beside its target; an absent one is staged whole
/// beside it and appears only on the commit ([`stage_folder`]), so that a failed or
/// interrupted run never leaves it empty or half filled.
pub fn stage_page(
    dir: &Path,
    figures: &[Figure],
    page: &str,
    inputs: &[&Path],
) -> anyhow::Result<Vec<Staged>> {
    let index = dir.join("index.html");
    let paths: Vec<PathBuf> = figures
        .iter()
        .map(|f| dir.join(&f.name))
        .chain(std::iter::once(index))
        .collect();
    let refs: Vec<&Path> = paths.iter().map(|p| p.as_path()).collect();
    check_outputs(&refs, inputs)?;
    let contents: Vec<&[u8]> = figures
        .iter()
        .map(|f| f.svg.as_bytes())
        .chain(std::iter::once(page.as_bytes()))
        .collect();
    if !dir.exists() {
        let names: Vec<&str> = figures
            .iter()
            .map(|f| f.name.as_str())
            .chain(std::iter::once("index.html"))
            .collect();
        let files: Vec<(&str, &[u8])> = names.into_iter().zip(contents).collect();
        let staged = stage_folder(dir, &files)
            .with_context(|| format!("{}: cannot write the folder", dir.display()))?;
        return Ok(vec![staged]);
    }
    let mut staged = Vec::with_capacity(paths.len());
    for (path, bytes) in paths.iter().zip(contents) {
        staged.push(
            stage(path, |w| w.write_all(bytes))
                .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    Ok(staged)
}

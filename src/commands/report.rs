//! `jointid report`: SVG figures and index.html of a study CSV.

use anyhow::Context;

use crate::cli::ReportArgs;
use std::path::Path;

use jointid::output::study_report::{Figure, figure_page, index_html, study_figures};
use jointid::output::write_atomically;
use jointid::report::StudyResults;

pub fn run(args: &ReportArgs) -> anyhow::Result<()> {
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
    write_page(&args.out, &figures, &page)?;
    println!(
        "{}: {} figure(s) and index.html",
        args.out.display(),
        figures.len()
    );
    Ok(())
}

/// Writes the figures and a plain page showing them (for `diagnose --plots`).
pub fn write_figures(dir: &Path, title: &str, figures: &[Figure]) -> anyhow::Result<()> {
    write_page(dir, figures, &figure_page(title, figures))
}

fn write_page(dir: &Path, figures: &[Figure], page: &str) -> anyhow::Result<()> {
    std::fs::create_dir_all(dir)
        .with_context(|| format!("{}: cannot create the directory", dir.display()))?;
    for f in figures {
        let path = dir.join(&f.name);
        write_atomically(&path, |w| w.write_all(f.svg.as_bytes()))
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    let index = dir.join("index.html");
    write_atomically(&index, |w| w.write_all(page.as_bytes()))
        .with_context(|| format!("{}: cannot write", index.display()))
}

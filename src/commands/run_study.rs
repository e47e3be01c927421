//! Running a study file cell by cell, shared by `study` and `check`: progress bar on stderr,
//! optional per-trial CSV, result CSV written whole or not at all.

use std::io::IsTerminal;
use std::path::Path;
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::cli::StudyArgs;
use jointid::output::study::{TrialsWriter, write_results};
use jointid::output::write_atomically;
use jointid::study::{CellResult, Study, StudyRun};

/// A finished study.
pub struct Finished {
    pub run: StudyRun,
    pub results: Vec<CellResult>,
    pub names: Vec<String>,
}

/// Reads, validates and runs every study of `args` in turn, handing each to `finished`.
pub fn run_studies(
    args: &StudyArgs,
    mut finished: impl FnMut(&Finished) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    if args.studies.len() > 1 && (args.out.is_some() || args.trials_csv.is_some()) {
        bail!(
            "--out and --trials-csv take one study file, not {}",
            args.studies.len()
        );
    }
    for path in &args.studies {
        finished(&run_study(path, args)?)?;
    }
    Ok(())
}

/// Reads, validates and runs one study, writing its outputs.
fn run_study(path: &Path, args: &StudyArgs) -> anyhow::Result<Finished> {
    let study = Study::from_path(path)?;
    let run = StudyRun::new(study)?;
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(args.threads.unwrap_or(0))
        .build()
        .context("cannot start the worker threads")?;
    let names: Vec<String> = run.context.params.iter().map(|p| p.name.clone()).collect();
    let bar = progress_bar(run.trial_count(), args.quiet);
    let done = AtomicU64::new(0);
    let progress = |count: u64| {
        let total = done.fetch_add(count, Ordering::Relaxed) + count;
        bar.set_position(total);
    };
    let results = match &args.trials_csv {
        None => run
            .cells
            .iter()
            .map(|cell| pool.install(|| run.run_cell(cell, &progress)).0)
            .collect(),
        Some(path) => {
            let mut results = Vec::with_capacity(run.cells.len());
            write_atomically(path, |w| {
                let mut trials = TrialsWriter::new(w)?;
                for cell in &run.cells {
                    let (result, samples) = pool.install(|| run.run_cell(cell, &progress));
                    trials.write_cell(cell.index, &run.study.modes, &names, &samples)?;
                    results.push(result);
                }
                trials.finish()
            })
            .with_context(|| format!("{}: cannot write the trials", path.display()))?;
            results
        }
    };
    bar.finish_and_clear();
    let out = args.out.as_deref().unwrap_or(&run.study.output_csv);
    write_output(out, &results, &names, &run)?;
    Ok(Finished {
        run,
        results,
        names,
    })
}

fn write_output(
    out: &Path,
    results: &[CellResult],
    names: &[String],
    run: &StudyRun,
) -> anyhow::Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the directory", dir.display()))?;
    }
    write_atomically(out, |w| write_results(w, results, names, run.study.noise))
        .with_context(|| format!("{}: cannot write the results", out.display()))
}

fn progress_bar(total: u64, quiet: bool) -> ProgressBar {
    if quiet || !std::io::stderr().is_terminal() {
        return ProgressBar::hidden();
    }
    let bar = ProgressBar::with_draw_target(Some(total), ProgressDrawTarget::stderr());
    bar.set_style(
        ProgressStyle::with_template(
            "{bar:40} {human_pos}/{human_len} trials  {per_sec}  ETA {eta}",
        )
        .expect("the template is valid"),
    );
    bar
}

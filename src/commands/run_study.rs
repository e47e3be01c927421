//! Running a study file cell by cell, shared by `study` and `check`: progress bar on stderr,
//! optional per-trial CSV, result CSV written whole or not at all.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::cli::StudyArgs;
use jointid::cluster::{ShardHeader, ShardSpec, fingerprint, study_assignment, write_shard};
use jointid::output::study::{TrialsWriter, write_results};
use jointid::output::write_atomically;
use jointid::study::{CellResult, Study, StudyRun};

/// A finished study (or shard of a study).
pub struct Finished {
    pub run: StudyRun,
    pub results: Vec<CellResult>,
    pub names: Vec<String>,
    /// The file written.
    pub out: PathBuf,
    /// The shard run, if any.
    pub shard: Option<ShardSpec>,
}

/// The tool's version as the fingerprint records it.
pub fn tool_version() -> String {
    format!("jointid {}", env!("CARGO_PKG_VERSION"))
}

/// The default shard file of `output_csv`: `NAME.shard-K-of-N.csv` beside it.
fn shard_path(output_csv: &Path, spec: ShardSpec) -> PathBuf {
    let stem = output_csv
        .file_stem()
        .map_or_else(|| "study".into(), |s| s.to_string_lossy().into_owned());
    output_csv.with_file_name(format!("{stem}.shard-{}-of-{}.csv", spec.index, spec.count))
}

/// Reads, validates and runs every study of `args` in turn, handing each to `finished`.
pub fn run_studies(
    args: &StudyArgs,
    mut finished: impl FnMut(&Finished) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    if args.studies.len() > 1
        && (args.out.is_some() || args.trials_csv.is_some() || args.shard.is_some())
    {
        bail!(
            "--out, --trials-csv and --shard take one study file, not {}",
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
    // The cells to run: all, or those the balanced assignment gives to the shard.
    let assignment = args
        .shard
        .map(|spec| study_assignment(&run.study, &run.cells, spec.count));
    let cells: Vec<&jointid::study::Cell> = match (&assignment, args.shard) {
        (Some(a), Some(spec)) => run
            .cells
            .iter()
            .filter(|c| a[c.index] == spec.index)
            .collect(),
        _ => run.cells.iter().collect(),
    };
    let bar = progress_bar((cells.len() * run.study.trials) as u64, args.quiet);
    let done = AtomicU64::new(0);
    let progress = |count: u64| {
        let total = done.fetch_add(count, Ordering::Relaxed) + count;
        bar.set_position(total);
    };
    let results = match &args.trials_csv {
        None => cells
            .iter()
            .map(|cell| pool.install(|| run.run_cell(cell, &progress)).0)
            .collect(),
        Some(path) => {
            let mut results = Vec::with_capacity(cells.len());
            write_atomically(path, |w| {
                let mut trials = TrialsWriter::new(w)?;
                for cell in &cells {
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
    let out = match (&args.out, args.shard) {
        (Some(out), _) => out.clone(),
        (None, Some(spec)) => shard_path(&run.study.output_csv, spec),
        (None, None) => run.study.output_csv.clone(),
    };
    match (args.shard, assignment) {
        (Some(spec), Some(assignment)) => {
            let header = ShardHeader {
                spec,
                study: run.study.name.clone(),
                fingerprint: study_fingerprint(&run.study)?,
                tool: tool_version(),
                rows_per_cell: run.study.modes.len() * names.len(),
                assignment,
            };
            write_output(&out, |w| {
                write_shard(w, &header, &results, &names, run.study.noise)
            })?;
        }
        _ => write_output(&out, |w| {
            write_results(w, &results, &names, run.study.noise)
        })?,
    }
    Ok(Finished {
        run,
        results,
        names,
        out,
        shard: args.shard,
    })
}

/// The fingerprint of a study: this tool's version, the study file and its model file.
pub fn study_fingerprint(study: &Study) -> anyhow::Result<String> {
    let read = |path: &Path| {
        std::fs::read(path).with_context(|| format!("{}: cannot read", path.display()))
    };
    Ok(fingerprint(
        &tool_version(),
        &read(&study.file)?,
        &read(&study.model_file)?,
    ))
}

fn write_output(
    out: &Path,
    fill: impl FnOnce(&mut dyn std::io::Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    if let Some(dir) = out.parent().filter(|d| !d.as_os_str().is_empty()) {
        std::fs::create_dir_all(dir)
            .with_context(|| format!("{}: cannot create the directory", dir.display()))?;
    }
    write_atomically(out, fill)
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

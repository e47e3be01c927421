//! Running a study file cell by cell, shared by `study` and `check`: progress bar on stderr,
//! optional per-trial CSV, result CSV written whole or not at all.

use std::io::IsTerminal;
use std::path::{Path, PathBuf};
use std::sync::atomic::{AtomicU64, Ordering};

use anyhow::{Context, bail};
use indicatif::{ProgressBar, ProgressDrawTarget, ProgressStyle};

use crate::cli::StudyArgs;
use jointid::cluster::{ShardHeader, ShardSpec, study_assignment, write_shard};
use jointid::output::guard::model_inputs;
use jointid::output::study::TrialsWriter;
use jointid::output::{check_outputs, commit_all, stage};
use jointid::study::check;

use crate::commands::resources::check_memory;
use jointid::study::fingerprint::{study_fingerprint, tool_version};
use jointid::study::resources::peak_bytes;
use jointid::study::results::write_results;
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

/// The default shard file of `output_csv`: `NAME.shard-K-of-N.csv` beside it.
fn shard_path(output_csv: &Path, spec: ShardSpec) -> PathBuf {
    let stem = output_csv
        .file_stem()
        .map_or_else(|| "study".into(), |s| s.to_string_lossy().into_owned());
    output_csv.with_file_name(format!("{stem}.shard-{}-of-{}.csv", spec.index, spec.count))
}

/// Where the results of `study` go: `--out`, else the shard file, else `[output].csv`.
fn output_path(study: &Study, args: &StudyArgs) -> PathBuf {
    match (&args.run.out, args.shard) {
        (Some(out), _) => out.clone(),
        (None, Some(spec)) => shard_path(&study.output_csv, spec),
        (None, None) => study.output_csv.clone(),
    }
}

/// Reads and validates every study of `args` (with its `[check]` when `gate`), then runs
/// them in turn, handing each to `finished`. Nothing is computed or written before every
/// study and every output path has passed.
pub fn run_studies(
    args: &StudyArgs,
    gate: bool,
    mut finished: impl FnMut(&Finished) -> anyhow::Result<()>,
) -> anyhow::Result<()> {
    if args.run.studies.len() > 1
        && (args.run.out.is_some() || args.run.trials_csv.is_some() || args.shard.is_some())
    {
        bail!(
            "--out, --trials-csv and --shard take one study file, not {}",
            args.run.studies.len()
        );
    }
    let pool = worker_pool(args.run.threads)?;
    let runs = args
        .run
        .studies
        .iter()
        .map(|path| prepare(path, args, gate, pool.current_num_threads()))
        .collect::<anyhow::Result<Vec<StudyRun>>>()?;
    for run in runs {
        finished(&execute(run, args, &pool)?)?;
    }
    Ok(())
}

/// The most worker threads a run may ask for, per core.
const THREADS_PER_CORE: usize = 8;

fn worker_pool(threads: Option<usize>) -> anyhow::Result<rayon::ThreadPool> {
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let limit = THREADS_PER_CORE * cores;
    if let Some(t) = threads.filter(|t| !(1..=limit).contains(t)) {
        bail!(
            "--threads {t} is invalid: it must be from 1 to {limit} ({THREADS_PER_CORE} per core, {cores} core(s) here)"
        );
    }
    rayon::ThreadPoolBuilder::new()
        .num_threads(threads.unwrap_or(0))
        .build()
        .context("cannot start the worker threads")
}

/// Reads and validates one study: its cells, its gate when `gate`, its output paths.
fn prepare(path: &Path, args: &StudyArgs, gate: bool, threads: usize) -> anyhow::Result<StudyRun> {
    let study = Study::from_path(path)?;
    if let Some(spec) = args.shard {
        let cells = study.cells().len();
        if spec.count > cells {
            bail!(
                "--shard {spec} is invalid: {} has {cells} cell(s), so N must be from 1 to {cells}",
                study.file.display()
            );
        }
    }
    if gate {
        check::gate(&study)?;
    }
    let out = output_path(&study, args);
    let mut outputs = vec![out.as_path()];
    outputs.extend(args.run.trials_csv.as_deref());
    let mut inputs = model_inputs(&study.model_file);
    inputs.push(study.file.clone());
    inputs.extend(study.measured_noise.iter().map(|m| m.file.clone()));
    let inputs: Vec<&Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&outputs, &inputs)?;
    check_memory(
        peak_bytes(&study, threads),
        &format!(
            "{} (one cell of {} trials)",
            study.file.display(),
            study.trials
        ),
        "monte_carlo.trials, the number of grid modes, or the identified parameters (hold some with `fixed`)",
    )?;
    Ok(StudyRun::new(study)?)
}

/// Runs a validated study and writes its outputs together.
fn execute(run: StudyRun, args: &StudyArgs, pool: &rayon::ThreadPool) -> anyhow::Result<Finished> {
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
    let bar = progress_bar((cells.len() * run.study.trials) as u64, args.run.quiet);
    let done = AtomicU64::new(0);
    let progress = |count: u64| {
        let total = done.fetch_add(count, Ordering::Relaxed) + count;
        bar.set_position(total);
    };
    let (results, trials) = match &args.run.trials_csv {
        None => (
            cells
                .iter()
                .map(|cell| pool.install(|| run.run_cell(cell, &progress)).0)
                .collect(),
            None,
        ),
        Some(path) => {
            let mut results = Vec::with_capacity(cells.len());
            create_parent(path)?;
            let staged = stage(path, |w| {
                let mut trials = TrialsWriter::new(w)?;
                for cell in &cells {
                    let (result, samples) = pool.install(|| run.run_cell(cell, &progress));
                    trials.write_cell(cell.index, &run.study.modes, &names, &samples)?;
                    results.push(result);
                }
                trials.finish()
            })
            .with_context(|| format!("{}: cannot write the trials", path.display()))?;
            (results, Some(staged))
        }
    };
    bar.finish_and_clear();
    let out = output_path(&run.study, args);
    let header = match (args.shard, assignment) {
        (Some(spec), Some(assignment)) => Some(ShardHeader {
            spec,
            study: run.study.name.clone(),
            fingerprint: study_fingerprint(&run.study)?,
            tool: tool_version(),
            rows_per_cell: run.study.modes.len() * names.len(),
            assignment,
            modes: run.study.modes.clone(),
            params: names.clone(),
        }),
        _ => None,
    };
    create_parent(&out)?;
    let staged = stage(&out, |w| match &header {
        Some(header) => write_shard(w, header, &results, &names, run.study.noise_name()),
        None => write_results(w, &results, &names, run.study.noise_name()),
    })
    .with_context(|| format!("{}: cannot write the results", out.display()))?;
    commit_all(trials.into_iter().chain(std::iter::once(staged)).collect())?;
    Ok(Finished {
        run,
        results,
        names,
        out,
        shard: args.shard,
    })
}

/// Creates the directory of `out` when missing (registered: a failed or interrupted run
/// removes it again).
fn create_parent(out: &Path) -> anyhow::Result<()> {
    if let Some(dir) = out.parent() {
        jointid::output::atomic::create_folders(dir)
            .with_context(|| format!("{}: cannot create the directory", dir.display()))?;
    }
    Ok(())
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

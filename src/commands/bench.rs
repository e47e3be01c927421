//! `jointid bench`: trial-modes per second of the study engine on the paper cell (case I,
//! n 10, m 5, NF 5, inverse weighting, uniform 4% shape noise, modes 1-4), with 1 thread and
//! with every core, optionally beside the numpy baseline, runs interleaved so that both see
//! the same machine load. Medians of `--repeat` runs.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, bail};

use super::bench_limit::Limit;
use crate::cli::BenchArgs;
use jointid::study::{CellPlan, Study, StudyContext, simulate_cell};

/// The most timed runs per configuration.
const MAX_REPEAT: usize = 1000;

const MODEL: &str = include_str!("../../models/paper-case-1.toml");

fn paper_cell_study(trials: usize) -> anyhow::Result<Study> {
    let text = format!(
        r#"name = "bench"
model = "paper-case-1.toml"
[truth]
delta = {{ k1 = 2.0e6, k2 = 2.0e3 }}
[grid]
modes = [1, 2, 3, 4]
n = [10]
m = [5]
nf = [5]
weighting = ["inverse"]
shape_noise = [0.04]
frequency_noise = [0.0]
[monte_carlo]
trials = {trials}
seed = 1
noise = "uniform"
[output]
csv = "bench.csv"
"#
    );
    let model = jointid::model::from_toml(MODEL, Path::new("models/paper-case-1.toml"))?;
    Ok(Study::from_toml_with_model(
        &text,
        Path::new("bench.toml"),
        model,
        Path::new("models/paper-case-1.toml"),
    )?)
}

fn median(mut x: Vec<f64>) -> f64 {
    x.sort_by(f64::total_cmp);
    x[x.len() / 2]
}

pub fn run(args: &BenchArgs) -> anyhow::Result<()> {
    let max_trials = jointid::study::config::MAX_TRIALS as usize;
    if !(1..=max_trials).contains(&args.trials) {
        bail!(
            "--trials {} is invalid: it must be from 1 to {max_trials}",
            args.trials
        );
    }
    if !(1..=MAX_REPEAT).contains(&args.repeat) {
        bail!(
            "--repeat {} is invalid: it must be from 1 to {MAX_REPEAT}",
            args.repeat
        );
    }
    let study = paper_cell_study(args.trials)?;
    let context = StudyContext::new(&study)?;
    let cell = &study.cells()[0];
    let plan = CellPlan::new(&study, &context, cell).map_err(anyhow::Error::msg)?;
    let cores = std::thread::available_parallelism().map_or(1, |n| n.get());
    let pools: Vec<(usize, rayon::ThreadPool)> = [1, cores]
        .into_iter()
        .map(|t| {
            (
                t,
                rayon::ThreadPoolBuilder::new()
                    .num_threads(t)
                    .build()
                    .expect("thread pool"),
            )
        })
        .collect();
    let trial_modes = (args.trials * plan.modes.len()) as f64;
    let mut ours: Vec<Vec<f64>> = vec![Vec::new(); pools.len()];
    let mut numpy = Vec::new();
    let mut limits = Vec::new();
    // Warm-up, then interleaved timed runs.
    pools[0]
        .1
        .install(|| simulate_cell(&study, cell, &plan, &|_| {}));
    for _ in 0..args.repeat {
        for (k, (_, pool)) in pools.iter().enumerate() {
            let start = Instant::now();
            let samples = pool.install(|| simulate_cell(&study, cell, &plan, &|_| {}));
            ours[k].push(trial_modes / start.elapsed().as_secs_f64());
            std::hint::black_box(samples);
        }
        limits.push(
            pools[0]
                .1
                .install(|| Limit::measure(&plan, cell.n.0, args.trials)),
        );
        if let Some(script) = &args.numpy {
            numpy.push(run_numpy(script, args.trials)?);
        }
    }
    // Written through the checked stdout at the end: a closed or full stdout is an error
    // (exit 2), not a panic.
    let mut text = format!(
        "paper cell: case I, n 10, m 5, NF 5, inverse, uniform 4%, modes 1-4; {} trials per run, median of {}\n",
        args.trials, args.repeat
    );
    let mut single = 0.0;
    for ((threads, _), rates) in pools.iter().zip(ours) {
        let rate = median(rates);
        if *threads == 1 {
            single = rate;
        }
        text += &format!("jointid, {threads} thread(s): {rate:.3e} trial-modes/s\n");
    }
    if !numpy.is_empty() {
        text += &format!(
            "numpy baseline (batched):  {:.3e} trial-modes/s\n",
            median(numpy)
        );
    }
    let kernel_ns = 1e9 / single;
    let limit = Limit {
        draws_ns: median(limits.iter().map(|l| l.draws_ns).collect()),
        flops: limits[0].flops,
        flop_rate: median(limits.iter().map(|l| l.flop_rate).collect()),
    };
    text += &format!(
        "kernel, 1 thread: {kernel_ns:.1} ns per trial-mode; limit {:.1} ns = draws alone {:.1} ns + {} flops at {:.3e} flop/s (measured peak of independent mul and add, same runs); {:.1}x the limit\n",
        limit.ns(),
        limit.draws_ns,
        limit.flops,
        limit.flop_rate,
        kernel_ns / limit.ns()
    );
    super::to_stdout(|w| w.write_all(text.as_bytes()))
}

fn run_numpy(script: &Path, trials: usize) -> anyhow::Result<f64> {
    let out = Command::new("python3")
        .arg(script)
        .arg(trials.to_string())
        .env("OMP_NUM_THREADS", "1")
        .env("OPENBLAS_NUM_THREADS", "1")
        .output()
        .with_context(|| format!("cannot run python3 {}", script.display()))?;
    if !out.status.success() {
        bail!(
            "{} failed: {}",
            script.display(),
            String::from_utf8_lossy(&out.stderr)
        );
    }
    let text = String::from_utf8_lossy(&out.stdout);
    text.lines()
        .find_map(|l| {
            l.split_once(" trial-modes/s")
                .and_then(|(rate, _)| rate.trim().parse::<f64>().ok())
        })
        .with_context(|| {
            format!(
                "no `trial-modes/s` line in the output of {}:\n{text}",
                script.display()
            )
        })
}

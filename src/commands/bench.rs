//! `jointid bench`: trial-modes per second of the study engine on the paper cell (case I,
//! n 10, m 5, NF 5, inverse weighting, uniform 4% shape noise, modes 1-4), with 1 thread and
//! with every core, optionally beside the numpy baseline, runs interleaved so that both see
//! the same machine load. Medians of `--repeat` runs.

use std::path::Path;
use std::process::Command;
use std::time::Instant;

use anyhow::{Context, bail};

use crate::cli::BenchArgs;
use jointid::study::{CellPlan, Study, StudyContext, simulate_cell};

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
    if args.trials == 0 || args.repeat == 0 {
        bail!("--trials and --repeat must be at least 1");
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
        if let Some(script) = &args.numpy {
            numpy.push(run_numpy(script, args.trials)?);
        }
    }
    println!(
        "paper cell: case I, n 10, m 5, NF 5, inverse, uniform 4%, modes 1-4; {} trials per run, median of {}",
        args.trials, args.repeat
    );
    for ((threads, _), rates) in pools.iter().zip(ours) {
        println!(
            "jointid, {threads} thread(s): {:.3e} trial-modes/s",
            median(rates)
        );
    }
    if !numpy.is_empty() {
        println!(
            "numpy baseline (batched):  {:.3e} trial-modes/s",
            median(numpy)
        );
    }
    Ok(())
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

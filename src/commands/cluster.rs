//! `jointid cluster slurm`: the batch scripts of a sharded study.

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::cli::{ClusterCommand, SlurmArgs};
use crate::commands::flagged;
use jointid::cluster::{SlurmPlan, check_settings};
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, write_atomically};
use jointid::study::Study;

pub fn run(command: &ClusterCommand) -> anyhow::Result<()> {
    match command {
        ClusterCommand::Slurm(args) => slurm(args),
    }
}

fn absolute(path: &Path) -> anyhow::Result<PathBuf> {
    std::path::absolute(path).with_context(|| format!("{}: cannot resolve", path.display()))
}

fn slurm(args: &SlurmArgs) -> anyhow::Result<()> {
    let study = Study::from_path(&args.study)?;
    let cells = study.cells().len();
    check_settings(&study, args.shards, args.cpus_per_task).map_err(|e| {
        flagged(
            e,
            &[("shards", "--shards"), ("cpus_per_task", "--cpus-per-task")],
        )
    })?;
    let jointid = match &args.jointid {
        Some(p) => absolute(p)?,
        None => std::env::current_exe().context("cannot find this jointid binary")?,
    };
    let dir = absolute(
        &args
            .dir
            .clone()
            .unwrap_or_else(|| Path::new("slurm").join(&study.name)),
    )?;
    let plan = SlurmPlan {
        name: study.name.clone(),
        jointid,
        study: absolute(&args.study)?,
        out: absolute(args.out.as_deref().unwrap_or(&study.output_csv))?,
        dir,
        shards: args.shards,
        partition: args.partition.clone(),
        time: args.time.clone(),
        account: args.account.clone(),
        mem: args.mem.clone(),
        cpus_per_task: args.cpus_per_task,
        extra: args.extra.clone(),
    };
    let scripts = plan.scripts().map_err(|e| {
        flagged(
            e,
            &[
                ("partition", "--partition"),
                ("account", "--account"),
                ("time", "--time"),
                ("mem", "--mem"),
                ("sbatch", "--sbatch"),
                ("dir", "--dir"),
                ("out", "--out"),
                ("jointid", "--jointid"),
            ],
        )
    })?;
    // Nothing the run writes (scripts, shard files, the merged CSV) may be one of its
    // inputs: the study, its model, the files the model names.
    let mut outputs = vec![
        plan.array_path(),
        plan.merge_path(),
        plan.submit_path(),
        plan.out.clone(),
    ];
    outputs.extend((1..=plan.shards).map(|k| plan.shard_file(k)));
    let mut inputs = vec![plan.study.clone()];
    inputs.extend(model_inputs(&study.model_file));
    inputs.extend(study.measured_noise.iter().map(|m| m.file.clone()));
    let outputs: Vec<&Path> = outputs.iter().map(|p| p.as_path()).collect();
    let inputs: Vec<&Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&outputs, &inputs)?;
    jointid::output::atomic::create_folders(&plan.log_dir())
        .with_context(|| format!("{}: cannot create the directory", plan.log_dir().display()))?;
    if let Some(parent) = plan.out.parent() {
        jointid::output::atomic::create_folders(parent)
            .with_context(|| format!("{}: cannot create the directory", parent.display()))?;
    }
    for (path, text) in [
        (plan.array_path(), &scripts.array),
        (plan.merge_path(), &scripts.merge),
        (plan.submit_path(), &scripts.submit),
    ] {
        write_atomically(&path, |w| w.write_all(text.as_bytes()))
            .with_context(|| format!("{}: cannot write", path.display()))?;
    }
    super::to_stdout(|w| {
        writeln!(
            w,
            "{} shards of {} ({cells} cells): submit with\n  sh {}",
            args.shards,
            study.name,
            plan.submit_path().display()
        )
    })
}

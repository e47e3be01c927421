//! One file per command: each reads its inputs, calls the library and writes its outputs.

mod amplitude;
mod bench;
mod bench_limit;
mod calibrate;
mod check;
mod cluster;
mod diagnose;
mod export;
mod extract;
mod identify;
mod merge;
mod plan;
mod report;
mod resources;
mod run_study;
mod simulate;
mod solid;
mod study;

use std::io::Write;
use std::process::ExitCode;

use jointid::input::SettingError;

use crate::cli::{Cli, Command};

/// A setting the library refused, said as the command line takes it: named by its flag when
/// `flags` (library setting, flag) has one (`--n 39 is invalid: ...`), else as the library
/// names it.
fn flagged(e: SettingError, flags: &[(&str, &str)]) -> anyhow::Error {
    match flags.iter().find(|(setting, _)| *setting == e.setting) {
        Some((_, flag)) => anyhow::anyhow!(e.with_name(flag)),
        None => e.into(),
    }
}

/// Writes a command's output to stdout with `write` and flushes it. A stdout that cannot take
/// it (a full device, a closed pipe) is an error of the run like any other (exit 2), after
/// the run's files are committed; never a panic.
pub(crate) fn to_stdout(
    write: impl FnOnce(&mut dyn Write) -> std::io::Result<()>,
) -> anyhow::Result<()> {
    let mut out = std::io::stdout().lock();
    write(&mut out)
        .and_then(|()| out.flush())
        .map_err(|e| anyhow::anyhow!("stdout: cannot write: {e}"))
}

/// Reads and validates a model file. An external model's open faces (coincident DOFs that
/// nothing ties) are accepted and said once on stderr.
fn read_model(path: &std::path::Path) -> anyhow::Result<jointid::structure::Structure> {
    Ok(read_model_solved(path, &|_| 0)?.0)
}

/// [`read_model`], and an external model's lowest pairs, `elastic` of the structure beyond
/// its declared rigid-body modes at least, from the check of its rigid-body modes, with the
/// factor that solve made ([`jointid::model::from_path_solved`]).
fn read_model_solved(
    path: &std::path::Path,
    elastic: jointid::model::matrices::build::Elastic,
) -> anyhow::Result<(
    jointid::structure::Structure,
    Option<jointid::modal::ModalSolution>,
)> {
    let (model, nominal) = jointid::model::from_path_solved(path, elastic)?;
    if model.open_faces > 0 {
        eprintln!(
            "note: {}: {} pair(s) of coincident DOFs that nothing ties (open faces: a lap's notch, a crack) change no entry of K or M; a sensor on one is named by its label",
            path.display(),
            model.open_faces
        );
    }
    Ok((model, nominal))
}

/// [`read_model_solved`] for a command on the measured modes at `measured`: the pairs the
/// check of an external model's rigid-body modes solves are those `count` asks for on the
/// modes read on the model as read (rigid-body modes included), so that the command takes
/// them: one solve where there were two. When the modes cannot be read, or `count` has none,
/// the check solves its own few pairs, and the command says the error in its turn.
fn read_model_for(
    path: &std::path::Path,
    measured: &std::path::Path,
    count: impl Fn(&jointid::structure::Structure, &jointid::measured::MeasuredModes) -> Option<usize>,
) -> anyhow::Result<(
    jointid::structure::Structure,
    Option<jointid::modal::ModalSolution>,
)> {
    let elastic = |read: &jointid::structure::Structure| {
        jointid::measured::MeasuredModes::from_path(measured, read)
            .ok()
            .and_then(|modes| count(read, &modes))
            .map_or(0, |count| count.saturating_sub(read.rigid))
    };
    read_model_solved(path, &elastic)
}

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Identify(args) => identify::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Study(args) => study::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Plan(args) => plan::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Check(args) => check::run(&args),
        Command::Merge(args) => merge::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Cluster(command) => cluster::run(&command).map(|()| ExitCode::SUCCESS),
        Command::Simulate(args) => simulate::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Extract(args) => extract::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Calibrate(args) => calibrate::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Diagnose(args) => diagnose::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Report(args) => report::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Bench(args) => bench::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Export(args) => export::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Amplitude(args) => amplitude::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Solid(args) => solid::run(&args).map(|()| ExitCode::SUCCESS),
    }
}

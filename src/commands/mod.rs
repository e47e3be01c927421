//! One file per command: each reads its inputs, calls the library and writes its outputs.

mod bench;
mod check;
mod diagnose;
mod export;
mod extract;
mod identify;
mod report;
mod resources;
mod run_study;
mod simulate;
mod study;

use std::process::ExitCode;

use crate::cli::{Cli, Command};

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<ExitCode> {
    match cli.command {
        Command::Identify(args) => identify::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Study(args) => study::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Check(args) => check::run(&args),
        Command::Simulate(args) => simulate::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Extract(args) => extract::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Diagnose(args) => diagnose::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Report(args) => report::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Bench(args) => bench::run(&args).map(|()| ExitCode::SUCCESS),
        Command::Export(args) => export::run(&args).map(|()| ExitCode::SUCCESS),
    }
}

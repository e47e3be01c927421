//! One file per command: each reads its inputs, calls the library and writes its outputs.

mod identify;

use crate::cli::{Cli, Command};

/// Runs the parsed command.
pub fn run(cli: Cli) -> anyhow::Result<()> {
    match cli.command {
        Command::Identify(args) => identify::run(&args),
    }
}

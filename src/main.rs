//! The `jointid` binary: parses arguments, runs the command, prints the error chain.
//! Exit codes: 0 success, 1 a failed check (`jointid check`), 2 an error.

mod cli;
mod commands;

use std::process::ExitCode;

use clap::Parser;

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    match commands::run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

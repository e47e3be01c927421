//! The `jointid` binary: parses arguments, runs the command, prints the error chain.
//! Exit codes: 0 success, 1 a failed check (`jointid check`), 2 an error; 130 / 143 when
//! interrupted by SIGINT / SIGTERM, after removing every temporary file of the run.

mod cli;
mod commands;

use std::process::ExitCode;

use clap::Parser;
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// On SIGINT or SIGTERM: remove the run's temporaries and end with 128 + the signal.
fn clean_up_on_signals() {
    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            jointid::output::atomic::remove_temporaries();
            std::process::exit(128 + signal);
        }
    });
}

fn main() -> ExitCode {
    let cli = cli::Cli::parse();
    clean_up_on_signals();
    match commands::run(cli) {
        Ok(code) => code,
        Err(e) => {
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

//! The `jointid` binary: parses arguments, runs the command, prints the error chain.
//! Exit codes: 0 success, 1 a failed check (`jointid check`), 2 an error; 130 / 143 when
//! interrupted by SIGINT / SIGTERM. On a signal or an error every temporary of the run and
//! every folder it created (and left empty) is removed first.

mod cli;
mod commands;

use std::process::ExitCode;

use clap::Parser;
use signal_hook::consts::{SIGINT, SIGTERM};
use signal_hook::iterator::Signals;

/// On SIGINT or SIGTERM: remove the run's temporaries and end with 128 + the signal. Installed
/// before anything else, so before any output path exists.
fn clean_up_on_signals() {
    let Ok(mut signals) = Signals::new([SIGINT, SIGTERM]) else {
        return;
    };
    std::thread::spawn(move || {
        if let Some(signal) = signals.forever().next() {
            jointid::output::atomic::remove_temporaries_and_exit(128 + signal);
        }
    });
}

fn main() -> ExitCode {
    clean_up_on_signals();
    let cli = cli::Cli::parse();
    match commands::run(cli) {
        Ok(code) => code,
        Err(e) => {
            jointid::output::atomic::remove_temporaries();
            eprintln!("error: {e:#}");
            ExitCode::from(2)
        }
    }
}

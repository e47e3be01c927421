//! `jointid check`: run studies and hold each one's estimator bias to its `[check]`.

use std::io::Write;
use std::process::ExitCode;

use anyhow::bail;

use crate::cli::StudyArgs;
use crate::commands::run_study::{Finished, run_studies};
use jointid::study::check::evaluate;

/// Exit 1 when any study fails its gate; every study is run and reported.
pub fn run(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    let mut failed = false;
    run_studies(args, true, |finished| {
        failed |= !check_one(finished)?;
        Ok(())
    })?;
    Ok(if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Holds one finished study to its gate; `Ok(false)` when it fails.
fn check_one(finished: &Finished) -> anyhow::Result<bool> {
    let study = &finished.run.study;
    // Both were validated before the study ran (run_studies with its gate).
    let Some(spec) = &study.check else {
        bail!("{}: there is no [check] table", study.file.display());
    };
    let report = evaluate(spec, &finished.results, &finished.names);
    let mut out = std::io::stdout().lock();
    if report.failures.is_empty() {
        writeln!(
            out,
            "check passed: {} (cell, mode, parameter) rows within |relative bias| <= {} + 3 se ({})",
            report.checked, spec.max_abs_relative_bias, study.name
        )?;
        return Ok(true);
    }
    writeln!(
        out,
        "check FAILED: {} of {} rows exceed the bias threshold ({}):",
        report.failures.len(),
        report.checked,
        study.name
    )?;
    for f in &report.failures {
        writeln!(
            out,
            "  cell {} ({}), mode {}, {}: {}",
            f.cell.index,
            f.cell.describe(),
            f.mode,
            f.param,
            f.reason
        )?;
    }
    Ok(false)
}

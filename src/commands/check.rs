//! `jointid check`: run a study and hold its estimator bias to `[check]`.

use std::io::Write;
use std::process::ExitCode;

use anyhow::bail;

use crate::cli::StudyArgs;
use crate::commands::run_study::run_study;
use jointid::study::check::evaluate;

pub fn run(args: &StudyArgs) -> anyhow::Result<ExitCode> {
    let finished = run_study(args)?;
    let study = &finished.run.study;
    let Some(spec) = &study.check else {
        bail!(
            "{}: there is no [check] table: nothing to hold the study to",
            study.file.display()
        );
    };
    let report = evaluate(spec, &finished.results, &finished.names);
    if report.checked == 0 {
        bail!(
            "{}: [check].where selects no (cell, mode, parameter) of the grid",
            study.file.display()
        );
    }
    let mut out = std::io::stdout().lock();
    if report.failures.is_empty() {
        writeln!(
            out,
            "check passed: {} (cell, mode, parameter) rows within |relative bias| <= {} + 3 se",
            report.checked, spec.max_abs_relative_bias
        )?;
        return Ok(ExitCode::SUCCESS);
    }
    writeln!(
        out,
        "check FAILED: {} of {} rows exceed the bias threshold:",
        report.failures.len(),
        report.checked
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
    Ok(ExitCode::from(1))
}

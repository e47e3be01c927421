//! `jointid check`: run studies (or read a study's result CSV) and hold each one's estimator
//! bias to its `[check]`.

use std::io::Write;
use std::process::ExitCode;

use anyhow::bail;

use crate::cli::{CheckArgs, StudyArgs};
use crate::commands::run_study::run_studies;
use jointid::cluster::read_results_path;
use jointid::study::check::{evaluate, gate};
use jointid::study::{CellResult, Study};

/// Exit 1 when any study fails its gate; every study is run and reported.
pub fn run(args: &CheckArgs) -> anyhow::Result<ExitCode> {
    let failed = match &args.results {
        Some(path) => {
            let [file] = args.study.studies.as_slice() else {
                bail!(
                    "--results takes one study file, not {}",
                    args.study.studies.len()
                );
            };
            if args.study.out.is_some() || args.study.trials_csv.is_some() {
                bail!("--results reads a result: --out and --trials-csv have nothing to write");
            }
            let study = Study::from_path(file)?;
            gate(&study)?;
            let names = study.model.identified_names();
            let results = read_results_path(path, &study)?;
            !check_one(&study, &results, &names)?
        }
        None => {
            let mut failed = false;
            let whole = StudyArgs {
                run: args.study.clone(),
                shard: None,
            };
            run_studies(&whole, true, |finished| {
                failed |= !check_one(&finished.run.study, &finished.results, &finished.names)?;
                Ok(())
            })?;
            failed
        }
    };
    Ok(if failed {
        ExitCode::from(1)
    } else {
        ExitCode::SUCCESS
    })
}

/// Holds one study's results to its gate; `Ok(false)` when it fails.
fn check_one(study: &Study, results: &[CellResult], names: &[String]) -> anyhow::Result<bool> {
    // Both were validated before the study ran or was read.
    let Some(spec) = &study.check else {
        bail!("{}: there is no [check] table", study.file.display());
    };
    let report = evaluate(spec, results, names);
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

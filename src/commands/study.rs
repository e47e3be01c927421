//! `jointid study`: run a study, write its CSV, print the paper-layout summary.

use std::io::Write;

use crate::cli::StudyArgs;
use crate::commands::run_study::run_study;
use jointid::output::study::write_paper_table;

pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    let finished = run_study(args)?;
    let study = &finished.run.study;
    let stdout = std::io::stdout();
    let mut out = stdout.lock();
    writeln!(
        out,
        "{}: {} cell(s) x {} trial(s), {} noise; median [q05, q95] of each correction",
        study.name,
        finished.results.len(),
        study.trials,
        study.noise
    )?;
    write_paper_table(&mut out, &finished.results, &finished.names, &study.modes)?;
    writeln!(
        out,
        "results: {}",
        args.out.as_deref().unwrap_or(&study.output_csv).display()
    )?;
    Ok(())
}

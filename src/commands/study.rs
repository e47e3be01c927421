//! `jointid study`: run studies, write their CSVs, print the paper-layout summaries.

use std::io::Write;

use crate::cli::StudyArgs;
use crate::commands::run_study::run_studies;
use jointid::output::study::write_paper_table;

pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    run_studies(args, false, |finished| {
        let study = &finished.run.study;
        let mut out = std::io::stdout().lock();
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
            "results: {}\n",
            args.out.as_deref().unwrap_or(&study.output_csv).display()
        )?;
        Ok(())
    })
}

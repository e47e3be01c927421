//! `jointid study`: run studies, write their CSVs, print the paper-layout summaries.

use std::io::Write;

use crate::cli::StudyArgs;
use crate::commands::run_study::run_studies;
use jointid::output::study::{noise_description, write_paper_table};

pub fn run(args: &StudyArgs) -> anyhow::Result<()> {
    run_studies(args, false, |finished| {
        let study = &finished.run.study;
        let mut out = std::io::stdout().lock();
        let part = finished.shard.map_or_else(String::new, |s| {
            format!(
                " (shard {s}: {} of the {} cells)",
                finished.results.len(),
                finished.run.cells.len()
            )
        });
        writeln!(
            out,
            "{}{part}: {} cell(s) x {} trial(s), {}; median [q05, q95] of each correction",
            study.name,
            finished.results.len(),
            study.trials,
            noise_description(study)
        )?;
        write_paper_table(&mut out, &finished.results, &finished.names, &study.modes)?;
        writeln!(out, "results: {}\n", finished.out.display())?;
        Ok(())
    })
}

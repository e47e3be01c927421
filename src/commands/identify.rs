//! `jointid identify`: the paper's per-mode corrections for measured data.

use std::io::Write;

use anyhow::{Context, bail};

use crate::cli::IdentifyArgs;
use jointid::identify::{Identifier, Settings};
use jointid::measured::MeasuredModes;
use jointid::modal::ModalSolution;
use jointid::output::{identify as out, write_atomically};

pub fn run(args: &IdentifyArgs) -> anyhow::Result<()> {
    let model = jointid::model::from_path(&args.model)?;
    let measured = MeasuredModes::from_path(&args.measured, &model)?;
    let modal = ModalSolution::solve(&model.assemble())
        .with_context(|| format!("{}: modal solution", args.model.display()))?;
    let settings = Settings {
        n: args.n,
        m: args.m,
        weighting: args.weighting,
    };
    let identifier = Identifier::for_structure(&model, &modal, settings)?;
    let modes: Vec<usize> = match &args.modes {
        Some(list) => list.clone(),
        None => measured.modes().iter().map(|m| m.mode).collect(),
    };
    let mut outcomes = Vec::with_capacity(modes.len());
    for &r in &modes {
        let Some(mode) = measured.get(r) else {
            let have: Vec<String> = measured
                .modes()
                .iter()
                .map(|m| m.mode.to_string())
                .collect();
            bail!(
                "--modes asks for mode {r}, which {} does not hold (it has modes {})",
                args.measured.display(),
                have.join(",")
            );
        };
        outcomes.push(
            identifier
                .identify(mode)
                .with_context(|| format!("{}", args.measured.display()))?,
        );
    }
    for o in &outcomes {
        if let Err(rd) = &o.relative {
            eprintln!(
                "warning: mode {}: S_r has rank {} < q = {}: its corrections are left empty; retain more equations (--m) or measure more DOFs",
                o.mode,
                rd.rank,
                identifier.parameters().len()
            );
        }
    }
    let rows = out::rows(&outcomes, identifier.parameters());
    match &args.out {
        Some(path) => write_atomically(path, |w| out::write_csv(w, &rows))
            .with_context(|| format!("{}: cannot write", path.display()))?,
        None => {
            let stdout = std::io::stdout();
            let mut lock = stdout.lock();
            out::write_text(&mut lock, &rows)?;
            lock.flush()?;
        }
    }
    Ok(())
}

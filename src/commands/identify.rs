//! `jointid identify`: the paper's per-mode corrections for measured data.

use std::io::Write;

use anyhow::{Context, bail};

use crate::cli::IdentifyArgs;
use crate::commands::flagged;
use jointid::identify::{Identifier, Selection, Settings};
use jointid::measured::MeasuredModes;
use jointid::modal::{ModalSolution, check_elastic};
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, identify as out, write_atomically};

pub fn run(args: &IdentifyArgs) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = args.out.iter().map(|p| p.as_path()).collect();
    let mut inputs = model_inputs(&args.model);
    inputs.push(args.measured.clone());
    let inputs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&outputs, &inputs)?;
    let model = jointid::model::from_path(&args.model)?;
    let measured = MeasuredModes::from_path(&args.measured, &model)?;
    let matrices = model.assemble();
    let settings = Settings::new(args.n, args.m, args.weighting, &model)
        .map_err(|e| flagged(e, &[("n", "--n")]))?;
    let modal = ModalSolution::lowest_of(&matrices, args.n)
        .with_context(|| format!("{}: modal solution", args.model.display()))?;
    check_elastic(&matrices, &modal, model.rigid)
        .with_context(|| format!("{}", args.model.display()))?;
    let all = model.identified();
    let (params, selection) = match args.params.as_deref() {
        None => (all, Selection::All),
        Some([auto]) if auto == "auto" => (all, Selection::Auto),
        Some(names) => {
            let mut chosen = Vec::with_capacity(names.len());
            for name in names {
                let Some(p) = all.iter().find(|p| &p.name == name) else {
                    let known: Vec<&str> = all.iter().map(|p| p.name.as_str()).collect();
                    bail!(
                        "--params {name} is invalid: the model identifies {} (or give `auto`)",
                        known.join(", ")
                    );
                };
                if chosen
                    .iter()
                    .any(|c: &jointid::structure::Parameter| &c.name == name)
                {
                    bail!("--params lists {name} twice");
                }
                chosen.push(p.clone());
            }
            (chosen, Selection::All)
        }
    };
    let identifier = Identifier::new(&modal, params, model.rigid, settings)?;
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
                .identify_selected(mode, identifier.basis_index(mode.mode)?, selection)
                .with_context(|| format!("{}", args.measured.display()))?,
        );
    }
    if measured.has_std() {
        eprintln!(
            "noise: the data's own standard errors (frequency_std, value_std) weigh the projections and give the corrections' standard deviations"
        );
    }
    out::write_notes(
        &mut std::io::stderr().lock(),
        &outcomes,
        identifier.parameters(),
    )?;
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

//! `jointid identify`: the paper's per-mode corrections for measured data, and one parameter
//! per mode from its frequency alone where a mode's shape cannot carry the paper's system.

use anyhow::{Context, bail};

use crate::cli::IdentifyArgs;
use crate::commands::flagged;
use rayon::prelude::*;

use jointid::identify::frequency_only::{self, Choice, Fallback, FrequencyError, FrequencyOutcome};
use jointid::identify::{Identifier, IdentifyError, ModeOutcome, Selection, Settings};
use jointid::input::{Number, RELATIVE_STD};
use jointid::measured::{MeasuredMode, MeasuredModes};
use jointid::modal::{ModalSolution, check_elastic};
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, identify as out, write_atomically};
use jointid::structure::{Parameter, Structure};

pub fn run(args: &IdentifyArgs) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = args.out.iter().map(|p| p.as_path()).collect();
    let mut inputs = model_inputs(&args.model);
    inputs.push(args.measured.clone());
    let inputs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&outputs, &inputs)?;
    if let Some(v) = args.frequency_noise
        && !(v.is_finite() && v >= RELATIVE_STD.0 && v < 1.0)
    {
        bail!(
            "--frequency-noise {} is invalid: a relative standard deviation from 1e-12 to below 1",
            Number(v)
        );
    }
    let model = super::read_model(&args.model)?;
    let measured = MeasuredModes::from_path(&args.measured, &model)?;
    let all = model.identified();
    if all.is_empty() {
        // before the eigensolution, and the same refusal with or without --from-frequency
        return Err(IdentifyError::NoParameters)
            .with_context(|| format!("{}", args.model.display()));
    }
    let (params, selection, choice) = chosen(args.params.as_deref(), &all)?;
    // The settings are checked before the eigensolution, which takes minutes on a large model.
    let settings = match (args.n, args.m, args.weighting) {
        (Some(n), Some(m), Some(weighting)) => {
            let s =
                Settings::new(n, m, weighting, &model).map_err(|e| flagged(e, &[("n", "--n")]))?;
            s.check_equations(params.len(), model.rigid)?;
            Some(s)
        }
        _ => None,
    };
    let modes = selected(args, &measured)?;
    // Each mode pairs by order with a model mode the model must have.
    for mode in &modes {
        model
            .model_mode(mode.mode)
            .with_context(|| format!("{}", args.measured.display()))?;
    }
    if let Some(s) = &settings {
        for mode in &modes {
            jointid::identify::basis_index(mode.mode, model.rigid, s.n)
                .with_context(|| format!("{}", args.measured.display()))?;
        }
    }
    let matrices = model.assemble();
    // the paper's basis of n pairs, or every pair the modes' frequencies pair with
    let reach = modes.iter().map(|m| m.mode + model.rigid).max();
    let count = args.n.or(reach).unwrap_or(model.rigid + 1);
    let modal = ModalSolution::lowest_of(&matrices, count)
        .with_context(|| format!("{}: modal solution", args.model.display()))?;
    check_elastic(&matrices, &modal, model.rigid)
        .with_context(|| format!("{}", args.model.display()))?;
    let identifier = settings
        .map(|settings| Identifier::new(&modal, params.clone(), model.rigid, settings))
        .transpose()?;
    let planned = planned(identifier.as_ref(), modes, selection, args)?;
    // A fallback solves the model about seven times (minutes on a solid of 2e5 DOFs): the
    // modes in parallel, each one's result the same as alone.
    let solved: Vec<Solved> = planned
        .into_par_iter()
        .map(|(mode, plan)| {
            let solved = plan.map_err(|why| {
                let f_std = mode
                    .frequency_std
                    .map(|s| s / mode.frequency_hz)
                    .or(args.frequency_noise);
                let f = model
                    .model_mode(mode.mode)
                    .map_err(FrequencyError::from)
                    .and_then(|t| {
                        frequency_only::identify(
                            &model,
                            t,
                            mode.mode,
                            mode.frequency_hz,
                            f_std,
                            choice,
                        )
                    });
                (why, f)
            });
            (mode, solved)
        })
        .collect();
    let Gathered {
        rows,
        outcomes,
        fallbacks,
    } = gathered(solved, args, &model, &modal, &params, &all)?;
    report(args, &measured, &outcomes, &fallbacks, &params, &all, &rows)
}

/// The CSV rows of every mode, with the outcomes of the paper's system and of the fallbacks.
struct Gathered {
    rows: Vec<out::IdentifyRow>,
    outcomes: Vec<ModeOutcome>,
    fallbacks: Vec<(FrequencyOutcome, Fallback)>,
}

/// Each mode's rows in mode order: its paper's outcome, else its frequency-only outcome, else
/// empty corrections with a warning; a modal solution that fails is an error.
fn gathered(
    solved: Vec<Solved>,
    args: &IdentifyArgs,
    model: &Structure,
    modal: &ModalSolution,
    params: &[Parameter],
    all: &[Parameter],
) -> anyhow::Result<Gathered> {
    let mut rows = Vec::new();
    let mut outcomes = Vec::new();
    let mut fallbacks = Vec::new();
    for (mode, solved) in solved {
        let (why, solved) = match solved {
            Ok(o) => {
                rows.extend(out::rows(std::slice::from_ref(&o), params));
                outcomes.push(o);
                continue;
            }
            Err(fallback) => fallback,
        };
        match solved {
            Ok(f) => {
                rows.extend(out::frequency_rows(&f, mode.frequency_hz, all));
                fallbacks.push((f, why));
            }
            Err(FrequencyError::Modal(e)) => {
                return Err(e).with_context(|| format!("{}: modal solution", args.model.display()));
            }
            Err(e) => {
                eprintln!("warning: {e}; its corrections are left empty");
                match why {
                    Fallback::RankDeficient(o) => {
                        rows.extend(out::rows(std::slice::from_ref(&o), params));
                        outcomes.push(o);
                    }
                    _ => {
                        rows.extend(out::unsolved_rows(
                            mode.mode,
                            mode.frequency_hz,
                            modal.frequency_hz(model.model_mode(mode.mode)?),
                            all,
                        ));
                    }
                }
            }
        }
    }
    Ok(Gathered {
        rows,
        outcomes,
        fallbacks,
    })
}

/// A mode and its paper's outcome, or why it fell back to its frequency and what that gave.
type Solved<'a> = (
    &'a MeasuredMode,
    Result<ModeOutcome, (Fallback, Result<FrequencyOutcome, FrequencyError>)>,
);

/// The paper's system on each mode's shape (`identifier`: None with --from-frequency), or why
/// the mode falls back to its frequency alone; an error where the projection cannot be made.
fn planned<'a>(
    identifier: Option<&Identifier>,
    modes: Vec<&'a MeasuredMode>,
    selection: Selection,
    args: &IdentifyArgs,
) -> anyhow::Result<Vec<(&'a MeasuredMode, Result<ModeOutcome, Fallback>)>> {
    let mut planned = Vec::new();
    for mode in modes {
        let shape = identifier
            .map(|id| id.identify_selected(mode, id.basis_index(mode.mode)?, selection))
            .transpose();
        let plan = match shape {
            Ok(Some(o)) if o.relative.is_ok() => Ok(o),
            Ok(Some(o)) => Err(Fallback::RankDeficient(o)),
            Ok(None) => Err(Fallback::Asked),
            Err(e @ IdentifyError::Projection { .. }) => {
                return Err(anyhow::anyhow!(
                    "{e}: lower --n to the shape components the modes have, or identify each mode's parameter from its frequency alone (--from-frequency)"
                ))
                .with_context(|| format!("{}", args.measured.display()));
            }
            Err(e) => return Err(e).with_context(|| format!("{}", args.measured.display())),
        };
        planned.push((mode, plan));
    }
    Ok(planned)
}

/// The notes on stderr, then the rows (CSV to --out, or a table).
fn report(
    args: &IdentifyArgs,
    measured: &MeasuredModes,
    outcomes: &[jointid::identify::ModeOutcome],
    fallbacks: &[(frequency_only::FrequencyOutcome, Fallback)],
    params: &[Parameter],
    all: &[Parameter],
    rows: &[out::IdentifyRow],
) -> anyhow::Result<()> {
    if measured.has_std() {
        eprintln!(
            "noise: the data's own standard errors (frequency_std, value_std) weigh the projections and give the corrections' standard deviations"
        );
    }
    let mut err = std::io::stderr().lock();
    out::write_notes(&mut err, outcomes, params)?;
    out::write_frequency_notes(&mut err, fallbacks, all)?;
    match &args.out {
        Some(path) => write_atomically(path, |w| out::write_csv(w, rows))
            .with_context(|| format!("{}: cannot write", path.display()))?,
        None => super::to_stdout(|w| out::write_text(w, rows))?,
    }
    Ok(())
}

/// The parameters of the paper's system (--params), its selection, and the parameter a mode's
/// frequency identifies (the one named when --params names one, else the most sensitive).
fn chosen(
    names: Option<&[String]>,
    all: &[Parameter],
) -> anyhow::Result<(Vec<Parameter>, Selection, Choice)> {
    let names = match names {
        None => return Ok((all.to_vec(), Selection::All, Choice::MostSensitive)),
        Some([auto]) if auto == "auto" => {
            return Ok((all.to_vec(), Selection::Auto, Choice::MostSensitive));
        }
        Some(names) if names.iter().any(|n| n == "auto") => bail!(
            "--params {} is invalid: `auto` chooses the parameters on each mode and is given alone, not with names",
            names.join(",")
        ),
        Some(names) => names,
    };
    let mut chosen: Vec<Parameter> = Vec::with_capacity(names.len());
    for name in names {
        let Some(p) = all.iter().find(|p| &p.name == name) else {
            let known: Vec<&str> = all.iter().map(|p| p.name.as_str()).collect();
            bail!(
                "--params {name} is invalid: the model identifies {} (or give `auto`)",
                known.join(", ")
            );
        };
        if chosen.iter().any(|c| &c.name == name) {
            bail!("--params lists {name} twice");
        }
        chosen.push(p.clone());
    }
    let choice = match chosen.as_slice() {
        [one] => Choice::Named(all.iter().position(|p| p.name == one.name).unwrap_or(0)),
        _ => Choice::MostSensitive,
    };
    Ok((chosen, Selection::All, choice))
}

/// The measured modes --modes asks for (every one by default).
fn selected<'a>(
    args: &IdentifyArgs,
    measured: &'a MeasuredModes,
) -> anyhow::Result<Vec<&'a MeasuredMode>> {
    let Some(list) = &args.modes else {
        return Ok(measured.modes().iter().collect());
    };
    if let Some(r) = list
        .iter()
        .enumerate()
        .find_map(|(i, r)| list[..i].contains(r).then_some(r))
    {
        bail!("--modes lists mode {r} twice");
    }
    list.iter()
        .map(|&r| {
            measured.get(r).ok_or_else(|| {
                let have: Vec<String> = measured
                    .modes()
                    .iter()
                    .map(|m| m.mode.to_string())
                    .collect();
                anyhow::anyhow!(
                    "--modes asks for mode {r}, which {} does not hold (it has modes {})",
                    args.measured.display(),
                    have.join(",")
                )
            })
        })
        .collect()
}

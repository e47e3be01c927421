//! `jointid identify`: the paper's per-mode corrections for measured data, and one parameter
//! per mode from its frequency alone where a mode's shape cannot carry the paper's system.

use anyhow::Context;

use crate::cli::IdentifyArgs;
use crate::commands::flagged;

use jointid::identify::frequency_only::{self, Fallback};
use jointid::identify::run::{Request, RunError, identify_modes_solved, nominal_count};
use jointid::measured::MeasuredModes;
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, identify as out, write_atomically};
use jointid::structure::Parameter;

/// The library's settings by their flags.
const FLAGS: &[(&str, &str)] = &[
    ("n", "--n"),
    ("params", "--params"),
    ("modes", "--modes"),
    ("frequency_noise", "--frequency-noise"),
];

pub fn run(args: &IdentifyArgs) -> anyhow::Result<()> {
    let outputs: Vec<&std::path::Path> = args.out.iter().map(|p| p.as_path()).collect();
    let mut inputs = model_inputs(&args.model);
    inputs.push(args.measured.clone());
    let inputs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&outputs, &inputs)?;
    let request = Request {
        n: args.n,
        m: args.m,
        weighting: args.weighting,
        params: args.params.clone(),
        modes: args.modes.clone(),
        frequency_noise: args.frequency_noise,
    };
    let (model, nominal) = super::read_model_for(&args.model, &args.measured, |read, modes| {
        nominal_count(read, modes, &request)
    })?;
    let measured = MeasuredModes::from_path(&args.measured, &model)?;
    let identified = identify_modes_solved(&model, &measured, &request, nominal).map_err(|e| {
        let (model, measured) = (args.model.display(), args.measured.display());
        match e {
            RunError::Setting(e) => flagged(e, FLAGS),
            RunError::Projection(e) => anyhow::anyhow!(
                "{measured}: {e}: lower --n to the shape components the modes have, or identify each mode's parameter from its frequency alone (--from-frequency)"
            ),
            e @ RunError::Modal(_) => anyhow::anyhow!("{model}: {e}"),
            e @ (RunError::Model(_) | RunError::Mechanism(_)) => anyhow::anyhow!("{model}: {e}"),
            e @ (RunError::Beyond(_) | RunError::Measured(_)) => {
                anyhow::anyhow!("{measured}: {e}")
            }
        }
    })?;
    let gathered = out::gathered(&identified);
    for warning in &gathered.warnings {
        eprintln!("warning: {warning}");
    }
    report(
        args,
        &measured,
        &gathered.outcomes,
        &gathered.fallbacks,
        &identified.params,
        &identified.all,
        &gathered.rows,
    )
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

//! `jointid simulate`: measured modes of a model, with optional errors, as CSV.

use anyhow::{Context, bail};

use crate::cli::{Measure, SimulateArgs};
use crate::commands::flagged;
use jointid::input::SettingError;
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, write_atomically};
use jointid::simulate::{Errors, first_modes, measured_points, simulate_from};
use jointid::study::NoiseKind;

/// The library's settings by their flags.
const FLAGS: &[(&str, &str)] = &[
    ("modes", "--modes"),
    ("noise", "--noise"),
    ("shape_noise", "--shape-noise"),
    ("frequency_noise", "--frequency-noise"),
];

pub fn run(args: &SimulateArgs) -> anyhow::Result<()> {
    let inputs = model_inputs(&args.model);
    let inputs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&[&args.out], &inputs)?;
    let (model, nominal) = super::read_model_solved(&args.model, &|_| args.modes)?;
    // the pairs alone: the factor of their solve is not needed here
    let nominal = nominal.map(|mut n| {
        n.take_factor();
        n
    });
    let modes = first_modes(&model, args.modes).map_err(|e| flagged(e, FLAGS))?;
    let kind: NoiseKind = args.noise.parse().map_err(|allowed: String| {
        flagged(SettingError::new("noise", &args.noise, allowed), FLAGS)
    })?;
    let errors = Errors::new(args.shape_noise, args.frequency_noise, kind, args.seed)
        .map_err(|e| flagged(e, FLAGS))?;
    let measure = match args.measure {
        Measure::W => jointid::simulate::Measure::W,
        Measure::Theta => jointid::simulate::Measure::Theta,
        Measure::All => jointid::simulate::Measure::All,
        Measure::Sensors => jointid::simulate::Measure::Sensors,
    };
    let Some(points) = measured_points(&model, measure) else {
        bail!(
            "--measure sensors: {} declares no [[sensor]]",
            args.model.display()
        );
    };
    let measured = simulate_from(&model, nominal, &args.effects, &modes, &points, errors)?;
    write_atomically(&args.out, |w| {
        measured.write_csv(w, &model).map_err(std::io::Error::other)
    })
    .with_context(|| format!("{}: cannot write", args.out.display()))?;
    Ok(())
}

//! `jointid simulate`: measured modes of a model, with optional errors, as CSV.

use anyhow::{Context, bail};

use crate::cli::{Measure, SimulateArgs};
use jointid::output::write_atomically;
use jointid::simulate::{Errors, simulate};
use jointid::structure::Observation;
use jointid::study::NoiseKind;

pub fn run(args: &SimulateArgs) -> anyhow::Result<()> {
    let model = jointid::model::from_path(&args.model)?;
    let deformable = model.dof_count() - model.rigid;
    if args.modes == 0 || args.modes > deformable {
        bail!(
            "--modes {} is invalid: the model has deformable modes 1 to {deformable}",
            args.modes
        );
    }
    for (name, v) in [
        ("--shape-noise", args.shape_noise),
        ("--frequency-noise", args.frequency_noise),
    ] {
        if !(v.is_finite() && (0.0..1.0).contains(&v)) {
            bail!("{name} {v} is invalid: it must be a relative level from 0 to below 1");
        }
    }
    let kind: NoiseKind = args
        .noise
        .parse()
        .map_err(|e: String| anyhow::anyhow!("--noise {} is invalid: {e}", args.noise))?;
    let points: Vec<Observation> = match args.measure {
        Measure::Sensors if model.sensors.is_empty() => bail!(
            "--measure sensors: {} declares no [[sensor]]",
            args.model.display()
        ),
        Measure::Sensors => model.sensors.clone(),
        _ => (0..model.dof_count())
            .filter(|&d| {
                let rotation = model.dofs.get(d).direction.is_rotation();
                match args.measure {
                    Measure::W => !rotation,
                    Measure::Theta => rotation,
                    _ => true,
                }
            })
            .map(|d| Observation::dof(&model.dofs, d))
            .collect(),
    };
    let modes: Vec<usize> = (1..=args.modes).collect();
    let errors = Errors {
        shape: args.shape_noise,
        frequency: args.frequency_noise,
        kind,
        seed: args.seed,
    };
    let measured = simulate(&model, &args.effects, &modes, &points, errors)?;
    write_atomically(&args.out, |w| {
        measured.write_csv(w, &model).map_err(std::io::Error::other)
    })
    .with_context(|| format!("{}: cannot write", args.out.display()))
}

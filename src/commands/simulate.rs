//! `jointid simulate`: measured modes of a model, with optional errors, as CSV.

use anyhow::{Context, bail};

use crate::cli::{Measure, SimulateArgs};
use jointid::model::{Dof, Model, RIGID_BODY_MODES, dof_of_index};
use jointid::output::write_atomically;
use jointid::simulate::{Errors, simulate};
use jointid::study::NoiseKind;

pub fn run(args: &SimulateArgs) -> anyhow::Result<()> {
    let model = Model::from_path(&args.model)?;
    let deformable = model.dof_count() - RIGID_BODY_MODES;
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
    let dofs: Vec<usize> = (0..model.dof_count())
        .filter(|&d| match args.measure {
            Measure::W => dof_of_index(d).1 == Dof::W,
            Measure::Theta => dof_of_index(d).1 == Dof::Theta,
            Measure::All => true,
        })
        .collect();
    let modes: Vec<usize> = (1..=args.modes).collect();
    let errors = Errors {
        shape: args.shape_noise,
        frequency: args.frequency_noise,
        kind,
        seed: args.seed,
    };
    let measured = simulate(&model, &args.effects, &modes, &dofs, errors)?;
    write_atomically(&args.out, |w| {
        measured.write_csv(w).map_err(std::io::Error::other)
    })
    .with_context(|| format!("{}: cannot write", args.out.display()))
}

//! `jointid amplitude`: the amplitude dependence of every mode across the levels of a levels
//! file, as CSV tables and one figure per mode (and, with `--joint`, the joint's), all written
//! or none.

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::cli::AmplitudeArgs;
use jointid::amplitude::{Levels, fit_levels};
use jointid::output::amplitude as out;
use jointid::output::guard::model_inputs;
use jointid::output::{Staged, check_outputs, commit_all, stage};

/// The CSV tables and their writers.
type Table = (
    &'static str,
    fn(&mut dyn std::io::Write, &jointid::amplitude::AmplitudeFit) -> std::io::Result<()>,
);

const TABLES: [Table; 4] = [
    ("amplitude_levels.csv", out::write_levels),
    ("amplitude_laws.csv", out::write_laws),
    ("amplitude_parameters.csv", out::write_parameters),
    ("amplitude_bands.csv", out::write_bands),
];

/// The joint's tables, with `--joint`.
const JOINT_TABLES: [Table; 5] = [
    ("joint_levels.csv", out::write_joint_levels),
    ("joint_laws.csv", out::write_joint_laws),
    ("joint_parameters.csv", out::write_joint_parameters),
    ("joint_bands.csv", out::write_joint_bands),
    ("joint_errors.csv", out::write_joint_errors),
];

pub fn run(args: &AmplitudeArgs) -> anyhow::Result<()> {
    let levels = Levels::from_path(&args.levels)?;
    let fit = fit_levels(&levels, args.joint.as_deref())?;
    let mut figures: Vec<(PathBuf, String)> = Vec::new();
    for m in &fit.modes {
        let name = format!("amplitude_mode{}.svg", m.data.mode);
        figures.push((args.out.join(name), out::figure(m)?));
        if let Some(svg) = out::joint_figure(m) {
            let name = format!("joint_mode{}.svg", m.data.mode);
            figures.push((args.out.join(name), svg?));
        }
    }
    let chosen: Vec<&Table> = if args.joint.is_some() {
        TABLES.iter().chain(&JOINT_TABLES).collect()
    } else {
        TABLES.iter().collect()
    };
    let tables: Vec<PathBuf> = chosen.iter().map(|(n, _)| args.out.join(n)).collect();
    let outputs: Vec<&Path> = tables
        .iter()
        .chain(figures.iter().map(|(p, _)| p))
        .map(|p| p.as_path())
        .collect();
    let mut inputs = model_inputs(&levels.model);
    inputs.extend(levels.inputs());
    let inputs: Vec<&Path> = inputs.iter().map(|p| p.as_path()).collect();
    check_outputs(&outputs, &inputs)?;
    jointid::output::atomic::create_folders(&args.out)
        .with_context(|| format!("{}: cannot create the directory", args.out.display()))?;
    let mut staged: Vec<Staged> = Vec::new();
    for ((_, write), path) in chosen.iter().zip(&tables) {
        staged.push(
            stage(path, |w| write(w, &fit))
                .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    for (path, svg) in &figures {
        staged.push(
            stage(path, |w| w.write_all(svg.as_bytes()))
                .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    commit_all(staged)?;
    super::to_stdout(|w| w.write_all(out::summary(&fit).as_bytes()))
}

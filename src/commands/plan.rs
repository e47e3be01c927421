//! `jointid plan`: where to put the sensors before the test; the plan as JSON, the table and
//! the `[[sensor]]` entries on stdout, optionally the confirming study and the figure. Every
//! input is checked before anything is computed; the files are written together or not at all.

use std::path::{Path, PathBuf};

use anyhow::Context;

use crate::cli::PlanArgs;
use crate::commands::{flagged, to_stdout};
use jointid::identify::Settings;
use jointid::input::SettingError;
use jointid::output::guard::model_inputs;
use jointid::output::plan::{StudyFile, study_toml, write_json, write_sensor_entries, write_table};
use jointid::output::plan_figure::plan_svg;
use jointid::output::{check_outputs, commit_all, stage};
use jointid::plan::{Objective, PlanError, Request, SettingsChoice, Sites, plan, request};
use jointid::study::NoiseKind;

/// The library's settings by their flags.
const FLAGS: &[(&str, &str)] = &[
    ("sites", "--sites"),
    ("sensors", "--sensors"),
    ("modes", "--modes"),
    ("noise", "--noise"),
    ("shape_noise", "--shape-noise"),
    ("frequency_noise", "--frequency-noise"),
    ("fixed", "--fixed"),
    ("objective", "--objective"),
    ("n", "--n"),
    ("m", "--m"),
];

fn request(args: &PlanArgs) -> Result<Request, SettingError> {
    let settings = match (args.n, args.m, args.weighting) {
        (Some(n), Some(m), Some(weighting)) => SettingsChoice::Given(Settings { n, m, weighting }),
        _ => SettingsChoice::Chosen,
    };
    Ok(Request {
        sites: Sites::parse(&args.sites)?,
        counts: request::parse_counts(&args.sensors)?,
        modes: args.modes.clone(),
        frequency_noise: args.frequency_noise,
        shape_noise: args.shape_noise,
        noise: args
            .noise
            .parse::<NoiseKind>()
            .map_err(|allowed| SettingError::new("noise", &args.noise, allowed))?,
        fixed: args.fixed.clone(),
        objective: Objective::parse(&args.objective)?,
        settings,
    })
}

/// The study's results CSV beside it: same stem.
fn study_csv(study: &Path) -> PathBuf {
    study.with_extension("csv")
}

pub fn run(args: &PlanArgs) -> anyhow::Result<()> {
    let inputs = model_inputs(&args.model);
    let inputs: Vec<&Path> = inputs.iter().map(|p| p.as_path()).collect();
    let csv = args.study.as_deref().map(study_csv);
    let mut outputs: Vec<&Path> = vec![&args.out];
    outputs.extend(args.study.as_deref());
    outputs.extend(csv.as_deref());
    outputs.extend(args.figure.as_deref());
    check_outputs(&outputs, &inputs)?;
    let req = request(args).map_err(|e| flagged(e, FLAGS))?;
    let model = super::read_model(&args.model)?;
    let plan = plan(&model, &req).map_err(|e| match e {
        PlanError::Setting(s) => flagged(s, FLAGS),
        other => other.into(),
    })?;
    let mut staged = Vec::new();
    let mut grids = Vec::new();
    if let Some(path) = &args.study {
        let model_path = std::fs::canonicalize(&args.model)
            .with_context(|| format!("{}: cannot resolve", args.model.display()))?;
        let labels: Vec<String> = model.dofs.dofs().iter().map(|d| d.label.clone()).collect();
        let name = study_name(path);
        let csv_name = study_csv(path);
        let csv_name = csv_name
            .file_name()
            .map(|n| n.to_string_lossy().into_owned())
            .unwrap_or_default();
        let (text, written) = study_toml(
            &plan,
            &StudyFile {
                name: &name,
                model: &model_path,
                labels: &labels,
                noise: req.noise.name(),
                shape_noise: req.shape_noise,
                frequency_noise: req.frequency_noise,
                trials: args.trials,
                seed: args.seed,
                csv: &csv_name,
            },
        );
        if written.is_empty() {
            anyhow::bail!(
                "--study {}: no layout determines every mode, so no study can confirm one: add sensors (the table says how many)",
                path.display()
            );
        }
        grids = written;
        staged.push(stage(path, |w| w.write_all(text.as_bytes()))?);
    }
    if let Some(path) = &args.figure {
        let svg = plan_svg(&plan)?;
        staged.push(stage(path, |w| w.write_all(svg.as_bytes()))?);
    }
    staged.push(stage(&args.out, |w| write_json(w, &plan, &grids))?);
    commit_all(staged)?;
    to_stdout(|out| {
        write_table(out, &plan)?;
        for count in &plan.counts {
            let chosen = &count.layouts[0];
            writeln!(
                out,
                "\n# the chosen {} sensors, to paste into the model:",
                count.sensors
            )?;
            write_sensor_entries(out, &plan, &chosen.sites)?;
        }
        writeln!(out, "plan: {}", args.out.display())?;
        if let Some(path) = &args.study {
            writeln!(
                out,
                "confirm by Monte-Carlo: jointid study {}",
                path.display()
            )?;
        }
        Ok(())
    })
}

/// The study's name from its file: the stem, with every character a plain file name does
/// not allow replaced by `-`.
fn study_name(path: &Path) -> String {
    let stem = path
        .file_stem()
        .map_or_else(|| "plan".into(), |s| s.to_string_lossy().into_owned());
    stem.chars()
        .map(|c| {
            if c.is_ascii_alphanumeric() || "._-".contains(c) {
                c
            } else {
                '-'
            }
        })
        .collect()
}

//! `jointid diagnose`: calibrate, trace the residual to a missing effect, report.

use anyhow::{Context, bail};

use crate::cli::DiagnoseArgs;
use jointid::diagnose::{DiagnoseSettings, Noise, PairingRule, diagnose};
use jointid::identify::Settings;
use jointid::measured::MeasuredModes;
use jointid::output::diagnose_plots::diagnose_figures;
use jointid::output::{check_outputs, commit_all, diagnose as out, stage};

use crate::commands::report::stage_figures;

pub fn run(args: &DiagnoseArgs) -> anyhow::Result<()> {
    for (name, v) in [
        ("--frequency-noise", args.frequency_noise),
        ("--shape-noise", args.shape_noise),
    ] {
        if !(v.is_finite() && v > 0.0 && v < 1.0) {
            bail!(
                "{name} {v} is invalid: the stated noise is a relative standard deviation, above 0 and below 1"
            );
        }
    }
    let inputs = [args.model.as_path(), args.measured.as_path()];
    let mut outputs: Vec<&std::path::Path> = args.json.iter().map(|p| p.as_path()).collect();
    let index = args.plots.as_ref().map(|dir| dir.join("index.html"));
    outputs.extend(index.as_deref());
    check_outputs(&outputs, &inputs)?;
    let model = jointid::model::from_path(&args.model)?;
    let measured = MeasuredModes::from_path(&args.measured, &model)?;
    let per_mode = match (args.n, args.m) {
        (None, None) => None,
        (Some(n), Some(m)) => Some(Settings {
            n,
            m,
            weighting: args.weighting,
        }),
        _ => bail!("--n and --m go together (or leave both out for the defaults)"),
    };
    if !(args.pairing_window.is_finite()
        && args.pairing_window > 0.0
        && args.pairing_window <= 10.0)
    {
        bail!(
            "--pairing-window {} is invalid: it is a relative half-width above 0 and at most 10",
            args.pairing_window
        );
    }
    let settings = DiagnoseSettings {
        noise: Noise {
            frequency: args.frequency_noise,
            shape: args.shape_noise,
        },
        pairing: PairingRule {
            window: args.pairing_window,
            given: args.pair.clone(),
        },
        per_mode,
        extended: args.extended,
    };
    let report = diagnose(&model, &measured, settings)
        .with_context(|| format!("{}", args.measured.display()))?;
    let mut staged = Vec::new();
    if let Some(path) = &args.json {
        staged.push(
            stage(path, |w| {
                serde_json::to_writer_pretty(&mut *w, &report).map_err(std::io::Error::other)
            })
            .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    if let Some(dir) = &args.plots {
        let figures = diagnose_figures(&report, &measured)?;
        let title = format!(
            "Diagnosis of {}: verdict {}",
            args.measured.display(),
            match report.verdict {
                jointid::diagnose::Verdict::None => "none".to_string(),
                jointid::diagnose::Verdict::Effect => report.selected.clone().unwrap_or_default(),
                jointid::diagnose::Verdict::Ambiguous =>
                    format!("ambiguous ({})", report.contenders.join(", ")),
                jointid::diagnose::Verdict::Unexplained => "unexplained".to_string(),
                jointid::diagnose::Verdict::FrequencyDependent => "frequency-dependent".to_string(),
            }
        );
        staged.extend(stage_figures(dir, &title, &figures, &inputs)?);
    }
    commit_all(staged)?;
    out::write_text(&mut std::io::stdout().lock(), &report)?;
    Ok(())
}

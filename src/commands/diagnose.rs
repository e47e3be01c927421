//! `jointid diagnose`: calibrate, trace the residual to a missing effect, report.

use anyhow::{Context, bail};

use crate::cli::DiagnoseArgs;
use jointid::diagnose::{DiagnoseSettings, Noise, PairingRule, diagnose};
use jointid::identify::Settings;
use jointid::measured::MeasuredModes;
use jointid::output::diagnose_page::diagnose_page;
use jointid::output::diagnose_plots::diagnose_figures;
use jointid::output::guard::model_inputs;
use jointid::output::{check_outputs, commit_all, diagnose as out, stage};

use crate::commands::flagged;
use crate::commands::report::stage_page;

pub fn run(args: &DiagnoseArgs) -> anyhow::Result<()> {
    let per_mode = match (args.n, args.m) {
        (None, None) => None,
        (Some(n), Some(m)) => Some(Settings {
            n,
            m,
            weighting: args.weighting,
        }),
        _ => bail!("--n and --m go together (or leave both out for the defaults)"),
    };
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
    settings.check().map_err(|e| {
        flagged(
            e,
            &[
                ("frequency_noise", "--frequency-noise"),
                ("shape_noise", "--shape-noise"),
                ("pairing_window", "--pairing-window"),
            ],
        )
    })?;
    let mut inputs = model_inputs(&args.model);
    inputs.push(args.measured.clone());
    let inputs: Vec<&std::path::Path> = inputs.iter().map(|p| p.as_path()).collect();
    let mut outputs: Vec<&std::path::Path> = args.json.iter().map(|p| p.as_path()).collect();
    let index = args.plots.as_ref().map(|dir| dir.join("index.html"));
    outputs.extend(index.as_deref());
    check_outputs(&outputs, &inputs)?;
    let model = jointid::model::from_path(&args.model)?;
    let measured = MeasuredModes::from_path(&args.measured, &model)?;
    let measured = if args.stated_noise {
        measured.without_std()
    } else {
        measured
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
            out::verdict_text(&report, false)
        );
        let page = diagnose_page(&title, &report, &figures);
        staged.extend(stage_page(dir, &figures, &page, &inputs)?);
    }
    commit_all(staged)?;
    out::write_text(&mut std::io::stdout().lock(), &report)?;
    Ok(())
}

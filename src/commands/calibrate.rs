//! `jointid calibrate`: the beams of a model adjusted on a reference test, written as a
//! calibrated model file (and the calibration as JSON), nothing written on an error.

use anyhow::Context;

use crate::cli::CalibrateArgs;
use crate::commands::flagged;
use jointid::calibrate::adjusted::adjusted_model;
use jointid::calibrate::{
    CalibrateError, Request, Specimen, calibrate, parse_fits, specimen_chain,
};
use jointid::diagnose::DiagnoseSettings;
use jointid::input::read_file;
use jointid::measured::MeasuredModes;
use jointid::output::{calibrate as out, check_outputs, commit_all, stage};

/// The settings calibrate shares with diagnose, and their flags.
const FLAGS: [(&str, &str); 3] = [
    ("frequency_noise", "--frequency-noise"),
    ("shape_noise", "--shape-noise"),
    ("pairing_window", "--pairing-window"),
];

pub fn run(args: &CalibrateArgs) -> anyhow::Result<()> {
    let noise = args.error.noise();
    let pairing = args.error.pairing(Vec::new());
    // The noise and the window mean what they mean to diagnose, checked as it checks them.
    DiagnoseSettings {
        noise,
        pairing: pairing.clone(),
        per_mode: None,
        extended: false,
        full_model: false,
        causes: Vec::new(),
    }
    .check()
    .map_err(|e| flagged(e, &FLAGS))?;
    let specimen: Specimen = args
        .specimen
        .parse()
        .map_err(|why| anyhow::anyhow!("--specimen {why}"))?;
    let fits = parse_fits(&args.fit).context("--fit")?;
    let mut outputs = vec![args.out.as_path()];
    outputs.extend(args.json.as_deref());
    check_outputs(&outputs, &[args.model.as_path(), args.reference.as_path()])?;
    let text = read_file(&args.model)?;
    let chain = jointid::model::chain_from_toml(&text, &args.model)?;
    let structure = specimen_chain(&chain, specimen)
        .with_context(|| format!("--specimen {specimen}"))?
        .build();
    let measured = args
        .error
        .weighed(MeasuredModes::from_path(&args.reference, &structure)?);
    let reference = args
        .reference
        .file_name()
        .map_or_else(String::new, |n| n.to_string_lossy().into_owned());
    let request = Request {
        specimen,
        fits,
        noise,
        pairing,
        measured_std: measured.has_std(),
        reference,
    };
    let calibrated = calibrate(&chain, &measured, &request).map_err(|e| match e {
        CalibrateError::OnlyTheRatio => anyhow::anyhow!("--fit {}: {e}", args.fit.join(",")),
        e => anyhow::Error::new(e).context(format!("{}", args.reference.display())),
    })?;
    let header = format!(
        "{} with its beams calibrated by jointid calibrate on {} ({}).",
        args.model.display(),
        args.reference.display(),
        specimen
    );
    let adjusted = adjusted_model(&text, &calibrated.records, &chain.calibration, &header)
        .with_context(|| format!("{}", args.model.display()))?;
    // The file written must read back as the model it claims to be.
    jointid::model::chain_from_toml(&adjusted, &args.out)
        .context("the calibrated model does not read back")?;
    let mut staged = vec![
        stage(&args.out, |w| w.write_all(adjusted.as_bytes()))
            .with_context(|| format!("{}: cannot write", args.out.display()))?,
    ];
    if let Some(path) = &args.json {
        staged.push(
            stage(path, |w| {
                serde_json::to_writer_pretty(&mut *w, &calibrated).map_err(std::io::Error::other)
            })
            .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    commit_all(staged)?;
    super::to_stdout(|w| out::write_text(w, &calibrated))
}

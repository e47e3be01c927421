//! `jointid extract`: FRFs in universal files to a measured-modes CSV (and a stabilisation
//! chart). Every input is read and checked, and the extraction done, before anything is
//! written; the files are written whole or not at all.

use std::path::PathBuf;

use anyhow::Context;

use crate::cli::{ExtractArgs, FrfQuantity};
use crate::commands::flagged;
use jointid::extract::report::Report;
use jointid::extract::{
    BandSource, EdgeNote, ExtractError, Extraction, FrfSet, NoiseSource, Quantity, Settings, csv,
    extract, universal,
};
use jointid::input::Number;
use jointid::output::stabilization::{ChartUnits, stabilization_svg};
use jointid::output::{check_outputs, commit_all, stage};

use jointid::uff::{FunctionType, Record, read_path};

/// The FRFs of `args.frf` with their chart's units, and the coordinates of their response
/// points from `args.geometry`.
fn read_inputs(
    args: &ExtractArgs,
    say: &dyn Fn(String),
) -> anyhow::Result<(universal::UffFrfs, ChartUnits, Vec<[f64; 3]>)> {
    let mut files: Vec<(PathBuf, Vec<Record>)> = Vec::new();
    for path in &args.frf {
        say(format!("reading {}", path.display()));
        files.push((path.clone(), read_path(path)?));
    }
    let quantity = args.quantity.map(|q| match q {
        FrfQuantity::Displacement => Quantity::Displacement,
        FrfQuantity::Velocity => Quantity::Velocity,
        FrfQuantity::Acceleration => Quantity::Acceleration,
    });
    let responses = if args.space {
        universal::Responses::Space
    } else {
        universal::Responses::Bending
    };
    let input = universal::frfs_of(&files, quantity, responses)?;
    let units = chart_units(&files, input.set.quantity);
    drop(files);
    let geometry: Vec<_> = read_path(&args.geometry)?
        .into_iter()
        .filter_map(|r| match r {
            Record::Nodes(n) => Some(n),
            _ => None,
        })
        .collect();
    let xyz = universal::coordinates(&input.channels, &geometry, &args.geometry)?;
    Ok((input, units, xyz))
}

/// The modes CSV, the report and the chart staged (written to temporaries, not committed).
fn stage_outputs(
    args: &ExtractArgs,
    ex: &Extraction,
    channels: &[universal::Channel],
    xyz: &[[f64; 3]],
    chart: Option<String>,
) -> anyhow::Result<Vec<jointid::output::Staged>> {
    let mut staged = vec![
        stage(&args.out, |w| {
            if args.space {
                csv::write_modes_in_space(w, &ex.modes, channels, xyz)
            } else {
                let x: Vec<f64> = xyz.iter().map(|c| c[0]).collect();
                csv::write_modes(w, &ex.modes, channels, &x)
            }
            .map_err(std::io::Error::other)
        })
        .with_context(|| format!("{}: cannot write", args.out.display()))?,
    ];
    if let Some(path) = &args.report {
        let report = Report::of(ex);
        staged.push(
            stage(path, |w| report.write(w))
                .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    if let (Some(path), Some(svg)) = (&args.chart, chart) {
        staged.push(
            stage(path, |w| w.write_all(svg.as_bytes()))
                .with_context(|| format!("{}: cannot write", path.display()))?,
        );
    }
    Ok(staged)
}

/// Below this MPC a mode is named on stderr as complex.
const MPC_WARN: f64 = 0.9;

/// Where an automatic band came from, for the band's line; empty for a band given.
fn band_origin(ex: &Extraction) -> String {
    let source = match ex.band_source {
        BandSource::Given => return String::new(),
        BandSource::Coherence => "where the coherence and the level show excitation",
        BandSource::Level => "where the FRFs' level stands above their noise",
    };
    match ex.extended_from {
        Some((lo, hi)) => format!(
            " ({source}: {lo:.3}..{hi:.3} Hz, extended for the modes' margins to its edges)"
        ),
        None => format!(" ({source})"),
    }
}

/// Says the band and every mode found, why each candidate was kept or rejected (when the band
/// or the modes were chosen automatically), and notes the complex modes.
fn describe(ex: &Extraction, say: &dyn Fn(String)) {
    say(format!(
        "band {:.3}..{:.3} Hz{}, {} modes:",
        ex.band_hz.0,
        ex.band_hz.1,
        band_origin(ex),
        ex.modes.len()
    ));
    say(format!(
        "standard errors from {}",
        match ex.noise {
            NoiseSource::Coherence { averages } =>
                format!("the coherence over {averages} averages (H1)"),
            NoiseSource::Residuals =>
                "the residuals of the modal fit (give --averages to use the coherence)".to_string(),
            NoiseSource::ResidualsCoherenceOne { response } => format!(
                "the residuals of the modal fit: response {} has coherence 1 on every line of the band, a noise below what the file resolves",
                response + 1
            ),
        }
    ));
    for (r, m) in ex.modes.iter().enumerate() {
        say(format!(
            "  mode {}: {:.4} +- {:.4} Hz, damping {:.4} +- {:.4}%, MPC {:.4}, MPD {:.2} deg, stable orders {}..{}",
            r + 1,
            m.frequency_hz,
            m.std.frequency_hz,
            100.0 * m.damping_ratio,
            100.0 * m.std.damping_ratio,
            m.mpc,
            m.mpd_deg,
            m.stable_orders.0,
            m.stable_orders.1
        ));
    }
    // With both the band and the number of modes given, the lines of the earlier versions only.
    let automatic = ex.band_source != BandSource::Given || ex.requested.is_none();
    for d in ex.decisions.iter().filter(|_| automatic) {
        let what = match (&d.rejected, d.mode) {
            (Some(why), _) => format!("  rejected {:.4} Hz: {why}", d.frequency_hz),
            (None, Some(r)) => format!("  kept mode {r}"),
            (None, None) => continue,
        };
        let edge = match &d.edge {
            Some(EdgeNote::BandGiven) => "; the band was given",
            Some(EdgeNote::DataEnd { .. }) => "; the data end there",
            Some(EdgeNote::ExtendedOnce) => "; the band was extended once already",
            None => "",
        };
        say(format!(
            "{what} (stable from order {}, a run of {} orders, MPC {:.3}, {:.1} and {:.1} \
             half-power bandwidths from the band's edges{edge})",
            d.run.0, d.run.1, d.mpc, d.margins.0, d.margins.1
        ));
    }
    for (r, m) in ex.modes.iter().enumerate() {
        if m.mpc < MPC_WARN {
            say(format!(
                "  note: mode {} has MPC {:.2} < {MPC_WARN}: a complex mode (noise, a mode out of \
                 the bending plane, a spurious pole, or a band wider than the well-excited \
                 one); see the chart, narrow --band or fix --modes",
                r + 1,
                m.mpc
            ));
        }
    }
}

/// The chart's units: those of the first FRF of the files (all FRFs share them).
fn chart_units(files: &[(PathBuf, Vec<Record>)], quantity: Quantity) -> ChartUnits {
    files
        .iter()
        .flat_map(|(_, records)| records)
        .find_map(|r| match r {
            Record::Function(f) if f.function_type == FunctionType::Frf => Some(f),
            _ => None,
        })
        .map_or_else(
            || ChartUnits::si(quantity),
            |f| ChartUnits::of_function(f, quantity),
        )
}

/// The stabilisation chart of the extraction, titled with the FRF files' names.
fn draw_chart(
    args: &ExtractArgs,
    frf: &FrfSet,
    ex: &Extraction,
    units: &ChartUnits,
) -> anyhow::Result<String> {
    let names: Vec<String> = args
        .frf
        .iter()
        .map(|p| {
            p.file_name()
                .map_or_else(|| p.display().to_string(), |n| n.to_string_lossy().into())
        })
        .collect();
    let title = format!("Stabilisation chart: {}", names.join(", "));
    stabilization_svg(frf, ex, &title, units).context("cannot draw the chart")
}

pub fn run(args: &ExtractArgs) -> anyhow::Result<()> {
    let say = |text: String| {
        if !args.quiet {
            eprintln!("{text}");
        }
    };
    let mut inputs: Vec<&std::path::Path> = args.frf.iter().map(|p| p.as_path()).collect();
    inputs.push(&args.geometry);
    let mut outputs = vec![args.out.as_path()];
    outputs.extend(args.chart.as_deref());
    outputs.extend(args.report.as_deref());
    check_outputs(&outputs, &inputs)?;
    let (input, units, xyz) = read_inputs(args, &say)?;
    let inputs = args
        .frf
        .iter()
        .map(|p| p.display().to_string())
        .collect::<Vec<_>>()
        .join(", ");
    input
        .set
        .validate()
        .with_context(|| format!("{inputs}: the FRFs cannot be used"))?;
    say(format!(
        "{} FRFs ({}, {}) to reference node {} direction {}, {} lines, coherence {}",
        input.channels.len(),
        input.set.quantity.name(),
        input.units,
        input.reference.0,
        input.reference.1,
        input.set.frequencies_hz.len(),
        if input.set.coherence.is_some() {
            "given"
        } else {
            "absent"
        }
    ));
    let failed = || format!("{inputs}: extraction failed");
    let settings = Settings {
        band_hz: args.band,
        n_modes: args.modes,
        max_order: args.max_order,
        averages: args.averages,
        mpc_min: args.mpc_min,
        ..Settings::default()
    };
    // --modes and --averages are refused as the flags they are; any other setting as the
    // extraction refuses it.
    let flags = [
        ("n_modes", "--modes"),
        ("averages", "--averages"),
        ("mpc_min", "--mpc-min"),
    ];
    settings.check().map_err(|e| match e.setting {
        "n_modes" | "averages" | "mpc_min" => flagged(e, &flags),
        _ => anyhow::Error::new(ExtractError::Setting(e)).context(failed()),
    })?;
    let last = std::cell::Cell::new(0);
    let ex = extract(&input.set, &settings, &|done, total| {
        let tenth = 10 * done / total.max(1);
        if tenth > last.get() {
            last.set(tenth);
            say(format!("extracting: {}%", 10 * tenth));
        }
    })
    .map_err(|e| match e {
        ExtractError::NoExcitation { lo, hi, .. } => {
            anyhow::anyhow!(
                "{inputs}: --band {}:{} is refused: {e}",
                Number(lo),
                Number(hi)
            )
        }
        e => anyhow::Error::new(e).context(failed()),
    })?;
    describe(&ex, &say);
    let chart = match &args.chart {
        Some(_) => Some(draw_chart(args, &input.set, &ex, &units)?),
        None => None,
    };
    let staged = stage_outputs(args, &ex, &input.channels, &xyz, chart)?;
    commit_all(staged)?;
    say(format!("wrote {}", args.out.display()));
    for path in args.chart.iter().chain(&args.report) {
        say(format!("wrote {}", path.display()));
    }
    Ok(())
}

//! Runs `jointid::extract` on FRFs in a plain text file and prints the modes as JSON (the Rust
//! side of `bench/extract_vs_sdypy.py`; `jointid extract` is the same extraction on universal
//! files).
//!
//! ```text
//! cargo run --release --example extract_synthetic -- FRFS.txt [--band LO HI] [--max-order N]
//!     [--modes K] [--no-refine] [--svg CHART.svg]
//! ```
//!
//! The file: `#` lines are comments; a header of `key value` lines, `quantity
//! displacement|velocity|acceleration` and `responses R`; then one line per frequency:
//! `f_hz re_1 im_1 ... re_R im_R`, whitespace separated.

use std::time::Instant;

use faer::c64;
use jointid::extract::{FrfSet, Quantity, Settings, extract};
use jointid::output::stabilization::{ChartUnits, stabilization_svg};

fn parse(text: &str) -> Result<FrfSet, String> {
    let mut quantity = None;
    let mut count = None;
    let mut frequencies = Vec::new();
    let mut responses: Vec<Vec<c64>> = Vec::new();
    for (number, line) in text.lines().enumerate() {
        let line = line.trim();
        if line.is_empty() || line.starts_with('#') {
            continue;
        }
        let mut words = line.split_whitespace();
        let first = words.next().unwrap_or_default();
        match first {
            "quantity" => {
                quantity = Some(match words.next() {
                    Some("displacement") => Quantity::Displacement,
                    Some("velocity") => Quantity::Velocity,
                    Some("acceleration") => Quantity::Acceleration,
                    other => return Err(format!("line {}: quantity {other:?}", number + 1)),
                })
            }
            "responses" => {
                let r: usize = words
                    .next()
                    .and_then(|w| w.parse().ok())
                    .ok_or(format!("line {}: responses needs a count", number + 1))?;
                count = Some(r);
                responses = vec![Vec::new(); r];
            }
            _ => {
                let r = count.ok_or("the header must give `responses R` before the data")?;
                let values: Vec<f64> = line
                    .split_whitespace()
                    .map(|w| w.parse::<f64>())
                    .collect::<Result<_, _>>()
                    .map_err(|e| format!("line {}: {e}", number + 1))?;
                if values.len() != 1 + 2 * r {
                    return Err(format!(
                        "line {}: {} numbers, expected {}",
                        number + 1,
                        values.len(),
                        1 + 2 * r
                    ));
                }
                frequencies.push(values[0]);
                for (o, series) in responses.iter_mut().enumerate() {
                    series.push(c64::new(values[1 + 2 * o], values[2 + 2 * o]));
                }
            }
        }
    }
    Ok(FrfSet {
        frequencies_hz: frequencies,
        responses,
        coherence: None,
        quantity: quantity.ok_or("the header must give `quantity`")?,
    })
}

fn main() -> Result<(), String> {
    let args: Vec<String> = std::env::args().skip(1).collect();
    let path = args
        .first()
        .ok_or("usage: extract_synthetic FRFS.txt [options]")?;
    let mut settings = Settings::default();
    let mut svg_path = None;
    let mut i = 1;
    let value = |i: usize| -> Result<&String, String> {
        args.get(i).ok_or(format!("{} needs a value", args[i - 1]))
    };
    while i < args.len() {
        match args[i].as_str() {
            "--band" => {
                let lo = value(i + 1)?.parse().map_err(|e| format!("--band: {e}"))?;
                let hi = value(i + 2)?.parse().map_err(|e| format!("--band: {e}"))?;
                settings.band_hz = Some((lo, hi));
                i += 3;
            }
            "--max-order" => {
                settings.max_order = value(i + 1)?
                    .parse()
                    .map_err(|e| format!("--max-order: {e}"))?;
                i += 2;
            }
            "--modes" => {
                settings.n_modes =
                    Some(value(i + 1)?.parse().map_err(|e| format!("--modes: {e}"))?);
                i += 2;
            }
            "--no-refine" => {
                settings.refine = false;
                i += 1;
            }
            "--svg" => {
                svg_path = Some(value(i + 1)?.clone());
                i += 2;
            }
            other => return Err(format!("unknown option {other}")),
        }
    }
    let text = std::fs::read_to_string(path).map_err(|e| format!("{path}: {e}"))?;
    let set = parse(&text).map_err(|e| format!("{path}: {e}"))?;
    let start = Instant::now();
    let ex = extract(&set, &settings, &|_, _| {}).map_err(|e| format!("{path}: {e}"))?;
    let seconds = start.elapsed().as_secs_f64();
    if let Some(out) = svg_path {
        let title = format!(
            "Stabilisation chart: {} modes in {:.0}-{:.0} Hz",
            ex.modes.len(),
            ex.band_hz.0,
            ex.band_hz.1
        );
        let body = stabilization_svg(&set, &ex, &title, &ChartUnits::si(set.quantity))
            .map_err(|e| e.to_string())?;
        std::fs::write(&out, body).map_err(|e| format!("{out}: {e}"))?;
    }
    let modes: Vec<serde_json::Value> = ex
        .modes
        .iter()
        .map(|m| {
            serde_json::json!({
                "frequency_hz": m.frequency_hz,
                "damping_ratio": m.damping_ratio,
                "real_shape": m.real_shape,
                "mpc": m.mpc,
                "mpd_deg": m.mpd_deg,
                "stable_orders": [m.stable_orders.0, m.stable_orders.1],
            })
        })
        .collect();
    let rejected: Vec<String> = ex
        .decisions
        .iter()
        .filter_map(|d| {
            let why = d.rejected.as_ref()?;
            Some(format!("{:.3} Hz: {why}", d.frequency_hz))
        })
        .collect();
    let out = serde_json::json!({
        "seconds": seconds,
        "band_hz": [ex.band_hz.0, ex.band_hz.1],
        "rejected": rejected,
        "refined": ex.refined,
        "fit_error": ex.fit_error,
        "modes": modes,
    });
    println!("{out}");
    Ok(())
}

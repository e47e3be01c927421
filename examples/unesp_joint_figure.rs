//! The figure of results/unesp-bert/: the joint's rotational stiffness k2 identified per mode
//! (`jointid identify --params k2`) against the excitation level and against the mode.
//!
//! ```text
//! cargo run --release --example unesp_joint_figure -- DIR
//! ```
//! reads `DIR/corrections_<level>V.csv` (the identify CSVs, levels 0p05 .. 0p30) and writes
//! `DIR/k2_vs_level.svg` and `DIR/k2_vs_mode.svg`.

use std::collections::BTreeMap;
use std::path::Path;

use jointid::output::plot::{LineAxes, Series, lines, svg};

/// (level in V, mode, corrected k2) of every identify CSV in `dir`.
fn read(dir: &Path) -> Result<Vec<(f64, usize, f64)>, String> {
    let mut rows = Vec::new();
    for level in ["0p05", "0p10", "0p15", "0p20", "0p25", "0p30"] {
        let path = dir.join(format!("corrections_{level}V.csv"));
        let volts: f64 = level.replace('p', ".").parse().map_err(|e| format!("{e}"))?;
        let mut r = csv::Reader::from_path(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let head = r.headers().map_err(|e| format!("{}: {e}", path.display()))?.clone();
        let col = |name: &str| {
            head.iter()
                .position(|h| h == name)
                .ok_or(format!("{}: no column {name}", path.display()))
        };
        let (mode, param, corrected) = (col("mode")?, col("param")?, col("corrected")?);
        for rec in r.records() {
            let rec = rec.map_err(|e| format!("{}: {e}", path.display()))?;
            if &rec[param] != "k2" {
                continue;
            }
            let m: usize = rec[mode].parse().map_err(|e| format!("{}: {e}", path.display()))?;
            let k: f64 = rec[corrected].parse().map_err(|e| format!("{}: {e}", path.display()))?;
            rows.push((volts, m, k));
        }
    }
    Ok(rows)
}

fn main() -> Result<(), String> {
    let dir = std::env::args().nth(1).ok_or("usage: unesp_joint_figure DIR")?;
    let dir = Path::new(&dir);
    let rows = read(dir)?;
    let mut by_mode: BTreeMap<usize, Vec<(f64, f64)>> = BTreeMap::new();
    let mut by_level: BTreeMap<String, Vec<(f64, f64)>> = BTreeMap::new();
    for &(v, m, k) in &rows {
        by_mode.entry(m).or_default().push((v, k));
        by_level
            .entry(format!("{v:.2} V"))
            .or_default()
            .push((m as f64, k));
    }
    let axes = |x: &str| LineAxes {
        x_desc: x.to_string(),
        y_desc: "identified k2 (N m/rad)".to_string(),
        log_x: false,
        log_y: false,
        reference: Some((300.0, "nominal k2 = 300".to_string())),
        clip_errors: false,
    };
    let series = |map: BTreeMap<String, Vec<(f64, f64)>>| -> Vec<Series> {
        map.into_iter()
            .map(|(name, points)| Series {
                name,
                points,
                errors: None,
                line: true,
            })
            .collect()
    };
    let level_series = series(
        by_mode
            .into_iter()
            .map(|(m, p)| (format!("mode {m}"), p))
            .collect(),
    );
    let mode_series = series(by_level);
    let a = svg((900, 500), |area| {
        lines(
            area,
            "UNESP-BERT: joint rotational stiffness against excitation level",
            &axes("excitation level (V, amplifier input)"),
            &level_series,
        )
    })
    .map_err(|e| e.0)?;
    let b = svg((900, 500), |area| {
        lines(
            area,
            "UNESP-BERT: joint rotational stiffness against mode",
            &axes("mode"),
            &mode_series,
        )
    })
    .map_err(|e| e.0)?;
    for (name, text) in [("k2_vs_level.svg", a), ("k2_vs_mode.svg", b)] {
        std::fs::write(dir.join(name), text).map_err(|e| format!("{name}: {e}"))?;
    }
    Ok(())
}

//! The figure of results/unesp-bert/: the joint's rotational stiffness k2 identified per mode
//! (`jointid identify --params k2`) against the excitation level and against the mode.
//!
//! ```text
//! cargo run --release --example unesp_joint_figure -- DIR
//! ```
//! reads `DIR/corrections_<level>V.csv` (the identify CSVs, levels 0p05 .. 0p30) and
//! `DIR/diagnose_<level>V.json` (the joint calibrated on both modes, `after`), writes
//! `DIR/k2_vs_level.svg`, `DIR/k2_vs_mode.svg` and `DIR/calibrated.csv` (level, k1, k2 and their
//! standard errors).

use std::collections::BTreeMap;
use std::path::Path;

use jointid::output::plot::{LineAxes, Series, lines, svg};

const LEVELS: [&str; 6] = ["0p05", "0p10", "0p15", "0p20", "0p25", "0p30"];

/// (level in V, mode, corrected k2) of every identify CSV in `dir`.
fn read(dir: &Path) -> Result<Vec<(f64, usize, f64)>, String> {
    let mut rows = Vec::new();
    for level in LEVELS {
        let path = dir.join(format!("corrections_{level}V.csv"));
        let volts = volts(level)?;
        let mut r =
            csv::Reader::from_path(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let head = r
            .headers()
            .map_err(|e| format!("{}: {e}", path.display()))?
            .clone();
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
            let m: usize = rec[mode]
                .parse()
                .map_err(|e| format!("{}: {e}", path.display()))?;
            let k: f64 = rec[corrected]
                .parse()
                .map_err(|e| format!("{}: {e}", path.display()))?;
            rows.push((volts, m, k));
        }
    }
    Ok(rows)
}

/// (level in V, [k1, se, k2, se]) of the calibrated joint of every diagnose JSON in `dir`.
fn calibrated(dir: &Path) -> Result<Vec<(f64, [f64; 4])>, String> {
    let mut out = Vec::new();
    for level in LEVELS {
        let path = dir.join(format!("diagnose_{level}V.json"));
        let text =
            std::fs::read_to_string(&path).map_err(|e| format!("{}: {e}", path.display()))?;
        let json: serde_json::Value =
            serde_json::from_str(&text).map_err(|e| format!("{}: {e}", path.display()))?;
        let params = json["after"]["parameters"]
            .as_array()
            .ok_or(format!("{}: no after.parameters", path.display()))?;
        let get = |name: &str, field: &str| {
            params
                .iter()
                .find(|p| p["name"] == name)
                .and_then(|p| p[field].as_f64())
                .ok_or(format!("{}: no {name}.{field}", path.display()))
        };
        out.push((
            volts(level)?,
            [
                get("k1", "value")?,
                get("k1", "se")?,
                get("k2", "value")?,
                get("k2", "se")?,
            ],
        ));
    }
    Ok(out)
}

fn volts(level: &str) -> Result<f64, String> {
    level
        .replace('p', ".")
        .parse()
        .map_err(|e| format!("{level}: {e}"))
}

fn main() -> Result<(), String> {
    let dir = std::env::args()
        .nth(1)
        .ok_or("usage: unesp_joint_figure DIR")?;
    let dir = Path::new(&dir);
    let rows = read(dir)?;
    let joint = calibrated(dir)?;
    let mut table = String::from("level_V,k1,k1_se,k2,k2_se\n");
    for (v, [k1, s1, k2, s2]) in &joint {
        table.push_str(&format!("{v:.2},{k1},{s1},{k2},{s2}\n"));
    }
    std::fs::write(dir.join("calibrated.csv"), table)
        .map_err(|e| format!("calibrated.csv: {e}"))?;
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
    let mut level_series = series(
        by_mode
            .into_iter()
            .map(|(m, p)| (format!("mode {m} (identify, k2 only)"), p))
            .collect(),
    );
    level_series.push(Series {
        name: "both modes (diagnose, k1 and k2)".to_string(),
        points: joint.iter().map(|(v, k)| (*v, k[2])).collect(),
        errors: Some(joint.iter().map(|(_, k)| k[3]).collect()),
        line: true,
    });
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

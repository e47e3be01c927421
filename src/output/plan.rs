//! A plan ([`crate::plan::Plan`]) in words and files: the table per layout, the `[[sensor]]`
//! entries to paste into the model, the study TOML whose Monte-Carlo run confirms the
//! predicted spreads (one `[[grid]]` per determinate layout, its unmeasured DOFs as `nf`), and
//! the figure (in [`super::plan_figure`]).

use std::io::{self, Write};
use std::path::Path;

use crate::plan::{Layout, Plan, Status};

/// The terminal table: per count, per layout, its sensors, settings, and per mode the
/// relative std of every parameter, cond(W S) and the least resolution; what a deficient
/// layout lacks and the sensors that complete it.
pub fn write_table(out: &mut dyn Write, plan: &Plan) -> io::Result<()> {
    writeln!(
        out,
        "objective: {}; relative std of each correction (std(Delta p) / p), first order",
        plan.objective
    )?;
    let mut layouts: Vec<(String, &Layout)> = Vec::new();
    for count in &plan.counts {
        for l in &count.layouts {
            layouts.push((format!("{} sensors, {}", count.sensors, l.kind.name()), l));
        }
    }
    if let Some(l) = &plan.model_layout {
        layouts.push((format!("{} sensors, the model's", l.sites.len()), l));
    }
    for (title, layout) in layouts {
        write_layout(out, plan, &title, layout)?;
    }
    Ok(())
}

fn write_layout(out: &mut dyn Write, plan: &Plan, title: &str, l: &Layout) -> io::Result<()> {
    let e = &l.evaluation;
    let settings = e.settings.map_or("no basis fits".to_string(), |s| {
        format!("n = {}, m = {}, weighting = {}", s.n, s.m, s.weighting)
    });
    writeln!(
        out,
        "\n{title}: {settings}; objective {}",
        fmt_value(e.score.value)
    )?;
    writeln!(out, "  sensors: {}", positions(plan, &l.sites))?;
    writeln!(
        out,
        "  mode  {}  cond(WS)  resolution  status",
        plan.parameters
            .iter()
            .map(|p| format!("{:>10}", format!("std {p}")))
            .collect::<Vec<_>>()
            .join(" ")
    )?;
    for m in &e.modes {
        let stds = match &m.relative_std {
            Some(s) => s
                .iter()
                .map(|v| format!("{:>10}", pct(*v)))
                .collect::<Vec<_>>(),
            None => plan
                .parameters
                .iter()
                .map(|_| format!("{:>10}", "-"))
                .collect(),
        };
        let cond = m.condition.map_or("-".into(), |c| format!("{c:.3e}"));
        let res = m.resolution.as_ref().map_or("-".into(), |r| {
            format!("{:.3}", r.iter().copied().fold(f64::INFINITY, f64::min))
        });
        let status = match (m.status, &m.fallback) {
            (Status::Determinate, _) => "determinate".to_string(),
            (s, Some(f)) => format!(
                "{} (fallback: {} from the frequency, std {})",
                status_name(s),
                f.param,
                pct(f.relative_std)
            ),
            (s, None) => status_name(s).to_string(),
        };
        writeln!(
            out,
            "  {:>4}  {}  {cond:>8}  {res:>10}  {status}",
            m.mode,
            stds.join(" ")
        )?;
    }
    if e.score.undetermined > 0 {
        match &l.addition {
            Some(a) => writeln!(
                out,
                "  rank-deficient for {} mode(s): {} {} sensor(s) more make every mode determinate: {}",
                e.score.undetermined,
                if a.fewest { "the fewest," } else { "greedily," },
                a.added.len(),
                positions(plan, &a.added)
            )?,
            None => writeln!(
                out,
                "  rank-deficient for {} mode(s): no addition of candidate sites makes every mode determinate",
                e.score.undetermined
            )?,
        }
    }
    Ok(())
}

/// Why a mode is not determined, in words.
pub fn status_name(s: Status) -> &'static str {
    match s {
        Status::Determinate => "determinate",
        Status::TooFewSensors => "too few sensors for any basis",
        Status::BeyondBasis => "beyond the basis",
        Status::Unprojectable => "shapes dependent at the sensors",
        Status::RankDeficient => "rank-deficient W S",
    }
}

fn pct(v: f64) -> String {
    if v.is_finite() {
        format!("{:.3}%", 100.0 * v)
    } else {
        "inf".into()
    }
}

fn fmt_value(v: f64) -> String {
    if v.is_finite() {
        pct(v)
    } else {
        "undefined (no determinate mode)".into()
    }
}

/// `label (x m)` of each candidate index.
fn positions(plan: &Plan, sites: &[usize]) -> String {
    sites
        .iter()
        .map(|&i| {
            let c = &plan.candidates[i];
            format!("{} ({} m)", c.label, (c.x * 1e6).round() / 1e6)
        })
        .collect::<Vec<_>>()
        .join(", ")
}

/// The `[[sensor]]` entries of a layout's sensors, to paste into a beam-chain model (position
/// and label; a sensor at an existing node adds none).
pub fn write_sensor_entries(out: &mut dyn Write, plan: &Plan, sites: &[usize]) -> io::Result<()> {
    for (k, &i) in sites.iter().enumerate() {
        let c = &plan.candidates[i];
        writeln!(out, "[[sensor]]\nx = {}\nlabel = \"s{}\"", c.x, k + 1)?;
        if c.direction != "w" {
            writeln!(
                out,
                "# reads {} ({}): name it by this label in a measured file",
                c.label, c.direction
            )?;
        }
        writeln!(out)?;
    }
    Ok(())
}

/// A layout written to the confirming study: its place in the plan and its grid's index.
#[derive(Debug, Clone, PartialEq, serde::Serialize)]
pub struct StudyGrid {
    /// The study's field path of the grid (`grid[0]`).
    pub grid: String,
    /// The count of sensors (`None`: the model's layout).
    pub sensors: Option<usize>,
    /// The layout's kind name.
    pub kind: &'static str,
}

/// What the confirming study needs beside the plan.
#[derive(Debug, Clone)]
pub struct StudyFile<'a> {
    /// The study's name (a plain file name).
    pub name: &'a str,
    /// The model file as the study names it (absolute, or relative to the study file).
    pub model: &'a Path,
    /// Every DOF label of the model, in DOF order (the unmeasured ones become `nf`).
    pub labels: &'a [String],
    /// Noise distribution name, levels.
    pub noise: &'a str,
    /// Shape noise level.
    pub shape_noise: f64,
    /// Frequency noise level.
    pub frequency_noise: f64,
    /// Trials per cell.
    pub trials: usize,
    /// Seed.
    pub seed: u64,
    /// The result CSV, relative to the study file.
    pub csv: &'a str,
}

/// The study TOML that runs every layout whose modes are all determinate (one `[[grid]]` each,
/// at the plan's settings and noise, truth = the nominal model), and the grids it holds.
pub fn study_toml(plan: &Plan, file: &StudyFile) -> (String, Vec<StudyGrid>) {
    let mut text = format!(
        "# Written by `jointid plan`: the Monte-Carlo confirmation of its predicted spreads.\n\
         # One grid per layout whose every mode is determinate; the unmeasured DOFs are nf.\n\
         name = \"{}\"\nmodel = \"{}\"\n\n[truth]\ndelta = {{ {} }}\n",
        file.name,
        file.model.display().to_string().replace('\\', "/"),
        plan.parameters
            .iter()
            .map(|p| format!("\"{p}\" = 0.0"))
            .collect::<Vec<_>>()
            .join(", ")
    );
    let mut grids = Vec::new();
    let mut all: Vec<(Option<usize>, &Layout)> = Vec::new();
    for c in &plan.counts {
        all.extend(c.layouts.iter().map(|l| (Some(c.sensors), l)));
    }
    all.extend(plan.model_layout.iter().map(|l| (None, l)));
    for (sensors, l) in all {
        let Some(s) = l
            .evaluation
            .settings
            .filter(|_| l.evaluation.score.undetermined == 0)
        else {
            continue;
        };
        let measured: Vec<usize> = l.sites.iter().map(|&i| plan.candidates[i].dof).collect();
        let nf: Vec<String> = (0..file.labels.len())
            .filter(|d| !measured.contains(d))
            .map(|d| format!("\"{}\"", file.labels[d]))
            .collect();
        text += &format!(
            "\n# {} sensors, {}\n[[grid]]\nmodes = {:?}\nn = [{}]\nm = [{}]\nnf = [[{}]]\nweighting = [\"{}\"]\nshape_noise = [{}]\nfrequency_noise = [{}]\n",
            l.sites.len(),
            l.kind.name(),
            plan.modes,
            s.n,
            s.m,
            nf.join(", "),
            s.weighting,
            file.shape_noise,
            file.frequency_noise
        );
        grids.push(StudyGrid {
            grid: format!("grid[{}]", grids.len()),
            sensors,
            kind: l.kind.name(),
        });
    }
    text += &format!(
        "\n[monte_carlo]\ntrials = {}\nseed = {}\nnoise = \"{}\"\n\n[output]\ncsv = \"{}\"\n",
        file.trials, file.seed, file.noise, file.csv
    );
    (text, grids)
}

/// The plan as JSON, with the confirming study's grids (empty without a study).
pub fn write_json(out: &mut dyn Write, plan: &Plan, grids: &[StudyGrid]) -> io::Result<()> {
    #[derive(serde::Serialize)]
    struct File<'a> {
        plan: &'a Plan,
        study_grids: &'a [StudyGrid],
    }
    serde_json::to_writer_pretty(
        &mut *out,
        &File {
            plan,
            study_grids: grids,
        },
    )
    .map_err(io::Error::other)?;
    writeln!(out)
}

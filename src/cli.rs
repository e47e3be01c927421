//! Command-line definitions.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use jointid::identify::Weighting;

/// Identify joint stiffness from measured vibration modes, mode by mode.
#[derive(Debug, Parser)]
#[command(name = "jointid", version, about)]
pub struct Cli {
    /// The command.
    #[command(subcommand)]
    pub command: Command,
}

/// The commands.
#[derive(Debug, Subcommand)]
pub enum Command {
    /// Per-mode correction of the joint stiffnesses (the paper's method, eq. (5)-(16)).
    Identify(IdentifyArgs),
    /// Monte-Carlo robustness study from a TOML file: bias and spread of every per-mode
    /// correction over the grid.
    Study(StudyArgs),
    /// Run a study and exit 1 when the estimator bias in the cells of `[check]` exceeds
    /// its threshold (a CI gate).
    Check(StudyArgs),
    /// Measured modes simulated from a model, with optional measurement errors, in the
    /// measured-modes CSV format.
    Simulate(SimulateArgs),
    /// Diagnose measured data: calibrate the joint, trace the residual to a missing effect,
    /// report before and after.
    Diagnose(DiagnoseArgs),
    /// Figures of a study CSV and a page that shows them (`DIR/index.html`).
    Report(ReportArgs),
    /// Speed of the study engine on the paper cell, optionally beside the numpy baseline.
    Bench(BenchArgs),
}

/// `jointid study` and `jointid check`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// Study files (TOML), run one after the other.
    #[arg(required = true)]
    pub studies: Vec<PathBuf>,
    /// Worker threads (default: all cores). The output does not depend on it.
    #[arg(long)]
    pub threads: Option<usize>,
    /// Also write every trial's corrections to this CSV.
    #[arg(long)]
    pub trials_csv: Option<PathBuf>,
    /// Write the results here instead of the study's `[output].csv` (one study only).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// No progress bar (it is hidden anyway when stderr is not a terminal).
    #[arg(long)]
    pub quiet: bool,
}

/// Which DOFs a simulated test measures.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum Measure {
    /// Translations only (the usual accelerometer test).
    W,
    /// Rotations only.
    Theta,
    /// Every DOF.
    All,
    /// The sensors the model declares (`[[sensor]]`).
    Sensors,
}

/// `jointid simulate`.
#[derive(Debug, Args)]
pub struct SimulateArgs {
    /// Model to simulate (the "real" structure).
    #[arg(long)]
    pub model: PathBuf,
    /// Number of deformable modes, from the first.
    #[arg(long)]
    pub modes: usize,
    /// Relative error of every shape element (standard deviation; maximum for uniform).
    #[arg(long, default_value_t = 0.0)]
    pub shape_noise: f64,
    /// Relative standard deviation of every frequency.
    #[arg(long, default_value_t = 0.0)]
    pub frequency_noise: f64,
    /// Error distribution: gaussian or uniform.
    #[arg(long, default_value = "gaussian")]
    pub noise: String,
    /// An effect the model lacks, `name=size` (repeatable): joint_coupling, joint_mass,
    /// sensor_mass, suspension, shear, element_damage, rising_joint (see README for sizes).
    #[arg(long = "effect", value_parser = parse_effect)]
    pub effects: Vec<(String, f64)>,
    /// Measured DOFs.
    #[arg(long, value_enum, default_value_t = Measure::All)]
    pub measure: Measure,
    /// Seed of the errors.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Output CSV.
    #[arg(long)]
    pub out: PathBuf,
}

/// `jointid report`.
#[derive(Debug, Args)]
pub struct ReportArgs {
    /// A study result CSV (the output of `jointid study`).
    pub results: PathBuf,
    /// Directory for the SVG figures and index.html (created if absent).
    #[arg(long)]
    pub out: PathBuf,
    /// Title of the page and figures (default: the CSV's file name).
    #[arg(long)]
    pub title: Option<String>,
}

/// `jointid bench`.
#[derive(Debug, Args)]
pub struct BenchArgs {
    /// Trials per timed run (each trial identifies 4 modes).
    #[arg(long, default_value_t = 200_000)]
    pub trials: usize,
    /// Timed runs per configuration; medians are reported.
    #[arg(long, default_value_t = 5)]
    pub repeat: usize,
    /// The numpy baseline script, run side by side (python3 with numpy and scipy needed).
    #[arg(long)]
    pub numpy: Option<PathBuf>,
}

/// `jointid identify`.
#[derive(Debug, Args)]
pub struct IdentifyArgs {
    /// Model file (TOML).
    #[arg(long)]
    pub model: PathBuf,
    /// Measured modes (CSV: mode,frequency_hz, then node,dof or x,dof or label, then value).
    #[arg(long)]
    pub measured: PathBuf,
    /// Basis size n: calculated eigenpairs, rigid-body modes included.
    #[arg(long)]
    pub n: usize,
    /// Retained sensitivity equations m (q <= m <= n - 2).
    #[arg(long)]
    pub m: usize,
    /// Weighting of the retained equations: equal, inverse (16-a), inverse-sqrt (16-b).
    #[arg(long, value_parser = parse_weighting)]
    pub weighting: Weighting,
    /// Modes to identify (default: every measured mode), e.g. 1,2,3.
    #[arg(long, value_delimiter = ',')]
    pub modes: Option<Vec<usize>>,
    /// Parameters to identify, e.g. k2 (the others held at their values), or `auto`: on each
    /// mode, the parameters the mode determines (default: every identified parameter).
    #[arg(long, value_delimiter = ',')]
    pub params: Option<Vec<String>>,
    /// Write CSV here instead of printing a table.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

fn parse_weighting(s: &str) -> Result<Weighting, String> {
    s.parse()
}

fn parse_effect(s: &str) -> Result<(String, f64), String> {
    let (name, size) = s
        .split_once('=')
        .ok_or_else(|| format!("`{s}` is not name=size, e.g. joint_mass=0.05"))?;
    let size: f64 = size
        .parse()
        .map_err(|_| format!("`{size}` is not a number (the size of {name})"))?;
    if !size.is_finite() {
        return Err(format!("the size of {name} must be finite"));
    }
    Ok((name.to_string(), size))
}

/// `jointid diagnose`.
#[derive(Debug, Args)]
pub struct DiagnoseArgs {
    /// Model file (TOML): the nominal model, without the effect to be found.
    #[arg(long)]
    pub model: PathBuf,
    /// Measured modes (CSV).
    #[arg(long)]
    pub measured: PathBuf,
    /// Relative standard deviation of the measured frequencies.
    #[arg(long, default_value_t = 0.001)]
    pub frequency_noise: f64,
    /// Relative standard deviation of the measured shape components.
    #[arg(long, default_value_t = 0.02)]
    pub shape_noise: f64,
    /// Also write the report as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// Also write the figures (SVG) and an index.html into this directory.
    #[arg(long)]
    pub plots: Option<PathBuf>,
    /// Basis size n of the per-mode corrections (default: the fewest identified DOFs of a mode).
    #[arg(long)]
    pub n: Option<usize>,
    /// Retained equations m of the per-mode corrections (default: min(n - 2, 6)).
    #[arg(long)]
    pub m: Option<usize>,
    /// Weighting of the per-mode corrections.
    #[arg(long, value_parser = parse_weighting, default_value = "inverse")]
    pub weighting: Weighting,
    /// Half-width of the frequency window in which a measured mode looks for its model mode,
    /// relative to its frequency (0 < w <= 10).
    #[arg(long, default_value_t = jointid::diagnose::pairing::DEFAULT_WINDOW)]
    pub pairing_window: f64,
    /// Pairs given by number, `r:t` (measured mode r with the model's deformable mode t),
    /// comma-separated; the other modes pair by MAC within the window.
    #[arg(long, value_delimiter = ',', value_parser = parse_pair)]
    pub pair: Vec<(usize, usize)>,
}

fn parse_pair(s: &str) -> Result<(usize, usize), String> {
    let (r, t) = s
        .split_once(':')
        .ok_or_else(|| format!("`{s}` is not r:t, e.g. 3:4 (measured mode 3 with model mode 4)"))?;
    let number = |text: &str| {
        text.trim()
            .parse::<usize>()
            .ok()
            .filter(|&n| (1..=100_000).contains(&n))
            .ok_or_else(|| format!("`{text}` in `{s}` is not a mode number from 1 to 100000"))
    };
    Ok((number(r)?, number(t)?))
}

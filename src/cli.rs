//! Command-line definitions.

use std::path::PathBuf;

use clap::{Args, Parser, Subcommand};

use jointid::cluster::ShardSpec;
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
    /// Before the test: where to put the sensors (and which n, m, weighting) so that the
    /// per-mode joint corrections spread least; beside Effective Independence, evenly spaced
    /// sensors and the model's own; with the study that confirms it by Monte-Carlo.
    Plan(PlanArgs),
    /// Run a study (or read its result CSV with `--results`) and exit 1 when the estimator
    /// bias in the cells of `[check]` exceeds its threshold (a CI gate).
    Check(CheckArgs),
    /// Merge the shard files of `study --shard K/N` into the study's result CSV, byte for
    /// byte the single-machine one.
    Merge(MergeArgs),
    /// Scripts that run a study's shards on a cluster's batch scheduler.
    #[command(subcommand)]
    Cluster(ClusterCommand),
    /// Measured modes simulated from a model, with optional measurement errors, in the
    /// measured-modes CSV format.
    Simulate(SimulateArgs),
    /// Modal parameters from measured FRFs (universal files): poles with a stabilisation
    /// chart, residues, real modes and their complexity, as a measured-modes CSV.
    Extract(ExtractArgs),
    /// The paper's first step: E (or rho) of the beams fitted on the modes of a reference
    /// specimen (the beams in one piece, or one beam alone), with standard errors, written as
    /// a calibrated model file that identify, diagnose and study read.
    Calibrate(CalibrateArgs),
    /// Diagnose measured data: calibrate the joint, trace the residual to a missing effect,
    /// report before and after.
    Diagnose(DiagnoseArgs),
    /// Figures of a study CSV and a page that shows them (`DIR/index.html`).
    Report(ReportArgs),
    /// Speed of the study engine on the paper cell, optionally beside the numpy baseline.
    Bench(BenchArgs),
    /// Write a model as an external model (`kind = "matrices"`): Matrix Market K, M, dK/dp
    /// (dM/dp) per parameter, the DOF table and a model.toml that reads back.
    Export(ExportArgs),
    /// Amplitude dependence across excitation levels: per mode, the stiffness and damping
    /// against the response amplitude by three laws (constant, power law, Iwan), one chosen
    /// by AICc, with bands and a figure.
    Amplitude(AmplitudeArgs),
    /// Make a 3D brick model of a bolted lap specimen (two bars tied by interface springs)
    /// from a TOML file, written as an external model.
    Solid(SolidArgs),
}

/// `jointid calibrate`.
#[derive(Debug, Args)]
pub struct CalibrateArgs {
    /// Model file (TOML, a beam chain): the jointed model whose beams are calibrated.
    #[arg(long)]
    pub model: PathBuf,
    /// The reference test's modes (measured-modes CSV), positions along the specimen.
    #[arg(long)]
    pub reference: PathBuf,
    /// The reference specimen: `monolithic` (the beams in one piece, every joint rigid) or
    /// `beam:K` (beam K alone, positions from its start).
    #[arg(long, default_value = "monolithic")]
    pub specimen: String,
    /// What is fitted, comma-separated: `youngs_modulus` (E, and G with it) and/or `density`,
    /// one factor for the specimen's beams, or `:each` for one per beam.
    #[arg(long, value_delimiter = ',', default_value = "youngs_modulus")]
    pub fit: Vec<String>,
    /// The calibrated model file to write (never one of the inputs).
    #[arg(long)]
    pub out: PathBuf,
    /// Also write the calibration as JSON here.
    #[arg(long)]
    pub json: Option<PathBuf>,
    /// The measurement error and the pairing.
    #[command(flatten)]
    pub error: ErrorModelArgs,
}

/// The measurement error a fit weighs with and the window its pairing looks in, as
/// `calibrate` and `diagnose` take them.
#[derive(Debug, Args)]
pub struct ErrorModelArgs {
    /// Relative standard deviation of the measured frequencies.
    #[arg(long, default_value_t = 0.001)]
    pub frequency_noise: f64,
    /// Relative standard deviation of the measured shape components.
    #[arg(long, default_value_t = 0.02)]
    pub shape_noise: f64,
    /// Judge with the stated noise (--frequency-noise, --shape-noise) even when the measured
    /// file carries standard errors (they describe the random error of the test alone).
    #[arg(long)]
    pub stated_noise: bool,
    /// Half-width of the frequency window in which a measured mode looks for its model mode,
    /// relative to its frequency (0 < w <= 10).
    #[arg(long, default_value_t = jointid::diagnose::pairing::DEFAULT_WINDOW)]
    pub pairing_window: f64,
}

impl ErrorModelArgs {
    /// The stated noise.
    pub fn noise(&self) -> jointid::diagnose::Noise {
        jointid::diagnose::Noise {
            frequency: self.frequency_noise,
            shape: self.shape_noise,
        }
    }

    /// The pairing rule: the window, and the pairs `given` by number.
    pub fn pairing(&self, given: Vec<(usize, usize)>) -> jointid::diagnose::PairingRule {
        jointid::diagnose::PairingRule {
            window: self.pairing_window,
            given,
        }
    }

    /// `measured` as the fit weighs it: without its standard errors under --stated-noise.
    pub fn weighed(
        &self,
        measured: jointid::measured::MeasuredModes,
    ) -> jointid::measured::MeasuredModes {
        if self.stated_noise {
            measured.without_std()
        } else {
            measured
        }
    }
}

/// `jointid amplitude`.
#[derive(Debug, Args)]
pub struct AmplitudeArgs {
    /// The levels file (TOML: the model, per level the modes file and the amplitude source).
    pub levels: PathBuf,
    /// Folder of the outputs (created if absent): amplitude_levels.csv, amplitude_laws.csv,
    /// amplitude_parameters.csv, amplitude_bands.csv, amplitude_mode<r>.svg.
    #[arg(long)]
    pub out: PathBuf,
    /// Also the joint's own stiffness and damping against amplitude: the named identified
    /// parameter of the model (e.g. k2) from each level's frequency of each mode, the joint's
    /// damping zeta / s; writes joint_levels.csv, joint_laws.csv, joint_parameters.csv,
    /// joint_bands.csv, joint_errors.csv (frequencies before and after), joint_mode<r>.svg.
    #[arg(long)]
    pub joint: Option<String>,
}

/// `jointid solid`.
#[derive(Debug, Args)]
pub struct SolidArgs {
    /// The specimen (TOML: width, overlap, material, two bars, interface, mesh).
    pub config: PathBuf,
    /// A new folder for the files (it must not exist, or be empty).
    #[arg(long)]
    pub out: PathBuf,
}

/// `jointid export`.
#[derive(Debug, Args)]
pub struct ExportArgs {
    /// Model to export (any kind).
    pub model: PathBuf,
    /// A new folder for the files (it must not exist, or be empty).
    #[arg(long)]
    pub out: PathBuf,
}

/// `jointid plan`.
#[derive(Debug, Args)]
pub struct PlanArgs {
    /// Model file (TOML): a beam chain or an external model.
    #[arg(long)]
    pub model: PathBuf,
    /// Candidate sites: `nodes` (the w DOF of every node), positions in m (`0,0.1,0.35`: nodes
    /// there) or DOF labels (`3:w,7:w`, an external model's labels).
    #[arg(long, default_value = "nodes")]
    pub sites: String,
    /// Sensors to place: a count (`6`) or a range (`3-6`).
    #[arg(long)]
    pub sensors: String,
    /// The deformable modes to be measured, comma-separated (from 1).
    #[arg(long, value_delimiter = ',', required = true)]
    pub modes: Vec<usize>,
    /// Relative standard deviation of the measured frequencies (> 0).
    #[arg(long, allow_hyphen_values = true)]
    pub frequency_noise: f64,
    /// Relative error of every shape component (> 0): the standard deviation (gaussian) or
    /// the half-width (uniform), as a study reads it.
    #[arg(long, allow_hyphen_values = true)]
    pub shape_noise: f64,
    /// Noise distribution: gaussian or uniform.
    #[arg(long, default_value = "gaussian")]
    pub noise: String,
    /// Sensors that stay (the shaker's reference...): positions (m) or DOF labels, each one
    /// of the candidate sites.
    #[arg(long, value_delimiter = ',')]
    pub fixed: Vec<String>,
    /// What the search minimises: `worst` (the largest relative std of any mode and
    /// parameter), `mean`, or `det` (per mode det of the covariance, geometric mean).
    #[arg(long, default_value = "worst")]
    pub objective: String,
    /// Basis size n, held (with --m and --weighting); by default n, m and W are chosen with
    /// each layout.
    #[arg(long, requires_all = ["m", "weighting"])]
    pub n: Option<usize>,
    /// Retained equations m, held.
    #[arg(long, requires_all = ["n", "weighting"])]
    pub m: Option<usize>,
    /// Weighting, held: equal, inverse or inverse-sqrt.
    #[arg(long, value_parser = parse_weighting, requires_all = ["n", "m"])]
    pub weighting: Option<Weighting>,
    /// Seed of the confirming study's random streams.
    #[arg(long, default_value_t = 1)]
    pub seed: u64,
    /// Trials per layout of the confirming study.
    #[arg(long, default_value_t = 20000)]
    pub trials: usize,
    /// The plan as JSON.
    #[arg(long)]
    pub out: PathBuf,
    /// Also write the confirming study (TOML; its results CSV beside it, same stem).
    #[arg(long)]
    pub study: Option<PathBuf>,
    /// Also write the figure (SVG).
    #[arg(long)]
    pub figure: Option<PathBuf>,
}

/// `jointid study`.
#[derive(Debug, Args)]
pub struct StudyArgs {
    /// The studies and how to run them.
    #[command(flatten)]
    pub run: RunArgs,
    /// Run only the cells of shard K of N (one study only) and write a shard file (default
    /// name: the study's CSV with `.shard-K-of-N.csv`); `jointid merge` joins the shards.
    #[arg(long, value_name = "K/N")]
    pub shard: Option<ShardSpec>,
}

/// The studies to run and how: shared by `jointid study` and `jointid check` (which holds
/// whole studies, so has no `--shard`).
#[derive(Debug, Clone, Args)]
pub struct RunArgs {
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

/// `jointid check`.
#[derive(Debug, Args)]
pub struct CheckArgs {
    /// The studies and how to run them.
    #[command(flatten)]
    pub study: RunArgs,
    /// Hold this result CSV of the study (e.g. a merged one) to its `[check]` instead of
    /// running the study (one study only).
    #[arg(long, value_name = "F.csv")]
    pub results: Option<PathBuf>,
}

/// `jointid merge`.
#[derive(Debug, Args)]
pub struct MergeArgs {
    /// The shard files, in any order.
    #[arg(required = true)]
    pub shards: Vec<PathBuf>,
    /// The merged result CSV.
    #[arg(long)]
    pub out: PathBuf,
}

/// `jointid cluster`.
#[derive(Debug, Subcommand)]
pub enum ClusterCommand {
    /// Write a Slurm job array (one task per shard), the dependent merge job and a submit
    /// script; run the submit script on the cluster's login node.
    Slurm(SlurmArgs),
}

/// `jointid cluster slurm`.
#[derive(Debug, Args)]
pub struct SlurmArgs {
    /// The study file (TOML).
    pub study: PathBuf,
    /// Number of shards N (array tasks).
    #[arg(long)]
    pub shards: usize,
    /// Slurm partition.
    #[arg(long)]
    pub partition: Option<String>,
    /// Time limit of every task and of the merge (Slurm syntax, e.g. 02:00:00).
    #[arg(long)]
    pub time: Option<String>,
    /// Slurm account.
    #[arg(long)]
    pub account: Option<String>,
    /// Memory of every shard task (Slurm syntax, e.g. 4G).
    #[arg(long)]
    pub mem: Option<String>,
    /// Cores of every shard task (its worker threads).
    #[arg(long, default_value_t = 1)]
    pub cpus_per_task: usize,
    /// A further `#SBATCH` option, verbatim (repeatable), e.g. --sbatch=--qos=short.
    #[arg(long = "sbatch", value_name = "OPTION", allow_hyphen_values = true)]
    pub extra: Vec<String>,
    /// Directory of the scripts, shard files and logs (default: slurm/NAME), on a file
    /// system the nodes share.
    #[arg(long)]
    pub dir: Option<PathBuf>,
    /// The merged result CSV (default: the study's `[output].csv`).
    #[arg(long)]
    pub out: Option<PathBuf>,
    /// The jointid binary the nodes run (default: this one).
    #[arg(long)]
    pub jointid: Option<PathBuf>,
}

/// `jointid extract`.
#[derive(Debug, Args)]
pub struct ExtractArgs {
    /// FRF files (universal file, dataset 58 ASCII or 58b): FRFs of one reference, with their
    /// coherences (optional); several files are read as one set.
    #[arg(long, required = true, num_args = 1..)]
    pub frf: Vec<PathBuf>,
    /// Geometry (universal file, dataset 15 or 2411): x along the beam of every response node.
    #[arg(long)]
    pub geometry: PathBuf,
    /// Measured-modes CSV to write (`x,dof` rows; damping_ratio, mpc and the standard errors
    /// frequency_std, damping_std, value_std).
    #[arg(long)]
    pub out: PathBuf,
    /// Analysis band LO:HI in Hz, used as given (refused when the files' coherence shows no
    /// excitation in it). Default: where the coherence and the FRFs' level show excitation
    /// (without coherence, where the level stands above its noise), moved out when a mode
    /// lies within 5 half-power bandwidths of an edge.
    #[arg(long, value_parser = parse_band)]
    pub band: Option<(f64, f64)>,
    /// Number of modes: the candidates stable at the most orders. Default: the automatic
    /// choice (stable over a run of orders that starts in the lower two thirds, MPC >=
    /// --mpc-min, not a duplicate).
    #[arg(long)]
    pub modes: Option<usize>,
    /// Least MPC of a mode of the automatic choice (without --modes), in (0, 1].
    #[arg(long, default_value_t = jointid::extract::MPC_MIN)]
    pub mpc_min: f64,
    /// Also write the choices as JSON: the band and where it came from, the rules, every
    /// candidate mode with why it was kept or rejected.
    #[arg(long)]
    pub report: Option<PathBuf>,
    /// Highest model order of the LSCF estimator.
    #[arg(long, default_value_t = jointid::extract::MAX_ORDER)]
    pub max_order: usize,
    /// Number of averages of the FRF estimates (H1): with the files' coherence it gives the
    /// noise of every line and so the modes' standard errors (default: the noise estimated
    /// from the residuals of the modal fit).
    #[arg(long)]
    pub averages: Option<usize>,
    /// The FRFs' response quantity when the files do not say it.
    #[arg(long)]
    pub quantity: Option<FrfQuantity>,
    /// Also write the stabilisation chart (SVG) with the FRF sum and the synthesised FRFs.
    #[arg(long)]
    pub chart: Option<PathBuf>,
    /// Rows by coordinates in space (`x,y,z,dof`: the geometry's coordinates, the response
    /// direction x, y, z, rx, ry, rz) for an external 3D model, instead of `x,dof` along a
    /// beam; every response direction is then allowed.
    #[arg(long)]
    pub space: bool,
    /// No progress on stderr.
    #[arg(long)]
    pub quiet: bool,
}

/// The response quantity of FRFs.
#[derive(Debug, Clone, Copy, PartialEq, Eq, clap::ValueEnum)]
pub enum FrfQuantity {
    /// Receptance.
    Displacement,
    /// Mobility.
    Velocity,
    /// Accelerance.
    Acceleration,
}

fn parse_band(text: &str) -> Result<(f64, f64), String> {
    let bad = || format!("{text:?} is not a band LO:HI in Hz with 0 <= LO < HI (e.g. 5:110)");
    let (lo, hi) = text.split_once(':').ok_or_else(bad)?;
    let lo: f64 = lo.trim().parse().map_err(|_| bad())?;
    let hi: f64 = hi.trim().parse().map_err(|_| bad())?;
    if lo.is_finite() && hi.is_finite() && 0.0 <= lo && lo < hi {
        Ok((lo, hi))
    } else {
        Err(bad())
    }
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
    /// An effect the model lacks, `name=size` (repeatable; the names come from the registry).
    #[arg(long = "effect", value_parser = parse_effect, help = effect_help())]
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
    /// Basis size n: calculated eigenpairs, rigid-body modes included (not with
    /// --from-frequency).
    #[arg(long, required_unless_present = "from_frequency")]
    pub n: Option<usize>,
    /// Retained sensitivity equations m (q <= m <= n - 2).
    #[arg(long, required_unless_present = "from_frequency")]
    pub m: Option<usize>,
    /// Weighting of the retained equations: equal, inverse (16-a), inverse-sqrt (16-b).
    #[arg(long, value_parser = parse_weighting, required_unless_present = "from_frequency")]
    pub weighting: Option<Weighting>,
    /// Identify every mode from its frequency alone: one parameter per mode, the one named by
    /// --params (a single name) or the one the mode is most sensitive to, the others held. A
    /// mode whose shape components cannot carry the paper's system gets this anyway.
    #[arg(long, conflicts_with_all = ["n", "m", "weighting"])]
    pub from_frequency: bool,
    /// Relative standard deviation of the measured frequencies, for the standard deviation of
    /// a correction from a frequency alone when the measured file carries no frequency_std.
    #[arg(long)]
    pub frequency_noise: Option<f64>,
    /// Modes to identify, each once (default: every measured mode), e.g. 1,2,3.
    #[arg(long, value_delimiter = ',')]
    pub modes: Option<Vec<usize>>,
    /// Parameters to identify, e.g. k2 (the others held at their values), each once; or `auto`
    /// alone: on each mode, the parameters the mode determines (default: every identified
    /// parameter).
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
    /// The measurement error and the pairing.
    #[command(flatten)]
    pub error: ErrorModelArgs,
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
    /// Pairs given by number, `r:t` (measured mode r with the model's deformable mode t),
    /// comma-separated; the other modes pair by MAC within the window.
    #[arg(long, value_delimiter = ',', value_parser = parse_pair)]
    pub pair: Vec<(usize, usize)>,
    /// Also search the candidates of the extended tier (listed from the registry).
    #[arg(long, help = extended_help())]
    pub extended: bool,
    /// Causes to try together from the start, `a+b` (repeatable): candidates that combine
    /// (the effects of the library and the layered lap), each named once; tried beside the
    /// candidates alone, counted as one hypothesis each.
    #[arg(long)]
    pub causes: Vec<String>,
    /// Solve every eigenproblem on the full model, never on the reduced model that large
    /// external models (3D solids) are otherwise diagnosed on: a check of its results, at the
    /// full model's cost.
    #[arg(long)]
    pub full_model: bool,
    /// No log of the diagnosis's steps on stderr (a run that ends within 2 s logs nothing
    /// anyway).
    #[arg(long)]
    pub quiet: bool,
}

/// simulate's `--effect` help: every name it accepts, from the registries.
fn effect_help() -> String {
    let names: Vec<String> = jointid::simulate::effect_catalogue()
        .into_iter()
        .map(|(name, _)| name)
        .collect();
    format!(
        "An effect the model lacks, `name=size` (repeatable): {} (see the candidate table of docs/diagnosis.md for what each size means)",
        names.join(", ")
    )
}

/// diagnose's `--extended` help: the candidates of the extended tier, from the registry.
fn extended_help() -> String {
    let names: Vec<&str> = jointid::diagnose::registry()
        .iter()
        .filter(|c| c.tier() == jointid::diagnose::Tier::Extended)
        .map(|c| c.name())
        .collect();
    format!(
        "Also search the candidates of the extended tier: {} (see the candidate table of docs/diagnosis.md)",
        names.join(", ")
    )
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

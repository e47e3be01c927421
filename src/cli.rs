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
}

/// `jointid identify`.
#[derive(Debug, Args)]
pub struct IdentifyArgs {
    /// Model file (TOML).
    #[arg(long)]
    pub model: PathBuf,
    /// Measured modes (CSV: mode,frequency_hz,node,dof,value).
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
    /// Write CSV here instead of printing a table.
    #[arg(long)]
    pub out: Option<PathBuf>,
}

fn parse_weighting(s: &str) -> Result<Weighting, String> {
    s.parse()
}

//! The integration tests, one binary (one link of the crate instead of one per file: the
//! build, not the tests, took most of `cargo test`'s time). Each module is what was one file
//! of `tests/`; run one with `cargo test --test suite MODULE::`.
//!
//! Two kinds of test are `#[ignore]`d, each with its reason, so that `cargo test --locked`
//! shows them as ignored instead of passing them silently; `.ci/run` runs both in release:
//! - the long tests (the diagnosis battery, the lapped beams and 3D laps diagnosed, the
//!   Monte-Carlo calibration checks: tens of seconds each unoptimised, seconds in release;
//!   the crate is built at opt-level 1 for tests, which brings the rest to seconds):
//!   `cargo test --release --locked -- --ignored --skip unesp`;
//! - the tests on the real UNESP-BERT files in `../shared/data/unesp-bert/` (never copied into
//!   the project: their licence), every one with `unesp` in its name: `cargo test --release
//!   --locked -- --ignored unesp` where the folder is present.

mod common;

mod amplitude;
mod amplitude_joint;
mod amplitude_levels;
mod analytic_beam;
mod bounded_input;
mod calibrate;
mod candidates;
mod cli_extract;
mod cli_identify;
mod cli_matrices;
mod cluster;
mod diagnose;
mod diagnose_battery;
mod diagnose_unesp;
mod external_solid;
mod extract;
mod extract_uncertainty;
mod extract_unesp;
mod frequency_joint;
mod frequency_only;
mod fuzz;
mod identification;
mod lap3d;
mod lap_beam;
mod large_models;
mod layered_lap;
mod layered_lap_cli;
mod matrices;
mod merge_integrity;
mod messages;
mod numerics_refused;
mod outputs_guarded;
mod plan;
mod reduced;
mod registry;
mod reliability;
mod report;
mod results;
mod sensors_in_space;
mod setups;
mod signals;
mod slurm_injection;
mod solid;
mod sparse_solver;
mod study;
mod study_measured_noise;
mod timoshenko;
mod uff_formats;
mod uff_pyuff;
mod uff_robustness;
mod uff_unesp;
mod uff_write;

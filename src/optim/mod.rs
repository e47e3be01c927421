//! Least squares, the numerics beneath the calibration (`crate::diagnose::fit`) and the
//! extraction (`crate::extract`):
//! - [`lstsq`]: linear least squares by Householder QR (never the normal equations), and the
//!   covariance of a fit from the R of a QR;
//! - [`bounds`]: a feasible region of linear inequalities on the unknowns, kept by an active
//!   set;
//! - [`step`]: the damped linear subproblem of one iteration, by QR with Marquardt's column
//!   scaling in the null space of the active constraints;
//! - [`assignment`]: pairing rows with columns of largest total weight (the pairing of modes);
//! - [`lm`]: the one Levenberg-Marquardt solver, behind a problem trait, with typed reasons of
//!   termination and an observer;
//! - [`squared`]: the squared extrapolation that speeds up a slow fixed-point iteration (the
//!   alternation of a fit and its error model's variances).
//!
//! Layer 1 (foundations; see the crate docs): imports faer, serde and thiserror, nothing of
//! the crate.

pub mod assignment;
pub mod bounds;
pub mod lm;
pub mod lstsq;
pub mod squared;
pub mod step;

pub use bounds::Bounds;
pub use lm::{
    LevenbergMarquardt, Observer, Problem, Progress, SettingError, Silent, Solution, Termination,
};
pub use step::Linearisation;

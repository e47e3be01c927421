//! Exporters: CSV tables and terminal tables, written into any `io::Write`, and the atomic
//! file writer that puts them on disk whole or not at all.
//!
//! Layer 7 (outputs; see the crate docs): may import the layers below: [`crate::stats`],
//! [`crate::input`], [`crate::random`], [`crate::structure`], [`crate::uff`], [`crate::modal`],
//! [`crate::model`], [`crate::measured`], [`crate::extract`], [`crate::identify`],
//! [`crate::simulate`], [`crate::study`], [`crate::diagnose`], [`crate::report`],
//! [`crate::cluster`], [`crate::amplitude`], [`crate::calibrate`].

pub mod amplitude;
pub mod atomic;
pub mod calibrate;
pub mod catalogue;
pub mod diagnose;
pub mod diagnose_log;
pub mod diagnose_page;
pub mod diagnose_plots;
pub mod guard;
pub mod identify;
pub mod plan;
pub mod plan_figure;
pub mod plot;
pub mod reduction;
pub mod stabilization;
pub mod study;
pub mod study_report;
pub mod table;

pub use atomic::{Staged, commit_all, stage, write_atomically};
pub use guard::check_outputs;

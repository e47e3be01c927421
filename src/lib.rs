//! jointid: identification of the stiffness of mechanical joints from measured vibration
//! modes, mode by mode, after Abdel-Mohsen & Bassiouni, "Effect of vibration frequency on
//! dynamic contact stiffness of joints".
//!
//! The data flow one way; open the modules in this order:
//! 1. [`model`]: the model file, beam elements, the joint of eq. (17), assembly of K, M and
//!    of the parameter derivatives dK/dp (eq. (8)); or external matrices (Matrix Market);
//! 2. [`modal`]: the eigensolution of eq. (1)-(2);
//! 3. [`measured`]: measured modes (eigenvalues and partial shapes);
//! 4. [`identify`]: the per-mode method, eq. (5)-(16), and the first-order propagation of
//!    measurement errors through it;
//! 5. [`study`]: Monte-Carlo robustness studies of the method, summarised by [`stats`];
//!    [`plan`]: before the test, where to put the sensors so that the per-mode corrections
//!    spread least (first-order propagation of the study's noise model);
//! 6. [`diagnose`]: calibration of the invariant joint on all modes, the candidate effects of
//!    [`model::effects`], selection and the before/after report;
//! 7. [`output`]: CSV, terminal tables, figures; [`report`] reads study results back for them.
//!
//! Before them, [`calibrate`] adjusts the beams on a reference test (the paper's first step).
//! Beside diagnose, [`amplitude`] fits the joint's amplitude dependence across excitation
//! levels (constant, power law, four-parameter Iwan).
//!
//! Beside the flow: [`input`] (TOML with field paths), [`structure`] (the model-agnostic
//! structure every step works on), [`random`] (the random streams of studies and simulations),
//! [`simulate`] (measurements of a model, with effects and errors, for tests, studies and
//! rehearsals of a test campaign), [`uff`] (universal files: measured FRFs and geometry in, mode
//! shapes out), [`extract`] (modal parameters from measured FRFs: LSCF poles, stabilisation
//! chart, LSFD residues, real modes and their complexity), [`cluster`] (studies split into
//! shards that run anywhere), [`optim`] (linear and bounded nonlinear least squares: the one
//! Levenberg-Marquardt solver that diagnose and extract share).
//!
//! # Layers
//!
//! Every module sits in a layer, bottom first. A module may import the modules of the layers
//! below its own and those of its own layer, never in a circle; never one of a layer above.
//! Under every module the same holds for its submodules: no circles among siblings.
//! `#[cfg(test)]` code may take fixtures from anywhere. `tests/layers/` reads this list and
//! holds every `use crate::...` and every `crate::`/`super::` path of `src/` to it.
//!
//! 1. foundations: [`stats`], [`input`], [`random`], [`structure`], [`uff`], [`optim`]
//! 2. eigensolution: [`modal`]
//! 3. models and measurements: [`model`], [`measured`], [`extract`]
//! 4. identification: [`identify`]
//! 5. simulation and studies: [`simulate`], [`study`], [`plan`]
//! 6. diagnosis and results: [`diagnose`], [`calibrate`], [`report`], [`cluster`], [`amplitude`]
//! 7. outputs: [`output`]
//!
//! Above them all, the binary (`main.rs`, `cli.rs`, `commands/`) may import any of them, and
//! so may the Python package (`python/`, a crate of its own: bindings, no algorithm).

pub mod amplitude;
pub mod calibrate;
pub mod cluster;
pub mod diagnose;
pub mod extract;
pub mod identify;
pub mod input;
pub mod measured;
pub mod modal;
pub mod model;
pub mod optim;
pub mod output;
pub mod plan;
pub mod random;
pub mod report;
pub mod simulate;
pub mod stats;
pub mod structure;
pub mod study;
pub mod uff;

//! Why a mode's frequency could not give its parameter: the errors of the frequency-only
//! identification ([`super::frequency_only`]) and of its search ([`super::root`]).
//!
//! Layer 4 (identification), like [`super`].

use super::reach::REACH;
use crate::modal::ModalError;

/// Why a mode's frequency could not give its parameter.
#[derive(Debug, Clone, PartialEq, thiserror::Error)]
pub enum FrequencyError {
    /// The model identifies nothing.
    #[error("the model identifies no parameter")]
    NoParameter,
    /// The measured frequency lies beyond what the parameter can reach.
    #[error(
        "mode {mode}: {measured_hz:.4} Hz is beyond the reach of {param}: from {} to {} times its value, model mode {model_mode} spans {low_hz:.4} to {high_hz:.4} Hz (the mode disagrees with the model in more than {param})",
        1.0 / REACH, REACH
    )]
    OutOfReach {
        /// Measured mode r.
        mode: usize,
        /// The parameter's name.
        param: String,
        /// The model's deformable mode number (1-based).
        model_mode: usize,
        /// The measured frequency.
        measured_hz: f64,
        /// The mode's frequency with the parameter at 1 / REACH of its value.
        low_hz: f64,
        /// ... and at REACH times it.
        high_hz: f64,
    },
    /// The mode does not see the parameter.
    #[error(
        "mode {mode}: its frequency does not depend on {param} (d ln lambda / d ln p = {sensitivity:.1e} over its reach): name another parameter"
    )]
    Insensitive {
        /// Measured mode r.
        mode: usize,
        /// The parameter's name.
        param: String,
        /// The sensitivity found.
        sensitivity: f64,
    },
    /// The eigenproblem failed at some parameter value.
    #[error(transparent)]
    Modal(#[from] ModalError),
    /// The model has no elastic mode of the measured mode's number.
    #[error(transparent)]
    BeyondModel(#[from] crate::structure::ModeBeyondModel),
}

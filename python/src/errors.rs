//! The package's exceptions: `JointidError(ValueError)` and its kinds, each carrying the
//! library's message (the CLI's, with settings named as the Python arguments are).

use pyo3::create_exception;
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

create_exception!(
    _jointid,
    JointidError,
    PyValueError,
    "Every error of jointid: its message names the argument, field or index at fault, the value and what is allowed."
);
create_exception!(
    _jointid,
    InputError,
    JointidError,
    "A file or a document (model, study, measured modes, levels, universal file) that cannot be read or is invalid."
);
create_exception!(
    _jointid,
    SettingError,
    JointidError,
    "A setting (keyword argument) outside what is allowed."
);
create_exception!(
    _jointid,
    ComputationError,
    JointidError,
    "Valid inputs on which the method cannot work: a mechanism, an eigensolution that fails, a rank-deficient system, an extraction that finds no mode."
);

/// A library error as `InputError`, with its whole chain of causes in the message.
pub fn input(e: impl std::fmt::Display) -> PyErr {
    InputError::new_err(e.to_string())
}

/// A library error as `SettingError`.
pub fn setting(e: impl std::fmt::Display) -> PyErr {
    SettingError::new_err(e.to_string())
}

/// A library error as `ComputationError`.
pub fn computation(e: impl std::fmt::Display) -> PyErr {
    ComputationError::new_err(e.to_string())
}

/// Registers the exceptions in the module.
pub fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("JointidError", py.get_type::<JointidError>())?;
    m.add("InputError", py.get_type::<InputError>())?;
    m.add("SettingError", py.get_type::<SettingError>())?;
    m.add("ComputationError", py.get_type::<ComputationError>())?;
    Ok(())
}

//! The `jointid._jointid` extension module.
use pyo3::prelude::*;

#[pymodule]
fn _jointid(_m: &Bound<'_, PyModule>) -> PyResult<()> {
    Ok(())
}

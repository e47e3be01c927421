//! The `jointid._jointid` extension module: bindings of the jointid library, no algorithm of
//! its own. Each function takes numpy arrays or the library's objects, runs the library with
//! the GIL released (Ctrl-C raises `KeyboardInterrupt` within a tick, see [`work`]) and
//! returns arrays or the CLI's texts (CSV, JSON), which the pure-Python package `jointid`
//! turns into dicts, DataFrames and exceptions named by argument.

mod diagnose;
mod errors;
mod extract;
mod identify;
mod measured;
mod model;
mod simulate;
mod study;
mod work;

use pyo3::prelude::*;

#[pymodule]
fn _jointid(m: &Bound<'_, PyModule>) -> PyResult<()> {
    errors::register(m)?;
    m.add_class::<model::Model>()?;
    m.add_class::<measured::Measured>()?;
    m.add_function(wrap_pyfunction!(identify::identify, m)?)?;
    m.add_function(wrap_pyfunction!(diagnose::diagnose, m)?)?;
    m.add_function(wrap_pyfunction!(study::study, m)?)?;
    m.add_function(wrap_pyfunction!(study::json_to_toml, m)?)?;
    m.add_function(wrap_pyfunction!(extract::extract, m)?)?;
    m.add_function(wrap_pyfunction!(extract::even_lines, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::simulate, m)?)?;
    m.add_function(wrap_pyfunction!(simulate::amplitude, m)?)?;
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    Ok(())
}

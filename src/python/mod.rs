//! The pyo3 binding layer, and the only pyo3 code: NumPy buffers in, core calls with the GIL
//! released and panics caught, NumPy buffers out (moved, not copied), and one exhaustive
//! mapping from [`KnitError`] to the Python exception hierarchy.

mod conversion;
mod detail;
mod errors;
mod knit;
mod measure;
mod pattern;
mod pile;
mod settings;
mod surface;
mod texture;
mod tuning_store;

use conversion::*;
use errors::*;
use knit::*;
use measure::*;
use pattern::*;
use surface::*;

use pyo3::prelude::*;

use crate::error::KnitError;

/// Raises InternalError from a deliberate panic in the core: proves that no Rust panic
/// crosses into Python. For tests.
#[pyfunction]
fn _force_internal_error(py: Python<'_>) -> PyResult<()> {
    guarded(py, || -> Result<(), KnitError> {
        panic!("forced internal error (test hook)")
    })
}

#[pymodule]
fn _core(m: &Bound<'_, PyModule>) -> PyResult<()> {
    let py = m.py();
    m.add("__version__", env!("CARGO_PKG_VERSION"))?;
    m.add("KnitError", py.get_type::<PyKnitError>())?;
    m.add("SurfaceError", py.get_type::<SurfaceError>())?;
    m.add("PatternError", py.get_type::<PatternError>())?;
    m.add("ParameterError", py.get_type::<ParameterError>())?;
    m.add("BudgetError", py.get_type::<BudgetError>())?;
    m.add("CancelledError", py.get_type::<CancelledError>())?;
    m.add("InternalError", py.get_type::<InternalError>())?;
    m.add_class::<PyGridSurface>()?;
    m.add_class::<PyMeshSurface>()?;
    m.add_class::<PyPattern>()?;
    m.add_class::<PyColorPattern>()?;
    m.add_class::<PyKnitResult>()?;
    m.add_class::<PyKnit>()?;
    m.add_function(wrap_pyfunction!(measure_clearance, m)?)?;
    m.add_function(wrap_pyfunction!(measure_cover, m)?)?;
    m.add_function(wrap_pyfunction!(_force_internal_error, m)?)?;
    m.add_function(wrap_pyfunction!(cancel, m)?)?;
    m.add_function(wrap_pyfunction!(check_budget, m)?)?;
    pile::register(m)?;
    texture::register(m)?;
    settings::register(m)?;
    detail::register(m)?;
    tuning_store::register(m)?;
    Ok(())
}

//! The tuning store's folder ([`crate::skeleton::tuning_store`]), set and read from Python.

use std::path::PathBuf;

use pyo3::prelude::*;

use crate::skeleton::tuning_store as store;

/// Keeps tunings in `path` (None: on no disk), for this process, overriding the
/// KNITWEAR_TUNING_STORE environment variable.
#[pyfunction]
#[pyo3(signature = (path))]
fn set_tuning_store(path: Option<PathBuf>) {
    store::set_dir(path);
}

/// The folder tunings are kept in, or None.
#[pyfunction]
fn tuning_store() -> Option<String> {
    store::dir().map(|d| d.to_string_lossy().into_owned())
}

pub(super) fn register(m: &Bound<'_, PyModule>) -> PyResult<()> {
    m.add_function(wrap_pyfunction!(set_tuning_store, m)?)?;
    m.add_function(wrap_pyfunction!(tuning_store, m)?)
}

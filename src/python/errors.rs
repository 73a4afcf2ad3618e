//! The core's typed errors as Python exceptions, and the guard every call into the core
//! runs under: the GIL released, and no Rust panic crossing into Python.

use std::panic::{catch_unwind, AssertUnwindSafe};

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use crate::error::KnitError;

create_exception!(
    knitwear,
    PyKnitError,
    PyException,
    "Base class of every error a user can cause."
);

create_exception!(
    knitwear,
    SurfaceError,
    PyKnitError,
    "The surface cannot be knitted."
);

create_exception!(
    knitwear,
    PatternError,
    PyKnitError,
    "A pattern that does not parse."
);

create_exception!(
    knitwear,
    ParameterError,
    PyKnitError,
    "A setting out of range."
);

create_exception!(
    knitwear,
    BudgetError,
    PyKnitError,
    "The output would exceed the budget."
);

create_exception!(
    knitwear,
    InternalError,
    PyKnitError,
    "A bug in knitwear; please report it."
);

/// The one mapping from core errors to Python exceptions.
pub(crate) fn to_py(e: KnitError) -> PyErr {
    let msg = e.to_string();
    match e {
        KnitError::Surface(_) => SurfaceError::new_err(msg),
        KnitError::Pattern(_) => PatternError::new_err(msg),
        KnitError::Parameter(_) => ParameterError::new_err(msg),
        KnitError::Budget(_) => BudgetError::new_err(msg),
        KnitError::Internal(_) => InternalError::new_err(msg),
    }
}

/// Runs core work without the GIL, turning a panic into a [`KnitError::Internal`].
pub(crate) fn guarded<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> Result<T, KnitError> + Send,
) -> PyResult<T> {
    py.detach(|| match catch_unwind(AssertUnwindSafe(f)) {
        Ok(r) => r,
        Err(payload) => {
            let what = payload
                .downcast_ref::<&str>()
                .map(|s| s.to_string())
                .or_else(|| payload.downcast_ref::<String>().cloned())
                .unwrap_or_else(|| "unknown panic".into());
            Err(KnitError::Internal(what))
        }
    })
    .map_err(to_py)
}

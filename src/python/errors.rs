//! The core's typed errors as Python exceptions, and the guard every call into the core
//! runs under: the GIL released, and no Rust panic crossing into Python.

use std::panic::{catch_unwind, AssertUnwindSafe};
use std::sync::mpsc::RecvTimeoutError;
use std::time::Duration;

use pyo3::create_exception;
use pyo3::exceptions::PyException;
use pyo3::prelude::*;

use crate::cancel as core_cancel;
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
    CancelledError,
    PyKnitError,
    "The call was stopped by knitwear.cancel() before it finished; nothing was kept."
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
        KnitError::Cancelled => CancelledError::new_err(msg),
        KnitError::Internal(_) => InternalError::new_err(msg),
    }
}

/// How often a call waiting on the core looks for Ctrl-C (Python runs signal handlers only
/// between bytecodes of the main thread, so the core's caller must look on their behalf).
const SIGNAL_POLL: Duration = Duration::from_millis(50);
/// Stack of the thread that runs the core: the size of a main thread's, so that nothing
/// deep the core does behaves differently from a call made on one.
const CORE_STACK_BYTES: usize = 8 << 20;

/// Runs core work without the GIL, turning a panic into a [`KnitError::Internal`].
///
/// The work runs on a thread of its own while this one waits, every [`SIGNAL_POLL`], for
/// the work or for Ctrl-C: a `KeyboardInterrupt` asks the core to stop ([`core_cancel::request`])
/// and is raised once the work has stopped, within a fraction of a second. A
/// `knitwear.cancel()` from another thread (Esc in Blender) stops it with a
/// `CancelledError`.
pub(crate) fn guarded<T: Send>(
    py: Python<'_>,
    f: impl FnOnce() -> Result<T, KnitError> + Send,
) -> PyResult<T> {
    let _call = core_cancel::Call::begin();
    let mut interrupted: Option<PyErr> = None;
    let result = py.detach(|| {
        std::thread::scope(|s| {
            let (done, finished) = std::sync::mpsc::channel();
            let worker = std::thread::Builder::new()
                .name("knitwear-call".into())
                .stack_size(CORE_STACK_BYTES)
                .spawn_scoped(s, move || {
                    let r = catch_unwind(AssertUnwindSafe(f));
                    // The waiter may have gone only if it panicked itself: nothing to tell.
                    let _ = done.send(());
                    r
                });
            let worker = match worker {
                Ok(w) => w,
                Err(e) => {
                    return Err(KnitError::Internal(format!(
                        "cannot start the core's thread: {e}"
                    )))
                }
            };
            while let Err(RecvTimeoutError::Timeout) = finished.recv_timeout(SIGNAL_POLL) {
                if interrupted.is_none() {
                    if let Err(e) = Python::attach(|py| py.check_signals()) {
                        interrupted = Some(e);
                        core_cancel::request();
                    }
                }
            }
            match worker.join() {
                Ok(Ok(r)) => r,
                Ok(Err(payload)) | Err(payload) => Err(KnitError::Internal(panic_text(&payload))),
            }
        })
    });
    if let Some(e) = interrupted {
        return Err(e);
    }
    result.map_err(to_py)
}

fn panic_text(payload: &Box<dyn std::any::Any + Send>) -> String {
    payload
        .downcast_ref::<&str>()
        .map(|s| s.to_string())
        .or_else(|| payload.downcast_ref::<String>().cloned())
        .unwrap_or_else(|| "unknown panic".into())
}

/// Stops every knitwear call now running, from any thread (the add-on calls this when the
/// user presses Esc): each raises `CancelledError` within a fraction of a second, having
/// kept nothing. A call that starts afterwards runs normally.
#[pyfunction]
pub(crate) fn cancel() {
    core_cancel::request();
}

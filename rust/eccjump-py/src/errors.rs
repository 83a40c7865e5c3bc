//! The core's one error enum, mapped to Python exceptions, and the way every long call runs:
//! with the GIL released and Ctrl-C honoured between chunks of work.

use eccjump_core::error::try_filled;
use eccjump_core::Error;
use pyo3::exceptions::{PyKeyboardInterrupt, PyMemoryError, PyRuntimeError, PyValueError};
use pyo3::prelude::*;
use std::sync::Mutex;

/// Bad input (`InvalidParameter`, `NoBracket`, `AtIndex`) → `ValueError`; an output too large
/// → `MemoryError`; an interruption → `KeyboardInterrupt`; a failure to converge is ours →
/// `RuntimeError` (no public call reaches it: the core consumes those internally).
pub fn to_py(err: Error) -> PyErr {
    match err {
        Error::InvalidParameter { .. } | Error::NoBracket { .. } | Error::AtIndex { .. } => {
            PyValueError::new_err(err.to_string())
        }
        Error::OutOfMemory { .. } => PyMemoryError::new_err(err.to_string()),
        Error::Interrupted => PyKeyboardInterrupt::new_err("interrupted"),
        Error::NoConvergence { .. } => PyRuntimeError::new_err(err.to_string()),
    }
}

/// Runs `work` with the GIL released. It gets a `stop` to ask between chunks of work: `stop`
/// takes the GIL for a moment and runs Python's signal handlers; if one raises (Ctrl-C →
/// `KeyboardInterrupt`), the work ends and that exception is raised here.
pub fn detached<T: Send>(
    py: Python<'_>,
    work: impl FnOnce(&dyn Fn() -> bool) -> Result<T, Error> + Send,
) -> PyResult<T> {
    let pending: Mutex<Option<PyErr>> = Mutex::new(None);
    let out = py.detach(|| {
        let stop = || {
            Python::attach(|py| match py.check_signals() {
                Ok(()) => false,
                Err(e) => {
                    if let Ok(mut p) = pending.lock() {
                        *p = Some(e);
                    }
                    true
                }
            })
        };
        work(&stop)
    });
    match out {
        Ok(v) => Ok(v),
        Err(Error::Interrupted) => Err(pending
            .into_inner()
            .ok()
            .flatten()
            .unwrap_or_else(|| to_py(Error::Interrupted))),
        Err(e) => Err(to_py(e)),
    }
}

/// `work` run by [`detached`] into `len` values `init` it overwrites (an error in `len`, e.g.
/// an axis that is empty, is raised first), allocated fallibly: a `MemoryError` naming
/// `what` if they do not fit. Every call that fills one value per point goes through here.
pub fn detached_filled<T: Clone + Send>(
    py: Python<'_>,
    what: &'static str,
    len: Result<usize, Error>,
    init: T,
    work: impl FnOnce(&mut [T], &dyn Fn() -> bool) -> Result<(), Error> + Send,
) -> PyResult<Vec<T>> {
    let len = len.map_err(to_py)?;
    detached(py, |stop| {
        let mut out = try_filled(what, len, init)?;
        work(&mut out, stop)?;
        Ok(out)
    })
}

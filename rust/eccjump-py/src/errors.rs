//! The core's one error enum, mapped to Python exceptions.

use eccjump_core::Error;
use pyo3::exceptions::{PyRuntimeError, PyValueError};
use pyo3::PyErr;

/// `InvalidParameter` and `NoBracket` are the caller's input → `ValueError`; a failure to
/// converge is ours → `RuntimeError`.
pub fn to_py(err: Error) -> PyErr {
    match err {
        Error::InvalidParameter { .. } | Error::NoBracket { .. } => {
            PyValueError::new_err(err.to_string())
        }
        Error::NoConvergence { .. } => PyRuntimeError::new_err(err.to_string()),
    }
}

//! The one error type of the core. The Python bridge maps every variant to a Python
//! exception (`InvalidParameter` → `ValueError`), so no failure ever surfaces as a panic.

use thiserror::Error;

/// Everything that can go wrong in the core.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A parameter is NaN, infinite or outside its allowed range.
    #[error("{name} = {value} is outside the allowed range {allowed}")]
    InvalidParameter {
        name: &'static str,
        value: f64,
        allowed: String,
    },
    /// A root finder was handed an interval whose ends do not bracket a root.
    #[error("no sign change on [{a}, {b}]: f(a) = {fa}, f(b) = {fb}")]
    NoBracket { a: f64, b: f64, fa: f64, fb: f64 },
    /// An iteration limit was reached before convergence.
    #[error("{what} did not converge within {iterations} iterations")]
    NoConvergence {
        what: &'static str,
        iterations: usize,
    },
}

/// Shorthand used throughout the core.
pub type Result<T> = std::result::Result<T, Error>;

/// Checks that `value` is finite and lies in `[lo, hi]`, naming the parameter otherwise.
pub fn check_range(name: &'static str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            allowed: format!("[{lo}, {hi}]"),
        })
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn check_positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::InvalidParameter {
            name,
            value,
            allowed: "(0, inf)".to_string(),
        })
    }
}

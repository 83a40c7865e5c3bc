//! The one error type of the core. The Python bridge maps every variant to a Python
//! exception (`InvalidParameter` → `ValueError`), so no failure ever surfaces as a panic.

use thiserror::Error;

/// Everything that can go wrong in the core.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A parameter is NaN, infinite or outside its allowed range.
    #[error("{name} = {} is outside the allowed range {allowed}", short(*value))]
    InvalidParameter {
        /// The parameter's name as the Python API spells it.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, e.g. "[0, 1]".
        allowed: String,
    },
    /// A root finder was handed an interval whose ends do not bracket a root.
    #[error("no sign change on [{a}, {b}]: f(a) = {fa}, f(b) = {fb}")]
    NoBracket {
        /// Left end.
        a: f64,
        /// Right end.
        b: f64,
        /// f(a).
        fa: f64,
        /// f(b).
        fb: f64,
    },
    /// An iteration limit was reached before convergence.
    #[error("{what} did not converge within {iterations} iterations")]
    NoConvergence {
        /// What did not converge.
        what: &'static str,
        /// The iteration limit.
        iterations: usize,
    },
}

/// Shorthand used throughout the core.
pub type Result<T> = std::result::Result<T, Error>;

/// A number as it appears in a message: short (at most 17 significant digits, exponent
/// form for very large or small magnitudes), ±f64::MAX as ±inf (an open end).
pub fn short(x: f64) -> String {
    if x >= f64::MAX {
        "inf".to_string()
    } else if x <= -f64::MAX {
        "-inf".to_string()
    } else if x != 0.0 && (x.abs() >= 1e9 || x.abs() < 1e-5) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Checks that `value` is finite and lies in `[lo, hi]`, naming the parameter otherwise
/// (hi = f64::MAX reads as an open end, "inf)").
pub fn check_range(name: &'static str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        let close = if hi >= f64::MAX { ")" } else { "]" };
        Err(Error::InvalidParameter {
            name,
            value,
            allowed: format!("[{}, {}{close}", short(lo), short(hi)),
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

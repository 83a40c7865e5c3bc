//! Parsing of the options shared by the classification entry points.

use crate::rule::parse_rule;
use eccjump_core::jarm::JarmOptions;
use eccjump_core::region::Method;
use pyo3::exceptions::PyValueError;
use pyo3::{FromPyObject, PyResult};

/// The options of a classification call, passed from Python as one tuple
/// `(n, rule, method, rtol, atol, theta0, omega0, max_turns, refine_extrema, n_threads)`
/// (built and documented by `eccjump.classification`).
#[derive(FromPyObject)]
pub struct CallOptions(
    Option<u32>,
    String,
    String,
    f64,
    f64,
    f64,
    f64,
    u32,
    bool,
    usize,
);

impl CallOptions {
    /// The validated classification options, route and thread count.
    pub fn parse(&self) -> PyResult<(JarmOptions, Method, usize)> {
        let CallOptions(n, rule, method, rtol, atol, theta0, omega0, max_turns, refine, threads) =
            self;
        let opts = jarm_options(rule, *n, *max_turns, *theta0, *omega0, *refine)?;
        Ok((opts, parse_method(method, *rtol, *atol)?, *threads))
    }
}

/// The route: "closed_form" or "ode" (with its tolerances).
pub fn parse_method(method: &str, rtol: f64, atol: f64) -> PyResult<Method> {
    match method {
        "closed_form" => Ok(Method::ClosedForm),
        "ode" => {
            if !(rtol.is_finite() && (1e-15..=1.0).contains(&rtol)) {
                return Err(PyValueError::new_err(format!(
                    "rtol = {rtol} is outside the allowed range [1e-15, 1]"
                )));
            }
            if !(atol.is_finite() && atol > 0.0) {
                return Err(PyValueError::new_err(format!(
                    "atol = {atol} is outside the allowed range (0, inf)"
                )));
            }
            Ok(Method::Ode { rtol, atol })
        }
        other => Err(PyValueError::new_err(format!(
            "method = {other:?} is not one of 'closed_form', 'ode'"
        ))),
    }
}

/// Classification options; `n = None` means the first jump, whatever its turn.
pub fn jarm_options(
    rule: &str,
    n: Option<u32>,
    max_turns: u32,
    theta0: f64,
    omega0: f64,
    refine_extrema: bool,
) -> PyResult<JarmOptions> {
    if n == Some(0) {
        return Err(PyValueError::new_err(
            "n = 0 is outside the allowed range [1, inf) (None: the first jump)",
        ));
    }
    if max_turns == 0 {
        return Err(PyValueError::new_err(
            "max_turns = 0 is outside the allowed range [1, inf)",
        ));
    }
    for (name, v) in [("theta0", theta0), ("omega0", omega0)] {
        if !v.is_finite() {
            return Err(PyValueError::new_err(format!(
                "{name} = {v} is outside the allowed range (-inf, inf)"
            )));
        }
    }
    if omega0 < 0.0 {
        return Err(PyValueError::new_err(format!(
            "omega0 = {omega0} is outside the allowed range [0, inf) (rolling down the ramp)"
        )));
    }
    Ok(JarmOptions {
        rule: parse_rule(rule)?,
        n: n.unwrap_or(0),
        max_turns,
        theta0,
        omega0,
        refine_extrema,
    })
}

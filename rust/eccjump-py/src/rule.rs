//! Parsing of the lift-off rule name shared by every entry point.

use eccjump_core::rule::Rule;
use pyo3::exceptions::PyValueError;
use pyo3::PyResult;

pub fn parse_rule(rule: &str) -> PyResult<Rule> {
    match rule {
        "paper" => Ok(Rule::Paper),
        "normal_force" => Ok(Rule::NormalForce),
        other => Err(PyValueError::new_err(format!(
            "rule = {other:?} is not one of 'paper', 'normal_force'"
        ))),
    }
}

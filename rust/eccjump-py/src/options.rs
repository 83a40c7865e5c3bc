//! The options of the classification entry points, as one typed struct taken from the
//! Python layer's dict (built and documented by `eccjump.classification`). Only names are
//! converted here; every range is checked by the core.

use crate::errors::to_py;
use eccjump_core::jarm::{JarmOptions, Method};
use eccjump_core::ode::Method as Integrator;
use eccjump_core::Rule;
use pyo3::exceptions::PyValueError;
use pyo3::{FromPyObject, PyResult};

/// `{"rule", "method", "rtol", "atol", "theta0", "omega0", "max_turns", "refine_extrema",
/// "stop_at_slip", "n_threads", "integrator"}`.
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct CallOptions {
    rule: String,
    method: String,
    rtol: f64,
    atol: f64,
    theta0: f64,
    omega0: f64,
    max_turns: u32,
    refine_extrema: bool,
    stop_at_slip: bool,
    n_threads: usize,
    integrator: String,
}

impl CallOptions {
    /// The classification options (turn `n`, 0 = the first jump), route and thread count.
    pub fn parse(&self, n: u32) -> PyResult<(JarmOptions, Method, usize)> {
        // Checked for every route: the closed form ignores them but they are recorded.
        Method::check_tolerances(self.rtol, self.atol).map_err(to_py)?;
        let pair = parse_integrator(&self.integrator)?;
        let method =
            Method::from_name(&self.method, self.rtol, self.atol, pair).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "method = {:?} is not one of 'closed_form', 'ode'",
                    self.method
                ))
            })?;
        let opts = JarmOptions {
            rule: parse_rule(&self.rule)?,
            n,
            max_turns: self.max_turns,
            theta0: self.theta0,
            omega0: self.omega0,
            refine_extrema: self.refine_extrema,
            stop_at_slip: self.stop_at_slip,
        };
        Ok((opts, method, self.n_threads))
    }
}

/// The Runge–Kutta pair named `integrator` ([`Integrator::name`]).
pub fn parse_integrator(integrator: &str) -> PyResult<Integrator> {
    Integrator::from_name(integrator).ok_or_else(|| {
        let names: Vec<String> = Integrator::ALL.map(|m| format!("'{}'", m.name())).into();
        PyValueError::new_err(format!(
            "integrator = {integrator:?} is not one of {}",
            names.join(", ")
        ))
    })
}

/// The lift-off rule named `rule`.
pub fn parse_rule(rule: &str) -> PyResult<Rule> {
    Rule::from_name(rule).ok_or_else(|| {
        PyValueError::new_err(format!(
            "rule = {rule:?} is not one of 'paper', 'normal_force'"
        ))
    })
}

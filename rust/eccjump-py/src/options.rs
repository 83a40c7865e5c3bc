//! Names to the core's enums (rule, integrator, route), and the options of the
//! classification entry points gathered for their conversion. Only names are converted
//! here; every range is checked by the core.

use crate::errors::to_py;
use eccjump_core::jarm::{JarmOptions, Method};
use eccjump_core::ode::Method as Integrator;
use eccjump_core::Rule;
use pyo3::exceptions::PyValueError;
use pyo3::PyResult;

/// The options of `jarm_points` and `jarm_grid`, their keyword-only parameters (those of
/// `eccjump._bridge.CallOptions` but the turn).
pub struct CallOptions<'a> {
    pub rule: &'a str,
    pub method: &'a str,
    pub rtol: f64,
    pub atol: f64,
    pub theta0: f64,
    pub omega0: f64,
    pub max_turns: u32,
    pub refine_extrema: bool,
    pub stop_at_slip: bool,
    pub n_threads: usize,
    pub integrator: &'a str,
}

impl CallOptions<'_> {
    /// The classification options (turn `n`, 0 = the first jump), route and thread count.
    pub fn parse(&self, n: u32) -> PyResult<(JarmOptions, Method, usize)> {
        // Checked for every route: the closed form ignores them but they are recorded.
        Method::check_tolerances(self.rtol, self.atol).map_err(to_py)?;
        let pair = parse_integrator(self.integrator)?;
        let method =
            Method::from_name(self.method, self.rtol, self.atol, pair).ok_or_else(|| {
                PyValueError::new_err(format!(
                    "method = {:?} is not one of 'closed_form', 'ode'",
                    self.method
                ))
            })?;
        let opts = JarmOptions {
            rule: parse_rule(self.rule)?,
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

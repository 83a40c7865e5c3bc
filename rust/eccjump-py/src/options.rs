//! Names to the core's enums (rule, integrator, route), and the option objects that several
//! entry points share: [`ClassifyOptions`] (`jarm_points`, `jarm_grid`),
//! [`BoundaryOptions`] (the three boundary searches) and [`MotionMapOptions`] (`motion_grid`,
//! `motion_points`). Only names are converted here; every range is checked by the core.

use crate::errors::to_py;
use eccjump_core::jarm::{JarmOptions, Method};
use eccjump_core::maps::boundary::boundary_options;
use eccjump_core::maps::motion::MotionMapOptions as MapOptions;
use eccjump_core::ode::{Integrator, SolverOptions};
use eccjump_core::{Cylinder, Ramp, Rule};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// The options of a classification call but the turn, converted once to the core's types:
/// made in Python (`eccjump._base.bridge`) from keyword-only plain values named as `eccjump.jarm`
/// names them, and passed to `jarm_points` or `jarm_grid`.
#[pyclass(frozen, module = "eccjump._core")]
pub struct ClassifyOptions {
    /// The classification options, the turn 0 (each call gives its own).
    jarm: JarmOptions,
    /// The route, with its tolerances and pair.
    method: Method,
    /// Threads of the call (0 = one per core).
    n_threads: usize,
}

#[pymethods]
impl ClassifyOptions {
    /// Converts the names (ValueError for an unknown rule, route or pair) and checks the
    /// tolerances, for every route: the closed form ignores them but they are recorded.
    #[new]
    #[pyo3(signature = (*, rule, method, rtol, atol, theta0, omega0, max_turns,
                        refine_extrema, stop_at_slip, n_threads, integrator))]
    #[allow(clippy::too_many_arguments)] // the options of `eccjump.jarm`, keyword-only
    fn new(
        rule: &str,
        method: &str,
        rtol: f64,
        atol: f64,
        theta0: f64,
        omega0: f64,
        max_turns: u32,
        refine_extrema: bool,
        stop_at_slip: bool,
        n_threads: usize,
        integrator: &str,
    ) -> PyResult<Self> {
        // Checked for either route: the closed form ignores them, but its results record them.
        SolverOptions::check_tolerances(rtol, atol).map_err(to_py)?;
        let pair = parse_integrator(integrator)?;
        let method = Method::from_name(method, rtol, atol, pair).ok_or_else(|| {
            PyValueError::new_err(format!(
                "method = {method:?} is not one of 'closed_form', 'ode'"
            ))
        })?;
        let jarm = JarmOptions {
            rule: parse_rule(rule)?,
            n: 0,
            max_turns,
            theta0,
            omega0,
            refine_extrema,
            stop_at_slip,
        };
        Ok(Self {
            jarm,
            method,
            n_threads,
        })
    }
}

impl ClassifyOptions {
    /// The classification options on turn `n` (0 = the first jump), route and thread count.
    pub fn on_turn(&self, n: u32) -> (JarmOptions, Method, usize) {
        (JarmOptions { n, ..self.jarm }, self.method, self.n_threads)
    }
}

/// The options every boundary search takes (`alpha_intervals`, `alpha_interval_around`,
/// `mu_s_min_path`): the turn, the rule and the threads, made in Python
/// (`eccjump.classification.boundary`) from keyword-only plain values named as there.
#[pyclass(frozen, module = "eccjump._core")]
pub struct BoundaryOptions {
    /// The core's classification options of a boundary search.
    pub jarm: JarmOptions,
    /// Threads of the call (0 = one per core).
    pub n_threads: usize,
}

#[pymethods]
impl BoundaryOptions {
    /// Converts the rule's name (ValueError for an unknown one).
    #[new]
    #[pyo3(signature = (*, n, rule, n_threads))]
    fn new(n: u32, rule: &str, n_threads: usize) -> PyResult<Self> {
        Ok(Self {
            jarm: boundary_options(parse_rule(rule)?, n),
            n_threads,
        })
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

/// The options every point of a motion map or of `motion_points` runs with, and the threads
/// of the call: made in Python (`eccjump.motion.options.MotionOptions.bridge`) from
/// keyword-only plain values named as `eccjump.motion_map` names them (ValueError for an
/// unknown rule or pair; ranges are checked by the core).
#[pyclass(frozen, module = "eccjump._core")]
pub struct MotionMapOptions {
    /// The options every point shares.
    pub map: MapOptions,
    /// Threads of the call (0 = one per core).
    pub n_threads: usize,
}

#[pymethods]
impl MotionMapOptions {
    /// Converts the rule's and the pair's names.
    #[new]
    #[pyo3(signature = (*, rule, t_max, max_transitions, rtol, atol, max_steps, n_threads,
                        integrator))]
    #[allow(clippy::too_many_arguments)] // the options of `eccjump.motion_map`, keyword-only
    fn new(
        rule: &str,
        t_max: f64,
        max_transitions: usize,
        rtol: f64,
        atol: f64,
        max_steps: usize,
        n_threads: usize,
        integrator: &str,
    ) -> PyResult<Self> {
        let map = MapOptions {
            rule: parse_rule(rule)?,
            t_max,
            max_transitions,
            solver: solver_options(rtol, atol, max_steps, integrator)?,
        };
        Ok(Self { map, n_threads })
    }
}

/// The solver options of a run: the tolerances, the step budget and the pair by name.
pub fn solver_options(
    rtol: f64,
    atol: f64,
    max_steps: usize,
    integrator: &str,
) -> PyResult<SolverOptions> {
    Ok(SolverOptions {
        rtol,
        atol,
        max_steps,
        method: parse_integrator(integrator)?,
        ..SolverOptions::default()
    })
}

/// The ramp of angle `alpha` under the body (χ, k_m); ValueError naming a bad parameter.
pub fn ramp(chi: f64, km: f64, alpha: f64) -> PyResult<Ramp> {
    Ramp::new(Cylinder::new(chi, km).map_err(to_py)?, alpha).map_err(to_py)
}

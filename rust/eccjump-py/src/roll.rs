//! `roll`: one pure-rolling run, computed with the GIL released, returned by name as plain
//! values (`eccjump.roll` makes the `RollResult`).

use crate::columns::{dense_rows, Records};
use crate::errors::detached;
use crate::names::ROLL_EVENTS;
use crate::options::{parse_rule, ramp, solver_options};
use eccjump_core::mechanics::friction::friction_ratio;
use eccjump_core::modes::rolling::run::{roll_until, RollOptions, RollStatus};
use eccjump_core::modes::rolling::solution::RollSolution;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Integrates pure rolling of the body (χ, k_m) on a ramp of angle α, with the options of
/// `eccjump.roll` (keyword-only, named as there). Bad input raises ValueError (from the
/// core's checks: the ramp, then the rule and the pair by name, then the options) before
/// any work is done. The run comes back by the field names of `RollResult`: the series
/// (numpy arrays), `events` (one list per field of `Event`), `terminal_event` (a name or
/// None), `status`, `message`, `nfev` and `sol` (None unless `dense_output`).
#[pyfunction]
#[pyo3(signature = (chi, km, alpha, *, theta0, omega0, mu_s, t_max, theta_max, rtol, atol,
                    dense_output, max_steps, rule, integrator))]
#[allow(clippy::too_many_arguments)] // the options of one run
pub fn roll<'py>(
    py: Python<'py>,
    chi: f64,
    km: f64,
    alpha: f64,
    theta0: f64,
    omega0: f64,
    mu_s: Option<f64>,
    t_max: f64,
    theta_max: f64,
    rtol: f64,
    atol: f64,
    dense_output: bool,
    max_steps: usize,
    rule: &str,
    integrator: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let ramp = ramp(chi, km, alpha)?;
    let opts = RollOptions {
        theta0,
        omega0,
        mu_s,
        t_max,
        theta_max,
        rule: parse_rule(rule)?,
        solver: solver_options(rtol, atol, max_steps, integrator)?,
        dense_output,
    };
    let run = detached(py, |stop| roll_until(&ramp, &opts, stop))?;
    let terminal_event = match run.status {
        RollStatus::Event(e) => Some(ROLL_EVENTS.of(py, e)),
        _ => None,
    };
    let events = Records::new(py, &run.events)
        .field(intern!(py, "name"), |e| ROLL_EVENTS.of(py, e.event))?
        .field(intern!(py, "t"), |e| e.t)?
        .field(intern!(py, "theta"), |e| e.theta)?
        .field(intern!(py, "omega"), |e| e.omega)?;
    let d = PyDict::new(py);
    // The record's vectors move into numpy (no copy).
    let series = [
        (intern!(py, "t"), run.t),
        (intern!(py, "theta"), run.theta),
        (intern!(py, "omega"), run.omega),
        (intern!(py, "omega_dot"), run.omega_dot),
        (intern!(py, "Fx"), run.fx),
        (intern!(py, "Fy"), run.fy),
        (intern!(py, "l"), run.l),
        (intern!(py, "friction_ratio"), run.ratio),
    ];
    for (name, values) in series {
        d.set_item(name, values.into_pyarray(py))?;
    }
    d.set_item(intern!(py, "events"), events.into_dict())?;
    d.set_item(intern!(py, "terminal_event"), terminal_event)?;
    d.set_item(intern!(py, "status"), run.status.code())?;
    d.set_item(intern!(py, "message"), run.status.message())?;
    d.set_item(intern!(py, "nfev"), run.nfev)?;
    let sol = run.dense.map(|sol| DenseSolution { sol });
    d.set_item(intern!(py, "sol"), sol)?;
    Ok(d)
}

/// The dense output of a run (`RollResult.sol`): the state and the kinematics at any time
/// of the run, evaluated by the core; it ends where the run ends.
#[pyclass(frozen, module = "eccjump._core")]
pub struct DenseSolution {
    sol: RollSolution,
}

impl DenseSolution {
    /// The times covered, [start, end], for the messages about times outside them.
    fn range(&self) -> (f64, f64) {
        (self.sol.t_start(), self.sol.t_end)
    }
}

#[pymethods]
impl DenseSolution {
    /// First time covered.
    #[getter]
    fn t_min(&self) -> f64 {
        self.sol.t_start()
    }

    /// Last time covered: the end of the run (its terminal event).
    #[getter]
    fn t_max(&self) -> f64 {
        self.sol.t_end
    }

    /// (θ, θ̇) at the times `t` (1-D), shape (2, len(t)); a ValueError names the first time
    /// outside [t_min, t_max], a MemoryError a request too large for memory.
    fn states<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        dense_rows(py, "the dense states", t.as_slice()?, self.range(), |ti| {
            self.sol.state(ti).map(|y| [y[0], y[1]])
        })
    }

    /// θ, θ̇, θ̈, F_x, F_y and the friction ratio at the times `t` (1-D), as a dict of arrays
    /// (the rows of one (6, len(t)) array; errors as for `states`).
    fn kinematics<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let at = |ti| {
            let k = self.sol.kinematics(ti)?;
            let ratio = friction_ratio(k.fx, k.fy);
            Some([k.theta, k.omega, k.omega_dot, k.fx, k.fy, ratio])
        };
        let rows = dense_rows(py, "the dense kinematics", t.as_slice()?, self.range(), at)?;
        let d = PyDict::new(py);
        for (k, name) in ["theta", "omega", "omega_dot", "Fx", "Fy", "ratio"]
            .into_iter()
            .enumerate()
        {
            d.set_item(name, rows.get_item(k)?)?;
        }
        Ok(d)
    }
}

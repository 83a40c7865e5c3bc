//! `roll`: one pure-rolling run, computed with the GIL released, returned as a `RollResult`.

use crate::body::body_of;
use crate::columns::dense_rows;
use crate::errors::{detached, to_py};
use crate::names::ROLL_EVENTS;
use crate::options::{parse_integrator, parse_rule};
use crate::plain;
use crate::records::{RecordType, ResultType};
use eccjump_core::mechanics::friction::friction_ratio;
use eccjump_core::modes::rolling::run::{roll_until, RollOptions, RollRun, RollStatus};
use eccjump_core::modes::rolling::solution::RollSolution;
use eccjump_core::ode::SolverOptions;
use eccjump_core::Ramp;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyDict, PyString, PyType};

/// One event met: (name, t, θ, θ̇), `Event`'s fields.
type EventTuple<'py> = (Bound<'py, PyString>, f64, f64, f64);

/// `eccjump.rolling.Event`.
static EVENT: RecordType = RecordType::new("eccjump.rolling", "Event");

/// `eccjump.rolling.RollResult`, by its fields.
static ROLL_RESULT: ResultType<19> = ResultType::new(
    "eccjump.rolling",
    "RollResult",
    [
        "body",
        "alpha",
        "mu_s",
        "rule",
        "t",
        "theta",
        "omega",
        "omega_dot",
        "Fx",
        "Fy",
        "l",
        "friction_ratio",
        "events",
        "terminal_event",
        "status",
        "message",
        "nfev",
        "sol",
        "units",
    ],
);

/// `eccjump.dense.DenseSolution`, the Python face of [`DenseSolution`].
static DENSE_SOLUTION: PyOnceLock<Py<PyType>> = PyOnceLock::new();

/// Integrates pure rolling of `body` (an `eccjump.Cylinder`: its χ and k_m) on a ramp of
/// angle α; returns the run as an `eccjump.rolling.RollResult`. The parameters are those
/// of `eccjump.roll`, in its order (tested), and come positionally: matching thirteen
/// keywords by name took 0.15 µs of a 9 µs call. None, and nothing done, when an argument
/// is not of its plain type ([`crate::plain`]). Bad input raises ValueError (from the
/// core's checks) before any work is done.
#[pyfunction]
#[pyo3(signature = (body, alpha, theta0, omega0, mu_s, t_max, theta_max, rtol, atol,
                    dense_output, max_steps, rule, integrator, /))]
#[allow(clippy::too_many_arguments)] // the options of one run
pub fn roll<'py>(
    py: Python<'py>,
    body: &Bound<'py, PyAny>,
    alpha: &Bound<'py, PyAny>,
    theta0: &Bound<'py, PyAny>,
    omega0: &Bound<'py, PyAny>,
    mu_s: &Bound<'py, PyAny>,
    t_max: &Bound<'py, PyAny>,
    theta_max: &Bound<'py, PyAny>,
    rtol: &Bound<'py, PyAny>,
    atol: &Bound<'py, PyAny>,
    dense_output: &Bound<'py, PyAny>,
    max_steps: &Bound<'py, PyAny>,
    rule: &Bound<'py, PyAny>,
    integrator: &Bound<'py, PyAny>,
) -> PyResult<Option<Bound<'py, PyAny>>> {
    let (
        Some(alpha_value),
        Some(theta0),
        Some(omega0),
        Some(mu_s_value),
        Some(t_max),
        Some(theta_max),
        Some(rtol),
        Some(atol),
        Some(dense_output),
        Some(max_steps),
        Some(rule),
        Some(integrator),
    ) = (
        plain::float(alpha),
        plain::float(theta0),
        plain::float(omega0),
        plain::optional_float(mu_s),
        plain::float(t_max),
        plain::float(theta_max),
        plain::float(rtol),
        plain::float(atol),
        plain::flag(dense_output),
        plain::count(max_steps),
        plain::text(rule),
        plain::text(integrator),
    )
    else {
        return Ok(None);
    };
    let ramp = Ramp::new(body_of(body)?, alpha_value).map_err(to_py)?;
    let opts = RollOptions {
        theta0,
        omega0,
        mu_s: mu_s_value,
        t_max,
        theta_max,
        rule: parse_rule(rule.to_str()?)?,
        solver: SolverOptions {
            rtol,
            atol,
            max_steps,
            method: parse_integrator(integrator.to_str()?)?,
            ..SolverOptions::default()
        },
        dense_output,
    };
    let run = detached(py, |stop| roll_until(&ramp, &opts, stop))?;
    let inputs = [
        body.clone(),
        alpha.clone(),
        mu_s.clone(),
        rule.clone().into_any(),
    ];
    to_result(py, inputs, run).map(Some)
}

/// The `RollResult` of `run`, after its `inputs` (body, α, μ_s, rule).
fn to_result<'py>(
    py: Python<'py>,
    [body, alpha, mu_s, rule]: [Bound<'py, PyAny>; 4],
    run: RollRun,
) -> PyResult<Bound<'py, PyAny>> {
    let events = EVENT.tuple_of(
        py,
        run.events
            .iter()
            .map(|e| -> EventTuple<'py> { (ROLL_EVENTS.of(py, e.event), e.t, e.theta, e.omega) }),
    )?;
    let terminal_event = match run.status {
        RollStatus::Event(e) => ROLL_EVENTS.of(py, e).into_any(),
        _ => py.None().into_bound(py),
    };
    let sol = match run.dense {
        Some(sol) => DENSE_SOLUTION
            .import(py, "eccjump.dense", "DenseSolution")?
            .call1((Bound::new(py, DenseSolution { sol })?,))?,
        None => py.None().into_bound(py),
    };
    // The record's vectors move into numpy (no copy). One (8, n) array with row views was
    // measured too: 0.05 µs faster, but it copies the record, doubling the peak memory of
    // a long run.
    ROLL_RESULT.make(
        py,
        [
            body,
            alpha,
            mu_s,
            rule,
            run.t.into_pyarray(py).into_any(),
            run.theta.into_pyarray(py).into_any(),
            run.omega.into_pyarray(py).into_any(),
            run.omega_dot.into_pyarray(py).into_any(),
            run.fx.into_pyarray(py).into_any(),
            run.fy.into_pyarray(py).into_any(),
            run.l.into_pyarray(py).into_any(),
            run.ratio.into_pyarray(py).into_any(),
            events.into_any(),
            terminal_event,
            run.status.code().into_pyobject(py)?.into_any(),
            run.status.message().into_pyobject(py)?.into_any(),
            run.nfev.into_pyobject(py)?.into_any(),
            sol,
            py.None().into_bound(py),
        ],
    )
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

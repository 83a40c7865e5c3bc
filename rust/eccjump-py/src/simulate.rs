//! `simulate`: one full-motion run (rolling, slipping, flight, landing), computed with the
//! GIL released, returned by name as plain values (`eccjump.simulate` makes the
//! `MotionResult`).

use crate::columns::{dense_rows, set_column, Records};
use crate::errors::detached;
use crate::names::{MODES, REASONS, STATUSES};
use crate::options::{parse_rule, ramp, solver_options};
use eccjump_core::modes::contact::ContactLaw;
use eccjump_core::motion::record::{MotionStatus, Point};
use eccjump_core::motion::sensitivities::{
    sensitivities as motion_sensitivities, Sensitivities, PARAMETERS,
};
use eccjump_core::motion::solution::MotionSolution;
use eccjump_core::motion::{simulate_until, MotionRun, SimOptions};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArray3, PyArrayMethods, PyReadonlyArray1};
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// A run's sensitivities: d(t, θ)/dp of each transition and its flag.
type Derivatives<'py> = (Bound<'py, PyArray3<f64>>, Bound<'py, PyArray1<bool>>);

/// The full motion of the body (χ, k_m) on a ramp of angle α, with the options of
/// `eccjump.simulate` (keyword-only, named as there; μ_k resolved). Bad input raises
/// ValueError (from the core's checks) before any work is done. The run comes back by the
/// field names of `MotionResult`: the recorded points (one numpy array per field), the
/// records `transitions`, `flights`, `impacts`, `segments` (each one list per field of its
/// named tuple), the energy ledger, `status`, `message`, `nfev`, `sol` and the
/// sensitivities `d_transitions`, `d_singular` (each None unless asked for).
#[pyfunction]
#[pyo3(signature = (chi, km, alpha, *, mu_s, mu_k, restitution, rule, theta0, omega0, slip0,
                    t_max, l_max, max_transitions, rtol, atol, max_steps, dense_output,
                    integrator, sensitivities))]
#[allow(clippy::too_many_arguments)] // the options of one run
pub fn simulate<'py>(
    py: Python<'py>,
    chi: f64,
    km: f64,
    alpha: f64,
    mu_s: f64,
    mu_k: f64,
    restitution: f64,
    rule: &str,
    theta0: f64,
    omega0: f64,
    slip0: f64,
    t_max: f64,
    l_max: f64,
    max_transitions: usize,
    rtol: f64,
    atol: f64,
    max_steps: usize,
    dense_output: bool,
    integrator: &str,
    sensitivities: bool,
) -> PyResult<Bound<'py, PyDict>> {
    let ramp = ramp(chi, km, alpha)?;
    let opts = SimOptions {
        law: ContactLaw {
            mu_s,
            mu_k,
            rule: parse_rule(rule)?,
        },
        restitution,
        theta0,
        omega0,
        slip0,
        t_max,
        l_max,
        max_transitions,
        solver: solver_options(rtol, atol, max_steps, integrator)?,
        dense_output,
        ..SimOptions::default()
    };
    let (run, sens) = detached(py, |stop| {
        let run = simulate_until(&ramp, &opts, stop)?;
        let sens = match sensitivities {
            true => Some(motion_sensitivities(&ramp, &opts, &run, stop)?),
            false => None,
        };
        Ok((run, sens))
    })?;
    let d = points(py, &run.points)?;
    records(&d, &run)?;
    d.set_item(intern!(py, "energy0"), run.energy0)?;
    d.set_item(intern!(py, "dissipated_slip"), run.dissipated_slip)?;
    d.set_item(intern!(py, "dissipated_impacts"), run.dissipated_impacts)?;
    let status = run.status.unwrap_or(MotionStatus::Failed);
    d.set_item(intern!(py, "status"), STATUSES.of(py, status))?;
    d.set_item(intern!(py, "message"), run.message)?;
    d.set_item(intern!(py, "nfev"), run.nfev)?;
    d.set_item(intern!(py, "sol"), run.dense.map(|sol| MotionDense { sol }))?;
    let (d_transitions, d_singular) = match sens {
        Some(s) => derivatives(py, s).map(|(dt, ds)| (Some(dt), Some(ds)))?,
        None => (None, None),
    };
    d.set_item(intern!(py, "d_transitions"), d_transitions)?;
    d.set_item(intern!(py, "d_singular"), d_singular)?;
    Ok(d)
}

/// The sensitivities as (d_transitions of shape (transitions, 2, 8), d_singular).
fn derivatives(py: Python<'_>, s: Sensitivities) -> PyResult<Derivatives<'_>> {
    let n = s.transitions.len();
    let flat: Vec<f64> = s.transitions.iter().flatten().flatten().copied().collect();
    let d = flat.into_pyarray(py).reshape([n, 2, PARAMETERS.len()])?;
    Ok((d, s.singular.into_pyarray(py)))
}

/// The recorded points, one numpy array per field of `MotionResult`.
fn points<'py>(py: Python<'py>, p: &[Point]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    set_column(&d, intern!(py, "t"), p, |q| q.t)?;
    set_column(&d, intern!(py, "theta"), p, |q| q.state.theta)?;
    set_column(&d, intern!(py, "omega"), p, |q| q.state.omega)?;
    set_column(&d, intern!(py, "l"), p, |q| q.state.l)?;
    set_column(&d, intern!(py, "ldot"), p, |q| q.state.ldot)?;
    set_column(&d, intern!(py, "b"), p, |q| q.state.b)?;
    set_column(&d, intern!(py, "bdot"), p, |q| q.state.bdot)?;
    set_column(&d, intern!(py, "Fx"), p, |q| q.fx)?;
    set_column(&d, intern!(py, "Fy"), p, |q| q.fy)?;
    set_column(&d, intern!(py, "energy"), p, |q| q.energy)?;
    set_column(&d, intern!(py, "dissipated"), p, |q| q.dissipated)?;
    set_column(&d, intern!(py, "mode"), p, |q| q.mode as i8)?;
    Ok(d)
}

/// The records of `run` into `d`, each kind by its field of `MotionResult`, one list per
/// field of its named tuple (`Transition`, `FlightRecord`, `ImpactRecord`, `Segment`).
fn records(d: &Bound<'_, PyDict>, run: &MotionRun) -> PyResult<()> {
    let py = d.py();
    let transitions = Records::new(py, &run.transitions)
        .field(intern!(py, "t"), |t| t.t)?
        .field(intern!(py, "from_mode"), |t| {
            t.from.map(|m| MODES.of(py, m))
        })?
        .field(intern!(py, "to_mode"), |t| MODES.of(py, t.to))?
        .field(intern!(py, "reason"), |t| REASONS.of(py, t.reason))?
        .field(intern!(py, "theta"), |t| t.state.theta)?
        .field(intern!(py, "omega"), |t| t.state.omega)?
        .field(intern!(py, "l"), |t| t.state.l)?
        .field(intern!(py, "ldot"), |t| t.state.ldot)?
        .field(intern!(py, "b"), |t| t.state.b)?
        .field(intern!(py, "bdot"), |t| t.state.bdot)?;
    let flights = Records::new(py, &run.flights)
        .field(intern!(py, "t_liftoff"), |f| f.t_liftoff)?
        .field(intern!(py, "t_landing"), |f| f.t_landing)?
        .field(intern!(py, "theta_liftoff"), |f| f.theta_liftoff)?
        .field(intern!(py, "theta_landing"), |f| f.theta_landing)?
        .field(intern!(py, "apex"), |f| f.apex)?
        .field(intern!(py, "distance"), |f| f.distance)?;
    let impacts = Records::new(py, &run.impacts)
        .field(intern!(py, "t"), |i| i.t)?
        .field(intern!(py, "normal_speed"), |i| i.normal_speed)?
        .field(intern!(py, "slip_before"), |i| i.slip_before)?
        .field(intern!(py, "pt"), |i| i.pt)?
        .field(intern!(py, "pn"), |i| i.pn)?
        .field(intern!(py, "energy_lost"), |i| i.energy_lost)?
        .field(intern!(py, "sticking"), |i| i.sticking)?
        .field(intern!(py, "outcome"), |i| MODES.of(py, i.outcome))?;
    let segments = Records::new(py, &run.segments)
        .field(intern!(py, "mode"), |s| MODES.of(py, s.mode))?
        .field(intern!(py, "reason"), |s| REASONS.of(py, s.reason))?
        .field(intern!(py, "t_start"), |s| s.t_start)?
        .field(intern!(py, "t_end"), |s| s.t_end)?
        .field(intern!(py, "nfev"), |s| s.nfev)?;
    d.set_item(intern!(py, "transitions"), transitions.into_dict())?;
    d.set_item(intern!(py, "flights"), flights.into_dict())?;
    d.set_item(intern!(py, "impacts"), impacts.into_dict())?;
    d.set_item(intern!(py, "segments"), segments.into_dict())
}

/// The dense output of a full-motion run (`MotionResult.sol`), evaluated by the core.
#[pyclass(frozen, module = "eccjump._core")]
pub struct MotionDense {
    sol: MotionSolution,
}

#[pymethods]
impl MotionDense {
    /// Last time covered: the end of the run.
    #[getter]
    fn t_max(&self) -> f64 {
        self.sol.t_end
    }

    /// (θ, θ̇, l, l̇, b, ḃ) at the times `t` (1-D), shape (6, len(t)); a ValueError names the
    /// first time outside [0, t_max], a MemoryError a request too large for memory.
    fn states<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let range = (0.0, self.sol.t_end);
        dense_rows(py, "the dense states", t.as_slice()?, range, |ti| {
            self.sol.state(ti).map(|s| s.values())
        })
    }
}

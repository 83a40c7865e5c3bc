//! `simulate`: one full-motion run (rolling, slipping, flight, landing), computed with the
//! GIL released, returned as plain values (`eccjump.simulate` makes the `MotionResult`).

use crate::columns::dense_rows;
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
use pyo3::prelude::*;
use pyo3::types::PyString;

/// A name from [`crate::names`].
type Name<'py> = Bound<'py, PyString>;

/// One recorded series of a run.
type Series<'py> = Bound<'py, PyArray1<f64>>;

/// t, θ, θ̇, l, l̇, b, ḃ, F_x, F_y, energy, dissipated, and the mode codes: every recorded
/// point, one array per field.
type Points<'py> = (
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Series<'py>,
    Bound<'py, PyArray1<i8>>,
);

/// t, from mode, to mode, reason, θ, θ̇, l, l̇, b, ḃ: `Transition`'s fields.
type TransitionFields<'py> = (
    f64,
    Option<Name<'py>>,
    Name<'py>,
    Name<'py>,
    f64,
    f64,
    f64,
    f64,
    f64,
    f64,
);

/// `FlightRecord`'s fields.
type FlightFields = (f64, f64, f64, f64, f64, f64);

/// `ImpactRecord`'s fields.
type ImpactFields<'py> = (f64, f64, f64, f64, f64, f64, bool, Name<'py>);

/// `Segment`'s fields.
type SegmentFields<'py> = (Name<'py>, Name<'py>, f64, f64, usize);

/// The records of a run: its transitions, flights, impacts and segments.
type Records<'py> = (
    Vec<TransitionFields<'py>>,
    Vec<FlightFields>,
    Vec<ImpactFields<'py>>,
    Vec<SegmentFields<'py>>,
);

/// A finished run: its points, its records, the energy ledger (energy0, dissipated by
/// sliding, by impacts), the status's name, the message, the evaluations, the dense
/// output and the sensitivities (each None unless asked for).
type MotionOutput<'py> = (
    Points<'py>,
    Records<'py>,
    (f64, f64, f64),
    Name<'py>,
    String,
    usize,
    Option<MotionDense>,
    Option<Derivatives<'py>>,
);

/// A run's sensitivities: d(t, θ)/dp of each transition and its flag.
type Derivatives<'py> = (Bound<'py, PyArray3<f64>>, Bound<'py, PyArray1<bool>>);

/// The full motion of the body (χ, k_m) on a ramp of angle α, with the options of
/// `eccjump.simulate` (keyword-only, named as there; μ_k resolved). Bad input raises
/// ValueError (from the core's checks) before any work is done.
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
) -> PyResult<MotionOutput<'py>> {
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
    Ok((
        points(py, &run.points),
        records(py, &run),
        (run.energy0, run.dissipated_slip, run.dissipated_impacts),
        STATUSES.of(py, run.status.unwrap_or(MotionStatus::Failed)),
        run.message,
        run.nfev,
        run.dense.map(|sol| MotionDense { sol }),
        sens.map(|s| derivatives(py, s)).transpose()?,
    ))
}

/// The sensitivities as (d_transitions of shape (transitions, 2, 8), d_singular).
fn derivatives(py: Python<'_>, s: Sensitivities) -> PyResult<Derivatives<'_>> {
    let n = s.transitions.len();
    let flat: Vec<f64> = s.transitions.iter().flatten().flatten().copied().collect();
    let d = flat.into_pyarray(py).reshape([n, 2, PARAMETERS.len()])?;
    Ok((d, s.singular.into_pyarray(py)))
}

/// One field of every recorded point, as a numpy array.
fn column<'py>(py: Python<'py>, points: &[Point], field: impl Fn(&Point) -> f64) -> Series<'py> {
    points
        .iter()
        .map(field)
        .collect::<Vec<f64>>()
        .into_pyarray(py)
}

/// The recorded points, one array per field.
fn points<'py>(py: Python<'py>, p: &[Point]) -> Points<'py> {
    (
        column(py, p, |q| q.t),
        column(py, p, |q| q.state.theta),
        column(py, p, |q| q.state.omega),
        column(py, p, |q| q.state.l),
        column(py, p, |q| q.state.ldot),
        column(py, p, |q| q.state.b),
        column(py, p, |q| q.state.bdot),
        column(py, p, |q| q.fx),
        column(py, p, |q| q.fy),
        column(py, p, |q| q.energy),
        column(py, p, |q| q.dissipated),
        p.iter()
            .map(|q| q.mode as i8)
            .collect::<Vec<i8>>()
            .into_pyarray(py),
    )
}

/// The records of `run`, each as a tuple of its fields.
fn records<'py>(py: Python<'py>, run: &MotionRun) -> Records<'py> {
    let transitions = run.transitions.iter().map(|t| {
        let [theta, omega, l, ldot, b, bdot] = t.state.values();
        let from = t.from.map(|m| MODES.of(py, m));
        let (to, why) = (MODES.of(py, t.to), REASONS.of(py, t.reason));
        (t.t, from, to, why, theta, omega, l, ldot, b, bdot)
    });
    let flights = run.flights.iter().map(|f| {
        let (t0, t1) = (f.t_liftoff, f.t_landing);
        (t0, t1, f.theta_liftoff, f.theta_landing, f.apex, f.distance)
    });
    let impacts = run.impacts.iter().map(|i| {
        let outcome = MODES.of(py, i.outcome);
        (
            i.t,
            i.normal_speed,
            i.slip_before,
            i.pt,
            i.pn,
            i.energy_lost,
            i.sticking,
            outcome,
        )
    });
    let segments = run.segments.iter().map(|s| {
        let (mode, why) = (MODES.of(py, s.mode), REASONS.of(py, s.reason));
        (mode, why, s.t_start, s.t_end, s.nfev)
    });
    (
        transitions.collect(),
        flights.collect(),
        impacts.collect(),
        segments.collect(),
    )
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

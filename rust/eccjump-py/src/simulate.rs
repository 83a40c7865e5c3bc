//! `simulate`: one full-motion run (rolling, slipping, flight, landing), computed with the
//! GIL released, returned as an `eccjump.motion.MotionResult` made here.

use crate::body::body_of;
use crate::columns::dense_rows;
use crate::errors::{detached, to_py};
use crate::names::{MODES, REASONS, STATUSES};
use crate::options::{parse_integrator, parse_rule};
use crate::records::{RecordType, ResultType};
use eccjump_core::mechanics::BodyState;
use eccjump_core::modes::contact::ContactLaw;
use eccjump_core::motion::record::{MotionStatus, Point};
use eccjump_core::motion::solution::MotionSolution;
use eccjump_core::motion::{simulate_until, MotionRun, SimOptions};
use eccjump_core::ode::SolverOptions;
use eccjump_core::Ramp;
use numpy::{IntoPyArray, PyArray2, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::sync::PyOnceLock;
use pyo3::types::{PyString, PyType};

/// A name from [`crate::names`].
type Name<'py> = Bound<'py, PyString>;

/// t, from mode, to mode, reason, θ, θ̇, l, l̇, b, ḃ: `Transition`'s fields.
type TransitionTuple<'py> = (
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
type FlightTuple = (f64, f64, f64, f64, f64, f64);

/// `ImpactRecord`'s fields.
type ImpactTuple<'py> = (f64, f64, f64, f64, f64, f64, bool, Name<'py>);

/// `Segment`'s fields.
type SegmentTuple<'py> = (Name<'py>, Name<'py>, f64, f64, usize);

/// `eccjump.motion`'s records of a run.
static TRANSITION: RecordType = RecordType::new("eccjump.motion", "Transition");
static FLIGHT: RecordType = RecordType::new("eccjump.motion", "FlightRecord");
static IMPACT: RecordType = RecordType::new("eccjump.motion", "ImpactRecord");
static SEGMENT: RecordType = RecordType::new("eccjump.motion", "Segment");

/// `eccjump.motion.MotionResult`, by its fields.
static MOTION_RESULT: ResultType<30> = ResultType::new(
    "eccjump.motion",
    "MotionResult",
    [
        "body",
        "alpha",
        "mu_s",
        "mu_k",
        "restitution",
        "rule",
        "t",
        "theta",
        "omega",
        "l",
        "ldot",
        "b",
        "bdot",
        "Fx",
        "Fy",
        "energy",
        "dissipated",
        "mode",
        "transitions",
        "flights",
        "impacts",
        "segments",
        "energy0",
        "dissipated_slip",
        "dissipated_impacts",
        "status",
        "message",
        "nfev",
        "sol",
        "units",
    ],
);

/// `eccjump.motion.MotionSolution`, the Python face of [`MotionDense`].
static MOTION_SOLUTION: PyOnceLock<Py<PyType>> = PyOnceLock::new();

/// The full motion of `body` (an `eccjump.Cylinder`: its χ and k_m) on a ramp of angle α,
/// as an `eccjump.motion.MotionResult`. Options are keyword-only and checked by the core (a
/// ValueError naming the parameter).
#[pyfunction]
#[pyo3(signature = (body, alpha, *, mu_s, mu_k, restitution, rule, theta0, omega0, slip0,
                    t_max, l_max, max_transitions, rtol, atol, max_steps, dense_output,
                    integrator))]
#[allow(clippy::too_many_arguments)] // keyword-only options of one run
pub fn simulate<'py>(
    py: Python<'py>,
    body: &Bound<'py, PyAny>,
    alpha: f64,
    mu_s: f64,
    mu_k: f64,
    restitution: f64,
    rule: &Bound<'py, PyString>,
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
) -> PyResult<Bound<'py, PyAny>> {
    let ramp = Ramp::new(body_of(body)?, alpha).map_err(to_py)?;
    let opts = SimOptions {
        law: ContactLaw {
            mu_s,
            mu_k,
            rule: parse_rule(rule.to_str()?)?,
        },
        restitution,
        theta0,
        omega0,
        slip0,
        t_max,
        l_max,
        max_transitions,
        solver: SolverOptions {
            rtol,
            atol,
            max_steps,
            method: parse_integrator(integrator)?,
            ..SolverOptions::default()
        },
        dense_output,
        ..SimOptions::default()
    };
    let run = detached(py, |stop| simulate_until(&ramp, &opts, stop))?;
    let inputs = [
        body.clone(),
        alpha.into_pyobject(py)?.into_any(),
        mu_s.into_pyobject(py)?.into_any(),
        mu_k.into_pyobject(py)?.into_any(),
        restitution.into_pyobject(py)?.into_any(),
        rule.clone().into_any(),
    ];
    to_result(py, inputs, run)
}

/// (θ, θ̇, l, l̇, b, ḃ): the order of every full state handed to Python.
fn state_values(s: &BodyState) -> [f64; 6] {
    [s.theta, s.omega, s.l, s.ldot, s.b, s.bdot]
}

/// One field of every recorded point, as a numpy array.
fn column<'py>(
    py: Python<'py>,
    points: &[Point],
    field: impl Fn(&Point) -> f64,
) -> Bound<'py, PyAny> {
    points
        .iter()
        .map(field)
        .collect::<Vec<f64>>()
        .into_pyarray(py)
        .into_any()
}

/// The `MotionResult` of `run`, after its `inputs` (body, α, μ_s, μ_k, restitution, rule).
fn to_result<'py>(
    py: Python<'py>,
    [body, alpha, mu_s, mu_k, restitution, rule]: [Bound<'py, PyAny>; 6],
    run: MotionRun,
) -> PyResult<Bound<'py, PyAny>> {
    let p = &run.points;
    let transitions = TRANSITION.tuple_of(
        py,
        run.transitions.iter().map(|t| -> TransitionTuple<'py> {
            let [theta, omega, l, ldot, b, bdot] = state_values(&t.state);
            let from = t.from.map(|m| MODES.of(py, m));
            let (to, why) = (MODES.of(py, t.to), REASONS.of(py, t.reason));
            (t.t, from, to, why, theta, omega, l, ldot, b, bdot)
        }),
    )?;
    let flights = FLIGHT.tuple_of(
        py,
        run.flights.iter().map(|f| -> FlightTuple {
            (
                f.t_liftoff,
                f.t_landing,
                f.theta_liftoff,
                f.theta_landing,
                f.apex,
                f.distance,
            )
        }),
    )?;
    let impacts = IMPACT.tuple_of(
        py,
        run.impacts.iter().map(|i| -> ImpactTuple<'py> {
            (
                i.t,
                i.normal_speed,
                i.slip_before,
                i.pt,
                i.pn,
                i.energy_lost,
                i.sticking,
                MODES.of(py, i.outcome),
            )
        }),
    )?;
    let segments = SEGMENT.tuple_of(
        py,
        run.segments.iter().map(|s| -> SegmentTuple<'py> {
            let (mode, why) = (MODES.of(py, s.mode), REASONS.of(py, s.reason));
            (mode, why, s.t_start, s.t_end, s.nfev)
        }),
    )?;
    let sol = match run.dense {
        Some(sol) => MOTION_SOLUTION
            .import(py, "eccjump.motion", "MotionSolution")?
            .call1((Bound::new(py, MotionDense { sol })?,))?,
        None => py.None().into_bound(py),
    };
    let status = STATUSES.of(py, run.status.unwrap_or(MotionStatus::Failed));
    MOTION_RESULT.make(
        py,
        [
            body,
            alpha,
            mu_s,
            mu_k,
            restitution,
            rule,
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
                .into_pyarray(py)
                .into_any(),
            transitions.into_any(),
            flights.into_any(),
            impacts.into_any(),
            segments.into_any(),
            run.energy0.into_pyobject(py)?.into_any(),
            run.dissipated_slip.into_pyobject(py)?.into_any(),
            run.dissipated_impacts.into_pyobject(py)?.into_any(),
            status.into_any(),
            run.message.into_pyobject(py)?.into_any(),
            run.nfev.into_pyobject(py)?.into_any(),
            sol,
            py.None().into_bound(py),
        ],
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
            self.sol.state(ti).map(|s| state_values(&s))
        })
    }
}

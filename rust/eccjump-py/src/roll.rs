//! `roll`: one pure-rolling run, computed with the GIL released, returned as numpy arrays.

use crate::errors::to_py;
use crate::options::parse_rule;
use eccjump_core::mechanics::friction::friction_ratio;
use eccjump_core::modes::rolling::run::{roll as core_roll, RollOptions, RollRun, RollStatus};
use eccjump_core::modes::rolling::solution::RollSolution;
use eccjump_core::ode::SolverOptions;
use eccjump_core::{Cylinder, Ramp};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The options of a run, from the Python layer's dict (built by `eccjump.rolling.roll`).
#[derive(FromPyObject)]
#[pyo3(from_item_all)]
pub struct RollCallOptions {
    theta0: f64,
    omega0: f64,
    mu_s: Option<f64>,
    t_max: f64,
    theta_max: f64,
    rtol: f64,
    atol: f64,
    max_steps: usize,
    dense_output: bool,
    rule: String,
}

/// Integrates pure rolling of the body (χ, k_m) on a ramp of angle α; returns a dict of
/// arrays and scalars that the Python layer wraps in `RollResult`. Bad input raises
/// ValueError (from the core's checks) before any work is done.
#[pyfunction]
pub fn roll<'py>(
    py: Python<'py>,
    chi: f64,
    km: f64,
    alpha: f64,
    options: RollCallOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let ramp = Ramp::new(Cylinder::new(chi, km).map_err(to_py)?, alpha).map_err(to_py)?;
    let o = options;
    let opts = RollOptions {
        theta0: o.theta0,
        omega0: o.omega0,
        mu_s: o.mu_s,
        t_max: o.t_max,
        theta_max: o.theta_max,
        rule: parse_rule(&o.rule)?,
        solver: SolverOptions {
            rtol: o.rtol,
            atol: o.atol,
            max_steps: o.max_steps,
            ..SolverOptions::default()
        },
        dense_output: o.dense_output,
    };
    let run = py.detach(|| core_roll(&ramp, &opts)).map_err(to_py)?;
    to_dict(py, run)
}

fn to_dict<'py>(py: Python<'py>, run: RollRun) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    let events: Vec<(&str, f64, f64, f64)> = run
        .events
        .iter()
        .map(|e| (e.event.name(), e.t, e.theta, e.omega))
        .collect();
    d.set_item("status", run.status.code())?;
    d.set_item("message", run.status.message())?;
    d.set_item(
        "terminal_event",
        match run.status {
            RollStatus::Event(e) => Some(e.name()),
            _ => None,
        },
    )?;
    d.set_item("nfev", run.nfev)?;
    d.set_item("events", events)?;
    d.set_item("fx", run.fx.into_pyarray(py))?;
    d.set_item("fy", run.fy.into_pyarray(py))?;
    d.set_item("omega_dot", run.omega_dot.into_pyarray(py))?;
    d.set_item("t", run.t.into_pyarray(py))?;
    d.set_item("theta", run.theta.into_pyarray(py))?;
    // The distance rolled, l − l0 = θ − θ0 in pure rolling (from the core's record).
    d.set_item("l", run.l.into_pyarray(py))?;
    d.set_item("ratio", run.ratio.into_pyarray(py))?;
    d.set_item("omega", run.omega.into_pyarray(py))?;
    if let Some(sol) = run.dense {
        d.set_item("sol", Bound::new(py, DenseSolution { sol })?)?;
    }
    Ok(d)
}

/// The dense output of a run (`RollResult.sol`): the state and the kinematics at any time
/// of the run, evaluated by the core; it ends where the run ends.
#[pyclass(frozen, module = "eccjump._core")]
pub struct DenseSolution {
    sol: RollSolution,
}

impl DenseSolution {
    /// Applies `f` at every time of `t`, with a ValueError naming the first time outside
    /// the run.
    fn each<T>(&self, t: &[f64], f: impl Fn(&RollSolution, f64) -> Option<T>) -> PyResult<Vec<T>> {
        t.iter()
            .enumerate()
            .map(|(i, &ti)| {
                f(&self.sol, ti).ok_or_else(|| {
                    PyValueError::new_err(format!(
                        "t[{i}] = {ti} is outside the allowed range [{}, {}] of the dense output",
                        self.sol.t_start(),
                        self.sol.t_end
                    ))
                })
            })
            .collect()
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

    /// (θ, θ̇) at the times `t` (1-D), shape (2, len(t)).
    fn states<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyArray2<f64>>> {
        let t = t.as_slice()?;
        let ys = self.each(t, |s, ti| s.state(ti))?;
        let mut flat: Vec<f64> = ys.iter().map(|y| y[0]).collect();
        flat.extend(ys.iter().map(|y| y[1]));
        PyArray1::from_vec(py, flat).reshape([2, t.len()])
    }

    /// θ, θ̇, θ̈, F_x, F_y and the friction ratio at the times `t` (1-D), as a dict of arrays.
    fn kinematics<'py>(
        &self,
        py: Python<'py>,
        t: PyReadonlyArray1<'py, f64>,
    ) -> PyResult<Bound<'py, PyDict>> {
        let ks = self.each(t.as_slice()?, |s, ti| s.kinematics(ti))?;
        let d = PyDict::new(py);
        let col = |f: fn(&eccjump_core::modes::rolling::Kinematics) -> f64| {
            ks.iter().map(f).collect::<Vec<f64>>().into_pyarray(py)
        };
        d.set_item("theta", col(|k| k.theta))?;
        d.set_item("omega", col(|k| k.omega))?;
        d.set_item("omega_dot", col(|k| k.omega_dot))?;
        d.set_item("Fx", col(|k| k.fx))?;
        d.set_item("Fy", col(|k| k.fy))?;
        d.set_item("ratio", col(|k| friction_ratio(k.fx, k.fy)))?;
        Ok(d)
    }
}

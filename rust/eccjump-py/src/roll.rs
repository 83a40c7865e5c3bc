//! `roll`: one pure-rolling run, computed with the GIL released, returned as numpy arrays.

use crate::errors::to_py;
use crate::rule::parse_rule;
use eccjump_core::ode::SolverOptions;
use eccjump_core::roll::{roll as core_roll, RollOptions, RollRun};
use eccjump_core::{Cylinder, Rolling};
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Integrates pure rolling; returns a dict of arrays and scalars that the Python layer
/// wraps in `RollResult`. Bad input raises ValueError before any work is done.
#[pyfunction]
#[pyo3(signature = (chi, km, alpha, theta0, omega0, mu_s, t_max, theta_max, rtol, atol,
                    max_steps, dense_output, rule))]
#[allow(clippy::too_many_arguments)]
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
    max_steps: usize,
    dense_output: bool,
    rule: &str,
) -> PyResult<Bound<'py, PyDict>> {
    let rolling = Rolling::new(Cylinder::new(chi, km).map_err(to_py)?, alpha).map_err(to_py)?;
    let opts = RollOptions {
        theta0,
        omega0,
        mu_s,
        t_max,
        theta_max,
        rule: parse_rule(rule)?,
        solver: SolverOptions {
            rtol,
            atol,
            max_steps,
            ..SolverOptions::default()
        },
        dense_output,
    };
    let run = py.detach(|| core_roll(&rolling, &opts)).map_err(to_py)?;
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
            eccjump_core::roll::RollStatus::Event(e) => Some(e.name()),
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
    d.set_item("omega", run.omega.into_pyarray(py))?;
    if !run.dense.is_empty() {
        // Per step: t_old, h, y_old (2), Q (2 × 4), converted by hand (no nalgebra feature).
        let n = run.dense.len();
        let mut t_old = Vec::with_capacity(n);
        let mut h = Vec::with_capacity(n);
        let mut y_old = Vec::with_capacity(2 * n);
        let mut q = Vec::with_capacity(8 * n);
        for s in &run.dense {
            t_old.push(s.t_old);
            h.push(s.h);
            y_old.extend_from_slice(&[s.y_old[0], s.y_old[1]]);
            for comp in 0..2 {
                q.extend((0..4).map(|j| s.q[j][comp]));
            }
        }
        d.set_item("dense_t_old", t_old.into_pyarray(py))?;
        d.set_item("dense_h", h.into_pyarray(py))?;
        let y_old: Bound<'py, PyArray2<f64>> = PyArray1::from_vec(py, y_old).reshape([n, 2])?;
        d.set_item("dense_y_old", y_old)?;
        let q: Bound<'py, PyArray1<f64>> = PyArray1::from_vec(py, q);
        d.set_item("dense_q", q.reshape([n, 2, 4])?)?;
    }
    Ok(d)
}

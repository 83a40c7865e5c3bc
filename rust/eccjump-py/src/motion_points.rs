//! `motion_points`: the full motion to the first landing at given points (one column per
//! parameter, the body's k_m), each kept as the fixed-size summary of a motion map, computed
//! with the GIL released.

use crate::errors::detached;
use crate::motion_map::summary_columns;
use crate::options::MotionOptions;
use eccjump_core::error::try_filled;
use eccjump_core::maps::motion::MotionSummary;
use eccjump_core::maps::motion_points::{motion_points as points, MotionColumns};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Summaries of the points (alpha[i], chi[i], km[i], mu_s[i], mu_k[i], restitution[i],
/// theta0[i], omega0[i]) (an empty mu_k: μ_k = μ_s), one column per field.
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, mu_s, mu_k, restitution, theta0, omega0, *, options))]
#[allow(clippy::too_many_arguments)] // the eight columns and the shared options
pub fn motion_points<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: PyReadonlyArray1<'py, f64>,
    mu_k: PyReadonlyArray1<'py, f64>,
    restitution: PyReadonlyArray1<'py, f64>,
    theta0: PyReadonlyArray1<'py, f64>,
    omega0: PyReadonlyArray1<'py, f64>,
    options: &MotionOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let columns = MotionColumns {
        alpha: alpha.as_slice()?,
        chi: chi.as_slice()?,
        km: km.as_slice()?,
        mu_s: mu_s.as_slice()?,
        mu_k: mu_k.as_slice()?,
        restitution: restitution.as_slice()?,
        theta0: theta0.as_slice()?,
        omega0: omega0.as_slice()?,
    };
    let MotionOptions { map, n_threads } = options;
    let out = detached(py, |stop| {
        let mut out = try_filled("the points", columns.len()?, MotionSummary::invalid())?;
        points(&columns, map, *n_threads, &mut out, stop)?;
        Ok(out)
    })?;
    summary_columns(py, &out)
}

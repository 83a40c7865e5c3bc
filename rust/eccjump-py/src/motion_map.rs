//! Motion maps: the full motion to the first landing at every point of a grid
//! (`motion_grid`) or at given points (`motion_points`), each kept as a fixed-size summary
//! (one numpy column per field), computed with the GIL released. The two differ only in
//! their source of points; one driver ([`summaries`]) runs either.

use crate::columns::set_column;
use crate::errors::detached_filled;
use crate::options::MotionMapOptions;
use eccjump_core::maps::motion::{
    motion_map, LandingOutcome, MotionAxes, MotionPoints, MotionSummary,
};
use eccjump_core::maps::motion_points::MotionColumns;
use numpy::PyReadonlyArray1;
use pyo3::intern;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Summaries of the grid alpha × chi × frac × mu_s × mu_k × restitution × theta0 × omega0
/// (k_m = frac·(1 − χ); an empty mu_k: μ_k = μ_s), flat in C order.
#[pyfunction]
#[pyo3(signature = (alpha, chi, frac, mu_s, mu_k, restitution, theta0, omega0, *, options))]
#[allow(clippy::too_many_arguments)] // the eight axes and the shared options
pub fn motion_grid<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    frac: PyReadonlyArray1<'py, f64>,
    mu_s: PyReadonlyArray1<'py, f64>,
    mu_k: PyReadonlyArray1<'py, f64>,
    restitution: PyReadonlyArray1<'py, f64>,
    theta0: PyReadonlyArray1<'py, f64>,
    omega0: PyReadonlyArray1<'py, f64>,
    options: &MotionMapOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let axes = MotionAxes {
        alpha: alpha.as_slice()?,
        chi: chi.as_slice()?,
        frac: frac.as_slice()?,
        mu_s: mu_s.as_slice()?,
        mu_k: mu_k.as_slice()?,
        restitution: restitution.as_slice()?,
        theta0: theta0.as_slice()?,
        omega0: omega0.as_slice()?,
    };
    summaries(py, "the map", &axes, options)
}

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
    options: &MotionMapOptions,
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
    summaries(py, "the points", &columns, options)
}

/// The summary of every point of `points` (`what` names them in a MemoryError), one numpy
/// column per field.
fn summaries<'py>(
    py: Python<'py>,
    what: &'static str,
    points: &impl MotionPoints,
    options: &MotionMapOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let MotionMapOptions { map, n_threads } = options;
    let out = detached_filled(
        py,
        what,
        points.count(),
        MotionSummary::invalid(),
        |out, stop| motion_map(points, map, *n_threads, out, stop),
    )?;
    summary_columns(py, &out)
}

/// One numpy column per field of the summaries (the names of `eccjump.motion.fields.TABLE`).
fn summary_columns<'py>(py: Python<'py>, out: &[MotionSummary]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    set_column(&d, intern!(py, "status"), out, |s| s.status)?;
    set_column(&d, intern!(py, "sequence"), out, |s| s.sequence)?;
    set_column(&d, intern!(py, "n_modes"), out, |s| s.n_modes)?;
    set_column(&d, intern!(py, "jarm"), out, |s| s.jarm)?;
    set_column(&d, intern!(py, "slipped_first"), out, |s| s.slipped_first)?;
    set_column(&d, intern!(py, "slip_t"), out, |s| s.slip_t)?;
    set_column(&d, intern!(py, "slip_theta"), out, |s| s.slip_theta)?;
    set_column(&d, intern!(py, "liftoff_reason"), out, |s| s.liftoff_reason)?;
    set_column(&d, intern!(py, "liftoff_t"), out, |s| s.liftoff_t)?;
    set_column(&d, intern!(py, "liftoff_theta"), out, |s| s.liftoff_theta)?;
    set_column(&d, intern!(py, "flight_time"), out, |s| s.flight_time)?;
    set_column(&d, intern!(py, "apex"), out, |s| s.apex)?;
    set_column(&d, intern!(py, "distance"), out, |s| s.distance)?;
    set_column(&d, intern!(py, "landing"), out, |s| s.landing)?;
    set_column(&d, intern!(py, "energy_lost"), out, |s| s.energy_lost)?;
    Ok(d)
}

/// (code, name) of every landing outcome.
#[pyfunction]
pub fn landing_codes() -> Vec<(u8, &'static str)> {
    LandingOutcome::ALL
        .iter()
        .map(|o| (*o as u8, o.name()))
        .collect()
}

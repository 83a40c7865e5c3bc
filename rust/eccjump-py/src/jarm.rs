//! JARM classification of points and grids: arrays in, one array per result field out.

use crate::columns::set_column;
use crate::errors::detached;
use crate::options::CallOptions;
use eccjump_core::error::{try_filled, Result as CoreResult};
use eccjump_core::jarm::{JarmResult, Reason};
use eccjump_core::maps::region::{classify_grid, classify_points, grid_size};
use numpy::PyReadonlyArray1;
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Struct of arrays from the per-point results (the output is O(points), nothing more).
fn to_dict<'py>(py: Python<'py>, res: &[JarmResult]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    set_column(&d, "is_jarm", res, |r| r.is_jarm)?;
    set_column(&d, "reason", res, |r| r.reason as u8)?;
    set_column(&d, "n", res, |r| r.n)?;
    set_column(&d, "theta_J", res, |r| r.theta_j)?;
    set_column(&d, "theta_event", res, |r| r.theta_event)?;
    set_column(&d, "Fx_J", res, |r| r.fx_j)?;
    set_column(&d, "Fy_J", res, |r| r.fy_j)?;
    set_column(&d, "max_ratio", res, |r| r.max_ratio)?;
    set_column(&d, "theta_max_ratio", res, |r| r.theta_max_ratio)?;
    set_column(&d, "min_Fy", res, |r| r.min_fy)?;
    set_column(&d, "theta_min_Fy", res, |r| r.theta_min_fy)?;
    Ok(d)
}

/// The output of `len` points, allocated fallibly (`MemoryError` naming its size).
fn empty(len: usize) -> CoreResult<Vec<JarmResult>> {
    try_filled("the result", len, JarmResult::new(Reason::InvalidParams))
}

/// Classifies equal-length 1-D arrays of points (μ_s and the turn n, 0 = the first jump, may
/// have length 1).
#[pyfunction]
#[allow(clippy::too_many_arguments)] // five coordinates and the options
pub fn jarm_points<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: PyReadonlyArray1<'py, f64>,
    n: PyReadonlyArray1<'py, u32>,
    options: CallOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let (opts, method, n_threads) = options.parse(0)?;
    let (a, c, k, m, n) = (
        alpha.as_slice()?,
        chi.as_slice()?,
        km.as_slice()?,
        mu_s.as_slice()?,
        n.as_slice()?,
    );
    let out = detached(py, |stop| {
        let mut out = empty(a.len())?;
        classify_points(a, c, k, m, n, method, &opts, n_threads, &mut out, stop)?;
        Ok(out)
    })?;
    to_dict(py, &out)
}

/// Classifies the grid alpha × chi × frac (k_m = frac·(1 − χ)), flat in C order, on turn n
/// (0 = the first jump).
#[pyfunction]
pub fn jarm_grid<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    frac: PyReadonlyArray1<'py, f64>,
    mu_s: f64,
    n: u32,
    options: CallOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let (opts, method, n_threads) = options.parse(n)?;
    let (a, c, f) = (alpha.as_slice()?, chi.as_slice()?, frac.as_slice()?);
    let out = detached(py, |stop| {
        let mut out = empty(grid_size(a.len(), c.len(), f.len())?)?;
        classify_grid(a, c, f, mu_s, method, &opts, n_threads, &mut out, stop)?;
        Ok(out)
    })?;
    to_dict(py, &out)
}

/// (code, name) of every reason, for the Python IntEnum.
#[pyfunction]
pub fn reason_codes() -> Vec<(u8, &'static str)> {
    Reason::ALL.iter().map(|r| (r.code(), r.name())).collect()
}

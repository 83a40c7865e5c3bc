//! JARM classification of points and grids: arrays in, one array per result field out.

use crate::errors::detached;
use crate::options::CallOptions;
use eccjump_core::error::{try_filled, Result as CoreResult};
use eccjump_core::jarm::{JarmResult, Reason};
use eccjump_core::maps::region::{classify_grid, classify_points, grid_size};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// Struct of arrays from the per-point results (the output is O(points), nothing more).
fn to_dict<'py>(py: Python<'py>, res: &[JarmResult]) -> PyResult<Bound<'py, PyDict>> {
    let d = PyDict::new(py);
    // Each field allocated fallibly: a MemoryError, not an abort, if it does not fit.
    macro_rules! field {
        ($name:literal, $f:expr) => {
            let mut v = Vec::new();
            v.try_reserve_exact(res.len()).map_err(|_| {
                pyo3::exceptions::PyMemoryError::new_err(format!(
                    "the field {} of {} points does not fit in memory",
                    $name,
                    res.len()
                ))
            })?;
            v.extend(res.iter().map($f));
            d.set_item($name, v.into_pyarray(py))?;
        };
    }
    field!("is_jarm", |r| r.is_jarm);
    field!("reason", |r| r.reason as u8);
    field!("n", |r| r.n);
    field!("theta_J", |r| r.theta_j);
    field!("theta_event", |r| r.theta_event);
    field!("Fx_J", |r| r.fx_j);
    field!("Fy_J", |r| r.fy_j);
    field!("max_ratio", |r| r.max_ratio);
    field!("theta_max_ratio", |r| r.theta_max_ratio);
    field!("min_Fy", |r| r.min_fy);
    field!("theta_min_Fy", |r| r.theta_min_fy);
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

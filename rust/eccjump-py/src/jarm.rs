//! JARM classification of points and grids: arrays in, with the options as one
//! [`ClassifyOptions`], one array per result field out.

use crate::errors::detached;
use crate::options::ClassifyOptions;
use eccjump_core::error::Result;
use eccjump_core::jarm::Reason;
use eccjump_core::maps::columns::JarmColumns;
use eccjump_core::maps::parallel::pool;
use eccjump_core::maps::region::{classify_grid, classify_points, grid_size};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The map's result columns as numpy arrays (each takes its vector over without a copy),
/// by the field names of `JarmResult` in Python.
fn into_dict(py: Python<'_>, c: JarmColumns) -> PyResult<Bound<'_, PyDict>> {
    let d = PyDict::new(py);
    d.set_item("is_jarm", c.is_jarm.into_pyarray(py))?;
    d.set_item("reason", c.reason.into_pyarray(py))?;
    d.set_item("n", c.n.into_pyarray(py))?;
    for (name, v) in [
        ("theta_J", c.theta_j),
        ("theta_event", c.theta_event),
        ("Fx_J", c.fx_j),
        ("Fy_J", c.fy_j),
        ("max_ratio", c.max_ratio),
        ("theta_max_ratio", c.theta_max_ratio),
        ("min_Fy", c.min_fy),
        ("theta_min_Fy", c.theta_min_fy),
    ] {
        d.set_item(name, v.into_pyarray(py))?;
    }
    Ok(d)
}

/// Classifies equal-length 1-D arrays of points (μ_s and the turn n, 0 = the first jump, may
/// have length 1).
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, mu_s, n, *, options))]
pub fn jarm_points<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: PyReadonlyArray1<'py, f64>,
    n: PyReadonlyArray1<'py, u32>,
    options: &ClassifyOptions,
) -> PyResult<Bound<'py, PyDict>> {
    // Each point carries its own turn: the options' turn is 0.
    let (opts, method, n_threads) = options.on_turn(0);
    let (a, c, k, m, n) = (
        alpha.as_slice()?,
        chi.as_slice()?,
        km.as_slice()?,
        mu_s.as_slice()?,
        n.as_slice()?,
    );
    classified(
        py,
        || Ok(a.len()),
        n_threads,
        |out, stop| classify_points(a, c, k, m, n, method, &opts, n_threads, out, stop),
    )
}

/// Classifies the grid alpha × chi × frac (k_m = frac·(1 − χ)), flat in C order, on turn n
/// (0 = the first jump).
#[pyfunction]
#[pyo3(signature = (alpha, chi, frac, mu_s, *, n, options))]
pub fn jarm_grid<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    frac: PyReadonlyArray1<'py, f64>,
    mu_s: f64,
    n: u32,
    options: &ClassifyOptions,
) -> PyResult<Bound<'py, PyDict>> {
    let (opts, method, n_threads) = options.on_turn(n);
    let (a, c, f) = (alpha.as_slice()?, chi.as_slice()?, frac.as_slice()?);
    let len = || grid_size(a.len(), c.len(), f.len());
    classified(py, len, n_threads, |out, stop| {
        classify_grid(a, c, f, mu_s, method, &opts, n_threads, out, stop)
    })
}

/// The columns `classify` fills, of `len()` points on `n_threads` threads (each column
/// first touched by the threads that fill it), with the GIL released: the one driver of
/// `jarm_points` and `jarm_grid`, which differ in their source of points.
fn classified<'py>(
    py: Python<'py>,
    len: impl FnOnce() -> Result<usize> + Send,
    n_threads: usize,
    classify: impl FnOnce(&mut JarmColumns, &dyn Fn() -> bool) -> Result<()> + Send,
) -> PyResult<Bound<'py, PyDict>> {
    let out = detached(py, |stop| {
        let len = len()?;
        let mut out = JarmColumns::new(&pool(n_threads)?, len)?;
        classify(&mut out, stop)?;
        Ok(out)
    })?;
    into_dict(py, out)
}

/// (code, name) of every reason, for the Python IntEnum.
#[pyfunction]
pub fn reason_codes() -> Vec<(u8, &'static str)> {
    Reason::ALL.iter().map(|r| (r.code(), r.name())).collect()
}

//! JARM classification of points and grids: arrays in, one array per result field out.

use crate::errors::detached;
use crate::options::CallOptions;
use eccjump_core::error::Result as CoreResult;
use eccjump_core::jarm::{JarmResult, Reason};
use eccjump_core::maps::parallel::{column_on, filled_on, pool, ThreadPool};
use eccjump_core::maps::region::{classify_grid, classify_points, grid_size};
use numpy::{IntoPyArray, PyReadonlyArray1};
use pyo3::prelude::*;
use pyo3::types::PyDict;

/// The per-point results as one column per field (struct of arrays), built in parallel
/// with the GIL released; the numpy arrays then take the vectors over without a copy.
struct Columns {
    is_jarm: Vec<bool>,
    reason: Vec<u8>,
    n: Vec<u32>,
    real: Vec<(&'static str, Vec<f64>)>,
}

impl Columns {
    fn of(p: &ThreadPool, rows: &[JarmResult]) -> CoreResult<Self> {
        // One closure per field (not a table of fn pointers: an indirect call per value).
        let real = vec![
            ("theta_J", column_on(p, "theta_J", rows, |r| r.theta_j)?),
            (
                "theta_event",
                column_on(p, "theta_event", rows, |r| r.theta_event)?,
            ),
            ("Fx_J", column_on(p, "Fx_J", rows, |r| r.fx_j)?),
            ("Fy_J", column_on(p, "Fy_J", rows, |r| r.fy_j)?),
            (
                "max_ratio",
                column_on(p, "max_ratio", rows, |r| r.max_ratio)?,
            ),
            (
                "theta_max_ratio",
                column_on(p, "theta_max_ratio", rows, |r| r.theta_max_ratio)?,
            ),
            ("min_Fy", column_on(p, "min_Fy", rows, |r| r.min_fy)?),
            (
                "theta_min_Fy",
                column_on(p, "theta_min_Fy", rows, |r| r.theta_min_fy)?,
            ),
        ];
        Ok(Self {
            is_jarm: column_on(p, "is_jarm", rows, |r| r.is_jarm)?,
            reason: column_on(p, "reason", rows, |r| r.reason as u8)?,
            n: column_on(p, "n", rows, |r| r.n)?,
            real,
        })
    }

    fn into_dict(self, py: Python<'_>) -> PyResult<Bound<'_, PyDict>> {
        let d = PyDict::new(py);
        d.set_item("is_jarm", self.is_jarm.into_pyarray(py))?;
        d.set_item("reason", self.reason.into_pyarray(py))?;
        d.set_item("n", self.n.into_pyarray(py))?;
        for (name, v) in self.real {
            d.set_item(name, v.into_pyarray(py))?;
        }
        Ok(d)
    }
}

/// The output of `len` points, allocated fallibly (`MemoryError` naming its size) and
/// filled by the map's threads.
fn empty(p: &ThreadPool, len: usize) -> CoreResult<Vec<JarmResult>> {
    filled_on(p, "the result", len, JarmResult::new(Reason::InvalidParams))
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
        let p = pool(n_threads)?;
        let mut out = empty(&p, a.len())?;
        classify_points(a, c, k, m, n, method, &opts, n_threads, &mut out, stop)?;
        Columns::of(&p, &out)
    })?;
    out.into_dict(py)
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
        let p = pool(n_threads)?;
        let mut out = empty(&p, grid_size(a.len(), c.len(), f.len())?)?;
        classify_grid(a, c, f, mu_s, method, &opts, n_threads, &mut out, stop)?;
        Columns::of(&p, &out)
    })?;
    out.into_dict(py)
}

/// (code, name) of every reason, for the Python IntEnum.
#[pyfunction]
pub fn reason_codes() -> Vec<(u8, &'static str)> {
    Reason::ALL.iter().map(|r| (r.code(), r.name())).collect()
}

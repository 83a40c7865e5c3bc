//! JARM boundaries: α-intervals per body and μ_s,min along the path, in parallel.

use crate::errors::to_py;
use crate::options::jarm_options;
use eccjump_core::boundary::{alpha_intervals_many, mu_s_min_path_many};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

/// For each (χ_i, k_m,i): the list of (α_lo, α_hi) intervals of JARM.
#[pyfunction]
#[pyo3(signature = (chi, km, mu_s, n, rule, n_scan, n_threads))]
#[allow(clippy::too_many_arguments)]
pub fn alpha_intervals<'py>(
    py: Python<'py>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: f64,
    n: Option<u32>,
    rule: &str,
    n_scan: usize,
    n_threads: usize,
) -> PyResult<Vec<Vec<(f64, f64)>>> {
    let opts = jarm_options(rule, n, 10_000, 0.0, 0.0, false)?;
    let (c, k) = (chi.as_slice()?, km.as_slice()?);
    py.detach(|| alpha_intervals_many(c, k, mu_s, &opts, n_scan, n_threads))
        .map_err(to_py)
}

/// For each (α_i, χ_i, k_m,i): the smallest μ_s that gives a JARM.
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, n, rule, n_threads))]
pub fn mu_s_min_path<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    n: Option<u32>,
    rule: &str,
    n_threads: usize,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let opts = jarm_options(rule, n, 10_000, 0.0, 0.0, false)?;
    let (a, c, k) = (alpha.as_slice()?, chi.as_slice()?, km.as_slice()?);
    let mut out = vec![0.0; a.len()];
    py.detach(|| mu_s_min_path_many(a, c, k, &opts, n_threads, &mut out))
        .map_err(to_py)?;
    Ok(out.into_pyarray(py))
}

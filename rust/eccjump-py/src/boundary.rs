//! JARM boundaries: α-intervals per body and μ_s,min along the path, in parallel (the turn,
//! rule and threads as one [`BoundaryOptions`]; the scan and the step keyword-only).

use crate::errors::{detached, detached_filled};
use crate::options::BoundaryOptions;
use eccjump_core::maps::boundary::{
    alpha_interval_around_many, alpha_intervals_many, mu_s_min_path_many,
};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::prelude::*;

/// Two NumPy float arrays of equal length (the lower and upper interval ends).
type ArrayPair<'py> = (Bound<'py, PyArray1<f64>>, Bound<'py, PyArray1<f64>>);

/// For each (χ_i, k_m,i): the list of (α_lo, α_hi) intervals of JARM (turn n, 0 = first).
#[pyfunction]
#[pyo3(signature = (chi, km, mu_s, *, n_scan, options))]
pub fn alpha_intervals<'py>(
    py: Python<'py>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: f64,
    n_scan: usize,
    options: &BoundaryOptions,
) -> PyResult<Vec<Vec<(f64, f64)>>> {
    let BoundaryOptions { jarm, n_threads } = options;
    let (c, k) = (chi.as_slice()?, km.as_slice()?);
    detached(py, |stop| {
        alpha_intervals_many(c, k, mu_s, jarm, n_scan, *n_threads, stop)
    })
}

/// For each (α_i, χ_i, k_m,i): the smallest μ_s that gives a JARM (turn n, 0 = first).
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, *, options))]
pub fn mu_s_min_path<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    options: &BoundaryOptions,
) -> PyResult<Bound<'py, PyArray1<f64>>> {
    let BoundaryOptions { jarm, n_threads } = options;
    let (a, c, k) = (alpha.as_slice()?, chi.as_slice()?, km.as_slice()?);
    let out = detached_filled(py, "the result", Ok(a.len()), 0.0, |out, stop| {
        mu_s_min_path_many(a, c, k, jarm, *n_threads, out, stop)
    })?;
    Ok(out.into_pyarray(py))
}

/// For each (seed_i, χ_i, k_m,i): the ends (α_lo, α_hi) of the JARM α-interval holding the
/// JARM angle seed_i (NaN if seed_i is not a JARM), as two arrays.
#[pyfunction]
#[pyo3(signature = (seed, chi, km, mu_s, *, step, options))]
pub fn alpha_interval_around<'py>(
    py: Python<'py>,
    seed: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: f64,
    step: f64,
    options: &BoundaryOptions,
) -> PyResult<ArrayPair<'py>> {
    let BoundaryOptions { jarm, n_threads } = options;
    let (s, c, k) = (seed.as_slice()?, chi.as_slice()?, km.as_slice()?);
    let out = detached_filled(py, "the result", Ok(s.len()), (0.0, 0.0), |out, stop| {
        alpha_interval_around_many(s, c, k, mu_s, jarm, step, *n_threads, out, stop)
    })?;
    let (lo, hi): (Vec<f64>, Vec<f64>) = out.into_iter().unzip();
    Ok((lo.into_pyarray(py), hi.into_pyarray(py)))
}

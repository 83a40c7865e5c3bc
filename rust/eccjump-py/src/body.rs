//! Body constructors: validation lives in the core; here only conversion.

use crate::errors::to_py;
use eccjump_core::Cylinder;
use pyo3::prelude::*;

/// (Ĩ_C, Ĩ_CM, γ) of a validated (χ, k_m); raises ValueError naming a bad parameter.
#[pyfunction]
pub fn body_derived(chi: f64, km: f64) -> PyResult<(f64, f64, f64)> {
    let b = Cylinder::new(chi, km).map_err(to_py)?;
    Ok((b.ic, b.icm, b.gamma()))
}

/// (χ, k_m) of a body given by mass, radius, offset and moment of inertia about C.
#[pyfunction]
#[allow(non_snake_case)]
pub fn body_from_inertia(M: f64, R: f64, d: f64, I_C: f64) -> PyResult<(f64, f64)> {
    let b = Cylinder::from_inertia(M, R, d, I_C).map_err(to_py)?;
    Ok((b.chi, b.km))
}

/// (χ, k_m) of the paper's shell-plus-line-mass model.
#[pyfunction]
#[allow(non_snake_case)]
pub fn body_from_shell_and_line(m_C: f64, m_P: f64, R: f64, d: f64) -> PyResult<(f64, f64)> {
    let b = Cylinder::from_shell_and_line(m_C, m_P, R, d).map_err(to_py)?;
    Ok((b.chi, b.km))
}

//! The exact derivatives of a classification's lift-off angle and jump forces with respect
//! to (α, χ, k_m) (`eccjump_core::jarm::derivatives`), element-wise over equal-length
//! columns, for `eccjump.jarm(..., derivatives=True)` and `eccjump.region`.

use crate::errors::{detached, to_py};
use crate::options::parse_rule;
use eccjump_core::error::{try_filled, Error};
use eccjump_core::jarm::derivatives::jump_derivatives;
use eccjump_core::jarm::JarmOptions;
use numpy::{IntoPyArray, PyArray1, PyArray2, PyArrayMethods, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;

/// Ctrl-C is looked at every this many points (well under a second of work).
const POINTS_PER_SIGNAL_CHECK: usize = 1 << 16;

/// The derivatives' columns: d θ_J, d F_x,J, d F_y,J, d μ_J, each (N, 3) flat in C order,
/// and the flag of the points that are not differentiable.
struct Columns {
    d: [Vec<f64>; 4],
    singular: Vec<bool>,
}

impl Columns {
    fn new(len: usize) -> Result<Self, Error> {
        let wide = len.saturating_mul(3);
        Ok(Self {
            d: [
                try_filled("d_theta_J", wide, f64::NAN)?,
                try_filled("d_Fx_J", wide, f64::NAN)?,
                try_filled("d_Fy_J", wide, f64::NAN)?,
                try_filled("d_mu_J", wide, f64::NAN)?,
            ],
            singular: try_filled("d_singular", len, false)?,
        })
    }
}

/// (α, χ, k_m, μ_s, θ_J) → (dθ_J, dF_x,J, dF_y,J, dμ_J, singular): the first four of shape
/// (N, 3), derivatives with respect to (α, χ, k_m); NaN where θ_J is NaN, a parameter is
/// invalid or the point is singular. `rule`, `theta0`, `omega0` as the classification had
/// them.
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, mu_s, theta_j, *, rule, theta0, omega0))]
#[allow(clippy::too_many_arguments)] // five columns and the classification's options
#[allow(clippy::type_complexity)] // the plain arrays returned
pub fn jarm_derivatives<'py>(
    py: Python<'py>,
    alpha: PyReadonlyArray1<'py, f64>,
    chi: PyReadonlyArray1<'py, f64>,
    km: PyReadonlyArray1<'py, f64>,
    mu_s: PyReadonlyArray1<'py, f64>,
    theta_j: PyReadonlyArray1<'py, f64>,
    rule: &str,
    theta0: f64,
    omega0: f64,
) -> PyResult<(
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray2<f64>>,
    Bound<'py, PyArray1<bool>>,
)> {
    let o = JarmOptions {
        rule: parse_rule(rule)?,
        theta0,
        omega0,
        ..JarmOptions::default()
    };
    o.validate().map_err(to_py)?;
    let cols = [
        alpha.as_slice()?,
        chi.as_slice()?,
        km.as_slice()?,
        mu_s.as_slice()?,
        theta_j.as_slice()?,
    ];
    let len = cols[0].len();
    if cols.iter().any(|c| c.len() != len) {
        return Err(PyValueError::new_err("inputs must have equal lengths"));
    }
    let out = detached(py, |stop| {
        let mut out = Columns::new(len)?;
        for i in 0..len {
            if i % POINTS_PER_SIGNAL_CHECK == POINTS_PER_SIGNAL_CHECK - 1 && stop() {
                return Err(Error::Interrupted);
            }
            let [a, c, k, m, t] = cols.map(|col| col[i]);
            let d = jump_derivatives(a, c, k, m, t, &o);
            for (col, v) in out.d.iter_mut().zip([d.theta_j, d.fx_j, d.fy_j, d.mu_j]) {
                col[3 * i..3 * i + 3].copy_from_slice(&v);
            }
            out.singular[i] = d.singular;
        }
        Ok(out)
    })?;
    let [dt, dfx, dfy, dmu] = out.d.map(|v| v.into_pyarray(py).reshape([len, 3]));
    Ok((dt?, dfx?, dfy?, dmu?, out.singular.into_pyarray(py)))
}

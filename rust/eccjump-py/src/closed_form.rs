//! The paper's closed forms, one function each, element-wise over equal-length 1-D arrays
//! (the Python layer, `eccjump.closed_form`, broadcasts). Each returns the list of its output
//! columns; an invalid point raises ValueError naming the parameter and the index.

use crate::errors::detached;
use eccjump_core::error::{check_range, try_empty, Error, Result as CoreResult};
use eccjump_core::jarm::{from_rest, jump_point};
use eccjump_core::mechanics::{MAX_OMEGA0, MAX_THETA0};
use eccjump_core::{Cylinder, Ramp};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::f64::consts::FRAC_PI_2;

/// An input column.
type Input<'py> = PyReadonlyArray1<'py, f64>;

/// The output columns of a closed form with `O` outputs, or its error.
type Columns<'py, const O: usize> = PyResult<[Bound<'py, PyArray1<f64>>; O]>;

/// Ctrl-C is looked at every this many points (well under a second of work).
const POINTS_PER_SIGNAL_CHECK: usize = 1 << 16;

/// `f` at every point of the equal-length columns `inputs`, with the GIL released: one output
/// column per entry of its result. The first invalid point is a ValueError naming its index.
fn pointwise<'py, const I: usize, const O: usize>(
    py: Python<'py>,
    inputs: [Input<'py>; I],
    f: impl Fn([f64; I]) -> CoreResult<[f64; O]> + Sync,
) -> Columns<'py, O> {
    let mut cols: [&[f64]; I] = [&[]; I];
    for (c, a) in cols.iter_mut().zip(&inputs) {
        *c = a.as_slice()?;
    }
    let len = cols.first().map_or(0, |c| c.len());
    if cols.iter().any(|c| c.len() != len) {
        return Err(PyValueError::new_err("inputs must have equal lengths"));
    }
    let outs = detached(py, |stop| {
        let mut outs: [Vec<f64>; O] = std::array::from_fn(|_| Vec::new());
        for o in &mut outs {
            *o = try_empty("the result", len)?;
        }
        for i in 0..len {
            if i % POINTS_PER_SIGNAL_CHECK == POINTS_PER_SIGNAL_CHECK - 1 && stop() {
                return Err(Error::Interrupted);
            }
            let y = f(cols.map(|c| c[i])).map_err(|e| Error::AtIndex {
                index: i,
                source: Box::new(e),
            })?;
            for (o, v) in outs.iter_mut().zip(y) {
                o.push(v);
            }
        }
        Ok(outs)
    })?;
    Ok(outs.map(|o| o.into_pyarray(py)))
}

fn body(chi: f64, km: f64) -> CoreResult<Cylinder> {
    Cylinder::new(chi, km)
}

fn ramp(alpha: f64, chi: f64, km: f64) -> CoreResult<Ramp> {
    Ramp::new(body(chi, km)?, alpha)
}

/// An angle θ of a closed form: finite, |θ| ≤ 2π·10⁶ (the core's bound of a start).
fn angle(name: &'static str, theta: f64) -> CoreResult<f64> {
    check_range(name, theta, -MAX_THETA0, MAX_THETA0)
}

/// The ramp angle alone (closed forms without a body).
fn valid_alpha(a: f64) -> CoreResult<f64> {
    check_range("alpha", a, 0.0, FRAC_PI_2)
}

/// μ_s ≥ 0, finite.
fn valid_mu_s(m: f64) -> CoreResult<f64> {
    check_range("mu_s", m, 0.0, f64::MAX)
}

/// The start (θ0, θ̇0) of a path, as every classification checks it.
fn start(theta0: f64, omega0: f64) -> CoreResult<(f64, f64)> {
    Ok((
        check_range("theta0", theta0, -MAX_THETA0, MAX_THETA0)?,
        check_range("omega0", omega0, 0.0, MAX_OMEGA0)?,
    ))
}

fn or_nan(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

/// (α, χ, k_m, θ_J) → (F_x,J, F_y,J): Eqs. jump6, Njumpfn.
#[pyfunction]
pub fn jump_forces<'py>(
    py: Python<'py>,
    alpha: Input<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    theta_j: Input<'py>,
) -> Columns<'py, 2> {
    pointwise(py, [alpha, chi, km, theta_j], |[a, c, k, t]| {
        let r = ramp(a, c, k)?;
        let f = jump_point::jump_forces(&r.body, r.alpha, angle("theta_J", t)?);
        Ok([f.fx, f.fy])
    })
}

/// (χ, k_m, θ_J) → μ: Eq. ineq2 (signed).
#[pyfunction]
pub fn mu<'py>(
    py: Python<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    theta_j: Input<'py>,
) -> Columns<'py, 1> {
    pointwise(py, [chi, km, theta_j], |[c, k, t]| {
        Ok([jump_point::mu(&body(c, k)?, angle("theta_J", t)?)])
    })
}

/// (α, θ_J) → n of the green window 2πn − α < θ_J < 2πn, or 0.
#[pyfunction]
pub fn green_turn<'py>(py: Python<'py>, alpha: Input<'py>, theta_j: Input<'py>) -> Columns<'py, 1> {
    pointwise(py, [alpha, theta_j], |[a, t]| {
        let n = jump_point::green_turn(valid_alpha(a)?, angle("theta_J", t)?);
        Ok([n.map_or(0.0, f64::from)])
    })
}

/// (χ, k_m) → (μ_s,min, the angle of the minimum relative to 2πn).
#[pyfunction]
pub fn mu_s_min<'py>(py: Python<'py>, chi: Input<'py>, km: Input<'py>) -> Columns<'py, 2> {
    pointwise(py, [chi, km], |[c, k]| {
        let (m, t) = jump_point::mu_s_min(&body(c, k)?);
        Ok([m, t])
    })
}

/// (χ, k_m, μ_s) → (θ_J,min, θ_J,max) on turn n (n = 0: relative to 2πn).
#[pyfunction]
#[pyo3(signature = (chi, km, mu_s, *, n))]
pub fn theta_j_range<'py>(
    py: Python<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    mu_s: Input<'py>,
    n: u32,
) -> Columns<'py, 2> {
    pointwise(py, [chi, km, mu_s], |[c, k, m]| {
        let r = jump_point::theta_j_range_abs(&body(c, k)?, valid_mu_s(m)?, n);
        Ok([or_nan(r.map(|v| v.0)), or_nan(r.map(|v| v.1))])
    })
}

/// (χ, k_m, μ_s) → α_min = 2πn − θ_J,max.
#[pyfunction]
#[pyo3(signature = (chi, km, mu_s, *, n))]
pub fn alpha_min<'py>(
    py: Python<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    mu_s: Input<'py>,
    n: u32,
) -> Columns<'py, 1> {
    pointwise(py, [chi, km, mu_s], |[c, k, m]| {
        let b = body(c, k)?;
        Ok([or_nan(jump_point::alpha_min(&b, valid_mu_s(m)?, n))])
    })
}

/// (χ, k_m) → γ: Eq. dega2.
#[pyfunction]
pub fn gamma<'py>(py: Python<'py>, chi: Input<'py>, km: Input<'py>) -> Columns<'py, 1> {
    pointwise(py, [chi, km], |[c, k]| Ok([body(c, k)?.gamma()]))
}

/// (θ, α, χ, k_m) → J(θ): Eq. Jta as printed.
#[pyfunction]
pub fn j_paper<'py>(
    py: Python<'py>,
    theta: Input<'py>,
    alpha: Input<'py>,
    chi: Input<'py>,
    km: Input<'py>,
) -> Columns<'py, 1> {
    pointwise(py, [theta, alpha, chi, km], |[t, a, c, k]| {
        Ok([from_rest::j_paper(&ramp(a, c, k)?, angle("theta", t)?)])
    })
}

/// (θ, α, χ, k_m) → χ θ̇² cos θ − cos α along rolling from (θ0, θ̇0).
#[pyfunction]
#[pyo3(signature = (theta, alpha, chi, km, *, theta0, omega0))]
pub fn liftoff_function<'py>(
    py: Python<'py>,
    theta: Input<'py>,
    alpha: Input<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    theta0: f64,
    omega0: f64,
) -> Columns<'py, 1> {
    pointwise(py, [theta, alpha, chi, km], |[t, a, c, k]| {
        let r = ramp(a, c, k)?;
        let (t0, w0) = start(theta0, omega0)?;
        Ok([from_rest::liftoff_from(&r, t0, w0, angle("theta", t)?)])
    })
}

/// (α, χ, k_m) → (J(2πn − α), J(2πn)): Eqs. JtaC1, JtaC2.
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, *, n))]
pub fn j_brackets<'py>(
    py: Python<'py>,
    alpha: Input<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    n: u32,
) -> Columns<'py, 2> {
    pointwise(py, [alpha, chi, km], |[a, c, k]| {
        let r = ramp(a, c, k)?;
        Ok([from_rest::jtac1(&r, n), from_rest::jtac2(&r, n)])
    })
}

/// (α, χ, k_m) → θ_{n,J}: the root in [2πn − α, 2πn], or NaN.
#[pyfunction]
#[pyo3(signature = (alpha, chi, km, *, n))]
pub fn theta_nj<'py>(
    py: Python<'py>,
    alpha: Input<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    n: u32,
) -> Columns<'py, 1> {
    pointwise(py, [alpha, chi, km], |[a, c, k]| {
        Ok([or_nan(from_rest::theta_nj(&ramp(a, c, k)?, n))])
    })
}

/// (θ, α, χ, k_m) → (F_x, F_y) along rolling from (θ0, θ̇0), by energy.
#[pyfunction]
#[pyo3(signature = (theta, alpha, chi, km, *, theta0, omega0))]
pub fn path_forces<'py>(
    py: Python<'py>,
    theta: Input<'py>,
    alpha: Input<'py>,
    chi: Input<'py>,
    km: Input<'py>,
    theta0: f64,
    omega0: f64,
) -> Columns<'py, 2> {
    pointwise(py, [theta, alpha, chi, km], |[t, a, c, k]| {
        let (t0, w0) = start(theta0, omega0)?;
        let kin = ramp(a, c, k)?.kinematics_along(t0, w0, angle("theta", t)?);
        Ok([kin.fx, kin.fy])
    })
}

//! The paper's closed forms, element-wise over equal-length 1-D arrays (the Python layer
//! broadcasts). Each kind names a core function; invalid points raise ValueError naming the
//! parameter and the index.

use crate::errors::detached;
use eccjump_core::error::{check_range, try_filled, Error, Result as CoreResult};
use eccjump_core::jarm::{from_rest, jump_point};
use eccjump_core::mechanics::{MAX_OMEGA0, MAX_THETA0};
use eccjump_core::{Cylinder, Ramp};
use numpy::{IntoPyArray, PyArray1, PyReadonlyArray1};
use pyo3::exceptions::PyValueError;
use pyo3::prelude::*;
use std::f64::consts::FRAC_PI_2;

/// Number of inputs, outputs and the per-point function of each kind.
type PointFn = fn(&[f64], u32, (f64, f64)) -> CoreResult<[f64; 2]>;

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

/// The ramp angle alone (kinds without a body).
fn alpha(a: f64) -> CoreResult<f64> {
    check_range("alpha", a, 0.0, FRAC_PI_2)
}

/// μ_s ≥ 0, finite.
fn mu_s(m: f64) -> CoreResult<f64> {
    check_range("mu_s", m, 0.0, f64::MAX)
}

/// The start (θ0, θ̇0) of a path, as every classification checks it.
fn start((t0, w0): (f64, f64)) -> CoreResult<(f64, f64)> {
    Ok((
        check_range("theta0", t0, -MAX_THETA0, MAX_THETA0)?,
        check_range("omega0", w0, 0.0, MAX_OMEGA0)?,
    ))
}

fn opt(v: Option<f64>) -> f64 {
    v.unwrap_or(f64::NAN)
}

fn kind(name: &str) -> Option<(usize, usize, PointFn)> {
    Some(match name {
        // (alpha, chi, km, theta_J) -> (Fx_J, Fy_J): Eqs. jump6, Njumpfn.
        "jump_forces" => (4, 2, |x, _, _| {
            let r = ramp(x[0], x[1], x[2])?;
            let f = jump_point::jump_forces(&r.body, r.alpha, angle("theta_J", x[3])?);
            Ok([f.fx, f.fy])
        }),
        // (chi, km, theta_J) -> mu: Eq. ineq2 (signed).
        "mu" => (3, 1, |x, _, _| {
            Ok([
                jump_point::mu(&body(x[0], x[1])?, angle("theta_J", x[2])?),
                0.0,
            ])
        }),
        // (alpha, theta_J) -> n of the green window 2πn − α < θ_J < 2πn, or 0.
        "green" => (2, 1, |x, _, _| {
            Ok([
                jump_point::green_turn(alpha(x[0])?, angle("theta_J", x[1])?)
                    .map_or(0.0, f64::from),
                0.0,
            ])
        }),
        // (chi, km) -> (mu_s_min, theta at the minimum relative to 2πn).
        "mu_s_min" => (2, 2, |x, _, _| {
            let (m, t) = jump_point::mu_s_min(&body(x[0], x[1])?);
            Ok([m, t])
        }),
        // (chi, km, mu_s) -> (theta_J_min, theta_J_max) on turn n (n = 0: relative to 2πn).
        "theta_j_range" => (3, 2, |x, n, _| {
            let r = jump_point::theta_j_range_abs(&body(x[0], x[1])?, mu_s(x[2])?, n);
            Ok([opt(r.map(|v| v.0)), opt(r.map(|v| v.1))])
        }),
        // (chi, km, mu_s) -> alpha_min = 2πn − theta_J_max.
        "alpha_min" => (3, 1, |x, n, _| {
            Ok([
                opt(jump_point::alpha_min(&body(x[0], x[1])?, mu_s(x[2])?, n)),
                0.0,
            ])
        }),
        // (chi, km) -> gamma: Eq. dega2.
        "gamma" => (2, 1, |x, _, _| Ok([body(x[0], x[1])?.gamma(), 0.0])),
        // (theta, alpha, chi, km) -> J(theta): Eq. Jta as printed.
        "J" => (4, 1, |x, _, _| {
            Ok([
                from_rest::j_paper(&ramp(x[1], x[2], x[3])?, angle("theta", x[0])?),
                0.0,
            ])
        }),
        // (theta, alpha, chi, km) -> chi θ̇² cos θ − cos α along rolling from (θ0, θ̇0).
        "liftoff" => (4, 1, |x, _, s| {
            let r = ramp(x[1], x[2], x[3])?;
            let (t0, w0) = start(s)?;
            Ok([
                from_rest::liftoff_from(&r, t0, w0, angle("theta", x[0])?),
                0.0,
            ])
        }),
        // (alpha, chi, km) -> J(2πn − α), J(2πn): Eqs. JtaC1, JtaC2.
        "jtac" => (3, 2, |x, n, _| {
            let r = ramp(x[0], x[1], x[2])?;
            Ok([from_rest::jtac1(&r, n), from_rest::jtac2(&r, n)])
        }),
        // (alpha, chi, km) -> θ_{n,J}: the root in [2πn − α, 2πn], or NaN.
        "theta_nj" => (3, 1, |x, n, _| {
            Ok([opt(from_rest::theta_nj(&ramp(x[0], x[1], x[2])?, n)), 0.0])
        }),
        // (theta, alpha, chi, km) -> (Fx, Fy) along rolling from (θ0, θ̇0), by energy.
        "path_forces" => (4, 2, |x, _, s| {
            let (t0, w0) = start(s)?;
            let k = ramp(x[1], x[2], x[3])?.kinematics_along(t0, w0, angle("theta", x[0])?);
            Ok([k.fx, k.fy])
        }),
        _ => return None,
    })
}

/// Evaluates closed form `name` at every point of the input arrays.
#[pyfunction]
#[pyo3(signature = (name, inputs, n, theta0=0.0, omega0=0.0))]
pub fn pointwise<'py>(
    py: Python<'py>,
    name: &str,
    inputs: Vec<PyReadonlyArray1<'py, f64>>,
    n: u32,
    theta0: f64,
    omega0: f64,
) -> PyResult<Vec<Bound<'py, PyArray1<f64>>>> {
    let (n_in, n_out, f) =
        kind(name).ok_or_else(|| PyValueError::new_err(format!("no closed form {name:?}")))?;
    if inputs.len() != n_in {
        return Err(PyValueError::new_err(format!(
            "{name} takes {n_in} arrays, got {}",
            inputs.len()
        )));
    }
    let cols: Vec<&[f64]> = inputs
        .iter()
        .map(|a| a.as_slice())
        .collect::<Result<_, _>>()?;
    let len = cols.first().map_or(0, |c| c.len());
    if cols.iter().any(|c| c.len() != len) {
        return Err(PyValueError::new_err("inputs must have equal lengths"));
    }
    let outs = detached(py, |stop| {
        let mut outs = Vec::with_capacity(n_out);
        for _ in 0..n_out {
            let mut v = try_filled("the result", len, 0.0)?;
            v.clear();
            outs.push(v);
        }
        let mut x = vec![0.0; n_in];
        for i in 0..len {
            // Ctrl-C is looked at every 2^16 points (well under a second of work).
            if i % (1 << 16) == (1 << 16) - 1 && stop() {
                return Err(Error::Interrupted);
            }
            for (xj, c) in x.iter_mut().zip(&cols) {
                *xj = c[i];
            }
            let y = f(&x, n, (theta0, omega0)).map_err(|e| Error::AtIndex {
                index: i,
                source: Box::new(e),
            })?;
            for (o, v) in outs.iter_mut().zip(y) {
                o.push(v);
            }
        }
        Ok(outs)
    })?;
    Ok(outs.into_iter().map(|o| o.into_pyarray(py)).collect())
}

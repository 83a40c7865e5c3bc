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

/// Declares a closed form as a `#[pyfunction]`: its input columns (one point's values are
/// the closure's array, in this order), then after `;` its keyword-only options, the number
/// of output columns and the closure from one point to its outputs, run by [`pointwise`].
macro_rules! closed_form {
    ($(#[$doc:meta])* $name:ident($($col:ident),+ $(; $($opt:ident: $ty:ty),+)?) -> $o:literal,
     $f:expr) => {
        $(#[$doc])*
        #[pyfunction]
        #[pyo3(signature = ($($col),+ $(, *, $($opt),+)?))]
        pub fn $name<'py>(
            py: Python<'py>,
            $($col: Input<'py>,)+
            $($($opt: $ty,)+)?
        ) -> Columns<'py, $o> {
            pointwise(py, [$($col),+], $f)
        }
    };
}

closed_form! {
    /// (α, χ, k_m, θ_J) → (F_x,J, F_y,J): Eqs. jump6, Njumpfn.
    jump_forces(alpha, chi, km, theta_j) -> 2, |[a, c, k, t]| {
        let r = ramp(a, c, k)?;
        let f = jump_point::jump_forces(&r.body, r.alpha, angle("theta_J", t)?);
        Ok([f.fx, f.fy])
    }
}

closed_form! {
    /// (χ, k_m, θ_J) → μ: Eq. ineq2 (signed).
    mu(chi, km, theta_j) -> 1, |[c, k, t]| {
        Ok([jump_point::mu(&body(c, k)?, angle("theta_J", t)?)])
    }
}

closed_form! {
    /// (α, θ_J) → n of the green window 2πn − α < θ_J < 2πn, or 0.
    green_turn(alpha, theta_j) -> 1, |[a, t]| {
        let n = jump_point::green_turn(valid_alpha(a)?, angle("theta_J", t)?);
        Ok([n.map_or(0.0, f64::from)])
    }
}

closed_form! {
    /// (χ, k_m) → (μ_s,min, the angle of the minimum relative to 2πn).
    mu_s_min(chi, km) -> 2, |[c, k]| {
        let (m, t) = jump_point::mu_s_min(&body(c, k)?);
        Ok([m, t])
    }
}

closed_form! {
    /// (χ, k_m, μ_s) → (θ_J,min, θ_J,max) on turn n (n = 0: relative to 2πn).
    theta_j_range(chi, km, mu_s; n: u32) -> 2, |[c, k, m]| {
        let r = jump_point::theta_j_range_abs(&body(c, k)?, valid_mu_s(m)?, n);
        Ok([or_nan(r.map(|v| v.0)), or_nan(r.map(|v| v.1))])
    }
}

closed_form! {
    /// (χ, k_m, μ_s) → α_min = 2πn − θ_J,max.
    alpha_min(chi, km, mu_s; n: u32) -> 1, |[c, k, m]| {
        let b = body(c, k)?;
        Ok([or_nan(jump_point::alpha_min(&b, valid_mu_s(m)?, n))])
    }
}

closed_form! {
    /// (χ, k_m) → γ: Eq. dega2.
    gamma(chi, km) -> 1, |[c, k]| Ok([body(c, k)?.gamma()])
}

closed_form! {
    /// (θ, α, χ, k_m) → J(θ): Eq. Jta as printed.
    j_paper(theta, alpha, chi, km) -> 1, |[t, a, c, k]| {
        Ok([from_rest::j_paper(&ramp(a, c, k)?, angle("theta", t)?)])
    }
}

closed_form! {
    /// (θ, α, χ, k_m) → χ θ̇² cos θ − cos α along rolling from (θ0, θ̇0).
    liftoff_function(theta, alpha, chi, km; theta0: f64, omega0: f64) -> 1, |[t, a, c, k]| {
        let r = ramp(a, c, k)?;
        let (t0, w0) = start(theta0, omega0)?;
        Ok([from_rest::liftoff_from(&r, t0, w0, angle("theta", t)?)])
    }
}

closed_form! {
    /// (α, χ, k_m) → (J(2πn − α), J(2πn)): Eqs. JtaC1, JtaC2.
    j_brackets(alpha, chi, km; n: u32) -> 2, |[a, c, k]| {
        let r = ramp(a, c, k)?;
        Ok([from_rest::jtac1(&r, n), from_rest::jtac2(&r, n)])
    }
}

closed_form! {
    /// (α, χ, k_m) → θ_{n,J}: the root in [2πn − α, 2πn], or NaN.
    theta_nj(alpha, chi, km; n: u32) -> 1, |[a, c, k]| {
        Ok([or_nan(from_rest::theta_nj(&ramp(a, c, k)?, n))])
    }
}

closed_form! {
    /// (θ, α, χ, k_m) → (F_x, F_y) along rolling from (θ0, θ̇0), by energy.
    path_forces(theta, alpha, chi, km; theta0: f64, omega0: f64) -> 2, |[t, a, c, k]| {
        let (t0, w0) = start(theta0, omega0)?;
        let kin = ramp(a, c, k)?.kinematics_along(t0, w0, angle("theta", t)?);
        Ok([kin.fx, kin.fy])
    }
}

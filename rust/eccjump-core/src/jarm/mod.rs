//! The paper's Section 3: does the cylinder jump straight out of pure rolling (a JARM), and
//! if not, why. Two independent routes share one decision tree ([`decision`]), one catalogue
//! of contact events ([`crate::modes::rolling::events`]) and one check of the start:
//!
//! - [`jump_point`]: Sec. 3.1, forces and friction at a jump point (any start);
//! - [`from_rest`]: Sec. 3.2, J(θ), its brackets and θ_{n,J} for the start from rest;
//! - [`path`]: the rigorous scan of the contact conditions along rolling (closed form);
//! - [`mod@classify`]: the closed-form route (path scan + jump-point formulas);
//! - [`ode_route`]: the route by integration of the rolling equation with events;
//! - [`turns`]: the turn of an angle and the search bound n*;
//! - [`result`]: reasons, options and the per-point result.

pub mod classify;
pub mod decision;
pub mod from_rest;
pub mod jump_point;
pub mod ode_route;
pub mod path;
pub mod result;
pub mod turns;

pub use crate::mechanics::Rule;
pub use classify::classify;
pub use ode_route::classify_ode;
pub use result::{JarmOptions, JarmResult, Method, Reason};

/// Classifies one point by the chosen route (never panics; invalid points give
/// `InvalidParams`).
#[inline]
pub fn classify_with(
    method: Method,
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    opts: &JarmOptions,
) -> JarmResult {
    match method {
        Method::ClosedForm => classify(alpha, chi, km, mu_s, opts),
        Method::Ode { rtol, atol } => classify_ode(alpha, chi, km, mu_s, opts, rtol, atol),
    }
}

//! eccjump-core: the dynamics of an eccentric cylinder on a ramp, in pure Rust.
//!
//! Units throughout: g = R = M = 1 (time unit √(R/g), force unit M g); angles in radians.
//!
//! The layers, each using only those above it (see `docs/architecture.md`):
//! - [`error`]: the one error enum and the parameter checks, written once;
//! - [`trig`]: the elementary functions, the same bits on every platform;
//! - [`dual`]: forward-mode differentiation, so that a formula written once has exact
//!   partials;
//! - [`ode`]: generic embedded Runge–Kutta pairs (Dormand–Prince 5(4) as scipy's RK45,
//!   8(5,3) as DOP853, and Verner's 9(8)) with dense output and events, and bracketing root
//!   finders (no physics);
//! - [`mechanics`]: the body, the ramp, Newton–Euler in its general form, energy, the
//!   lift-off rules, friction and the Painlevé test: every formula once;
//! - [`modes`]: the modes of motion as constraints on Newton–Euler (pure rolling, slipping
//!   in time and in the normal impulse, flight with its landing search) and the consistency
//!   test that picks a contact state's mode;
//! - [`jarm`]: the paper's Section 3 (jump-point formulas, from-rest closed forms, the path
//!   scan, the ODE route and the decision tree they share);
//! - [`motion`]: the full motion (rolling, slipping, flight, landing), segment by segment;
//! - [`maps`]: bit-reproducible parallel maps over points and grids, and boundaries.

#![warn(missing_docs)]

#[macro_use]
mod named_enum;

pub mod dual;
pub mod error;
pub mod jarm;
pub mod maps;
pub mod mechanics;
pub mod modes;
pub mod motion;
pub mod ode;
pub mod trig;

#[cfg(test)]
mod testing;

pub use error::{Error, Result};
pub use mechanics::{Cylinder, Ramp, Rule};

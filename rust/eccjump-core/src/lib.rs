//! eccjump-core: the dynamics of an eccentric cylinder on a ramp, in pure Rust.
//!
//! Units throughout: g = R = M = 1 (time unit √(R/g), force unit M g); angles in radians.
//!
//! Modules, one concept each:
//! - [`body`]: the cylinder (χ, k_m) and its inertias;
//! - [`rolling`]: pure-rolling equation of motion and contact forces;
//! - [`roots`]: bracketing root finders;
//! - [`ode`]: a generic Dormand–Prince 5(4) integrator with dense output and events;
//! - [`error`]: the one error enum.

pub mod body;
pub mod boundary;
pub mod error;
pub mod from_rest;
pub mod jarm;
pub mod jump_point;
pub mod path;
pub mod region;
pub mod ode;
pub mod rolling;
pub mod roots;

pub use body::Cylinder;
pub use error::{Error, Result};
pub use rolling::Rolling;

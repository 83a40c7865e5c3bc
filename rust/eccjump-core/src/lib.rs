//! eccjump-core: the dynamics of an eccentric cylinder on a ramp, in pure Rust.
//!
//! Units throughout: g = R = M = 1 (time unit √(R/g), force unit M g); angles in radians.
//!
//! Modules, one concept each:
//! - [`body`]: the cylinder (χ, k_m) and its inertias;
//! - [`rolling`]: pure-rolling equation of motion and contact forces;
//! - [`roots`]: bracketing root finders;
//! - [`roll`]: a pure-rolling run with its contact events;
//! - [`ode`]: a generic Dormand–Prince 5(4) integrator with dense output and events;
//! - [`jump_point`]: the paper's Sec. 3.1, forces and friction at a jump point;
//! - [`from_rest`]: the paper's Sec. 3.2, J(θ), its brackets and θ_{n,J};
//! - [`path`]: rigorous scan of the contact conditions along pure rolling;
//! - [`jarm`]: classification of one parameter point (reason codes, lift-off rules);
//! - [`parallel`]: bit-reproducible parallel maps over independent points;
//! - [`region`]: JARM maps over points and grids;
//! - [`boundary`]: JARM boundaries in α and μ_s by bisection;
//! - [`rule`]: the lift-off rule shared by runs and classification;
//! - [`error`]: the one error enum.

pub mod body;
pub mod boundary;
pub mod error;
pub mod from_rest;
pub mod jarm;
pub mod jarm_ode;
pub mod jump_point;
pub mod ode;
pub mod parallel;
pub mod path;
pub mod region;
pub mod roll;
pub mod rolling;
pub mod roots;
pub mod rule;

pub use body::Cylinder;
pub use error::{Error, Result};
pub use rolling::Rolling;

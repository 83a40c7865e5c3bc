//! The mechanics of the body on the ramp, with no integrator and no analysis in it: the body
//! and its inertias, the ramp, Newton–Euler in its general form, energy, the lift-off rules
//! and Coulomb friction. Every mode of motion ([`crate::modes`]) is a constraint on these
//! equations, and every formula is written here once. A landing is an impact ([`impact`]).

pub mod body;
pub mod energy;
pub mod friction;
pub mod impact;
pub mod liftoff;
pub mod newton_euler;
pub mod ramp;
pub mod state;

/// |θ0| ≤ this (2π·10⁶ rad) for any start: far beyond any physical start; larger angles
/// lose the resolution the searches need (an ulp of θ0 approaches their steps).
pub const MAX_THETA0: f64 = 6_283_185.307179586;

/// |θ̇0| ≤ this (in √(g/R)) for any start: far beyond any physical start, small enough that
/// θ̇² and the forces stay finite.
pub const MAX_OMEGA0: f64 = 1e6;

pub use body::Cylinder;
pub use liftoff::Rule;
pub use newton_euler::{Constraint, Response};
pub use ramp::Ramp;
pub use state::BodyState;

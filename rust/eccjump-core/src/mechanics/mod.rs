//! The mechanics of the body on the ramp, with no integrator and no analysis in it: the body
//! and its inertias, the ramp, Newton–Euler in its general form, energy, the lift-off rules
//! and Coulomb friction. Every mode of motion ([`crate::modes`]) is a constraint on these
//! equations, and every formula is written here once.

pub mod body;
pub mod energy;
pub mod friction;
pub mod liftoff;
pub mod newton_euler;
pub mod ramp;

pub use body::Cylinder;
pub use liftoff::Rule;
pub use newton_euler::{Constraint, Response};
pub use ramp::Ramp;

//! A generic Dormand–Prince 5(4) integrator ("RK45", as scipy's `RK45`) for small
//! fixed-size states, with dense output and exactly located events.
//!
//! Kept apart, as in scipy's `_ivp`: the Butcher tableau ([`tableau`]), one adaptive step
//! with its error norm and step-size control ([`stepper`]), the 4th-order dense-output
//! interpolant ([`dense`]), event detection and root location ([`events`]), and the driver
//! loop that ties them together with step limits and statuses ([`solver`]).
//!
//! The driver never allocates: accepted steps and events are reported to an observer
//! callback, so a caller that needs only the end state pays nothing for a trajectory.

pub mod dense;
pub mod events;
pub mod roots;
pub mod solver;
pub mod stepper;
pub mod tableau;

pub use dense::{DenseBounds, DenseStep};
pub use events::{Direction, EventCarry, EventFunctions, EventSpec, NoEvents, EVENT_CHUNK};
pub use solver::{solve, solve_until, Observation, Outcome, SolverOptions, Status};

/// A state vector of fixed size N.
pub type State<const N: usize> = nalgebra::SVector<f64, N>;

/// A first-order system y' = f(t, y).
pub trait OdeSystem<const N: usize> {
    /// The right-hand side f(t, y).
    fn rhs(&self, t: f64, y: &State<N>) -> State<N>;
}

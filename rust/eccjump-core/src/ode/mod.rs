//! Embedded Runge–Kutta integrators for small fixed-size states (Dormand–Prince 5(4) as
//! scipy's `RK45`, the default, DOP853 as scipy's `DOP853`, and Verner's 9(8) pair `Vern9`;
//! [`Integrator`] names them), with dense output and exactly located events.
//!
//! Kept apart, as in scipy's `_ivp`: the Butcher tableaux ([`tableau`]), each pair's
//! stages, error norm and dense-output construction ([`pair`]), the step-size control that
//! every pair shares ([`stepper`]), the dense-output polynomial ([`dense`]), a step seen
//! from its ends before its dense output is made ([`ends`]), event
//! detection and root location ([`events`]), and the driver loop that ties them together
//! with step limits and statuses ([`solver`]). [`lanes`] runs that same loop for many
//! independent trajectories side by side.
//!
//! The driver never allocates: accepted steps and events are reported to an observer
//! callback, so a caller that needs only the end state pays nothing for a trajectory.

pub mod dense;
pub mod ends;
pub mod events;
pub mod hermite;
pub mod lanes;
pub mod pair;
pub mod roots;
pub mod solver;
pub mod stepper;
pub mod tableau;

pub use crate::trig::SinCos;
pub use dense::{DenseBounds, DenseStep};
pub use ends::StepEnds;
pub use events::{
    quiet_step, Change, Direction, EventBounds, EventCarry, EventFunctions, EventSpec, NoBounds,
    NoEvents, EVENT_CHUNK,
};
pub use pair::Integrator;
pub use solver::{solve, solve_until, Observation, Outcome, SolverOptions, Status};

/// A state vector of fixed size N.
pub type State<const N: usize> = nalgebra::SVector<f64, N>;

/// A first-order system y' = f(t, y).
pub trait OdeSystem<const N: usize> {
    /// The right-hand side f(t, y).
    fn rhs(&self, t: f64, y: &State<N>) -> State<N>;

    /// [`Self::rhs`] with the sine and cosine of y[0] it computed on the way, if any. The
    /// solver asks for them at each step's end (the FSAL evaluation) and hands them on, as
    /// an explicit argument, to the events, their change bounds and the observer at that
    /// same state ([`EventFunctions::values_at`], [`Observation::Step`]), so that none of
    /// them computes them again. None by default.
    #[inline]
    fn rhs_with_trig(&self, t: f64, y: &State<N>) -> (State<N>, Option<SinCos>) {
        (self.rhs(t, y), None)
    }
}

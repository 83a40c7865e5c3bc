//! Event functions g_k(t, y): their specs, and location of their zeros on the dense output.

use super::State;

/// Which zero crossings of g count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Any sign change.
    Any,
    /// g goes from negative to positive.
    Rising,
    /// g goes from positive to negative.
    Falling,
}

/// How an event behaves when it is met.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EventSpec {
    pub direction: Direction,
    /// A terminal event stops the integration at its root.
    pub terminal: bool,
}

/// A set of event functions, evaluated by index (no boxing, no allocation).
pub trait EventFunctions<const N: usize> {
    /// Number of event functions.
    fn count(&self) -> usize;
    /// Direction and terminality of event k.
    fn spec(&self, k: usize) -> EventSpec;
    /// g_k(t, y).
    fn value(&self, k: usize, t: f64, y: &State<N>) -> f64;
}

/// The empty event set.
pub struct NoEvents;

impl<const N: usize> EventFunctions<N> for NoEvents {
    fn count(&self) -> usize {
        0
    }
    fn spec(&self, _k: usize) -> EventSpec {
        unreachable!("NoEvents has no events")
    }
    fn value(&self, _k: usize, _t: f64, _y: &State<N>) -> f64 {
        unreachable!("NoEvents has no events")
    }
}

//! What a batch integrates: each trajectory's system, events and observer ([`Track`]), its
//! start ([`Start`]), and a track with its caller's key ([`Keyed`]).

use super::LaneRhs;
use crate::ode::{EventFunctions, Observation, SolverOptions, State};

/// One trajectory of a batch: its system, its events and what it does with what the
/// integration reports (as the observer of [`crate::ode::solve`]).
pub trait Track<const N: usize> {
    /// The system.
    type Sys: LaneRhs<N>;
    /// The events.
    type Events: EventFunctions<N>;
    /// The system.
    fn sys(&self) -> &Self::Sys;
    /// The events.
    fn events(&self) -> &Self::Events;
    /// An accepted step or an event, in the order [`crate::ode::solve`] reports them (by
    /// shared reference: the events, also borrowed from the track, are scanned meanwhile;
    /// a track keeps what it learns in cells).
    fn observe(&self, obs: Observation<'_, N>);
}

/// A trajectory to integrate: the track, its start (t0, y0), its end t_end and options (all
/// tracks of a batch share the pair P).
pub struct Start<T, const N: usize> {
    /// The trajectory.
    pub track: T,
    /// Initial time.
    pub t0: f64,
    /// Initial state.
    pub y0: State<N>,
    /// Final time.
    pub t_end: f64,
    /// Tolerances, limits, event samples.
    pub opts: SolverOptions,
}

/// A track with its caller's key, so that `done` knows whose outcome it gets.
pub struct Keyed<K, T> {
    /// The caller's key.
    pub key: K,
    /// The track.
    pub track: T,
}

impl<K, T: Track<N>, const N: usize> Track<N> for Keyed<K, T> {
    type Sys = T::Sys;
    type Events = T::Events;
    #[inline]
    fn sys(&self) -> &T::Sys {
        self.track.sys()
    }
    #[inline]
    fn events(&self) -> &T::Events {
        self.track.events()
    }
    #[inline]
    fn observe(&self, obs: Observation<'_, N>) {
        self.track.observe(obs)
    }
}

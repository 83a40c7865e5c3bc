//! Many independent trajectories side by side, [`LANES`] at a time: the same steps, events
//! and outcomes as [`crate::ode::solve`] gives each of them, bit for bit, in less time.
//!
//! One trajectory's step is a chain of dependent operations (stage after stage, each with a
//! `sin_cos`), so one trajectory keeps only a sliver of a core busy. Here the stages of
//! [`LANES`] trajectories are computed together, component by component across the lanes
//! ([`Lanes`]), which the compiler turns into vector instructions: the right-hand sides of
//! all lanes at once ([`LaneRhs`], with [`crate::trig::lanes`]), and each pair's weighted
//! sums of the stages for its error norm and dense output ([`RkPair::error_sums`],
//! [`RkPair::dense_sums`], generic over a state or lanes: one formula). Everything that
//! decides, per trajectory, stays the scalar code of [`crate::ode`], so it exists once: the
//! step-size control (`Stepper::first_trial`, `trial`, `judge_powered`), the error norm
//! and dense output from the sums ([`RkPair::error_from_sums`],
//! [`RkPair::dense_from_sums`]), the event scan and the observations (`solver::Run`). A
//! lane whose trajectory ends takes the next one at once; the last few finish alone.
//!
//! The right-hand side of a lane batch is autonomous (t does not enter it): the systems
//! integrated this way (rolling) are.

mod lanes;
mod round;
mod track;

pub use crate::trig::lanes::{Lane, LANES};
pub use lanes::{LaneRhs, Lanes};
pub use track::{Keyed, Start, Track};

use super::pair::{Dop853, Dp5, Method, RkPair, Vern9};
use super::Outcome;
use round::rounds;

/// Integrates every trajectory that `next` gives, [`LANES`] at a time with the pair P, each
/// exactly as [`crate::ode::solve_until`] would (the same steps, observations and outcome,
/// bit for bit), and hands each to `done` with its outcome as soon as it ends. `next` is
/// asked whenever a lane is free, so a `None` need not be its last word: `done` may give it
/// more (the continuation of a trajectory); the work ends when no lane is busy and `next`
/// has nothing. `stop` is asked as `solve_until` asks it, per trajectory. Uses AVX2 where
/// the CPU has it (the same operations, so the same bits; no fused multiply-add).
pub fn solve_lanes<P, T, const N: usize>(
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, the only feature the function is compiled for.
            unsafe { lanes_avx2::<P, T, N>(next, done, stop) };
            return;
        }
    }
    rounds::<P, T, N>(next, done, stop);
}

/// [`rounds`] compiled for AVX2 (two 4-wide registers per lane group instead of four SSE2
/// ones).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn lanes_avx2<P, T, const N: usize>(
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    rounds::<P, T, N>(next, done, stop);
}

/// [`solve_lanes`] with the pair `method`.
pub fn solve_lanes_with<T: Track<N>, const N: usize>(
    method: Method,
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) {
    match method {
        Method::Rk45 => solve_lanes::<Dp5<N>, T, N>(next, done, stop),
        Method::Dop853 => solve_lanes::<Dop853<N>, T, N>(next, done, stop),
        Method::Vern9 => solve_lanes::<Vern9<N>, T, N>(next, done, stop),
    }
}

#[cfg(test)]
mod tests;

//! [`LANES`] states side by side ([`Lanes`]: component by component across the lanes, the
//! form the compiler turns into vector instructions) and the systems whose right-hand side
//! takes them ([`LaneRhs`]).

// Lane loops index several arrays in step: the form that the compiler vectorizes.
#![allow(clippy::needless_range_loop)]

use crate::ode::pair::Summand;
use crate::ode::{OdeSystem, State};
use crate::trig::lanes::{Lane, LANES};

/// N components of [`LANES`] states: component i of lane l is `self.0[i][l]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lanes<const N: usize>(pub [Lane; N]);

impl<const N: usize> Lanes<N> {
    /// Lane l as a state.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> State<N> {
        State::<N>::from_fn(|i, _| self.0[i][l])
    }

    /// Sets lane l to `v`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, v: &State<N>) {
        for i in 0..N {
            self.0[i][l] = v[i];
        }
    }

    /// self + d·h, lane by lane (each lane's own h), in the order of `y + d * h` on states.
    #[inline(always)]
    pub(super) fn plus_times(&self, d: &Self, h: &Lane) -> Self {
        let mut out = *self;
        for i in 0..N {
            for l in 0..LANES {
                out.0[i][l] = self.0[i][l] + d.0[i][l] * h[l];
            }
        }
        out
    }
}

impl<const N: usize> std::ops::Add for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, rhs: Self) -> Self {
        for i in 0..N {
            for l in 0..LANES {
                self.0[i][l] += rhs.0[i][l];
            }
        }
        self
    }
}

impl<const N: usize> std::ops::Mul<f64> for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(mut self, w: f64) -> Self {
        for row in self.0.iter_mut() {
            for x in row.iter_mut() {
                *x *= w;
            }
        }
        self
    }
}

impl<const N: usize> Summand for Lanes<N> {
    #[inline(always)]
    fn zero() -> Self {
        Self([[0.0; LANES]; N])
    }
}

/// A system whose right-hand side can be evaluated for [`LANES`] states at once.
pub trait LaneRhs<const N: usize>: OdeSystem<N> {
    /// f at lane l's state by `systems[l]`, for every lane; bit for bit
    /// [`OdeSystem::rhs`] (at any t: the system is autonomous).
    fn rhs_lanes(systems: &[&Self; LANES], y: &Lanes<N>) -> Lanes<N>;

    /// Called once the stages of a round are done: lane l's system may prepare what the
    /// event scan of its step will ask at the step's end `y_new` (a memo of its
    /// trigonometry, say). Nothing by default.
    #[inline(always)]
    fn step_end_lanes(systems: &[&Self; LANES], y_new: &Lanes<N>) {
        let _ = (systems, y_new);
    }
}

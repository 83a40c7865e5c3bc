//! The rolling equation as a first-order system in y = (θ, θ̇): one state at a time, or
//! [`LANES`] at once, each handing on the trigonometry of θ it computed
//! ([`OdeSystem::rhs_with_trig`]), so that the event scan and the observer at a step's end
//! do not compute it again.

use crate::mechanics::Ramp;
use crate::ode::lanes::{Lane, LaneRhs, Lanes, LANES};
use crate::ode::{OdeSystem, SinCos, State};
use crate::trig::lanes::sin_cos_lanes;

impl OdeSystem<2> for Ramp {
    #[inline]
    fn rhs(&self, t: f64, y: &State<2>) -> State<2> {
        self.rhs_with_trig(t, y).0
    }

    /// f and (sin θ, cos θ).
    #[inline]
    fn rhs_with_trig(&self, _t: f64, y: &State<2>) -> (State<2>, Option<SinCos>) {
        // θ̇ made opaque to the optimiser, which otherwise sinks the stage's θ̇ past the
        // `sin_cos` call and packs it with the products of sin θ and cos θ, so that the
        // stage waits for the call: roll with Vern9 measured 8 % slower without it (an
        // identity: the same bits; docs/performance.md, "The memo as an explicit argument").
        let omega = std::hint::black_box(y[1]);
        let trig = SinCos::of(y[0]);
        let f = State::<2>::new(omega, self.omega_dot_sc(trig.sin, trig.cos, omega));
        (f, Some(trig))
    }
}

impl LaneRhs<2> for Ramp {
    /// [`OdeSystem::rhs`] of each lane's system, bit for bit (the same `sin_cos` by
    /// [`sin_cos_lanes`], the same θ̈ by [`Ramp::omega_dot_sc`]).
    #[inline(always)]
    fn rhs_lanes(systems: &[&Self; LANES], y: &Lanes<2>) -> Lanes<2> {
        Self::rhs_lanes_with_trig(systems, y).0
    }

    #[inline(always)]
    fn rhs_lanes_with_trig(
        systems: &[&Self; LANES],
        y: &Lanes<2>,
    ) -> (Lanes<2>, Option<[Lane; 2]>) {
        let [theta, omega] = &y.0;
        let (s, c) = sin_cos_lanes(theta);
        let mut acc = [0.0; LANES];
        for l in 0..LANES {
            acc[l] = systems[l].omega_dot_sc(s[l], c[l], omega[l]);
        }
        (Lanes([*omega, acc]), Some([s, c]))
    }
}

//! Pure rolling with a memo of the step end's trigonometry, shared by the right-hand side,
//! the event scan and the observer of a run.

use crate::mechanics::Ramp;
use crate::modes::rolling::Kinematics;
use crate::ode::lanes::{LaneRhs, Lanes, LANES};
use crate::ode::{OdeSystem, State};
use crate::trig::lanes::sin_cos_lanes;
use crate::trig::SinCosMemo;

/// Pure rolling with a one-entry memo of (sin θ, cos θ), keyed on the bits of θ. Each
/// accepted step ends with the FSAL evaluation of the right-hand side at the new state;
/// the step scan then evaluates the events there and the caller's observer looks at the
/// forces there, and both find sin_cos of that θ in the memo. sin_cos is a pure function,
/// so hits and misses give identical bits. Shared by the rolling run and the ODE route of the classification.
#[derive(Debug, Clone)]
pub(crate) struct RollingMemo {
    pub ramp: Ramp,
    trig: SinCosMemo,
}

impl RollingMemo {
    pub(crate) fn new(ramp: Ramp) -> Self {
        Self {
            ramp,
            trig: SinCosMemo::default(),
        }
    }

    #[inline]
    pub(crate) fn sin_cos(&self, theta: f64) -> (f64, f64) {
        self.trig.get(theta)
    }

    /// The memo's entry (θ, sin θ, cos θ): an anchor for [`ContactBounds::near`] (θ is
    /// NaN before the first evaluation, which the bounds treat as no anchor).
    #[inline]
    pub(crate) fn anchor(&self) -> (f64, f64, f64) {
        self.trig.entry()
    }

    /// [`Ramp::kinematics`], bit for bit.
    #[inline]
    pub(crate) fn kinematics(&self, theta: f64, omega: f64) -> Kinematics {
        let (s, c) = self.sin_cos(theta);
        self.ramp.kinematics_sc(theta, omega, s, c)
    }
}

impl OdeSystem<2> for RollingMemo {
    #[inline]
    fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
        let (s, c) = self.sin_cos(y[0]);
        State::<2>::new(y[1], self.ramp.omega_dot_sc(s, c, y[1]))
    }
}

impl LaneRhs<2> for RollingMemo {
    /// [`OdeSystem::rhs`] of each lane's system, bit for bit (the same `sin_cos` by
    /// [`sin_cos_lanes`], the same θ̈ by [`Ramp::omega_dot_sc`]).
    #[inline(always)]
    fn rhs_lanes(systems: &[&Self; LANES], y: &Lanes<2>) -> Lanes<2> {
        let [theta, omega] = &y.0;
        let (s, c) = sin_cos_lanes(theta);
        let mut acc = [0.0; LANES];
        for l in 0..LANES {
            acc[l] = systems[l].ramp.omega_dot_sc(s[l], c[l], omega[l]);
        }
        Lanes([*omega, acc])
    }

    /// Each memo gets the trigonometry of its lane's step end, where the event scan
    /// starts (after the extra stages of DOP853's dense output, which the scalar route
    /// leaves in the memo instead).
    #[inline(always)]
    fn step_end_lanes(systems: &[&Self; LANES], y_new: &Lanes<2>) {
        SinCosMemo::set_lanes(&y_new.0[0], |l| &systems[l].trig);
    }
}

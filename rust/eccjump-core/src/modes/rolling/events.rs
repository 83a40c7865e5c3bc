//! The one catalogue of events that end pure rolling, shared by the rolling run, the
//! closed-form path scan and the ODE route of the JARM classification: the paper's
//! lift-off (L = χθ̇² cos θ − cos α rising through 0), loss of normal force (F_y falling
//! through 0), slip (the margin μ_s F_y − |F_x| falling through 0), the body stopping
//! (θ̇² back to 0: it rocks back) and θ reaching its limit (a run's θ_max, the end of a
//! search).
//!
//! Ties are resolved in the order of [`ContactEvent::ALL`]; a condition already violated at
//! the start is found by [`violated_at_start`], the same test for both routes.
//! [`ContactEvents`] are the event functions of one integration, a run's or the ODE route's:
//! which events it watches and which of them end it.

use crate::mechanics::friction::{slip_margin, slip_margin_rate};
use crate::mechanics::{Ramp, Rule};
use crate::modes::rolling::bounds::ContactBounds;
use crate::modes::rolling::{ContactRates, Kinematics};
use crate::ode::{
    Change, DenseStep, Direction, EventBounds, EventFunctions, EventSpec, SinCos, State, StepEnds,
};

named_enum! {
    /// An event that ends pure rolling, in tie order (the index is the discriminant, and the
    /// index of its event function in a run and in the ODE route).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    #[repr(u8)]
    pub enum ContactEvent {
        /// The paper's lift-off: L reaches 0 from below.
        Liftoff = 0 => "liftoff",
        /// F_y reaches 0.
        NormalForce = 1 => "normal_force_zero",
        /// μ_s F_y − |F_x| reaches 0: the rolling branch leaves the friction cone.
        Slip = 2 => "slip",
        /// θ̇² returns to 0: the body stops and rolls back (watched by a search; a run rolls
        /// back and on).
        RocksBack = 3 => "rocks_back",
        /// θ reaches its limit: a run's θ_max, or the end of a search (nothing happened
        /// before it).
        ThetaLimit = 4 => "theta_limit",
    }
}

impl ContactEvent {
    /// The direction of its crossing: the lift-off and θ's limit rise through 0, the others
    /// fall.
    pub fn direction(self) -> Direction {
        match self {
            ContactEvent::Liftoff | ContactEvent::ThetaLimit => Direction::Rising,
            _ => Direction::Falling,
        }
    }
}

/// The events of the catalogue, in tie order.
pub const N_EVENTS: usize = ContactEvent::ALL.len();

/// The contact events of a rolling integration, a run's or a search's: which events of the
/// catalogue it watches and which of them end it. An event not watched is a constant on its
/// side before the crossing (−1 rising, 1 falling): it never crosses, and its change bound
/// is 0.
#[derive(Debug, Clone, Copy)]
pub struct ContactEvents {
    /// The body on its ramp (also the system integrated).
    pub ramp: Ramp,
    /// μ_s of the slip event (read only if the slip is watched).
    pub mu_s: f64,
    /// The angle of the `ThetaLimit` event (read only if it is watched).
    pub theta_end: f64,
    /// Whether each event is watched, in the order of [`ContactEvent::ALL`].
    pub watched: [bool; N_EVENTS],
    /// Whether each ends the integration, in the same order.
    pub terminal: [bool; N_EVENTS],
}

impl ContactEvents {
    /// A rolling run's: every event but the stop (a run rolls back and on), the slip only with
    /// μ_s, θ_max only if finite; the lift-off ends the run under the paper's rule only.
    pub fn of_run(ramp: Ramp, mu_s: Option<f64>, theta_max: f64, rule: Rule) -> Self {
        Self {
            ramp,
            mu_s: mu_s.unwrap_or(0.0),
            theta_end: theta_max,
            watched: [true, true, mu_s.is_some(), false, theta_max.is_finite()],
            terminal: [rule == Rule::Paper, true, mu_s.is_some(), false, true],
        }
    }

    /// A search's (the ODE route of the classification), every event terminal: the lift-off
    /// under the paper's rule only, the loss of contact (normal force, friction) unless
    /// `contact` is false (the continuation after a slip), the stop, and θ reaching
    /// `theta_end`.
    pub fn of_search(ramp: Ramp, mu_s: f64, theta_end: f64, rule: Rule, contact: bool) -> Self {
        Self {
            ramp,
            mu_s,
            theta_end,
            watched: [rule == Rule::Paper, contact, contact, true, true],
            terminal: [true; N_EVENTS],
        }
    }

    #[inline]
    fn watches(&self, e: ContactEvent) -> bool {
        self.watched[e as usize]
    }

    /// Whether the event ends the integration.
    #[inline]
    pub fn is_terminal(&self, e: ContactEvent) -> bool {
        self.terminal[e as usize]
    }

    /// g of the event from the kinematics `k` at a state.
    #[inline]
    fn value(&self, e: ContactEvent, k: &Kinematics) -> f64 {
        if !self.watches(e) {
            return if e.direction() == Direction::Rising {
                -1.0
            } else {
                1.0
            };
        }
        match e {
            ContactEvent::Liftoff => k.lift,
            ContactEvent::NormalForce => k.fy,
            // The margin, not the ratio: it stays finite as F_y → 0.
            ContactEvent::Slip => slip_margin(self.mu_s, k.fx, k.fy),
            ContactEvent::RocksBack => k.omega,
            ContactEvent::ThetaLimit => k.theta - self.theta_end,
        }
    }

    /// dg/dt of the event from the kinematics `k` and the contact functions' rates `r`.
    #[inline]
    fn rate(&self, e: ContactEvent, k: &Kinematics, r: &ContactRates) -> f64 {
        if !self.watches(e) {
            return 0.0;
        }
        match e {
            ContactEvent::Liftoff => r.lift,
            ContactEvent::NormalForce => r.fy,
            ContactEvent::Slip => slip_margin_rate(self.mu_s, k.fx, r.fx, r.fy),
            ContactEvent::RocksBack => k.omega_dot,
            ContactEvent::ThetaLimit => k.omega,
        }
    }

    /// [`EventBounds::change_bounds`] of all events, anchored at `anchor` (see
    /// `ContactBounds::near`).
    #[inline]
    pub(crate) fn change_bounds_near(
        &self,
        dense: &DenseStep<2>,
        anchor: Option<SinCos>,
    ) -> [Change; N_EVENTS] {
        self.of_all(ContactBounds::near(
            &self.ramp,
            self.slip_mu(),
            dense,
            anchor,
        ))
    }

    /// μ_s where the slip is watched (the bounds' argument).
    #[inline]
    fn slip_mu(&self) -> Option<f64> {
        self.watches(ContactEvent::Slip).then_some(self.mu_s)
    }

    /// The bounds of all events, in their order, from the contact functions'.
    #[inline]
    fn of_all(&self, b: ContactBounds) -> [Change; N_EVENTS] {
        let on = |e, x: Change| if self.watches(e) { x } else { Change::NONE };
        let theta_limit = if self.watches(ContactEvent::ThetaLimit) {
            b.theta_above(self.theta_end)
        } else {
            Change::NONE
        };
        [
            on(ContactEvent::Liftoff, b.liftoff),
            on(ContactEvent::NormalForce, b.fy),
            on(ContactEvent::Slip, b.slip),
            on(ContactEvent::RocksBack, b.omega),
            theta_limit,
        ]
    }
}

impl EventFunctions<2> for ContactEvents {
    const HAS_SLOPES: bool = true;
    fn count(&self) -> usize {
        N_EVENTS
    }
    fn spec(&self, k: usize) -> EventSpec {
        let e = ContactEvent::ALL[k];
        EventSpec {
            direction: e.direction(),
            terminal: self.is_terminal(e),
        }
    }
    #[inline]
    fn values(&self, first: usize, t: f64, y: &State<2>, out: &mut [f64]) {
        self.values_at(first, t, y, None, out);
    }
    /// All events from one evaluation of the kinematics (one `sin_cos` per sample, none
    /// with `trig`).
    #[inline]
    fn values_at(&self, first: usize, _: f64, y: &State<2>, trig: Option<SinCos>, out: &mut [f64]) {
        let k = self.ramp.kinematics_at(y[0], y[1], trig);
        for (o, &e) in out.iter_mut().zip(&ContactEvent::ALL[first..]) {
            *o = self.value(e, &k);
        }
    }
    /// Slopes for the dip test (grazing events between two samples).
    #[inline]
    fn slopes(&self, first: usize, _t: f64, y: &State<2>, out: &mut [f64]) {
        let k = self.ramp.kinematics(y[0], y[1]);
        let r = self.ramp.contact_rates(&k);
        for (o, &e) in out.iter_mut().zip(&ContactEvent::ALL[first..]) {
            *o = self.rate(e, &k, &r);
        }
    }
    #[inline]
    fn bounds(&self) -> Option<&impl EventBounds<2>> {
        Some(self)
    }
}

impl EventBounds<2> for ContactEvents {
    /// Change bounds from bounds on the partial derivatives of each g in θ and θ̇ over the
    /// step, times the bounds on |dθ/dt|, |dθ̇/dt| of the interpolant; tightened by the
    /// trigonometry of the step's end when it is there (`ContactBounds::near`).
    #[inline]
    fn change_bounds(
        &self,
        first: usize,
        dense: &DenseStep<2>,
        end_trig: Option<SinCos>,
        out: &mut [Change],
    ) {
        let b = self.change_bounds_near(dense, end_trig);
        out.copy_from_slice(&b[first..first + out.len()]);
    }
    /// The same from the step's ends alone (`ContactBounds::from_ends`).
    #[inline]
    fn change_bounds_ends(
        &self,
        first: usize,
        ends: &StepEnds<2>,
        bends: bool,
        end_trig: Option<SinCos>,
        out: &mut [Change],
    ) {
        let b = ContactBounds::from_ends(&self.ramp, self.slip_mu(), ends, end_trig, bends);
        out.copy_from_slice(&self.of_all(b)[first..first + out.len()]);
    }
}

/// Which of the conditions a search watches (the stop and the end are always watched).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Watched {
    /// The paper's lift-off (only under the paper's rule).
    pub liftoff: bool,
    /// Loss of normal force.
    pub normal_force: bool,
    /// The friction cone.
    pub friction: bool,
}

/// The contact functions at the start of a search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartValues {
    /// L and dL/dθ.
    pub lift: f64,
    /// dL/dθ along rolling.
    pub lift_slope: f64,
    /// F_x and F_y.
    pub fx: f64,
    /// F_y.
    pub fy: f64,
    /// The kinetic energy ½Ĩ_Pθ̇² and its slope dE/dθ = sin α + χ sin(α + θ).
    pub kinetic: f64,
    /// dE/dθ.
    pub kinetic_slope: f64,
}

/// The first condition (in tie order) already violated at the start, if any; NaN counts
/// as a violation. Lift-off: L ≥ 0 and not falling; normal force: F_y ≤ 0; friction:
/// μ_s F_y ∓ F_x < 0; stop: no kinetic energy and no forward acceleration.
pub fn violated_at_start(w: Watched, mu_s: f64, v: &StartValues) -> Option<ContactEvent> {
    if w.liftoff && liftoff_at_start(v.lift, v.lift_slope) {
        return Some(ContactEvent::Liftoff);
    }
    if w.normal_force && (v.fy.is_nan() || v.fy <= 0.0) {
        return Some(ContactEvent::NormalForce);
    }
    let m = mu_s * v.fy;
    let (mp, mm) = (m - v.fx, m + v.fx);
    if w.friction && (mp.is_nan() || mm.is_nan() || mp < 0.0 || mm < 0.0) {
        return Some(ContactEvent::Slip);
    }
    let (e, de) = (v.kinetic, v.kinetic_slope);
    if e < 0.0 || (e == 0.0 && (de.is_nan() || de <= 0.0)) {
        return Some(ContactEvent::RocksBack);
    }
    None
}

/// The paper's lift-off already at the start: L ≥ 0 (or NaN) and not falling from L = 0.
#[inline]
pub fn liftoff_at_start(lift: f64, lift_slope: f64) -> bool {
    (lift.is_nan() || lift >= 0.0) && !(lift == 0.0 && lift_slope < 0.0)
}

/// A start from rest in equilibrium (θ̈0 = 0 inside the contact conditions): nothing ever
/// happens (e.g. α = 0 from rest).
pub fn equilibrium_start(omega0: f64, omega_dot: f64, fx: f64, fy: f64, mu_s: f64) -> bool {
    omega0 == 0.0 && omega_dot == 0.0 && fy > 0.0 && mu_s * fy >= fx.abs()
}

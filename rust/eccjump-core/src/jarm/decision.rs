//! The decision tree shared by both routes of the classification: from the lift-off rule
//! and the first contact event on the rolling path (found by the path scan or by
//! integration) to the [`Reason`] and the reported fields. Also the start of a search
//! (equilibrium starts, the search bound) that both routes share.
//!
//! - `ThetaLimit` (the end of the search) → the end reason of the search (`NoRoot`, or
//!   `TurnLimit` past `max_turns`); `RocksBack` → `RocksBack`.
//! - Paper rule, lift-off: at the start → `LiftoffEarlier`; outside a green window
//!   2πn − α < θ_J < 2πn or with F_y,J ≤ 0 → `NormalForceLost`; μ(θ_J) > μ_s (Eq. ineq2) →
//!   `SlipAtJump`; else a JARM with the jump-point forces of Sec. 3.1.
//! - Paper rule, loss of normal force → `NormalForceLost`; slip → the route continues along
//!   rolling to the paper's lift-off: in a green window with ineq2 failing there it is
//!   `SlipAtJump`, else `SlipBefore` (with `stop_at_slip`: `Slip`, no continuation).
//! - Classical rule, loss of normal force → a JARM there (`LiftoffEarlier` at the start);
//!   slip → a JARM if sliding is inconsistent ([`slip_onset_flies`]), else `SlipBefore`.
//!
//! With an explicit turn n the result is then restricted to that turn (first-jump
//! semantics, [`restrict_to_turn`]).

use crate::jarm::jump_point::{green_turn, jump_forces, mu};
use crate::jarm::result::{JarmOptions, JarmResult, Reason};
use crate::jarm::turns::{turn_bound, turn_of, turns_before};
use crate::mechanics::friction::slip_onset_flies;
use crate::mechanics::{Cylinder, Ramp, Rule};
use crate::modes::rolling::events::ContactEvent;
use std::f64::consts::{PI, TAU};

/// The largest friction ratio and the smallest normal force met on the rolling path, with
/// the angles where they occur.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Extrema {
    /// max |F_x|/F_y.
    pub max_ratio: f64,
    /// Where.
    pub theta_max_ratio: f64,
    /// min F_y.
    pub min_fy: f64,
    /// Where.
    pub theta_min_fy: f64,
}

/// The rolling state where the deciding event happened.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventPoint {
    /// θ of the event.
    pub theta: f64,
    /// sin θ, cos θ (as the route computed them).
    pub sin_t: f64,
    /// cos θ.
    pub cos_t: f64,
    /// Contact force of the rolling branch there.
    pub fx: f64,
    /// Normal force there.
    pub fy: f64,
    /// The lift-off function there.
    pub lift: f64,
}

/// What a route found first along the rolling path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Found {
    /// The event (ties already resolved by the route).
    pub event: ContactEvent,
    /// True if the condition was already violated at the start.
    pub at_start: bool,
    /// Where.
    pub at: EventPoint,
    /// The path extrema up to there.
    pub extrema: Extrema,
}

/// One classification's fixed inputs.
#[derive(Debug, Clone, Copy)]
pub struct Case<'a> {
    /// The body.
    pub body: &'a Cylinder,
    /// The ramp angle.
    pub alpha: f64,
    /// Static friction.
    pub mu_s: f64,
    /// The lift-off rule.
    pub rule: Rule,
    /// The reason of a search that ends without an event.
    pub end_reason: Reason,
    /// Stop at a slip (paper rule): `Slip`, without the continuation to the lift-off.
    pub stop_at_slip: bool,
}

impl JarmResult {
    /// A result with `reason` carrying the path extrema (shared by both routes).
    pub(crate) fn with_extrema(reason: Reason, e: &Extrema) -> Self {
        let mut r = Self::new(reason);
        (r.max_ratio, r.theta_max_ratio) = (e.max_ratio, e.theta_max_ratio);
        (r.min_fy, r.theta_min_fy) = (e.min_fy, e.theta_min_fy);
        r
    }
}

/// The validated ramp of a point, or None (→ `InvalidParams`) if a parameter is out of range.
pub fn point_ramp(alpha: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> Option<Ramp> {
    if !(mu_s.is_finite() && mu_s >= 0.0) || o.validate().is_err() {
        return None;
    }
    Cylinder::new(chi, km)
        .and_then(|b| Ramp::new(b, alpha))
        .ok()
}

/// Where a search along rolling from (θ0, θ̇0) stops, and the reason if nothing happens by
/// then: the turn bound n* ([`turn_bound`]), capped `max_turns` turns after the start
/// (`TurnLimit`), and by 2πn + π for an explicit turn n. None if the search is empty (→ `NoRoot`).
pub fn search_end(r: &Ramp, o: &JarmOptions) -> Option<(f64, Reason)> {
    let last = turns_before(o.theta0) + o.max_turns as u64; // the cap counts from the start
    let (mut theta_end, end_reason) = match turn_bound(r, o.theta0, o.omega0, o.max_turns) {
        None => (o.theta0 + TAU, Reason::NoRoot), // α = 0 or χ = 0: periodic, one turn suffices
        Some(n) if n as u64 > last => (TAU * last as f64, Reason::TurnLimit),
        Some(n) => (TAU * n as f64, Reason::NoRoot),
    };
    if o.n > 0 {
        let lim = TAU * o.n as f64 + PI;
        if lim < theta_end {
            theta_end = lim;
        }
    }
    (theta_end > o.theta0).then_some((theta_end, end_reason))
}

/// The decision tree of the module notes. `liftoff_after_slip` continues along rolling from
/// the slip point to the paper's lift-off angle (paper rule only; None if there is none).
pub fn decide(
    case: &Case,
    found: &Found,
    liftoff_after_slip: impl FnOnce() -> Option<f64>,
) -> JarmResult {
    let ext = &found.extrema;
    let p = &found.at;
    let th = p.theta;
    let failure = |reason: Reason| {
        let mut x = JarmResult::with_extrema(reason, ext);
        x.theta_event = th;
        x.n = turn_of(th);
        x
    };
    // A failure with a lift-off angle: the earlier one, or the paper's after a slip.
    let failure_at = |reason: Reason, theta_j: f64| {
        let mut x = failure(reason);
        x.theta_j = theta_j;
        x
    };
    let liftoff_earlier = || failure_at(Reason::LiftoffEarlier, th);
    let jarm = |n: u32, fx: f64, fy: f64| {
        let mut x = JarmResult::with_extrema(Reason::Jarm, ext);
        (x.n, x.theta_j, x.fx_j, x.fy_j) = (n, th, fx, fy);
        x
    };
    match (case.rule, found.event) {
        (_, ContactEvent::ThetaLimit) => JarmResult::with_extrema(case.end_reason, ext),
        (_, ContactEvent::RocksBack) => {
            let mut x = JarmResult::with_extrema(Reason::RocksBack, ext);
            x.theta_event = th;
            x
        }
        (Rule::Paper, ContactEvent::Liftoff) if found.at_start => liftoff_earlier(),
        (Rule::Paper, ContactEvent::Liftoff) => {
            let jf = jump_forces(case.body, case.alpha, th);
            let green = green_turn(case.alpha, th);
            if green.is_none() || jf.fy <= 0.0 {
                failure(Reason::NormalForceLost)
            } else if mu(case.body, th) > case.mu_s {
                failure_at(Reason::SlipAtJump, th)
            } else {
                jarm(green.unwrap_or(0), jf.fx, jf.fy)
            }
        }
        (Rule::Paper, ContactEvent::NormalForce) => failure(Reason::NormalForceLost),
        (Rule::Paper, ContactEvent::Slip) if case.stop_at_slip => failure(Reason::Slip),
        (Rule::Paper, ContactEvent::Slip) => match liftoff_after_slip() {
            Some(tl) if green_turn(case.alpha, tl).is_some() && mu(case.body, tl) > case.mu_s => {
                failure_at(Reason::SlipAtJump, tl)
            }
            _ => failure(Reason::SlipBefore),
        },
        (Rule::NormalForce, ContactEvent::Slip) => {
            if !slip_onset_flies(case.body, p.sin_t, p.cos_t, p.fx, p.lift, case.mu_s) {
                failure(Reason::SlipBefore)
            } else if found.at_start {
                liftoff_earlier()
            } else {
                jarm(turn_of(th), p.fx, p.fy)
            }
        }
        // The classical rule: F_y = 0 is the lift-off (a lift-off event is not watched).
        (Rule::NormalForce, _) if found.at_start => liftoff_earlier(),
        (Rule::NormalForce, _) => jarm(turn_of(th), p.fx, p.fy),
    }
}

/// First-jump semantics for a requested turn n (0: any turn).
pub fn restrict_to_turn(mut res: JarmResult, n: u32) -> JarmResult {
    if n == 0 {
        return res;
    }
    match res.reason {
        Reason::Jarm if res.n == n => res,
        Reason::Jarm if res.n < n => {
            res.reason = Reason::LiftoffEarlier;
            res.is_jarm = false;
            res.theta_event = res.theta_j;
            res
        }
        Reason::Jarm => {
            res.reason = Reason::NoRoot;
            res.is_jarm = false;
            res
        }
        Reason::NormalForceLost
        | Reason::SlipBefore
        | Reason::SlipAtJump
        | Reason::Slip
        | Reason::RocksBack
            if res.n > n =>
        {
            res.reason = Reason::NoRoot;
            res
        }
        _ => res,
    }
}

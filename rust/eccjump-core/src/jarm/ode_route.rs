//! The second, independent route to the JARM classification: integrate the rolling equation
//! in time with the Dormand–Prince core ([`crate::ode`]) and let its events decide.
//!
//! Same inputs, semantics and [`Reason`] codes as [`fn@crate::jarm::classify`] (first-jump
//! semantics, the two [`Rule`]s, the turn bound n*, explicit n), but no closed form of the
//! path: pure rolling y = (θ, θ̇) is integrated from (θ0, θ̇0) with these terminal events,
//! located by Brent on the dense output (ties in time go to the lower index):
//!
//! 0. lift-off, L = χθ̇² cos θ − cos α rising (`Paper` rule only);
//! 1. normal force F_y falling through 0;
//! 2. slip margin μ_s F_y − |F_x| falling through 0 (a margin, finite as F_y → 0);
//! 3. θ̇ falling through 0: the body stops and rolls back (`RocksBack`);
//! 4. θ reaching the search bound θ_end (the closed form's n*-based bound, capped by
//!    `max_turns`, and by 2πn + π for an explicit n): `NoRoot` or `TurnLimit`.
//!
//! Conditions already violated at the start are tested first, in the closed form's order
//! (lift-off, F_y ≤ 0, friction, θ̇0 = 0 with θ̈0 ≤ 0) and give its reasons.
//!
//! After the deciding event the result is filled as the closed form fills it
//! ([`crate::jarm::decision`]): a `Paper` lift-off reached first already implies that the
//! path conditions held, and is tested for the green window, F_y,J > 0 and μ(θ_J) ≤ μ_s
//! ([`crate::jarm::jump_point`]); a slip under the `Paper` rule continues the integration
//! without the friction and normal-force events to the paper's lift-off and tests it there
//! (`SlipAtJump` vs `SlipBefore`); under the `NormalForce` rule the slip-onset consistency
//! test (K, D, Ĩ_CM, L ≥ 0) decides between flight (a JARM) and `SlipBefore`.
//!
//! Near-ties: where the slip margin vanishes together with F_y (Ĩ_CM = 0, k_m = 0: the margin
//! is F_y(μ_s − |tan(θ/2)|)), a slip root with F_y's own root within 1e-10(1 + θ) after it is
//! taken as a loss of normal force, as the closed form's tie rule does.
//!
//! Path extrema (largest |F_x|/F_y, smallest F_y, and their θ) are tracked only at the
//! accepted step ends and the event point, not refined inside steps: they are approximate
//! (the closed form refines them), and never used for the classification.
//!
//! Integrator failures: the only singular point of the rolling equation is θ = π for
//! χ = 1, k_m = 0 (Ĩ_P = 0, θ̇ → ∞). There the friction ratio is |tan(θ/2)| → ∞, so for any
//! finite μ_s the slip (or normal-force) event comes first and the singularity is not reached.
//! Should the integrator still stop (`StepTooSmall`, `NonFinite`, or the generous step budget
//! `MaxSteps`), the point is reported as `SolverFailed` at the last good θ: never a physical
//! verdict.
//!
//! Events are found on each step's dense output at 4 interior samples (the solver's
//! default), by a sign change between two samples or by a dip between them (the slope, θ̇
//! times the derivative along rolling, turns; [`ode::events`]), so a violation window
//! narrower than the sample spacing is found, as the closed form's derivative test finds it.
//! θ is accurate to ~rtol·|θ|, ×10 for shallow F_y roots. The samples of a step that the
//! rigorous change bounds (`modes::rolling::bounds`) prove free of crossings are skipped,
//! bit-identically, and the step end's trigonometry is handed on by the right-hand side to the
//! events and the observer (`ode::OdeSystem::rhs_with_trig`): their costs and gains are in
//! `docs/performance.md`, the dip test's history in `docs/jarm.md`.
//!
//! No heap allocation, no shared state: deterministic, bit-identical for any thread count.

use crate::jarm::decision::{
    decide, point_ramp, restrict_to_turn, search_end, Case, EventPoint, Extrema, Found,
};
use crate::jarm::result::{JarmOptions, JarmResult, Reason};
use crate::jarm::turns::turn_of;
use crate::mechanics::friction::friction_ratio;
use crate::mechanics::liftoff::liftoff_slope;
use crate::mechanics::{Ramp, Rule};
use crate::modes::rolling::events::{
    equilibrium_start, violated_at_start, ContactEvent, ContactEvents, StartValues, Watched,
};
use crate::modes::rolling::Kinematics;
use crate::ode::lanes::{solve_lanes_with, Start, Track};
use crate::ode::{self, Observation, Outcome, SolverOptions, State, Status};
use std::cell::Cell;
use std::f64::consts::TAU;

/// Event indices: the shared catalogue's order.
const EV_LIFTOFF: usize = ContactEvent::Liftoff as usize;
const EV_FY: usize = ContactEvent::NormalForce as usize;
const EV_SLIP: usize = ContactEvent::Slip as usize;

/// Relative θ-tolerance of the F_y / slip tie rule.
const TIE_TOL: f64 = 1e-10;

/// Accepted steps allowed per turn of the search interval (plus a fixed allowance).
const STEPS_PER_TURN: usize = 20_000;

/// Path extrema at the start (then sampled at step ends and the event point).
fn extrema_start(q: &Kinematics) -> Extrema {
    Extrema {
        max_ratio: friction_ratio(q.fx, q.fy),
        theta_max_ratio: q.theta,
        min_fy: q.fy,
        theta_min_fy: q.theta,
    }
}

#[inline]
fn extrema_add(e: &mut Extrema, q: &Kinematics) {
    let r = friction_ratio(q.fx, q.fy);
    if r > e.max_ratio {
        e.max_ratio = r;
        e.theta_max_ratio = q.theta;
    }
    if q.fy < e.min_fy {
        e.min_fy = q.fy;
        e.theta_min_fy = q.theta;
    }
}

/// How one integration ended.
#[derive(Debug, Clone, Copy)]
enum End {
    /// Terminal event k at state (θ, θ̇) and time t.
    Event { k: usize, t: f64, y: State<2> },
    /// The integrator stopped (step limit, step too small, non-finite values) at its last
    /// good state.
    Failed { y: State<2> },
}

/// The end of an integration from its outcome.
fn end_of(out: &Outcome<2>) -> End {
    match out.status {
        Status::Event(k) => End::Event {
            k,
            t: out.t,
            y: out.y,
        },
        _ => End::Failed { y: out.y },
    }
}

/// Integrates rolling from (t0, y0) until the first terminal event of `ev`, reporting the
/// kinematics at every accepted step end (the event point for the last step) to `track`.
fn integrate(
    ev: &ContactEvents,
    t0: f64,
    y0: State<2>,
    so: &SolverOptions,
    track: Option<&Cell<Extrema>>,
) -> End {
    let t_end = t0 + 1e300;
    let out = ode::solve(&ev.ramp, ev, t0, y0, t_end, so, &mut |obs| {
        if let Some(tr) = track {
            observe_extrema(ev, tr, obs);
        }
    });
    end_of(&out)
}

/// The path extrema at an accepted step's end.
#[inline]
fn observe_extrema(ev: &ContactEvents, track: &Cell<Extrema>, obs: Observation<'_, 2>) {
    if let Observation::Step { y, trig, .. } = obs {
        let mut e = track.get();
        extrema_add(&mut e, &ev.ramp.kinematics_at(y[0], y[1], trig));
        track.set(e);
    }
}

/// Classifies one point by integration: same semantics and reasons as
/// [`fn@crate::jarm::classify`]. `(rtol, atol)` are the integrator's tolerances (must be
/// positive and finite, else `InvalidParams`), `pair` its Runge–Kutta pair. Never panics,
/// never allocates.
pub fn classify_ode(
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    o: &JarmOptions,
    tol: (f64, f64),
    pair: ode::Integrator,
) -> JarmResult {
    let how = Integration {
        tol,
        pair,
        steps_per_turn: STEPS_PER_TURN,
    };
    classify_ode_budget(alpha, chi, km, mu_s, o, how)
}

/// How a point is integrated: the tolerances (rtol, atol), the pair and the step budget
/// per turn of the search.
#[derive(Debug, Clone, Copy)]
struct Integration {
    tol: (f64, f64),
    pair: ode::Integrator,
    steps_per_turn: usize,
}

/// [`classify_ode`] integrated as `how` says (its step budget, say).
fn classify_ode_budget(
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    o: &JarmOptions,
    how: Integration,
) -> JarmResult {
    match prepare(alpha, chi, km, mu_s, o, how) {
        Err(done) => done,
        Ok(p) => {
            let end = match p.at_start {
                Some(k) => End::Event { k, t: 0.0, y: p.y0 },
                None => integrate(&p.ev, 0.0, p.y0, &p.so, Some(&p.ext)),
            };
            finish(p, end)
        }
    }
}

/// A point ready for its integration, with what [`finish`] needs afterwards.
struct Prepared {
    ev: ContactEvents,
    y0: State<2>,
    so: SolverOptions,
    /// The path extrema, updated at each accepted step.
    ext: Cell<Extrema>,
    /// The event whose condition already holds at the start (no integration then).
    at_start: Option<usize>,
    alpha: f64,
    mu_s: f64,
    end_reason: Reason,
    o: JarmOptions,
}

/// Everything before the integration of [`classify_ode`]: the point's result if it needs
/// none (invalid input, an equilibrium start, no search interval), else the prepared run.
fn prepare(
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    o: &JarmOptions,
    how: Integration,
) -> Result<Prepared, JarmResult> {
    let ((rtol, atol), pair, steps_per_turn) = (how.tol, how.pair, how.steps_per_turn);
    let tol_ok = rtol.is_finite() && rtol > 0.0 && atol.is_finite() && atol > 0.0;
    let Some(r) = point_ramp(alpha, chi, km, mu_s, o).filter(|_| tol_ok) else {
        return Err(JarmResult::new(Reason::InvalidParams));
    };
    let (theta0, omega0) = (o.theta0, o.omega0);
    let q0 = r.kinematics(theta0, omega0);
    if equilibrium_start(omega0, q0.omega_dot, q0.fx, q0.fy, mu_s) {
        return Err(JarmResult::new(Reason::NoRoot));
    }
    let Some((theta_end, end_reason)) = search_end(&r, o) else {
        return Err(JarmResult::new(Reason::NoRoot));
    };
    let turns = ((theta_end - theta0) / TAU).ceil().min(1e9) as usize;
    let so = SolverOptions {
        rtol,
        atol,
        max_steps: steps_per_turn.saturating_mul(turns.saturating_add(1)),
        method: pair,
        ..SolverOptions::default()
    };
    let paper = o.rule == Rule::Paper;
    let ev = ContactEvents::of_search(r, mu_s, theta_end, o.rule, true);
    let chi_w2 = chi * (omega0 * omega0);
    let start = StartValues {
        lift: q0.lift,
        lift_slope: liftoff_slope(chi, chi_w2, q0.omega_dot, q0.sin_theta, q0.cos_theta),
        fx: q0.fx,
        fy: q0.fy,
        kinetic: 0.5 * r.contact_inertia(q0.cos_theta) * omega0 * omega0,
        kinetic_slope: r.sin_a + chi * r.shifted(q0.sin_theta, q0.cos_theta).0,
    };
    let watched = Watched {
        liftoff: paper,
        normal_force: true,
        friction: true,
    };
    Ok(Prepared {
        ev,
        y0: State::<2>::new(theta0, omega0),
        so,
        ext: Cell::new(extrema_start(&q0)),
        at_start: violated_at_start(watched, mu_s, &start).map(|e| e as usize),
        alpha,
        mu_s,
        end_reason,
        o: *o,
    })
}

/// Everything after the integration of [`classify_ode`]: the verdict from how it ended
/// (with the continuation to the lift-off after a slip, integrated here).
fn finish(p: Prepared, end: End) -> JarmResult {
    match found(p, end) {
        Err(done) => done,
        Ok(f) => {
            let liftoff = match f.continuation() {
                Some((cont, t, y)) => liftoff_of(integrate(&cont, t, y, &f.p.so, None)),
                None => None,
            };
            f.verdict(liftoff)
        }
    }
}

/// What the first integration found, before the verdict.
struct Finding {
    p: Prepared,
    found: Found,
    /// The time of the event.
    t: f64,
    /// The state at the event.
    y: State<2>,
}

/// The first stage of [`finish`]: what the integration found, or the point's result if
/// the integrator failed.
fn found(p: Prepared, end: End) -> Result<Finding, JarmResult> {
    let ext = p.ext.get();
    let r = p.ev.ramp;
    let (k, t, y) = match end {
        End::Event { k, t, y } => (k, t, y),
        End::Failed { y } => {
            // No physical verdict: the integrator stopped at its last good state.
            let mut x = JarmResult::with_extrema(Reason::SolverFailed, &ext);
            x.theta_event = y[0];
            x.n = turn_of(y[0]);
            return Err(restrict_to_turn(x, p.o.n));
        }
    };
    let th = y[0];
    let q = r.kinematics(th, y[1]);
    // Tie rule: a slip root with F_y's own root right after it is a loss of normal force.
    let dfy = r.force_slopes(&q).1;
    let k = if k == EV_SLIP && q.fy <= TIE_TOL * (1.0 + th.abs()) * (-dfy).max(0.0) {
        EV_FY
    } else {
        k
    };
    let found = Found {
        event: ContactEvent::ALL[k],
        at_start: p.at_start.is_some(),
        at: EventPoint {
            theta: th,
            sin_t: q.sin_theta,
            cos_t: q.cos_theta,
            fx: q.fx,
            fy: q.fy,
            lift: q.lift,
        },
        extrema: ext,
    };
    Ok(Finding { p, found, t, y })
}

impl Finding {
    /// The classification's fixed inputs.
    fn case(&self) -> Case<'_> {
        let p = &self.p;
        Case {
            body: &p.ev.ramp.body,
            alpha: p.alpha,
            mu_s: p.mu_s,
            rule: p.o.rule,
            end_reason: p.end_reason,
            stop_at_slip: p.o.stop_at_slip,
        }
    }

    /// After a slip under the paper's rule (unless `stop_at_slip`), the verdict needs the
    /// paper's lift-off further along rolling: the events of that continuation (no friction,
    /// no normal-force event) and where it starts.
    fn continuation(&self) -> Option<(ContactEvents, f64, State<2>)> {
        let o = &self.p.o;
        let needed =
            o.rule == Rule::Paper && self.found.event == ContactEvent::Slip && !o.stop_at_slip;
        let ev = &self.p.ev;
        needed.then(|| {
            let theta_end = ev.theta_end.max(self.y[0]);
            let cont = ContactEvents::of_search(ev.ramp, ev.mu_s, theta_end, o.rule, false);
            (cont, self.t, self.y)
        })
    }

    /// The verdict, given the continuation's lift-off angle (if it was needed and found).
    fn verdict(&self, liftoff: Option<f64>) -> JarmResult {
        let x = decide(&self.case(), &self.found, || liftoff);
        restrict_to_turn(x, self.p.o.n)
    }
}

/// The paper's lift-off angle where a continuation ended at it.
fn liftoff_of(end: End) -> Option<f64> {
    match end {
        End::Event {
            k: EV_LIFTOFF, y, ..
        } => Some(y[0]),
        _ => None,
    }
}

/// A point of a lane batch at one of its two integrations; its result goes to
/// `out[index]`.
enum RouteTrack {
    /// The search along rolling from the start.
    First { index: usize, p: Prepared },
    /// The continuation after a slip, to the paper's lift-off.
    Continued {
        index: usize,
        f: Box<Finding>,
        ev: ContactEvents,
    },
}

impl Track<2> for RouteTrack {
    type Sys = Ramp;
    type Events = ContactEvents;
    #[inline]
    fn sys(&self) -> &Ramp {
        &self.events().ramp
    }
    #[inline]
    fn events(&self) -> &ContactEvents {
        match self {
            RouteTrack::First { p, .. } => &p.ev,
            RouteTrack::Continued { ev, .. } => ev,
        }
    }
    #[inline]
    fn observe(&self, obs: Observation<'_, 2>) {
        if let RouteTrack::First { p, .. } = self {
            observe_extrema(&p.ev, &p.ext, obs);
        }
    }
}

/// [`classify_ode`] of many points, `point(i)` = (α, χ, k_m, μ_s, options) for each
/// `out[i]`, integrated side by side ([`ode::lanes`]): every result is bit for bit that of
/// `classify_ode` at its point. `stop` is asked before each point starts and as the
/// integrator asks it (every few thousand steps of a point); a `true` ends the points under
/// way as integrator failures and leaves the others as they were: the caller discards
/// them.
pub fn classify_ode_batch(
    point: impl Fn(usize) -> (f64, f64, f64, f64, JarmOptions),
    tol: (f64, f64),
    pair: ode::Integrator,
    out: &mut [JarmResult],
    stop: &dyn Fn() -> bool,
) {
    let out = Cell::from_mut(out).as_slice_of_cells();
    let how = Integration {
        tol,
        pair,
        steps_per_turn: STEPS_PER_TURN,
    };
    // Continuations waiting for a lane (a few at a time: each is taken at the next fill).
    let waiting = std::cell::RefCell::new(Vec::new());
    let mut i = 0;
    let next = || {
        // Once stopped, no point or continuation starts (the caller discards the results),
        // so a Ctrl-C waits only for the trajectories under way.
        if stop() {
            return None;
        }
        if let Some(start) = waiting.borrow_mut().pop() {
            return Some(start);
        }
        while i < out.len() {
            let index = i;
            i += 1;
            let (alpha, chi, km, mu_s, o) = point(index);
            match prepare(alpha, chi, km, mu_s, &o, how) {
                Err(done) => out[index].set(done),
                Ok(p) if p.at_start.is_some() => {
                    let k = p.at_start.unwrap_or_default();
                    let y = p.y0;
                    out[index].set(finish(p, End::Event { k, t: 0.0, y }));
                }
                Ok(p) => {
                    let (y0, opts) = (p.y0, p.so);
                    return Some(Start {
                        track: RouteTrack::First { index, p },
                        t0: 0.0,
                        y0,
                        t_end: 1e300,
                        opts,
                    });
                }
            }
        }
        None
    };
    let done = |track: RouteTrack, outcome: Outcome<2>| match track {
        RouteTrack::First { index, p } => match found(p, end_of(&outcome)) {
            Err(done) => out[index].set(done),
            Ok(f) => match f.continuation() {
                None => out[index].set(f.verdict(None)),
                Some((ev, t0, y0)) => {
                    let opts = f.p.so;
                    let track = RouteTrack::Continued {
                        index,
                        f: Box::new(f),
                        ev,
                    };
                    let start = Start {
                        track,
                        t0,
                        y0,
                        t_end: t0 + 1e300,
                        opts,
                    };
                    waiting.borrow_mut().push(start);
                }
            },
        },
        RouteTrack::Continued { index, f, .. } => {
            out[index].set(f.verdict(liftoff_of(end_of(&outcome))));
        }
    };
    solve_lanes_with(pair, next, done, stop);
}

#[cfg(test)]
mod tests;

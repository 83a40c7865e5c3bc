//! A pure-rolling run: the rolling equation integrated by the Dormand–Prince driver, with
//! the built-in contact events, until the first terminal one (or t_max / θ_max).
//!
//! Events, of the [`ContactEvent`] catalogue (all located on the dense output to near
//! machine precision):
//! - `Liftoff`: the paper's jump condition χ θ̇² cos θ − cos α = 0, rising;
//! - `NormalForce`: F_y = 0, falling (the contact would need to pull);
//! - `Slip`: μ_s F_y − |F_x| = 0, falling (the rolling branch leaves the friction cone);
//! - `ThetaLimit`: θ = θ_max, rising;
//! - `RocksBack` is not watched (a constant): a run rolls back and on.
//!
//! Which of them end the run is set by the lift-off [`Rule`].

use crate::error::{check_count, check_positive, check_range, short, try_grow, Error, Result};
use crate::mechanics::friction::friction_ratio;
use crate::mechanics::Ramp;
pub use crate::mechanics::Rule;
use crate::mechanics::{MAX_OMEGA0, MAX_THETA0};
pub use crate::modes::rolling::events::{ContactEvent, ContactEvents};
use crate::modes::rolling::solution::RollSolution;
use crate::modes::rolling::track::{Begun, RollTrack};
use crate::modes::rolling::Kinematics;
use crate::ode::lanes::Track;
use crate::ode::{self, EventFunctions, SolverOptions, State, Status};

/// The inputs of a rolling run besides the body and ramp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollOptions {
    /// Initial angle θ0 (rad) (default 0).
    pub theta0: f64,
    /// Initial angular velocity θ̇0 (default 0, rest).
    pub omega0: f64,
    /// Static friction coefficient μ_s ≥ 0; `None` (default) disables the slip event.
    pub mu_s: Option<f64>,
    /// End time of the run, > 0 (units g = R = 1; default 1000).
    pub t_max: f64,
    /// Angle (rad) that ends the run, > θ0; ∞ (default) disables it.
    pub theta_max: f64,
    /// The lift-off rule (default: the paper's).
    pub rule: Rule,
    /// Tolerances and limits of the integrator.
    pub solver: SolverOptions,
    /// Keep the dense output of every step (for `sol(t)` in Python).
    pub dense_output: bool,
}

impl Default for RollOptions {
    fn default() -> Self {
        Self {
            theta0: 0.0,
            omega0: 0.0,
            mu_s: None,
            t_max: 1e3,
            theta_max: f64::INFINITY,
            rule: Rule::Paper,
            solver: SolverOptions::default(),
            dense_output: false,
        }
    }
}

impl RollOptions {
    /// Checks every option, naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        let big = f64::MAX;
        check_range("theta0", self.theta0, -MAX_THETA0, MAX_THETA0)?;
        check_range("omega0", self.omega0, -MAX_OMEGA0, MAX_OMEGA0)?;
        if let Some(mu) = self.mu_s {
            check_range("mu_s", mu, 0.0, big)?;
        }
        check_positive("t_max", self.t_max)?;
        if self.theta_max.is_nan() || self.theta_max <= self.theta0 {
            return Err(Error::InvalidParameter {
                name: "theta_max",
                value: self.theta_max,
                allowed: format!("(theta0, inf] = ({}, inf]", short(self.theta0)),
            });
        }
        SolverOptions::check_tolerances(self.solver.rtol, self.solver.atol)?;
        check_count("max_steps", self.solver.max_steps, 1, MAX_STEPS)?;
        Ok(())
    }
}

/// One event met during the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventHit {
    /// Which event.
    pub event: ContactEvent,
    /// Time of the event.
    pub t: f64,
    /// θ (rad) at the event.
    pub theta: f64,
    /// θ̇ at the event.
    pub omega: f64,
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RollStatus {
    /// t reached t_max without a terminal event.
    TimeLimit,
    /// A terminal event ended the run.
    Event(ContactEvent),
    /// The integrator failed (step limit, step too small, non-finite values).
    Failed(Status),
}

impl RollStatus {
    /// scipy's convention: 0 reached the end, 1 a terminal event, −1 a failure.
    pub fn code(self) -> i32 {
        match self {
            RollStatus::TimeLimit => 0,
            RollStatus::Event(_) => 1,
            RollStatus::Failed(_) => -1,
        }
    }

    /// A human-readable description of how the run ended.
    pub fn message(self) -> String {
        match self {
            RollStatus::TimeLimit => "reached t_max".to_string(),
            RollStatus::Event(e) => format!("terminal event: {}", e.name()),
            RollStatus::Failed(Status::MaxSteps) => {
                "step limit reached (max_steps) before the end".to_string()
            }
            RollStatus::Failed(Status::StepTooSmall) => {
                "step size became too small: the motion is singular here (e.g. χ = 1, k_m = 0 \
                 at θ = π)"
                    .to_string()
            }
            RollStatus::Failed(Status::NonFinite) => {
                "non-finite value in the equations of motion".to_string()
            }
            RollStatus::Failed(s) => format!("integrator stopped: {s:?}"),
        }
    }
}

/// The recorded run: accepted steps (with the initial point and the end point), events, and
/// optionally the dense output of every step.
#[derive(Debug, Clone, PartialEq)]
pub struct RollRun {
    /// Times of the recorded points.
    pub t: Vec<f64>,
    /// θ (rad) at each recorded point.
    pub theta: Vec<f64>,
    /// θ̇ at each recorded point.
    pub omega: Vec<f64>,
    /// θ̈ at each recorded point ([`Ramp::kinematics`]).
    pub omega_dot: Vec<f64>,
    /// Contact force F_x (along the ramp) at each recorded point.
    pub fx: Vec<f64>,
    /// Contact force F_y (normal to the ramp) at each recorded point.
    pub fy: Vec<f64>,
    /// (sin θ, cos θ) at each recorded point, as the integrator computed them (for the
    /// energy of a full-motion run's points, without evaluating them again).
    pub trig: Vec<(f64, f64)>,
    /// The distance rolled along the ramp, l − l0 = θ − θ0 (pure rolling, R = 1).
    pub l: Vec<f64>,
    /// The friction ratio |F_x|/F_y (+∞ where F_y ≤ 0).
    pub ratio: Vec<f64>,
    /// Every event met, terminal or not, in order of time.
    pub events: Vec<EventHit>,
    /// How the run ended.
    pub status: RollStatus,
    /// Right-hand-side evaluations of the integrator.
    pub nfev: usize,
    /// The dense output, when asked for: ends where the run ends.
    pub dense: Option<RollSolution>,
}

/// The largest step budget of a run: bounds its time (a few seconds) and memory (the
/// record and the dense output, about 1.6 GB at most; beyond what can be allocated the run
/// is a `MemoryError`, never an abort).
pub const MAX_STEPS: usize = 10_000_000;

/// Points reserved per recorded array up front: a run to lift-off at the default
/// tolerances takes about a hundred steps; longer runs grow the arrays by doubling. 128
/// points are 1 kB, which glibc's allocator serves from its per-thread cache (256 made a
/// 12-step run 3 % slower).
pub(super) const RESERVE: usize = 128;

impl RollRun {
    /// The series derived from the recorded ones, in one pass after the run (off the
    /// integration's critical path): l − l0 = θ − θ0 and |F_x|/F_y.
    pub(super) fn derive(&mut self) -> Result<()> {
        let n = self.t.len();
        for v in [&mut self.l, &mut self.ratio] {
            v.try_reserve_exact(n).map_err(|_| Error::OutOfMemory {
                what: "the record of the run",
                bytes: (n * std::mem::size_of::<f64>()) as u64,
            })?;
        }
        let theta0 = self.theta.first().copied().unwrap_or(0.0);
        self.l.extend(self.theta.iter().map(|&th| th - theta0));
        let forces = self.fx.iter().zip(&self.fy);
        self.ratio
            .extend(forces.map(|(&fx, &fy)| friction_ratio(fx, fy)));
        Ok(())
    }

    /// Records one point with its kinematics (fallibly: `OutOfMemory` instead of an abort).
    #[inline]
    pub(super) fn push(&mut self, t: f64, k: &Kinematics) -> Result<()> {
        // The series are created, pushed, popped and grown together, so they are full
        // together: one test per point (the growth is out of line: the common path is a
        // comparison and six pushes).
        if self.t.len() == self.t.capacity() {
            self.grow()?;
        }
        self.t.push(t);
        self.theta.push(k.theta);
        self.omega.push(k.omega);
        self.omega_dot.push(k.omega_dot);
        self.fx.push(k.fx);
        self.fy.push(k.fy);
        self.trig.push((k.sin_theta, k.cos_theta));
        Ok(())
    }

    /// Room for more points in every recorded series (fallibly).
    #[cold]
    fn grow(&mut self) -> Result<()> {
        for v in [
            &mut self.t,
            &mut self.theta,
            &mut self.omega,
            &mut self.omega_dot,
            &mut self.fx,
            &mut self.fy,
        ] {
            try_grow("the record of the run", v)?;
        }
        try_grow("the record of the run", &mut self.trig)?;
        Ok(())
    }

    #[inline]
    pub(super) fn pop(&mut self) {
        self.t.pop();
        self.theta.pop();
        self.omega.pop();
        self.omega_dot.pop();
        self.fx.pop();
        self.fy.pop();
        self.trig.pop();
    }
}

/// Integrates pure rolling from (θ0, θ̇0) until a terminal event, t_max or θ_max.
pub fn roll(ramp: &Ramp, opts: &RollOptions) -> Result<RollRun> {
    roll_until(ramp, opts, &|| false)
}

/// [`roll`], asking `stop()` every few thousand steps; a `true` ends it with
/// `Error::Interrupted` (e.g. on Ctrl-C).
pub fn roll_until(ramp: &Ramp, opts: &RollOptions, stop: &dyn Fn() -> bool) -> Result<RollRun> {
    let (track, y0) = match RollTrack::begin(ramp, opts)? {
        Begun::Ended(run) => return Ok(run),
        Begun::Track(track, y0) => (track, y0),
    };
    let outcome = ode::solve_until(
        track.sys(),
        track.events(),
        0.0,
        y0,
        opts.t_max,
        &track.solver,
        &mut |obs| track.observe(obs),
        stop,
    );
    track.finish(&outcome)
}

/// The terminal event whose condition is already met at the start, if any.
pub(super) fn violated_at_start(
    events: &ContactEvents,
    theta: f64,
    omega: f64,
) -> Option<ContactEvent> {
    // Every event's value from one evaluation of the kinematics.
    let mut values = [0.0; ContactEvent::ALL.len()];
    events.values(0, 0.0, &State::<2>::new(theta, omega), &mut values);
    ContactEvent::ALL
        .into_iter()
        .zip(values)
        .find_map(|(e, g)| {
            let outside = match e {
                ContactEvent::Liftoff | ContactEvent::ThetaLimit => g > 0.0,
                // Contact needs a strictly positive normal force (on a vertical ramp at rest
                // F_y = 0: the body is not pressed onto the ramp at all).
                ContactEvent::NormalForce => g <= 0.0,
                ContactEvent::Slip => g < 0.0,
                ContactEvent::RocksBack => false,
            };
            // θ_max is validated to lie above θ0, so it never fires here.
            (events.is_terminal(e) && outside).then_some(e)
        })
}

#[cfg(test)]
mod skip_tests {
    use super::*;
    use crate::mechanics::Cylinder;
    use crate::ode::events::{check_change_bounds, WalkAll};
    use crate::ode::{Observation, SinCos};

    fn cases() -> Vec<(Ramp, ContactEvents)> {
        let mut out = Vec::new();
        for &(chi, km, alpha_deg, mu_s, rule, theta_max) in &[
            (0.15, 0.02, 40.0, None, Rule::Paper, f64::INFINITY),
            (0.5, 0.1, 20.0, Some(0.4), Rule::NormalForce, f64::INFINITY),
            (0.9, 0.1, 60.0, None, Rule::NormalForce, 40.0),
            (0.3, 0.3, 5.0, Some(2.0), Rule::Paper, 7.0),
        ] {
            let r = Ramp::new(Cylinder::new(chi, km).unwrap(), f64::to_radians(alpha_deg)).unwrap();
            let ev = ContactEvents::of_run(r, mu_s, theta_max, rule);
            out.push((r, ev));
        }
        out
    }

    #[test]
    fn a_grazing_slip_is_found_between_two_samples() {
        // The friction margin dips below 0 on turn 934 for a window narrower than the sample
        // spacing (the closed form's slip: θ = 5868.836162570985); sign sampling alone
        // slipped one turn later.
        let r = Ramp::new(
            Cylinder::new(0.001036140639499864, 0.5957722237251039).unwrap(),
            0.11715890776808541,
        )
        .unwrap();
        let opts = RollOptions {
            mu_s: Some(1.0),
            t_max: 1e5,
            ..RollOptions::default()
        };
        let run = roll(&r, &opts).unwrap();
        let slip = run
            .events
            .iter()
            .find(|e| e.event == ContactEvent::Slip)
            .unwrap();
        assert!((slip.theta - 5868.836162570985).abs() < 1e-6, "{slip:?}");
    }

    #[test]
    fn skipping_interior_samples_changes_nothing() {
        let opts = SolverOptions {
            dense_every_step: true,
            ..SolverOptions::default()
        };
        for (r, ev) in cases() {
            let mut with = Vec::new();
            let a = ode::solve(&r, &ev, 0.0, State::<2>::zeros(), 50.0, &opts, &mut |o| {
                if let Observation::Event { index, t, .. } = o {
                    with.push((index, t));
                }
            });
            let mut without = Vec::new();
            let b = ode::solve(
                &r,
                &WalkAll(&ev),
                0.0,
                State::<2>::zeros(),
                50.0,
                &opts,
                &mut |o| {
                    if let Observation::Event { index, t, .. } = o {
                        without.push((index, t));
                    }
                },
            );
            assert_eq!(a, b);
            assert_eq!(with, without);
        }
    }

    #[test]
    fn change_bounds_bound_the_change_along_each_step() {
        let opts = SolverOptions {
            dense_every_step: true,
            ..SolverOptions::default()
        };
        for (r, ev) in cases() {
            let mut steps = 0;
            ode::solve(&r, &ev, 0.0, State::<2>::zeros(), 50.0, &opts, &mut |o| {
                if let Observation::Step { dense, .. } = o {
                    let dense = dense.expect("every step's dense output");
                    steps += 1;
                    let g = |t: f64| {
                        let mut v = [0.0; 5];
                        ev.values(0, t, &dense.eval(t), &mut v);
                        v
                    };
                    // Plain, and anchored at the step's start and end (as the scan does).
                    let (th0, th1) = (dense.y_old[0], dense.eval(dense.t_old + dense.h)[0]);
                    for anchor in [None, Some(SinCos::of(th0)), Some(SinCos::of(th1))] {
                        let bound = ev.change_bounds_near(dense, anchor);
                        check_change_bounds(dense.t_old, dense.h, g, &bound).unwrap();
                    }
                }
            });
            assert!(steps > 5);
        }
    }
}

//! The driver of a full-motion run: one segment at a time (rolling and slipping integrated
//! by the ODE core (RK45, DOP853 or Vern9) with their events, flight exact with its rigorous landing search), the
//! impact law at every landing, and the consistency test after every event
//! (`docs/motion.md` specifies the model).

use crate::error::{Error, Result};
use crate::mechanics::{BodyState, Ramp};
use crate::modes::contact::{decide, Mode, TransitionReason, Verdict};
use crate::modes::flight::apex;
use crate::modes::flight::landing::Landing;
use crate::modes::flight::Flight;
use crate::modes::rolling::run::{roll_until, ContactEvent, RollOptions, RollRun, RollStatus};
use crate::modes::slipping::F_SWITCH;
use crate::modes::slipping::{SlipEvent, Slipping};
use crate::motion::landing::land;
use crate::motion::options::{SimOptions, MAX_ANGLE_STEP, MIN_ICM};
use crate::motion::record::{
    Crossing, FlightRecord, ImpactRecord, MotionRun, MotionStatus, Point, Segment, Transition,
};
use crate::motion::sliding::{slip_state, SlipTrack};
use crate::motion::solution::{MotionSolution, Piece};
use crate::ode::lanes::Track;
use crate::ode::roots::brent;
use crate::ode::{self, Outcome, Status};

/// What comes after a segment.
enum Next {
    /// Another mode, for a reason, from a state.
    Mode(Mode, TransitionReason, BodyState, f64),
    /// A landing in this state (b = 1, ḃ < 0): the impact law and the consistency test
    /// decide what follows, once the transition budget allows a transition (a run that
    /// stops at the budget keeps the state before the impact, and the ledger closes).
    Landing(BodyState),
    /// The slip under way goes on from this state with friction direction σ, in time again
    /// after a stretch in the normal impulse (a new segment, not a transition).
    Resume(BodyState, f64),
    /// The run ends.
    End(MotionStatus, String),
}

/// The mode chosen by the consistency test as a [`Next`], for `reason` where it flies.
fn after(verdict: Verdict, reason: TransitionReason, s: BodyState) -> Next {
    match verdict {
        Verdict::Roll => Next::Mode(Mode::Roll, reason, s, 0.0),
        Verdict::Slip { sigma } => Next::Mode(Mode::Slip, reason, s, sigma),
        Verdict::Flight(r) => Next::Mode(Mode::Flight, r, s, 0.0),
        Verdict::Jam => Next::End(
            MotionStatus::Jam,
            "no consistent contact mode and the ramp pushes the body back (L < 0): a dynamic \
             jam the rigid model cannot continue"
                .to_string(),
        ),
    }
}

struct Driver<'a> {
    ramp: &'a Ramp,
    opts: &'a SimOptions,
    stop: &'a dyn Fn() -> bool,
    run: MotionRun,
    t: f64,
    steps_left: usize,
    /// The state the segment under way began from.
    segment_start: BodyState,
    /// The event that ended the segment under way, once it has ended.
    crossing: Option<Crossing>,
}

/// Segments between two asks of `stop` (from Python each ask takes the GIL: 0.25 µs, a few
/// per cent of a short run if asked at every segment). Each rolling or sliding segment asks
/// it itself every few thousand steps, and a flight or an impact is a bounded piece of work,
/// so this many segments take milliseconds.
const STOP_EVERY: usize = 64;

/// Integrates the full motion from (θ0, θ̇0, slip0) until t_max, l_max, the transition
/// budget or an outcome the rigid model cannot continue.
pub fn simulate(ramp: &Ramp, opts: &SimOptions) -> Result<MotionRun> {
    simulate_until(ramp, opts, &|| false)
}

/// [`simulate`], asking `stop()` every few thousand steps and every [`STOP_EVERY`] segments;
/// a `true` ends it with `Error::Interrupted`.
pub fn simulate_until(
    ramp: &Ramp,
    opts: &SimOptions,
    stop: &dyn Fn() -> bool,
) -> Result<MotionRun> {
    let mut sim = Sim::begin(ramp, opts, stop)?;
    loop {
        match sim.advance()? {
            Need::Roll(o) => sim.rolled(roll_until(ramp, &o, stop))?,
            Need::Slip(track) => {
                let out = ode::solve_until(
                    track.sys(),
                    track.events(),
                    track.t0,
                    track.y0,
                    track.t_end,
                    &track.solver,
                    &mut |obs| track.observe(obs),
                    stop,
                );
                sim.slid(*track, &out)?;
            }
            Need::Done => return sim.finish(),
        }
    }
}

/// What a run needs before it can go on.
pub(crate) enum Need {
    /// A rolling segment: `roll_until` with these options, then [`Sim::rolled`].
    Roll(RollOptions),
    /// A sliding segment: this track integrated from (t0, y0) to t_end with its solver
    /// options, then [`Sim::slid`].
    Slip(Box<SlipTrack>),
    /// Nothing: the run is over ([`Sim::finish`]).
    Done,
}

/// A run between its segments: the loop of [`simulate`] turned inside out, so that a
/// caller can integrate the rolling and sliding segments of many runs side by side
/// (motion maps), each run the same as alone, bit for bit. Flights and impacts are computed
/// within [`Sim::advance`].
pub(crate) struct Sim<'a> {
    d: Driver<'a>,
    start: BodyState,
    /// What comes next (`None` while a segment is under way).
    next: Option<Next>,
    from: Option<Mode>,
    /// The segment under way: its mode, reason, start time, evaluations before it and
    /// friction direction.
    current: (Mode, TransitionReason, f64, usize, f64),
}

impl<'a> Sim<'a> {
    /// The run's start (its options checked).
    pub(crate) fn begin(
        ramp: &'a Ramp,
        opts: &'a SimOptions,
        stop: &'a dyn Fn() -> bool,
    ) -> Result<Self> {
        let (start, next) = opening(ramp, opts)?;
        let d = Driver {
            ramp,
            opts,
            stop,
            run: MotionRun {
                energy0: ramp.energy_of(&start),
                dense: opts.dense_output.then(MotionSolution::default),
                ..MotionRun::default()
            },
            t: 0.0,
            steps_left: opts.solver.max_steps,
            segment_start: start,
            crossing: None,
        };
        Ok(Self {
            d,
            start,
            next: Some(next),
            from: None,
            current: (Mode::Roll, TransitionReason::Start, 0.0, 0, 0.0),
        })
    }

    /// Goes on until the run needs a segment integrated, or ends.
    pub(crate) fn advance(&mut self) -> Result<Need> {
        let opts = self.d.opts;
        loop {
            let d = &mut self.d;
            let next = self
                .next
                .take()
                .expect("advance while a segment is under way");
            let budget_spent = d.run.transitions.len() > opts.max_transitions;
            if budget_spent && !matches!(next, Next::End(..)) {
                d.run.status = Some(MotionStatus::MaxTransitions);
                d.run.message = format!(
                    "{} transitions made (max_transitions)",
                    opts.max_transitions
                );
                return Ok(Need::Done);
            }
            let next = match next {
                Next::Landing(before) => d.impact(before),
                other => other,
            };
            let resumed = matches!(next, Next::Resume(..));
            let (mode, reason, state, sigma) = match next {
                Next::End(status, message) => {
                    d.run.status = Some(status);
                    d.run.message = message;
                    return Ok(Need::Done);
                }
                Next::Mode(mode, reason, state, sigma) => (mode, reason, state, sigma),
                Next::Resume(state, sigma) => (Mode::Slip, self.current.1, state, sigma),
                Next::Landing(_) => unreachable!("the impact law decides a mode or an end"),
            };
            if d.run.transitions.len() % STOP_EVERY == STOP_EVERY - 1 && (d.stop)() {
                return Err(Error::Interrupted);
            }
            if !resumed {
                // Mode reason: the reason for a slip that follows a slip is a reversal.
                let reason = match (self.from, mode, reason) {
                    (Some(Mode::Slip), Mode::Slip, TransitionReason::Slip) => {
                        TransitionReason::Reverse
                    }
                    (Some(Mode::Slip), Mode::Roll, TransitionReason::Slip) => {
                        TransitionReason::Stick
                    }
                    _ => reason,
                };
                d.run.transitions.push(Transition {
                    t: d.t,
                    from: self.from,
                    to: mode,
                    reason,
                    state,
                });
                if opts.stop_at_landing && !d.run.impacts.is_empty() {
                    d.run.status = Some(MotionStatus::Landed);
                    return Ok(Need::Done);
                }
            }
            let reason = d.run.transitions.last().map_or(reason, |tr| tr.reason);
            self.current = (mode, reason, d.t, d.run.nfev, sigma);
            let next = match mode {
                Mode::Roll => match d.roll_start(state) {
                    Ok(o) => return Ok(Need::Roll(o)),
                    Err(next) => next,
                },
                Mode::Slip => match d.slip_start(state, sigma)? {
                    Ok(track) => return Ok(Need::Slip(Box::new(track))),
                    Err(next) => next,
                },
                Mode::Flight => d.fly(state)?,
            };
            self.segment_done(next);
        }
    }

    /// The rolling segment [`Need::Roll`] asked for, integrated.
    pub(crate) fn rolled(&mut self, rr: Result<RollRun>) -> Result<()> {
        let next = self.d.roll_end(rr)?;
        self.segment_done(next);
        Ok(())
    }

    /// The sliding segment [`Need::Slip`] asked for, integrated: its track and outcome.
    pub(crate) fn slid(&mut self, track: SlipTrack, out: &Outcome<5>) -> Result<()> {
        let next = self.d.slip_end(track, out)?;
        self.segment_done(next);
        Ok(())
    }

    /// The segment under way has ended: `next` comes after it.
    fn segment_done(&mut self, next: Next) {
        let (mode, reason, t_start, nfev_before, sigma) = self.current;
        let run = &mut self.d.run;
        run.segments.push(Segment {
            mode,
            reason,
            t_start,
            t_end: self.d.t,
            nfev: run.nfev - nfev_before,
            sigma,
            crossing: self.d.crossing.take(),
        });
        self.from = Some(mode);
        self.next = Some(next);
    }

    /// The run, once [`Sim::advance`] said [`Need::Done`].
    pub(crate) fn finish(self) -> Result<MotionRun> {
        let (opts, start) = (self.d.opts, self.start);
        let mut d = self.d;
        if d.run.points.is_empty() && opts.record_points {
            // The run ended before its first segment (a jam at the start): record the start.
            let mode = d.run.transitions.first().map_or(
                if start.slip_velocity() != 0.0 {
                    Mode::Slip
                } else {
                    Mode::Roll
                },
                |t| t.to,
            );
            let trig = crate::trig::sin_cos(start.theta);
            let p = d.point(0.0, start, trig, (0.0, 0.0), mode);
            d.run.push(p)?;
        }
        if let Some(sol) = d.run.dense.as_mut() {
            if sol.pieces.is_empty() {
                sol.pieces.push((0.0, Piece::Still(start)));
            }
            sol.t_end = d.t;
        }
        if d.run.message.is_empty() {
            d.run.message = d.run.status.map_or("", |s| s.name()).to_string();
        }
        Ok(d.run)
    }
}

/// The checks of a run's options and its start: the state and what comes first.
fn opening(ramp: &Ramp, opts: &SimOptions) -> Result<(BodyState, Next)> {
    opts.validate()?;
    if ramp.body.icm.is_nan() || ramp.body.icm < MIN_ICM {
        let allowed = "(0, 1 - chi] with I_CM >= 1e-10 for simulate: at km = 0 all the mass is at \
                       the centre of mass, and below it the impact law loses every digit";
        return Err(Error::invalid("km", ramp.body.km, allowed));
    }
    let start = BodyState::in_contact(opts.theta0, opts.omega0, 0.0, opts.omega0 + opts.slip0);
    let next = match after(
        decide(ramp, &opts.law, &start, false),
        TransitionReason::Start,
        start,
    ) {
        Next::Mode(mode, _, state, sigma) => {
            Next::Mode(mode, TransitionReason::Start, state, sigma)
        }
        end => end,
    };
    Ok((start, next))
}

/// The integrator's options of a rolling or sliding segment in time (y₀ = θ): the run's,
/// with the step budget left and each step's turn capped at [`MAX_ANGLE_STEP`].
fn segment_solver(opts: &SimOptions, steps_left: usize) -> ode::SolverOptions {
    ode::SolverOptions {
        max_steps: steps_left.max(1),
        max_first_change: MAX_ANGLE_STEP,
        ..opts.solver
    }
}

impl Driver<'_> {
    /// A recorded point; `trig` = (sin θ, cos θ) of the state.
    fn point(
        &self,
        t: f64,
        state: BodyState,
        trig: (f64, f64),
        (fx, fy): (f64, f64),
        mode: Mode,
    ) -> Point {
        Point {
            t,
            state,
            fx,
            fy,
            energy: self.ramp.energy_of_trig(&state, trig),
            dissipated: self.run.dissipated(),
            mode,
        }
    }

    fn time_left(&self) -> f64 {
        self.opts.t_max - self.t
    }

    fn end_of_time(&self) -> Next {
        Next::End(MotionStatus::TimeLimit, "reached t_max".to_string())
    }

    fn end_of_ramp(&self) -> Next {
        Next::End(MotionStatus::DistanceLimit, "reached l_max".to_string())
    }

    fn failed(&self, what: &str, status: Status) -> Next {
        let why = match status {
            Status::MaxSteps => "step limit reached (max_steps)",
            Status::StepTooSmall => "step size became too small (a singular motion)",
            Status::NonFinite => "non-finite value in the equations of motion",
            _ => "integrator stopped",
        };
        Next::End(MotionStatus::Failed, format!("{what}: {why}"))
    }

    /// A rolling segment from `s`: the options of its `roll_until`, or what comes instead.
    fn roll_start(&mut self, s: BodyState) -> std::result::Result<RollOptions, Next> {
        if self.time_left() <= 0.0 {
            return Err(self.end_of_time());
        }
        self.segment_start = s;
        let opts = self.opts;
        Ok(RollOptions {
            theta0: s.theta,
            omega0: s.omega,
            mu_s: Some(opts.law.mu_s),
            t_max: self.time_left(),
            theta_max: s.theta + (opts.l_max - s.l),
            rule: opts.law.rule,
            solver: segment_solver(opts, self.steps_left),
            dense_output: opts.dense_output,
        })
    }

    /// The rolling segment begun by [`Self::roll_start`], integrated: what comes next.
    fn roll_end(&mut self, rr: Result<RollRun>) -> Result<Next> {
        let rr = match rr {
            Ok(rr) => rr,
            Err(Error::InvalidParameter { name, .. }) => {
                return Ok(Next::End(
                    MotionStatus::Failed,
                    format!("the rolling segment left the supported range ({name})"),
                ))
            }
            Err(e) => return Err(e),
        };
        let s = self.segment_start;
        self.steps_left = self.steps_left.saturating_sub(rr.t.len().saturating_sub(1));
        self.run.nfev += rr.nfev;
        let l_shift = s.l - s.theta;
        let t0 = self.t;
        for i in (0..rr.t.len()).filter(|_| self.opts.record_points) {
            let state = BodyState::rolling(rr.theta[i], rr.omega[i], rr.theta[i] + l_shift);
            let forces = (rr.fx[i], rr.fy[i]);
            let p = self.point(t0 + rr.t[i], state, rr.trig[i], forces, Mode::Roll);
            self.run.push(p)?;
        }
        let last = rr.t.len() - 1;
        self.t = t0 + rr.t[last];
        let end = BodyState::rolling(rr.theta[last], rr.omega[last], rr.theta[last] + l_shift);
        if let (Some(sol), Some(dense)) = (self.run.dense.as_mut(), rr.dense) {
            sol.pieces.push((
                t0,
                Piece::Roll {
                    steps: dense.steps,
                    l_shift,
                },
            ));
        }
        let law = &self.opts.law;
        Ok(match rr.status {
            RollStatus::TimeLimit => self.end_of_time(),
            // A run never ends rocking back (the event is not watched).
            RollStatus::Event(ContactEvent::ThetaLimit | ContactEvent::RocksBack) => {
                self.end_of_ramp()
            }
            RollStatus::Event(ContactEvent::Liftoff) => {
                self.crossing = Some(Crossing::Liftoff);
                Next::Mode(Mode::Flight, TransitionReason::Liftoff, end, 0.0)
            }
            RollStatus::Event(ContactEvent::NormalForce) => {
                self.crossing = Some(Crossing::NormalForce);
                after(
                    decide(self.ramp, law, &end, true),
                    TransitionReason::NormalForce,
                    end,
                )
            }
            RollStatus::Event(ContactEvent::Slip) => {
                self.crossing = Some(Crossing::FrictionCone);
                after(
                    decide(self.ramp, law, &end, true),
                    TransitionReason::Slip,
                    end,
                )
            }
            RollStatus::Failed(status) => self.failed("rolling", status),
        })
    }

    /// A sliding segment from `s` with friction direction σ: its track (its start point
    /// recorded), or what comes instead.
    fn slip_start(
        &mut self,
        s: BodyState,
        sigma: f64,
    ) -> Result<std::result::Result<SlipTrack, Next>> {
        if self.time_left() <= 0.0 {
            return Ok(Err(self.end_of_time()));
        }
        let k = Slipping::new(*self.ramp, sigma, self.opts.law.mu_k).kinematics(s.theta, s.omega);
        // (D ≤ 0 too: there the impulse form declares the jam)
        if !(k.d > 0.0 && k.fy <= F_SWITCH) {
            return Ok(Err(self.slip_in_impulse(s, sigma)?));
        }
        let solver = segment_solver(self.opts, self.steps_left);
        let track = SlipTrack::begin(
            self.ramp,
            self.opts,
            (s, sigma),
            (self.t, solver),
            (self.run.dissipated_slip, self.run.dissipated_impacts),
        )?;
        Ok(Ok(track))
    }

    /// The sliding segment begun by [`Self::slip_start`], integrated: what comes next.
    fn slip_end(&mut self, track: SlipTrack, outcome: &Outcome<5>) -> Result<Next> {
        let (t0, q0, sigma) = (track.t0, self.run.dissipated_slip, track.sigma());
        let (points, steps) = track.finish()?;
        for p in points {
            self.run.push(p)?;
        }
        if outcome.status == Status::Stopped {
            return Err(Error::Interrupted);
        }
        self.steps_left = self.steps_left.saturating_sub(outcome.n_accepted);
        self.run.nfev += outcome.nfev;
        self.run.dissipated_slip = q0 + outcome.y[4];
        self.t = outcome.t;
        if let Some(sol) = self.run.dense.as_mut() {
            sol.pieces.push((t0, Piece::Slip { steps }));
        }
        let end = slip_state(&outcome.y);
        Ok(match outcome.status {
            Status::Finished => self.end_of_time(),
            Status::Event(k) => match SlipEvent::ALL[k] {
                SlipEvent::NormalForce => {
                    self.crossing = Some(Crossing::NormalForce);
                    Next::Mode(Mode::Flight, TransitionReason::NormalForce, end, 0.0)
                }
                SlipEvent::Stops => {
                    self.crossing = Some(Crossing::SlipStops);
                    self.slip_stopped(end)
                }
                SlipEvent::Singular => self.slip_in_impulse(end, sigma)?,
                SlipEvent::LLimit => self.end_of_ramp(),
            },
            other => self.failed("slipping", other),
        })
    }

    /// What follows a slip that stopped at `end` (in time or in the impulse).
    fn slip_stopped(&self, mut end: BodyState) -> Next {
        end.ldot = end.omega;
        let verdict = decide(self.ramp, &self.opts.law, &end, false);
        after(verdict, TransitionReason::Slip, end)
    }

    /// A flight: exact, until the landing, then the impact.
    fn fly(&mut self, s: BodyState) -> Result<Next> {
        let f = Flight::new(*self.ramp, s);
        let t0 = self.t;
        let horizon = self.time_left();
        let landing = f.landing(horizon);
        let (tau_end, landed) = match landing {
            Landing::At(tau) => (tau, true),
            Landing::None => (horizon, false),
            Landing::Immediate => {
                return Ok(Next::End(
                    MotionStatus::Jam,
                    "neither contact nor flight is consistent here (the gap cannot open)"
                        .to_string(),
                ))
            }
            Landing::Undecided => {
                return Ok(Next::End(
                    MotionStatus::Failed,
                    "the landing search used up its evaluation budget".to_string(),
                ))
            }
        };
        // l_max inside the flight: the first sample past it, refined by Brent.
        let samples = apex::samples(s.omega, tau_end);
        let mut tau_stop = tau_end;
        let mut hit_l_max = false;
        if self.opts.l_max.is_finite() {
            let g = |tau: f64| f.state(tau).l - self.opts.l_max;
            let mut prev = (0.0, g(0.0));
            for i in 1..=samples {
                let tau = tau_end * i as f64 / samples as f64;
                let gi = g(tau);
                if prev.1 < 0.0 && gi >= 0.0 {
                    tau_stop = brent(g, prev.0, tau, prev.1, gi, 0.0, 4.0 * f64::EPSILON, 200)
                        .map_or(tau, |r| r.x);
                    hit_l_max = true;
                    break;
                }
                prev = (tau, gi);
            }
        }
        // The segment's last point carries the time the next segment starts from, exactly:
        // (τ·N)/N and t0 + τ may round past it, and times must never decrease.
        let t_end = if tau_stop == horizon {
            self.opts.t_max
        } else {
            t0 + tau_stop
        };
        for i in (0..=samples).filter(|_| self.opts.record_points) {
            let (tau, t) = if i == samples {
                (tau_stop, t_end)
            } else {
                let tau = tau_stop * i as f64 / samples as f64;
                (tau, (t0 + tau).min(t_end))
            };
            let state = if i == 0 { s } else { f.state(tau) };
            let trig = crate::trig::sin_cos(state.theta);
            let p = self.point(t, state, trig, (0.0, 0.0), Mode::Flight);
            self.run.push(p)?;
        }
        if let Some(sol) = self.run.dense.as_mut() {
            sol.pieces.push((t0, Piece::Flight(f)));
        }
        let end = f.state(tau_stop);
        self.t = t_end;
        self.run.flights.push(FlightRecord {
            t_liftoff: t0,
            t_landing: if landed && !hit_l_max {
                t0 + tau_stop
            } else {
                f64::NAN
            },
            theta_liftoff: s.theta,
            theta_landing: end.theta,
            apex: f.apex(tau_stop),
            distance: end.l - s.l,
        });
        if hit_l_max {
            return Ok(self.end_of_ramp());
        }
        if !landed {
            return Ok(self.end_of_time());
        }
        self.crossing = Some(Crossing::Landing);
        Ok(Next::Landing(BodyState { b: 1.0, ..end }))
    }

    /// The impact at a landing, then the mode after it.
    fn impact(&mut self, before: BodyState) -> Next {
        let (r, law) = (self.ramp, &self.opts.law);
        // simulate refuses bodies with Ĩ_CM = 0, the one case without a matrix.
        let Some(landed) = land(r, self.opts, &before) else {
            return Next::End(MotionStatus::Failed, "singular impact matrix".to_string());
        };
        let after_state = landed.state;
        let reason = if landed.settled {
            TransitionReason::Settle
        } else {
            TransitionReason::Impact
        };
        let lost = r.energy_of(&before) - r.energy_of(&after_state);
        self.run.dissipated_impacts += lost;
        let next = if landed.flies {
            Next::Mode(Mode::Flight, TransitionReason::Impact, after_state, 0.0)
        } else {
            match after(decide(r, law, &after_state, false), reason, after_state) {
                // After a landing the reason is the landing, whatever the mode.
                Next::Mode(m, _, st, sg) => Next::Mode(m, reason, st, sg),
                end => end,
            }
        };
        self.run.impacts.push(ImpactRecord {
            t: self.t,
            normal_speed: -before.bdot,
            slip_before: before.slip_velocity(),
            pt: landed.pt,
            pn: landed.pn,
            energy_lost: lost,
            sticking: landed.sticking,
            outcome: match &next {
                Next::Mode(m, ..) => *m,
                Next::Resume(..) => Mode::Slip,
                Next::Landing(..) | Next::End(..) => Mode::Flight,
            },
        });
        next
    }
}

mod impulse;

#[cfg(test)]
mod tests;

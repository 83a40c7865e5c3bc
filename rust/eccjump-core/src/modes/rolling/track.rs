//! A rolling run under way: its events (whose ramp is the system) and its record. One run is integrated alone by [`roll_until`]; many are integrated side
//! by side by [`roll_batch`] (the lanes of [`crate::ode::lanes`]), each with the same steps,
//! record and result as alone, bit for bit.
//!
//! [`roll_until`]: crate::modes::rolling::run::roll_until

use std::cell::RefCell;

use crate::error::{try_grow, Error, Result};
use crate::mechanics::Ramp;
use crate::modes::rolling::run::{
    violated_at_start, ContactEvent, ContactEvents, EventHit, RollOptions, RollRun, RollStatus,
    RESERVE,
};
use crate::modes::rolling::solution::RollSolution;
use crate::ode::lanes::{solve_lanes_with, Keyed, Start, Track};
use crate::ode::{DenseStep, Integrator, Observation, Outcome, SolverOptions, State, Status};

/// What a run has recorded so far.
struct Record {
    run: RollRun,
    /// The dense output of every step, when asked for.
    steps: Vec<DenseStep<2>>,
    /// The first failed allocation, if any: after it nothing more is recorded.
    memory: Option<Error>,
}

/// A rolling run between its start and its end.
pub(crate) struct RollTrack {
    events: ContactEvents,
    dense_output: bool,
    /// The integrator's options: the run's, with every step's dense output made when it
    /// is recorded.
    pub(crate) solver: SolverOptions,
    record: RefCell<Record>,
}

/// The start of a run: a track to integrate from y0, or the whole run if it ends at once.
#[allow(clippy::large_enum_variant)] // made once per run and taken apart at once: no box
pub(crate) enum Begun {
    /// A contact event already holds at t = 0: the run ends there.
    Ended(RollRun),
    /// Integrate the track from y0.
    Track(RollTrack, State<2>),
}

impl RollTrack {
    /// Checks the options and records the start.
    pub(crate) fn begin(ramp: &Ramp, opts: &RollOptions) -> Result<Begun> {
        opts.validate()?;
        let events = ContactEvents::of_run(*ramp, opts.mu_s, opts.theta_max, opts.rule);
        let capacity = RESERVE.min(opts.solver.max_steps.saturating_add(2));
        let mut run = RollRun {
            t: Vec::with_capacity(capacity),
            theta: Vec::with_capacity(capacity),
            omega: Vec::with_capacity(capacity),
            omega_dot: Vec::with_capacity(capacity),
            fx: Vec::with_capacity(capacity),
            fy: Vec::with_capacity(capacity),
            trig: Vec::with_capacity(capacity),
            l: Vec::new(),
            ratio: Vec::new(),
            events: Vec::new(),
            status: RollStatus::TimeLimit,
            nfev: 0,
            dense: None,
        };
        run.push(0.0, &ramp.kinematics(opts.theta0, opts.omega0))?;
        // A contact event that already holds at t = 0 ends the run there: the integrator
        // looks for crossings only, and a run that starts outside the contact conditions
        // must not roll on as if it were inside them.
        if let Some(event) = violated_at_start(&events, opts.theta0, opts.omega0) {
            run.events.push(EventHit {
                event,
                t: 0.0,
                theta: opts.theta0,
                omega: opts.omega0,
            });
            run.status = RollStatus::Event(event);
            run.derive()?;
            return Ok(Begun::Ended(run));
        }
        let steps = Vec::with_capacity(if opts.dense_output { capacity } else { 0 });
        let track = RollTrack {
            events,
            dense_output: opts.dense_output,
            solver: SolverOptions {
                dense_every_step: opts.solver.dense_every_step || opts.dense_output,
                ..opts.solver
            },
            record: RefCell::new(Record {
                run,
                steps,
                memory: None,
            }),
        };
        Ok(Begun::Track(
            track,
            State::<2>::new(opts.theta0, opts.omega0),
        ))
    }

    /// The run from the integration's outcome.
    pub(crate) fn finish(self, outcome: &Outcome<2>) -> Result<RollRun> {
        let Record {
            mut run,
            steps,
            memory,
        } = self.record.into_inner();
        if let Some(e) = memory {
            return Err(e);
        }
        if outcome.status == Status::Stopped {
            return Err(Error::Interrupted);
        }
        run.nfev = outcome.nfev;
        run.status = match outcome.status {
            Status::Finished => RollStatus::TimeLimit,
            Status::Event(k) => RollStatus::Event(ContactEvent::ALL[k]),
            other => RollStatus::Failed(other),
        };
        // The last accepted step ends past a terminal event: end the record at the event.
        if let Status::Event(_) = outcome.status {
            while run.t.len() > 1 && run.t.last().is_some_and(|&t| t > outcome.t) {
                run.pop();
            }
            if run.t.last().is_some_and(|&t| t < outcome.t) {
                let end = self.events.ramp.kinematics(outcome.y[0], outcome.y[1]);
                run.push(outcome.t, &end)?;
            }
        }
        if self.dense_output {
            run.dense = Some(RollSolution {
                ramp: self.events.ramp,
                steps,
                t_end: run.t.last().copied().unwrap_or(0.0),
            });
        }
        run.derive()?;
        Ok(run)
    }
}

impl Track<2> for RollTrack {
    type Sys = Ramp;
    type Events = ContactEvents;
    #[inline]
    fn sys(&self) -> &Ramp {
        &self.events.ramp
    }
    #[inline]
    fn events(&self) -> &ContactEvents {
        &self.events
    }
    #[inline]
    fn observe(&self, obs: Observation<'_, 2>) {
        let mut rec = self.record.borrow_mut();
        let Record { run, steps, memory } = &mut *rec;
        match obs {
            Observation::Step { dense, t, y, trig } => {
                // After a failed allocation the rest is not recorded; the run reports it.
                if memory.is_none() {
                    let k = self.events.ramp.kinematics_at(y[0], y[1], trig);
                    if let Err(e) = run.push(t, &k) {
                        *memory = Some(e);
                    } else if let (true, Some(dense)) = (self.dense_output, dense) {
                        // (always there: the solver makes every step's when it is recorded)
                        match try_grow("the dense output", steps) {
                            Ok(()) => steps.push(*dense),
                            Err(e) => *memory = Some(e),
                        }
                    }
                }
            }
            Observation::Event { index, t, y } => run.events.push(EventHit {
                event: ContactEvent::ALL[index],
                t,
                theta: y[0],
                omega: y[1],
            }),
        }
    }
}

/// [`roll_until`] of every run that `next` gives (a key, the ramp and the options, whose
/// pair must be `method`), integrated side by side: `done(key, result)` gets each run as
/// soon as it ends, bit for bit what `roll_until` gives. `stop` is asked before each run
/// starts and as `roll_until` asks it; a `true` ends the runs under way with
/// `Error::Interrupted` and starts no more.
///
/// [`roll_until`]: crate::modes::rolling::run::roll_until
pub(crate) fn roll_batch<K>(
    method: Integrator,
    mut next: impl FnMut() -> Option<(K, Ramp, RollOptions)>,
    done: impl FnMut(K, Result<RollRun>),
    stop: &dyn Fn() -> bool,
) {
    // Runs that end at their start go to `done` from within `next`.
    let done = RefCell::new(done);
    let starts = || {
        while !stop() {
            let (key, ramp, opts) = next()?;
            debug_assert_eq!(opts.solver.method, method, "one pair per batch");
            match RollTrack::begin(&ramp, &opts) {
                Err(e) => (done.borrow_mut())(key, Err(e)),
                Ok(Begun::Ended(run)) => (done.borrow_mut())(key, Ok(run)),
                Ok(Begun::Track(track, y0)) => {
                    return Some(Start {
                        opts: track.solver,
                        track: Keyed { key, track },
                        t0: 0.0,
                        y0,
                        t_end: opts.t_max,
                    })
                }
            }
        }
        None
    };
    let ended = |k: Keyed<K, RollTrack>, outcome: Outcome<2>| {
        let result = k.track.finish(&outcome);
        (done.borrow_mut())(k.key, result)
    };
    solve_lanes_with(method, starts, ended, stop);
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{Cylinder, Rule};
    use crate::modes::rolling::run::roll_until;
    use crate::ode::SolverOptions;
    use crate::testing::Lcg;

    /// Runs of every kind: from rest and moving, slipping or lifting off or reaching
    /// θ_max or t_max, ending at the start, with and without the dense output, and bad
    /// options (an error).
    fn runs(method: Integrator) -> Vec<(Ramp, RollOptions)> {
        let mut rng = Lcg(7);
        (0..90)
            .map(|i| {
                let chi = 0.9 * rng.next();
                let km = (1.0 - chi) * rng.next();
                let alpha = 1.5 * rng.next();
                let ramp = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap();
                let opts = RollOptions {
                    theta0: if i % 5 == 1 {
                        6.0 * rng.next() - 3.0
                    } else {
                        0.0
                    },
                    omega0: if i % 7 == 2 { 2.0 * rng.next() } else { 0.0 },
                    mu_s: (i % 3 != 0).then(|| 0.1 + 2.0 * rng.next()),
                    t_max: if i % 11 == 4 { 0.5 } else { 1e3 },
                    theta_max: if i % 13 == 6 { 8.0 } else { f64::INFINITY },
                    rule: if i % 2 == 0 {
                        Rule::Paper
                    } else {
                        Rule::NormalForce
                    },
                    solver: SolverOptions {
                        method,
                        rtol: if i % 17 == 8 { 0.5 } else { 1e-10 },
                        ..SolverOptions::default()
                    },
                    dense_output: i % 4 == 3,
                };
                (ramp, opts)
            })
            .collect()
    }

    #[test]
    fn a_batch_gives_each_run_as_alone_bit_for_bit() {
        for method in Integrator::ALL {
            let runs = runs(method);
            let mut got = vec![None; runs.len()];
            let mut queue = runs.iter().enumerate();
            roll_batch(
                method,
                || queue.next().map(|(i, (r, o))| (i, *r, *o)),
                |i, result| got[i] = Some(format!("{result:?}")),
                &|| false,
            );
            let (mut errors, mut ended_at_start) = (0, 0);
            for (i, (r, o)) in runs.iter().enumerate() {
                let alone = roll_until(r, o, &|| false);
                errors += alone.is_err() as usize;
                ended_at_start += alone.as_ref().is_ok_and(|run| run.t.len() == 1) as usize;
                assert_eq!(
                    got[i].as_deref(),
                    Some(format!("{alone:?}").as_str()),
                    "run {i}"
                );
            }
            assert!(
                errors > 0 && ended_at_start > 0,
                "{errors} {ended_at_start}"
            );
        }
    }

    #[test]
    fn a_stopped_batch_ends_its_runs_as_interrupted() {
        let runs = runs(Integrator::Rk45);
        let mut results = Vec::new();
        let mut queue = runs.iter().enumerate();
        roll_batch(
            Integrator::Rk45,
            || queue.next().map(|(i, (r, o))| (i, *r, *o)),
            |_, result| results.push(result),
            &|| true,
        );
        assert!(results.iter().all(|r| matches!(r, Err(Error::Interrupted))));
    }
}

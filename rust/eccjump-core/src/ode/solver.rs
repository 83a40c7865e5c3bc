//! The driver loop: initial step, adaptive steps, events, limits and statuses.
//!
//! Mirrors scipy's `solve_ivp` loop (f0, `select_initial_step`, then `step` until
//! t_bound) for any pair ([`Integrator`]), with events found on each accepted step's dense
//! output.
//! Everything lives on the stack; results go to the observer, so the loop never
//! allocates.

use super::events::{quiet_step, scan_step, EventCarry, NonFiniteEvent};
use super::pair::{all_finite, error_scale, Dop853, Dp5, Integrator, RkPair, Vern9};
use super::stepper::{select_initial_step, Point, StepStatus, Stepper, Trial};
use super::{DenseStep, EventFunctions, OdeSystem, SinCos, State, StepEnds};

/// Integration options, with scipy's meanings.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SolverOptions {
    /// Relative tolerance (scipy `rtol`).
    pub rtol: f64,
    /// Absolute tolerance (scipy `atol`), the same for every component.
    pub atol: f64,
    /// Stop with [`Status::MaxSteps`] after this many accepted steps.
    pub max_steps: usize,
    /// First step; `None` selects it automatically as scipy's `select_initial_step`.
    pub first_step: Option<f64>,
    /// Largest allowed step (scipy `max_step`).
    pub max_step: f64,
    /// Largest change of the first component y₀ per step: each trial is clipped to
    /// |h| ≤ this / |f₀| by its rate at the step's start, and an attempt whose y₀ changes
    /// more is retried shorter (∞, the default, gives scipy's steps). The full motion
    /// caps the angle θ so: with a rate that is nearly constant (χ → 0) the error estimate
    /// lets a step span several turns, too coarse to plot or to close the energy ledger.
    pub max_first_change: f64,
    /// Interior points per step at which event signs are sampled in addition to the step
    /// ends, so that a double crossing inside one step is not missed.
    pub event_samples: usize,
    /// The Runge–Kutta pair.
    pub method: Integrator,
    /// Make every accepted step's dense output, for an observer that keeps it. When false,
    /// a step of DOP853 whose ends alone clear it of events
    /// ([`crate::ode::EventBounds::change_bounds_ends`]) is observed without one, which saves the
    /// three extra evaluations of f it costs. The steps, events and states are the same
    /// either way; only `nfev` differs.
    pub dense_every_step: bool,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            max_steps: 1_000_000,
            first_step: None,
            max_step: f64::INFINITY,
            max_first_change: f64::INFINITY,
            event_samples: 4,
            method: Integrator::Rk45,
            dense_every_step: false,
        }
    }
}

impl SolverOptions {
    /// The tolerances every route accepts: rtol ∈ [1e-15, 1e-3], atol ∈ [1e-300, 1e-3].
    /// Looser tolerances make the ODE route's verdicts unreliable and a full motion's
    /// energy ledger meaningless (atol = 0.5 once gave a negative energy lost).
    pub fn check_tolerances(rtol: f64, atol: f64) -> crate::error::Result<()> {
        crate::error::check_range("rtol", rtol, 1e-15, 1e-3)?;
        crate::error::check_range("atol", atol, 1e-300, 1e-3)?;
        Ok(())
    }
}

/// Why the integration stopped.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Status {
    /// t reached t_end.
    Finished,
    /// Terminal event k was met.
    Event(usize),
    /// `max_steps` accepted steps were taken.
    MaxSteps,
    /// The step size fell below the spacing of floating-point numbers at t.
    StepTooSmall,
    /// The right-hand side or an event function returned NaN or inf.
    NonFinite,
    /// The caller's `stop` asked to end the integration (see [`solve_until`]).
    Stopped,
}

/// What the solver reports to the observer, in order of time.
#[derive(Debug, Clone, Copy)]
pub enum Observation<'a, const N: usize> {
    /// An accepted step ending at t in y.
    Step {
        /// Dense output of the whole step: always there under
        /// [`SolverOptions::dense_every_step`], else only where the event scan needed it.
        dense: Option<&'a DenseStep<N>>,
        /// End of the step (the event time if truncated at a terminal event).
        t: f64,
        /// State at `t`.
        y: &'a State<N>,
        /// sin and cos of y[0], if the right-hand side computed them there (handed on:
        /// [`OdeSystem::rhs_with_trig`]); `None` at a terminal event.
        trig: Option<SinCos>,
    },
    /// Event k met at (t, y) (terminal or not); `y` is the dense output at t.
    Event {
        /// Index k of the event function.
        index: usize,
        /// Time of the event.
        t: f64,
        /// State at the event.
        y: &'a State<N>,
    },
}

/// The end of an integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome<const N: usize> {
    /// Why the integration stopped.
    pub status: Status,
    /// Final time (the event point for a terminal event).
    pub t: f64,
    /// Final state (the event point for a terminal event).
    pub y: State<N>,
    /// Right-hand-side evaluations.
    pub nfev: usize,
    /// Accepted steps.
    pub n_accepted: usize,
    /// Rejected step attempts.
    pub n_rejected: usize,
}

/// Integrates y' = f(t, y) from (t0, y0) towards t_end (> t0), reporting every accepted
/// step and every event to `observer`. Never panics; any failure ends in a [`Status`].
///
/// Within one step, events are reported before the [`Observation::Step`] that contains
/// them. On a terminal event the step is reported truncated at the event (its `t`, `y`
/// are the event point; its dense output still spans the whole step) and the outcome is
/// the event point. Integration backwards (t_end < t0) works too; event directions are
/// then meant along the integration. Non-finite t0, t_end or y0 give
/// [`Status::NonFinite`] at once. On [`Status::NonFinite`] or [`Status::StepTooSmall`]
/// the outcome is the last accepted, fully checked point.
pub fn solve<S, E, O, const N: usize>(
    sys: &S,
    events: &E,
    t0: f64,
    y0: State<N>,
    t_end: f64,
    opts: &SolverOptions,
    observer: &mut O,
) -> Outcome<N>
where
    S: OdeSystem<N>,
    E: EventFunctions<N>,
    O: FnMut(Observation<'_, N>),
{
    solve_until(sys, events, t0, y0, t_end, opts, observer, &|| false)
}

/// Accepted steps between two calls of `stop` in [`solve_until`]: a few milliseconds.
pub(crate) const STOP_EVERY: usize = 4096;

/// [`solve`], asking `stop()` every few thousand accepted steps; a `true` ends the
/// integration with [`Status::Stopped`] at the last accepted point (e.g. on Ctrl-C). The
/// steps taken are the same as without `stop`.
#[allow(clippy::too_many_arguments)] // solve's arguments and the stop
pub fn solve_until<S, E, O, const N: usize>(
    sys: &S,
    events: &E,
    t0: f64,
    y0: State<N>,
    t_end: f64,
    opts: &SolverOptions,
    observer: &mut O,
    stop: &dyn Fn() -> bool,
) -> Outcome<N>
where
    S: OdeSystem<N>,
    E: EventFunctions<N>,
    O: FnMut(Observation<'_, N>),
{
    // One driver per pair, each compiled for it.
    macro_rules! drive_with {
        ($pair:ident) => {
            match Run::<$pair<N>, N>::begin(sys, t0, y0, t_end, opts) {
                Err(out) => out,
                Ok(run) => run.to_end(None, sys, events, observer, stop),
            }
        };
    }
    match opts.method {
        Integrator::Rk45 => drive_with!(Dp5),
        Integrator::Dop853 => drive_with!(Dop853),
        Integrator::Vern9 => drive_with!(Vern9),
    }
}

/// One integration between its steps: what [`solve_until`]'s loop carries from step to
/// step. The integrator of many trajectories side by side ([`crate::ode::lanes`]) runs
/// the same integration through the same parts, the steps' stages excepted.
#[derive(Debug, Clone, Copy)]
pub(crate) struct Run<P, const N: usize> {
    /// The stepper (state, step size, the last attempt's stages).
    pub st: Stepper<P, N>,
    /// The outcome so far (counts, last accepted point).
    pub out: Outcome<N>,
    carry: EventCarry<N>,
    /// The options.
    pub opts: SolverOptions,
    t_end: f64,
}

impl<P: RkPair<N>, const N: usize> Run<P, N> {
    /// The start of the integration: f0 and the first step size, or the outcome if it ends
    /// there (non-finite input or f0).
    pub(crate) fn begin<S: OdeSystem<N>>(
        sys: &S,
        t0: f64,
        y0: State<N>,
        t_end: f64,
        opts: &SolverOptions,
    ) -> Result<Self, Outcome<N>> {
        let mut out = Outcome {
            status: Status::NonFinite,
            t: t0,
            y: y0,
            nfev: 0,
            n_accepted: 0,
            n_rejected: 0,
        };
        if !t0.is_finite() || !t_end.is_finite() || !all_finite(&y0) {
            return Err(out);
        }
        let (f0, trig) = sys.rhs_with_trig(t0, &y0);
        out.nfev = 1;
        if !all_finite(&f0) {
            return Err(out);
        }
        let start = Point {
            t: t0,
            y: y0,
            f: f0,
        };
        let tol = (opts.rtol, opts.atol);
        let h_abs = match opts.first_step {
            Some(h) => h,
            None => {
                let power = (P::first_step_power as fn(f64) -> f64, P::FIRST_STEP_PROBES);
                let first = select_initial_step(
                    power,
                    sys,
                    &start,
                    t_end,
                    opts.max_step,
                    tol,
                    &mut out.nfev,
                );
                match first {
                    Some(h) => h,
                    None => return Err(out),
                }
            }
        };
        let st = Stepper::<P, N>::new(start, h_abs, t_end, opts.max_step, tol);
        let st = Stepper {
            max_first_change: opts.max_first_change,
            trig,
            ..st
        };
        Ok(Self {
            st,
            out,
            carry: EventCarry::default(),
            opts: *opts,
            t_end,
        })
    }

    /// The checks before each step: true (with the status set) if the integration ends
    /// here (t_end reached, the step limit, or `stop`).
    #[inline]
    pub(crate) fn ends_here(&mut self, stop: &dyn Fn() -> bool) -> bool {
        let out = &mut self.out;
        if self.st.t == self.t_end {
            out.status = Status::Finished;
            return true;
        }
        if out.n_accepted >= self.opts.max_steps {
            out.status = Status::MaxSteps;
            return true;
        }
        if out.n_accepted % STOP_EVERY == STOP_EVERY - 1 && stop() {
            out.status = Status::Stopped;
            return true;
        }
        false
    }

    /// After an accepted step with its dense output (`None` if a stage it needs is not
    /// finite): the event scan and the observations. True (with the status set) if the
    /// integration ends in this step.
    #[inline]
    pub(crate) fn after_step<E, O>(
        &mut self,
        events: &E,
        dense: Option<&DenseStep<N>>,
        observer: &mut O,
    ) -> bool
    where
        E: EventFunctions<N>,
        O: FnMut(Observation<'_, N>),
    {
        let out = &mut self.out;
        let Some(dense) = dense else {
            // The step's dense output is unknown: stop at its start, as for its events.
            out.status = Status::NonFinite;
            return true;
        };
        let st = &self.st;
        let scan = scan_step(
            events,
            dense,
            (st.t, &st.y, st.trig),
            self.opts.event_samples,
            &mut self.carry,
            |hit| {
                observer(Observation::Event {
                    index: hit.index,
                    t: hit.t,
                    y: &hit.y,
                })
            },
        );
        match scan {
            Err(NonFiniteEvent) => {
                // The step's events are unknown: stop at its start, the last checked point.
                out.status = Status::NonFinite;
                true
            }
            Ok(Some(hit)) => {
                out.n_accepted += 1;
                observer(Observation::Step {
                    dense: Some(dense),
                    t: hit.t,
                    y: &hit.y,
                    trig: None,
                });
                out.status = Status::Event(hit.index);
                out.t = hit.t;
                out.y = hit.y;
                true
            }
            Ok(None) => {
                out.n_accepted += 1;
                observer(Observation::Step {
                    dense: Some(dense),
                    t: st.t,
                    y: &st.y,
                    trig: st.trig,
                });
                out.t = st.t;
                out.y = st.y;
                false
            }
        }
    }

    /// After an accepted step that began with f = `f_old`, unless every step's dense
    /// output is wanted: true if the step's ends alone clear it of events
    /// ([`quiet_step`]); the step is then observed without dense output (whose extra
    /// stages are never evaluated).
    #[inline]
    pub(crate) fn after_quiet_step<E, O>(
        &mut self,
        events: &E,
        f_old: &State<N>,
        observer: &mut O,
    ) -> bool
    where
        E: EventFunctions<N>,
        O: FnMut(Observation<'_, N>),
    {
        // A pair whose dense output costs no evaluations (RK45) gains nothing: its dense
        // output and the scan on it are as cheap as the proof from the ends (measured).
        if self.opts.dense_every_step || P::EXTRA == 0 {
            return false;
        }
        let st = &self.st;
        let ends = StepEnds {
            t_old: st.t_old,
            t_new: st.t,
            h: st.t - st.t_old,
            y_old: st.y_old,
            f_old: *f_old,
            y_new: st.y,
            f_new: st.f,
            scale: error_scale(&st.y_old, &st.y, st.rtol, st.atol),
        };
        if !quiet_step(events, &ends, st.trig, &mut self.carry) {
            return false;
        }
        let out = &mut self.out;
        out.n_accepted += 1;
        observer(Observation::Step {
            dense: None,
            t: st.t,
            y: &st.y,
            trig: st.trig,
        });
        out.t = st.t;
        out.y = st.y;
        true
    }

    /// The integration from here to its end, one step at a time, the current step from
    /// `trial` (one begun elsewhere: the integrator of many trajectories hands over a
    /// trajectory in the middle of a step) or, if `None`, from its first trial.
    pub(crate) fn to_end<S, E, O>(
        mut self,
        mut trial: Option<Trial>,
        sys: &S,
        events: &E,
        observer: &mut O,
        stop: &dyn Fn() -> bool,
    ) -> Outcome<N>
    where
        S: OdeSystem<N>,
        E: EventFunctions<N>,
        O: FnMut(Observation<'_, N>),
    {
        loop {
            if trial.is_none() && self.ends_here(stop) {
                return self.out;
            }
            let first = trial.take().unwrap_or_else(|| self.st.first_trial());
            let f_old = self.st.f;
            let out = &mut self.out;
            match self
                .st
                .step_from(first, sys, &mut out.nfev, &mut out.n_rejected)
            {
                StepStatus::Accepted => {}
                StepStatus::TooSmall => {
                    out.status = Status::StepTooSmall;
                    return self.out;
                }
                StepStatus::NonFinite => {
                    out.status = Status::NonFinite;
                    return self.out;
                }
            }
            if self.after_quiet_step(events, &f_old, observer) {
                continue;
            }
            let dense = self.st.dense(sys, &mut self.out.nfev);
            if self.after_step(events, dense.as_ref(), observer) {
                return self.out;
            }
        }
    }
}

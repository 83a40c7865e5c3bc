//! The driver loop: initial step, adaptive steps, events, limits and statuses.
//! (Interface fixed; implementation to be written.)

use super::{DenseStep, EventFunctions, OdeSystem, State};

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
    /// Interior points per step at which event signs are sampled in addition to the step
    /// ends, so that a double crossing inside one step is not missed.
    pub event_samples: usize,
}

impl Default for SolverOptions {
    fn default() -> Self {
        Self {
            rtol: 1e-10,
            atol: 1e-12,
            max_steps: 1_000_000,
            first_step: None,
            max_step: f64::INFINITY,
            event_samples: 4,
        }
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
}

/// What the solver reports to the observer, in order of time.
#[derive(Debug, Clone, Copy)]
pub enum Observation<'a, const N: usize> {
    /// An accepted step from dense.t_old to t, ending in y.
    Step {
        dense: &'a DenseStep<N>,
        t: f64,
        y: &'a State<N>,
    },
    /// Event k met at (t, y) (terminal or not); `y` is the dense output at t.
    Event {
        index: usize,
        t: f64,
        y: &'a State<N>,
    },
}

/// The end of an integration.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Outcome<const N: usize> {
    pub status: Status,
    /// Final time and state (the event point for a terminal event).
    pub t: f64,
    pub y: State<N>,
    /// Right-hand-side evaluations.
    pub nfev: usize,
    pub n_accepted: usize,
    pub n_rejected: usize,
}

/// Integrates y' = f(t, y) from (t0, y0) towards t_end (> t0), reporting every accepted
/// step and every event to `observer`. Never panics; any failure ends in a [`Status`].
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
    let _ = (sys, events, t_end, opts, observer);
    todo!("Dormand–Prince driver: t0 = {t0}, y0 = {y0:?}")
}

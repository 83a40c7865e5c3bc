//! The inputs of a full-motion run and their checks.

use crate::error::{check_count, check_range, Error, Result};
use crate::mechanics::{Rule, MAX_OMEGA0, MAX_THETA0};
use crate::modes::contact::ContactLaw;
use crate::modes::rolling::run::MAX_STEPS;
use crate::ode::SolverOptions;

/// t_max ≤ this (in √(R/g)): bounds the work of a run together with `max_steps`.
pub const MAX_TIME: f64 = 1e6;

/// The largest turn of the body in one step of a rolling or sliding segment (rad, by θ̇ at
/// the step's start): about 12 steps a turn at least. Near χ = 0 the motion is nearly
/// uniformly accelerated, which a Runge–Kutta pair integrates almost exactly, so its error
/// estimate alone lets a step span several turns: a record too coarse to plot and an
/// energy ledger that drifts (1.7e-7 at χ = 1e-9 with RK45). Where the tolerances already
/// keep steps shorter (every run at the default rtol but such bodies) it changes nothing.
pub const MAX_ANGLE_STEP: f64 = 0.5;

/// The eight parameters of a run, in the order every full-motion interface takes them (the
/// axes of a motion map, the last axis of the sensitivities).
pub const PARAMETERS: [&str; 8] = [
    "alpha",
    "chi",
    "km",
    "mu_s",
    "mu_k",
    "restitution",
    "theta0",
    "omega0",
];

/// rtol and atol of a full-motion run ≤ this. The energy ledger (energy + dissipated =
/// energy at the start) is the run's own check, and it holds only to about the tolerances:
/// over random runs to t = 30 its worst error was 14 % of the energy scale at rtol = atol =
/// 1e-3 (the ODE routes' bound, scipy's default), with `dissipated` falling by 1e-4 in a step;
/// 7e-5 and 4e-9 at 1e-6 (`docs/limits.md`).
pub const MAX_MOTION_TOL: f64 = 1e-6;

/// The smallest inertia about the centre of mass Ĩ_CM = I_CM/(M R²) of a full-motion run. The
/// impact law's inverse effective mass carries 1/Ĩ_CM: at Ĩ_CM ≈ 1e-100 an impact "lost"
/// −1e168 (energy gained, found by the fuzz campaign of issue 46), while random runs at
/// k_m = 1e-8 and 1e-10 keep the ledger to 1e-9. Ĩ_CM = 0 (k_m = 0) leaves the spin in flight
/// undetermined.
pub const MIN_ICM: f64 = 1e-10;

/// max_transitions ≤ this.
pub const MAX_TRANSITIONS: usize = 1_000_000;

/// After an impact, a separation speed u_n (in √(gR)) at or below this is set to 0 and the
/// body stays in contact: the Zeno rule that ends bounces accumulating in finite time
/// (`docs/motion.md`). A numerical parameter, not physics.
pub const SETTLE_SPEED: f64 = 1e-6;

/// settle_speed ≤ this: a larger threshold would swallow real bounces.
pub const MAX_SETTLE_SPEED: f64 = 1e-2;

/// The inputs of [`crate::motion::simulate`] besides the body and the ramp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SimOptions {
    /// Friction coefficients and the lift-off rule.
    pub law: ContactLaw,
    /// Stronge's energetic coefficient of restitution e ∈ [0, 1].
    pub restitution: f64,
    /// Initial angle θ0 (rad).
    pub theta0: f64,
    /// Initial θ̇0.
    pub omega0: f64,
    /// Initial slip velocity l̇0 − θ̇0.
    pub slip0: f64,
    /// End time, in (0, [`MAX_TIME`]].
    pub t_max: f64,
    /// Distance along the ramp (from the start) that ends the run; ∞ disables it.
    pub l_max: f64,
    /// Transitions after the start that the run may make.
    pub max_transitions: usize,
    /// Tolerances of the integrator; `max_steps` bounds the accepted steps of the whole run.
    pub solver: SolverOptions,
    /// Keep the dense output of every segment (for `sol(t)`).
    pub dense_output: bool,
    /// The Zeno rule's threshold, in [0, [`MAX_SETTLE_SPEED`]] (default [`SETTLE_SPEED`]).
    /// Not offered in Python: it is here so the tests can show that the transitions before
    /// a settle do not depend on it.
    pub settle_speed: f64,
    /// End the run at the first landing, once the mode after it is chosen (status
    /// `landed`): all a motion map asks of a run.
    pub stop_at_landing: bool,
    /// Record the points of the run (a map keeps only transitions, flights and impacts).
    pub record_points: bool,
}

impl Default for SimOptions {
    fn default() -> Self {
        Self {
            law: ContactLaw {
                mu_s: 1.0,
                mu_k: 1.0,
                rule: Rule::Paper,
            },
            restitution: 0.0,
            theta0: 0.0,
            omega0: 0.0,
            slip0: 0.0,
            t_max: 100.0,
            l_max: f64::INFINITY,
            max_transitions: 100,
            solver: SolverOptions::default(),
            dense_output: false,
            settle_speed: SETTLE_SPEED,
            stop_at_landing: false,
            record_points: true,
        }
    }
}

impl SimOptions {
    /// Checks every option, naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        check_range("mu_s", self.law.mu_s, 0.0, f64::MAX)?;
        if !(self.law.mu_k >= 0.0 && self.law.mu_k <= self.law.mu_s) {
            return Err(Error::invalid("mu_k", self.law.mu_k, "[0, mu_s]"));
        }
        check_range("restitution", self.restitution, 0.0, 1.0)?;
        check_range("theta0", self.theta0, -MAX_THETA0, MAX_THETA0)?;
        check_range("omega0", self.omega0, -MAX_OMEGA0, MAX_OMEGA0)?;
        check_range("slip0", self.slip0, -MAX_OMEGA0, MAX_OMEGA0)?;
        if !(self.t_max > 0.0 && self.t_max <= MAX_TIME) {
            return Err(Error::invalid("t_max", self.t_max, "(0, 1e6]"));
        }
        if self.l_max.is_nan() || self.l_max <= 0.0 {
            return Err(Error::invalid("l_max", self.l_max, "(0, inf]"));
        }
        check_count("max_transitions", self.max_transitions, 1, MAX_TRANSITIONS)?;
        check_range("rtol", self.solver.rtol, 1e-15, MAX_MOTION_TOL)?;
        check_range("atol", self.solver.atol, 1e-300, MAX_MOTION_TOL)?;
        check_count("max_steps", self.solver.max_steps, 1, MAX_STEPS)?;
        check_range("settle_speed", self.settle_speed, 0.0, MAX_SETTLE_SPEED)?;
        Ok(())
    }
}

//! A pure-rolling run: the rolling equation integrated by the Dormand–Prince driver, with
//! the built-in contact events, until the first terminal one (or t_max / θ_max).
//!
//! Events (all located on the dense output to near machine precision):
//! - `Liftoff`: the paper's jump condition χ θ̇² cos θ − cos α = 0, rising;
//! - `NormalForceZero`: F_y = 0, falling (the contact would need to pull);
//! - `Slip`: μ_s F_y − |F_x| = 0, falling (the rolling branch leaves the friction cone);
//! - `ThetaLimit`: θ = θ_max, rising.
//!
//! Which of them end the run is set by the lift-off [`Rule`].

use crate::error::{check_positive, check_range, Error, Result};
use crate::ode::{
    self, DenseStep, Direction, EventFunctions, EventSpec, Observation, OdeSystem, SolverOptions,
    State, Status,
};
use crate::rolling::{Kinematics, Rolling};
pub use crate::rule::Rule;
use std::cell::Cell;

/// The built-in events of a rolling run, in the order of their indices.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
#[repr(u8)]
pub enum RollEvent {
    Liftoff = 0,
    NormalForceZero = 1,
    Slip = 2,
    ThetaLimit = 3,
}

impl RollEvent {
    pub const ALL: [RollEvent; 4] = [
        RollEvent::Liftoff,
        RollEvent::NormalForceZero,
        RollEvent::Slip,
        RollEvent::ThetaLimit,
    ];

    /// A stable lower-case name, used by the Python layer and the command line.
    pub fn name(self) -> &'static str {
        match self {
            RollEvent::Liftoff => "liftoff",
            RollEvent::NormalForceZero => "normal_force_zero",
            RollEvent::Slip => "slip",
            RollEvent::ThetaLimit => "theta_limit",
        }
    }
}

/// The rolling equation as a first-order system in y = (θ, θ̇).
impl OdeSystem<2> for Rolling {
    #[inline]
    fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
        State::<2>::new(y[1], self.omega_dot(y[0], y[1]))
    }
}

/// The event functions of a rolling run.
#[derive(Debug, Clone, Copy)]
pub struct RollEvents {
    pub rolling: Rolling,
    /// μ_s; `None` disables the slip event.
    pub mu_s: Option<f64>,
    pub theta_max: f64,
    pub rule: Rule,
}

impl RollEvents {
    /// g_k at a state, as a function of θ and θ̇ only.
    pub fn value_at(&self, event: RollEvent, theta: f64, omega: f64) -> f64 {
        match event {
            RollEvent::Liftoff => self.rolling.liftoff_function(theta, omega),
            RollEvent::NormalForceZero => self.rolling.kinematics(theta, omega).fy,
            RollEvent::Slip => {
                let k = self.rolling.kinematics(theta, omega);
                // The margin, not the ratio: it stays finite as F_y → 0.
                self.mu_s.map_or(1.0, |mu| mu * k.fy - k.fx.abs())
            }
            // θ_max = ∞ disables the event (a constant, finite g never crosses).
            RollEvent::ThetaLimit if self.theta_max.is_finite() => theta - self.theta_max,
            RollEvent::ThetaLimit => -1.0,
        }
    }

    /// Whether the event ends the run under the chosen rule.
    pub fn is_terminal(&self, event: RollEvent) -> bool {
        match event {
            RollEvent::Liftoff => self.rule == Rule::Paper,
            RollEvent::Slip => self.mu_s.is_some(),
            RollEvent::NormalForceZero | RollEvent::ThetaLimit => true,
        }
    }
}

impl EventFunctions<2> for RollEvents {
    fn count(&self) -> usize {
        RollEvent::ALL.len()
    }
    fn spec(&self, k: usize) -> EventSpec {
        let event = RollEvent::ALL[k];
        let direction = match event {
            RollEvent::Liftoff | RollEvent::ThetaLimit => Direction::Rising,
            RollEvent::NormalForceZero | RollEvent::Slip => Direction::Falling,
        };
        EventSpec {
            direction,
            terminal: self.is_terminal(event),
        }
    }
    fn value(&self, k: usize, _t: f64, y: &State<2>) -> f64 {
        self.value_at(RollEvent::ALL[k], y[0], y[1])
    }
    /// All events from one evaluation of the kinematics (one sin_cos per sample).
    #[inline]
    fn values(&self, first: usize, _t: f64, y: &State<2>, out: &mut [f64]) {
        self.values_from(&self.rolling.kinematics(y[0], y[1]), first, y, out);
    }
    /// Change bounds from bounds on the partial derivatives of each g in θ and θ̇ over
    /// the step (|sin|, |cos| ≤ 1, |θ̇| ≤ W, contact inertia ≥ Ĩ_C + 1 − 2χ), times the
    /// bounds on |dθ/dt|, |dθ̇/dt| of the interpolant.
    #[inline]
    fn change_bounds(&self, first: usize, dense: &DenseStep<2>, out: &mut [f64]) {
        let b = self.change_bounds_all(dense);
        for (i, o) in out.iter_mut().enumerate() {
            *o = b[first + i];
        }
    }
}

impl RollEvents {
    /// g_first, g_first+1, … at y from its kinematics `k`.
    #[inline]
    fn values_from(&self, k: &Kinematics, first: usize, y: &State<2>, out: &mut [f64]) {
        let chi = self.rolling.body.chi;
        for (i, o) in out.iter_mut().enumerate() {
            *o = match RollEvent::ALL[first + i] {
                RollEvent::Liftoff => {
                    // χ θ̇² cos θ − cos α, from the kinematics' own cos θ.
                    chi * k.omega * k.omega * k.cos_theta - self.rolling.cos_a
                }
                RollEvent::NormalForceZero => k.fy,
                RollEvent::Slip => self.mu_s.map_or(1.0, |mu| mu * k.fy - k.fx.abs()),
                RollEvent::ThetaLimit => self.value_at(RollEvent::ThetaLimit, y[0], y[1]),
            };
        }
    }

    /// [`EventFunctions::change_bounds`] of all four events (see [`ContactBounds`]).
    pub fn change_bounds_all(&self, dense: &DenseStep<2>) -> [f64; 4] {
        self.change_bounds_near(dense, None)
    }

    /// [`RollEvents::change_bounds_all`], tightened near an anchor angle (see
    /// [`ContactBounds::near`]).
    pub(crate) fn change_bounds_near(
        &self,
        dense: &DenseStep<2>,
        anchor: Option<(f64, f64, f64)>,
    ) -> [f64; 4] {
        let b = ContactBounds::near(&self.rolling, self.mu_s, dense, anchor);
        let theta_limit = if self.theta_max.is_finite() {
            b.theta_above(self.theta_max)
        } else {
            0.0
        };
        [b.liftoff, b.fy, b.slip, theta_limit]
    }
}

/// Bounds on how much the contact functions of pure rolling can change within one
/// dense-output step, in the sense of [`EventFunctions::change_bounds`]: shared by the
/// rolling run ([`RollEvents`]) and the ODE route of the classification
/// (`jarm_ode`).
///
/// Along the interpolant (θ(t), θ̇(t)), |dg/dt| ≤ G_θ |dθ/dt| + G_ω |dθ̇/dt| with
/// G_θ ≥ |∂g/∂θ|, G_ω ≥ |∂g/∂θ̇| over the step. With W ≥ |θ̇|, s = sin θ, c = cos θ,
/// θ̈ = N/D, N = χθ̇²s + χ sin(α+θ) + sin α, D = Ĩ_C + 1 + 2χc ≥ D_min = Ĩ_C + 1 − 2χ:
///   |θ̈| ≤ A = (χW² + χ + sin α)/D_min,
///   |∂θ̈/∂θ| ≤ A_θ = (χW² + χ)/D_min + 2χ A/D_min,   |∂θ̈/∂θ̇| ≤ A_ω = 2χW/D_min;
/// lift-off χθ̇²c − cos α: G_θ = χW², G_ω = 2χW;
/// F_y = cos α − χθ̇²c − χθ̈s: G_θ = χW² + χA + χA_θ, G_ω = 2χW + χA_ω;
/// F_x = −sin α − χθ̇²s + (1 + χc)θ̈: G_θ = χW² + χA + (1+χ)A_θ, G_ω = 2χW + (1+χ)A_ω;
/// slip μF_y − |F_x|: μ G(F_y) + G(F_x); θ − θ_lim: G_θ = 1, G_ω = 0; θ̇: G_θ = 0,
/// G_ω = 1.
/// The rounding allowance δ = 2⁻⁴⁰ (M + G_θ Θ + G_ω W), with M the sum of the
/// magnitudes of g's terms and Θ ≥ |θ|, is hundreds of times the error of a few
/// roundings in g, of the 1-ulp sin_cos, and of the interpolant (including its
/// mismatch with the exact step end). The bound is L |h| + 4δ.
/// A singular body (D_min ≤ 0) gives +∞ for the force events: never skipped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ContactBounds {
    /// Of the lift-off function χθ̇² cos θ − cos α.
    pub liftoff: f64,
    /// Of F_y.
    pub fy: f64,
    /// Of the slip margin μ_s F_y − |F_x|; 0 without μ_s (the event is then a constant).
    pub slip: f64,
    /// Of θ̇.
    pub omega: f64,
    /// Θ ≥ |θ|, |dθ/dt| and |h| over the step, for [`ContactBounds::theta_above`].
    theta_max: f64,
    theta_rate: f64,
    h: f64,
}

impl ContactBounds {
    /// The bounds over the step `dense`; without an anchor with |sin θ|, |cos θ| ≤ 1 and
    /// D ≥ D_min, else tightened by the trigonometry at one angle
    /// θ_c (any, typically the step end): `anchor` = (θ_c, sin θ_c, cos θ_c). Every θ
    /// of the step is within Δ = |θ_old − θ_c| + |h| sup|dθ/dt| of θ_c, so (sin and cos
    /// being 1-Lipschitz) |sin θ| ≤ S = min(1, |sin θ_c| + Δ'), |cos θ| ≤ C = min(1,
    /// |cos θ_c| + Δ'), and D ≥ max(D_min, Ĩ_C + 1 + 2χ(cos θ_c − Δ')), where Δ' adds
    /// to Δ a relative 2⁻⁴⁰ and an absolute 2⁻⁴⁰(1 + Θ), far above the rounding of θ
    /// along the interpolant and of sin_cos. The bounds of [`ContactBounds`] then hold
    /// with each |sin|, |cos| ≤ 1 replaced by S or C:
    ///   A = (χW²S + χ + sin α)/D_lo, A_θ = (χW²C + χ)/D_lo + 2χSA/D_lo, A_ω = 2χWS/D_lo;
    /// lift-off: G_θ = χW²S, G_ω = 2χWC; F_y: G_θ = χW²S + χAC + χSA_θ,
    /// G_ω = 2χWC + χSA_ω; F_x: G_θ = χW²C + χSA + (1+χC)A_θ, G_ω = 2χWS + (1+χC)A_ω
    /// (and M, the magnitudes of the terms, likewise). With S = C = 1, D_lo = D_min
    /// these are exactly the plain bounds.
    #[inline]
    pub(crate) fn near(
        rolling: &Rolling,
        mu_s: Option<f64>,
        dense: &DenseStep<2>,
        anchor: Option<(f64, f64, f64)>,
    ) -> Self {
        let bounds = dense.bounds();
        let (theta_max, w) = (bounds.value[0], bounds.value[1]);
        let (theta_rate, omega_rate) = (bounds.rate[0], bounds.rate[1]);
        let h = dense.h.abs();
        let chi = rolling.body.chi;
        let (sa, ca) = (rolling.sin_a, rolling.cos_a);
        let eps40 = 1.0 / (1u64 << 40) as f64;
        // δ = 2⁻⁴⁰ (M + G_θ Θ + G_ω W); the bound is L |h| + 4δ.
        let bound = |(m, g_theta, g_omega): (f64, f64, f64)| {
            let delta = (m + g_theta * theta_max + g_omega * w) * eps40;
            (g_theta * theta_rate + g_omega * omega_rate) * h + 4.0 * delta
        };
        let d_min = rolling.contact_inertia(-1.0);
        let (s_max, c_max, d_lo) = match anchor {
            Some((theta_c, s_c, c_c)) => {
                let reach = (dense.y_old[0] - theta_c).abs() + h * theta_rate;
                let reach = reach * (1.0 + eps40) + (1.0 + theta_max) * eps40;
                // NaN (never expected) falls back to the plain bounds through min/max.
                let s_max = (s_c.abs() + reach).min(1.0);
                let c_max = (c_c.abs() + reach).min(1.0);
                let d_lo = rolling.contact_inertia(c_c - reach).max(d_min);
                (s_max, c_max, d_lo)
            }
            None => (1.0, 1.0, d_min),
        };
        let chi_w2 = chi * w * w;
        let liftoff = bound((chi_w2 * c_max + ca, chi_w2 * s_max, 2.0 * chi * w * c_max));
        let (fy, slip) = if d_lo > 0.0 {
            let a = (chi_w2 * s_max + chi + sa) / d_lo;
            let a_theta = (chi_w2 * c_max + chi) / d_lo + 2.0 * chi * s_max * a / d_lo;
            let a_omega = 2.0 * chi * w * s_max / d_lo;
            let lever = 1.0 + chi * c_max;
            // (M, G_θ, G_ω) of F_y and F_x.
            let fy = (
                ca + chi_w2 * c_max + chi * a * s_max,
                chi_w2 * s_max + chi * a * c_max + chi * s_max * a_theta,
                2.0 * chi * w * c_max + chi * s_max * a_omega,
            );
            let fx = (
                sa + chi_w2 * s_max + lever * a,
                chi_w2 * c_max + chi * s_max * a + lever * a_theta,
                2.0 * chi * w * s_max + lever * a_omega,
            );
            let slip = mu_s.map_or(0.0, |mu| {
                bound((mu * fy.0 + fx.0, mu * fy.1 + fx.1, mu * fy.2 + fx.2))
            });
            (bound(fy), slip)
        } else {
            let slip = if mu_s.is_some() { f64::INFINITY } else { 0.0 };
            (f64::INFINITY, slip)
        };
        let omega = bound((w, 0.0, 1.0));
        Self {
            liftoff,
            fy,
            slip,
            omega,
            theta_max,
            theta_rate,
            h,
        }
    }

    /// Of θ − θ_lim (θ_lim finite).
    #[inline]
    pub(crate) fn theta_above(&self, theta_lim: f64) -> f64 {
        let delta =
            (self.theta_max + theta_lim.abs() + self.theta_max) * (1.0 / (1u64 << 40) as f64);
        self.theta_rate * self.h + 4.0 * delta
    }
}

/// Pure rolling with a one-entry memo of (sin θ, cos θ), keyed on the bits of θ. Each
/// accepted step ends with the FSAL evaluation of the right-hand side at the new state;
/// the step scan then evaluates the events there and the caller's observer looks at the
/// forces there, and both find sin_cos of that θ in the memo. sin_cos is a pure function,
/// so hits and misses give identical bits. Shared by the rolling run and `jarm_ode`.
#[derive(Debug, Clone)]
pub(crate) struct RollingMemo {
    pub rolling: Rolling,
    /// (θ, sin θ, cos θ) of the last evaluation; θ = NaN at first, whose sin_cos is NaN.
    trig: Cell<(f64, f64, f64)>,
}

impl RollingMemo {
    pub(crate) fn new(rolling: Rolling) -> Self {
        Self {
            rolling,
            trig: Cell::new((f64::NAN, f64::NAN, f64::NAN)),
        }
    }

    #[inline]
    pub(crate) fn sin_cos(&self, theta: f64) -> (f64, f64) {
        let (th, s, c) = self.trig.get();
        if th.to_bits() == theta.to_bits() {
            return (s, c);
        }
        let (s, c) = theta.sin_cos();
        self.trig.set((theta, s, c));
        (s, c)
    }

    /// The memo's entry (θ, sin θ, cos θ): an anchor for [`ContactBounds::near`] (θ is
    /// NaN before the first evaluation, which the bounds treat as no anchor).
    #[inline]
    pub(crate) fn anchor(&self) -> (f64, f64, f64) {
        self.trig.get()
    }

    /// [`Rolling::kinematics`], bit for bit.
    #[inline]
    pub(crate) fn kinematics(&self, theta: f64, omega: f64) -> Kinematics {
        let (s, c) = self.sin_cos(theta);
        self.rolling.kinematics_sc(theta, omega, s, c)
    }
}

impl OdeSystem<2> for RollingMemo {
    #[inline]
    fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
        let (s, c) = self.sin_cos(y[0]);
        State::<2>::new(y[1], self.rolling.omega_dot_sc(s, c, y[1]))
    }
}

/// The rolling system and its events sharing one [`RollingMemo`].
struct Memo<'a> {
    events: &'a RollEvents,
    sys: RollingMemo,
}

impl Memo<'_> {
    #[inline]
    fn kinematics(&self, theta: f64, omega: f64) -> Kinematics {
        self.sys.kinematics(theta, omega)
    }
}

impl OdeSystem<2> for Memo<'_> {
    #[inline]
    fn rhs(&self, t: f64, y: &State<2>) -> State<2> {
        self.sys.rhs(t, y)
    }
}

impl EventFunctions<2> for Memo<'_> {
    #[inline]
    fn count(&self) -> usize {
        self.events.count()
    }
    #[inline]
    fn spec(&self, k: usize) -> EventSpec {
        self.events.spec(k)
    }
    #[inline]
    fn value(&self, k: usize, t: f64, y: &State<2>) -> f64 {
        self.events.value(k, t, y)
    }
    #[inline]
    fn values(&self, first: usize, _t: f64, y: &State<2>, out: &mut [f64]) {
        self.events
            .values_from(&self.kinematics(y[0], y[1]), first, y, out);
    }
    /// [`RollEvents::change_bounds_all`] tightened by the memo's trigonometry.
    #[inline]
    fn change_bounds(&self, first: usize, dense: &DenseStep<2>, out: &mut [f64]) {
        let b = self
            .events
            .change_bounds_near(dense, Some(self.sys.anchor()));
        for (i, o) in out.iter_mut().enumerate() {
            *o = b[first + i];
        }
    }
}

/// The inputs of a rolling run besides the body and ramp.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollOptions {
    pub theta0: f64,
    pub omega0: f64,
    pub mu_s: Option<f64>,
    pub t_max: f64,
    pub theta_max: f64,
    pub rule: Rule,
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
        check_range("theta0", self.theta0, -big, big)?;
        check_range("omega0", self.omega0, -big, big)?;
        if let Some(mu) = self.mu_s {
            check_range("mu_s", mu, 0.0, big)?;
        }
        check_positive("t_max", self.t_max)?;
        if self.theta_max.is_nan() || self.theta_max <= self.theta0 {
            return Err(Error::InvalidParameter {
                name: "theta_max",
                value: self.theta_max,
                allowed: format!("(theta0, inf] = ({}, inf]", self.theta0),
            });
        }
        check_range("rtol", self.solver.rtol, 1e-15, 1.0)?;
        check_positive("atol", self.solver.atol)?;
        if self.solver.max_steps == 0 {
            return Err(Error::InvalidParameter {
                name: "max_steps",
                value: 0.0,
                allowed: "[1, inf)".to_string(),
            });
        }
        Ok(())
    }
}

/// One event met during the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventHit {
    pub event: RollEvent,
    pub t: f64,
    pub theta: f64,
    pub omega: f64,
}

/// How a run ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum RollStatus {
    /// t reached t_max without a terminal event.
    TimeLimit,
    /// A terminal event ended the run.
    Event(RollEvent),
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
    pub t: Vec<f64>,
    pub theta: Vec<f64>,
    pub omega: Vec<f64>,
    /// θ̈, F_x and F_y at each recorded point ([`Rolling::kinematics`]).
    pub omega_dot: Vec<f64>,
    pub fx: Vec<f64>,
    pub fy: Vec<f64>,
    pub events: Vec<EventHit>,
    pub status: RollStatus,
    pub nfev: usize,
    pub dense: Vec<DenseStep<2>>,
}

/// Points reserved per recorded array up front: a run to lift-off at the default
/// tolerances takes about a hundred steps; longer runs grow the arrays by doubling.
const RESERVE: usize = 256;

impl RollRun {
    /// Records one point with its kinematics.
    #[inline]
    fn push(&mut self, t: f64, k: &Kinematics) {
        self.t.push(t);
        self.theta.push(k.theta);
        self.omega.push(k.omega);
        self.omega_dot.push(k.omega_dot);
        self.fx.push(k.fx);
        self.fy.push(k.fy);
    }

    #[inline]
    fn pop(&mut self) {
        self.t.pop();
        self.theta.pop();
        self.omega.pop();
        self.omega_dot.pop();
        self.fx.pop();
        self.fy.pop();
    }
}

/// Integrates pure rolling from (θ0, θ̇0) until a terminal event, t_max or θ_max.
pub fn roll(rolling: &Rolling, opts: &RollOptions) -> Result<RollRun> {
    opts.validate()?;
    let events = RollEvents {
        rolling: *rolling,
        mu_s: opts.mu_s,
        theta_max: opts.theta_max,
        rule: opts.rule,
    };
    let memo = Memo {
        events: &events,
        sys: RollingMemo::new(*rolling),
    };
    let capacity = RESERVE.min(opts.solver.max_steps.saturating_add(2));
    let mut run = RollRun {
        t: Vec::with_capacity(capacity),
        theta: Vec::with_capacity(capacity),
        omega: Vec::with_capacity(capacity),
        omega_dot: Vec::with_capacity(capacity),
        fx: Vec::with_capacity(capacity),
        fy: Vec::with_capacity(capacity),
        events: Vec::new(),
        status: RollStatus::TimeLimit,
        nfev: 0,
        dense: Vec::with_capacity(if opts.dense_output { capacity } else { 0 }),
    };
    run.push(0.0, &memo.kinematics(opts.theta0, opts.omega0));
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
        return Ok(run);
    }
    let y0 = State::<2>::new(opts.theta0, opts.omega0);
    let outcome = ode::solve(
        &memo,
        &memo,
        0.0,
        y0,
        opts.t_max,
        &opts.solver,
        &mut |obs: Observation<'_, 2>| match obs {
            Observation::Step { dense, t, y } => {
                run.push(t, &memo.kinematics(y[0], y[1]));
                if opts.dense_output {
                    run.dense.push(*dense);
                }
            }
            Observation::Event { index, t, y } => run.events.push(EventHit {
                event: RollEvent::ALL[index],
                t,
                theta: y[0],
                omega: y[1],
            }),
        },
    );
    run.nfev = outcome.nfev;
    run.status = match outcome.status {
        Status::Finished => RollStatus::TimeLimit,
        Status::Event(k) => RollStatus::Event(RollEvent::ALL[k]),
        other => RollStatus::Failed(other),
    };
    // The last accepted step ends past a terminal event: end the record at the event.
    if let Status::Event(_) = outcome.status {
        while run.t.len() > 1 && run.t.last().is_some_and(|&t| t > outcome.t) {
            run.pop();
        }
        if run.t.last().is_some_and(|&t| t < outcome.t) {
            run.push(outcome.t, &memo.kinematics(outcome.y[0], outcome.y[1]));
        }
    }
    Ok(run)
}

/// The terminal event whose condition is already met at the start, if any.
fn violated_at_start(events: &RollEvents, theta: f64, omega: f64) -> Option<RollEvent> {
    RollEvent::ALL.into_iter().find(|&e| {
        let g = events.value_at(e, theta, omega);
        let outside = match e {
            RollEvent::Liftoff | RollEvent::ThetaLimit => g > 0.0,
            // Contact needs a strictly positive normal force (on a vertical ramp at rest
            // F_y = 0: the body is not pressed onto the ramp at all).
            RollEvent::NormalForceZero => g <= 0.0,
            RollEvent::Slip => g < 0.0,
        };
        // θ_max is validated to lie above θ0, so it never fires here.
        events.is_terminal(e) && outside
    })
}

#[cfg(test)]
mod skip_tests {
    use super::*;
    use crate::body::Cylinder;

    /// The roll events without change bounds: the scan always walks the interior samples.
    struct NoSkip(RollEvents);

    impl EventFunctions<2> for NoSkip {
        fn count(&self) -> usize {
            self.0.count()
        }
        fn spec(&self, k: usize) -> EventSpec {
            self.0.spec(k)
        }
        fn value(&self, k: usize, t: f64, y: &State<2>) -> f64 {
            self.0.value(k, t, y)
        }
        fn values(&self, first: usize, t: f64, y: &State<2>, out: &mut [f64]) {
            self.0.values(first, t, y, out)
        }
    }

    fn cases() -> Vec<(Rolling, RollEvents)> {
        let mut out = Vec::new();
        for &(chi, km, alpha_deg, mu_s, rule, theta_max) in &[
            (0.15, 0.02, 40.0, None, Rule::Paper, f64::INFINITY),
            (0.5, 0.1, 20.0, Some(0.4), Rule::NormalForce, f64::INFINITY),
            (0.9, 0.1, 60.0, None, Rule::NormalForce, 40.0),
            (0.3, 0.3, 5.0, Some(2.0), Rule::Paper, 7.0),
        ] {
            let r =
                Rolling::new(Cylinder::new(chi, km).unwrap(), f64::to_radians(alpha_deg)).unwrap();
            let ev = RollEvents {
                rolling: r,
                mu_s,
                theta_max,
                rule,
            };
            out.push((r, ev));
        }
        out
    }

    #[test]
    fn skipping_interior_samples_changes_nothing() {
        let opts = SolverOptions::default();
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
                &NoSkip(ev),
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
        let opts = SolverOptions::default();
        for (r, ev) in cases() {
            let mut steps = 0;
            ode::solve(&r, &ev, 0.0, State::<2>::zeros(), 50.0, &opts, &mut |o| {
                if let Observation::Step { dense, .. } = o {
                    steps += 1;
                    let g = |t: f64| {
                        let mut v = [0.0; 4];
                        ev.values(0, t, &dense.eval(t), &mut v);
                        v
                    };
                    let g0 = g(dense.t_old);
                    // Plain, and anchored at the step's start and end (as `Memo` does).
                    let (th0, th1) = (dense.y_old[0], dense.eval(dense.t_old + dense.h)[0]);
                    for anchor in [
                        None,
                        Some((th0, th0.sin(), th0.cos())),
                        Some((th1, th1.sin(), th1.cos())),
                    ] {
                        let bound = ev.change_bounds_near(dense, anchor);
                        for i in 1..=64 {
                            let gi = g(dense.t_old + dense.h * (i as f64 / 64.0));
                            for k in 0..4 {
                                assert!((gi[k] - g0[k]).abs() <= bound[k], "event {k}");
                            }
                        }
                    }
                }
            });
            assert!(steps > 5);
        }
    }
}

//! The outcome of a JARM classification, shared by both routes: the reasons, the options
//! and the per-point result.

use crate::error::{check_range, Result};
use crate::mechanics::Rule;
use crate::ode::SolverOptions;

named_enum! {
    /// Why a point is or is not a JARM. `#[repr(u8)]` with stable values (the bridge exports them).
    #[repr(u8)]
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Reason {
        /// 0: jump after pure rolling.
        Jarm = 0 => "jarm",
        /// 1: no lift-off (on the requested turn n, or ever: α = 0, χ = 0, or the path passes turn
        /// n without event).
        NoRoot = 1 => "no_root",
        /// 2: the lift-off rule held earlier: on an earlier turn than the requested n, or at the
        /// start itself (e.g. α = π/2 from rest, where F_y = 0 at θ0).
        LiftoffEarlier = 2 => "liftoff_earlier",
        /// 3: the normal force reached 0 before lift-off (or F_y,J ≤ 0 at it).
        NormalForceLost = 3 => "normal_force_lost",
        /// 4: the rolling branch needs more than μ_s of friction before lift-off (and the paper's
        /// jump-point test ineq2 alone would not have caught it), or slip is consistent there under
        /// the `NormalForce` rule.
        SlipBefore = 4 => "slip_before",
        /// 5: friction fails on the final approach: the paper's lift-off point that follows is in
        /// the green window but needs μ(θ_J) > μ_s (Eq. ineq2 fails). Paper rule only.
        SlipAtJump = 5 => "slip_at_jump",
        /// 6: θ̇² returns to 0 before any event: the body stops and rolls back (not possible from
        /// rest at θ0 = 0 with α > 0; see `from_rest::rock_back_angle`).
        RocksBack = 6 => "rocks_back",
        /// 7: nothing happened within `max_turns` turns and n* > `max_turns`.
        TurnLimit = 7 => "turn_limit",
        /// 8: a parameter is NaN or out of range.
        InvalidParams = 8 => "invalid_params",
        /// 9: the integrator of the ODE route failed (step too small, non-finite values, step
        /// budget): no physical verdict.
        SolverFailed = 9 => "solver_failed",
        /// 10: friction fails before the paper's lift-off, and the search stopped there
        /// (`JarmOptions::stop_at_slip`): `SlipBefore` or `SlipAtJump`, not told apart.
        /// Paper rule only.
        Slip = 10 => "slip",
    }
}

impl Reason {
    /// The numeric code.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// The reason for a code, if valid.
    pub fn from_code(code: u8) -> Option<Reason> {
        Reason::ALL.get(code as usize).copied()
    }
}

/// Options of a classification.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JarmOptions {
    /// The lift-off rule.
    pub rule: Rule,
    /// Required turn n ≥ 1, or 0 for automatic (the first jump, whatever its turn).
    pub n: u32,
    /// Turn cap of the search.
    pub max_turns: u32,
    /// Initial angle θ0 (default 0).
    pub theta0: f64,
    /// Initial angular velocity θ̇0 ≥ 0 (default: rest).
    pub omega0: f64,
    /// Refine the reported path extrema (max friction ratio, min F_y) to full precision
    /// (default); if false they are cell estimates (relative error ~1e-4) and the map is
    /// faster. The classification itself does not depend on it.
    pub refine_extrema: bool,
    /// Paper rule: stop at the first slip and report `Slip`, instead of following rolling
    /// on to the paper's lift-off to tell `SlipAtJump` from `SlipBefore` (default false).
    /// `is_jarm` and every other reason are the same; maps where most points slip are
    /// faster. No effect under the `NormalForce` rule, which decides at the slip itself.
    pub stop_at_slip: bool,
}

impl Default for JarmOptions {
    fn default() -> Self {
        Self {
            rule: Rule::Paper,
            n: 0,
            max_turns: 10_000,
            theta0: 0.0,
            omega0: 0.0,
            refine_extrema: true,
            stop_at_slip: false,
        }
    }
}

/// The classification of one point. Angles in radians (absolute θ); NaN where not applicable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JarmResult {
    /// Whether the point is a JARM (`reason == Reason::Jarm`).
    pub is_jarm: bool,
    /// Why it is or is not a JARM.
    pub reason: Reason,
    /// Turn of the jump (JARM), of the earlier lift-off (LiftoffEarlier) or of the event
    /// that decided (others); 0 if none.
    pub n: u32,
    /// Lift-off angle: the JARM's, the earlier one (LiftoffEarlier), or the paper's root
    /// after a friction failure (SlipAtJump); NaN otherwise.
    pub theta_j: f64,
    /// Where the deciding failure happened (NaN for a JARM).
    pub theta_event: f64,
    /// F_x at the jump (JARM only; NaN otherwise).
    pub fx_j: f64,
    /// F_y at the jump (JARM only; NaN otherwise).
    pub fy_j: f64,
    /// The largest |F_x|/F_y on the rolling path [θ0, θ_event or θ_J].
    pub max_ratio: f64,
    /// Where `max_ratio` is reached.
    pub theta_max_ratio: f64,
    /// The smallest F_y on the rolling path [θ0, θ_event or θ_J].
    pub min_fy: f64,
    /// Where `min_fy` is reached.
    pub theta_min_fy: f64,
}

impl JarmResult {
    /// Every field as f64 (reason, n and is_jarm as numbers), to compare or digest results
    /// bit for bit.
    pub fn as_f64s(&self) -> [f64; 11] {
        [
            self.reason as u8 as f64,
            self.n as f64,
            self.is_jarm as u8 as f64,
            self.theta_j,
            self.theta_event,
            self.fx_j,
            self.fy_j,
            self.max_ratio,
            self.theta_max_ratio,
            self.min_fy,
            self.theta_min_fy,
        ]
    }

    /// A result with `reason`, no turn (0) and every angle and force NaN.
    pub fn new(reason: Reason) -> Self {
        Self {
            is_jarm: reason == Reason::Jarm,
            reason,
            n: 0,
            theta_j: f64::NAN,
            theta_event: f64::NAN,
            fx_j: f64::NAN,
            fy_j: f64::NAN,
            max_ratio: f64::NAN,
            theta_max_ratio: f64::NAN,
            min_fy: f64::NAN,
            theta_min_fy: f64::NAN,
        }
    }
}

/// The largest turn cap of a search: every point's work is bounded by it (about a second
/// for the slowest point at this cap).
pub const MAX_TURNS: u32 = 1_000_000;

pub use crate::mechanics::{MAX_OMEGA0, MAX_THETA0};

impl JarmOptions {
    /// Checks the options that apply to a whole call, naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        crate::error::check_count("max_turns", self.max_turns as usize, 1, MAX_TURNS as usize)?;
        check_range("theta0", self.theta0, -MAX_THETA0, MAX_THETA0)?;
        check_range("omega0", self.omega0, 0.0, MAX_OMEGA0)?;
        Ok(())
    }
}

/// The route that classifies a point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Method {
    /// The paper's closed forms with a rigorous path scan ([`fn@crate::jarm::classify`]).
    #[default]
    ClosedForm,
    /// Integration of the rolling equation with events ([`crate::jarm::classify_ode`]).
    Ode {
        /// Relative tolerance, in [1e-15, 1].
        rtol: f64,
        /// Absolute tolerance, > 0.
        atol: f64,
        /// The Runge–Kutta pair.
        pair: crate::ode::Integrator,
    },
}

impl Method {
    /// The route named `name` ("closed_form" or "ode", the latter with its tolerances and
    /// pair).
    pub fn from_name(
        name: &str,
        rtol: f64,
        atol: f64,
        pair: crate::ode::Integrator,
    ) -> Option<Method> {
        match name {
            "closed_form" => Some(Method::ClosedForm),
            "ode" => Some(Method::Ode { rtol, atol, pair }),
            _ => None,
        }
    }

    /// Checks the tolerances of the ODE route.
    pub fn validate(&self) -> Result<()> {
        if let Method::Ode { rtol, atol, .. } = *self {
            SolverOptions::check_tolerances(rtol, atol)?;
        }
        Ok(())
    }
}

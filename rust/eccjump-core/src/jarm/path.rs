//! The rigorous path conditions along pure rolling (Sec. 3.2, Eqs. extraineqcondition1/2).
//!
//! Along pure rolling from (θ0, θ̇0), energy conservation gives θ̇² = w(θ) = 2E(θ)/Ĩ_P(θ) with
//! E(θ) = ½Ĩ_P(θ0)θ̇0² + (θ − θ0) sin α + χ[cos(α + θ0) − cos(α + θ)] and Ĩ_P = Ĩ_C + 1 + 2χ cos θ.
//! With a = θ̈ (roll-eq) and w' = dθ̇²/dθ = 2a, differentiating roll-eq along the path gives
//!
//!   a' = χ (4 a sin θ + w cos θ + cos(α + θ))/Ĩ_P,
//!   F_x  = −sin α − χ w sin θ + (1 + χ cos θ) a,   F_x' = −3χ a sin θ − χ w cos θ + (1 + χ cos θ) a',
//!   F_y  =  cos α − χ w cos θ − χ a sin θ,          F_y' = −3χ a cos θ + χ w sin θ − χ a' sin θ,
//!   L    =  χ w cos θ − cos α,                       L'   = 2χ a cos θ − χ w sin θ,
//!   E'   =  sin α + χ sin(α + θ).
//!
//! The constraints are tracked as functions g that must stay positive: F_y (> 0), the two
//! smooth friction margins M± = μ_s F_y ∓ F_x (≥ 0; together ⇔ μ_s F_y − |F_x| ≥ 0, tested as a
//! margin, never as a ratio), −L (< 0 until the paper's lift-off) and E (> 0, else the body
//! stops and rocks back). "A thin violation between sample points must not be missed": the
//! functions and their analytic derivatives are sampled on a grid of ≤ 2π/24 (`SAMPLES_PER_TURN`; finer where
//! Ĩ_P is small: step ≤ ¼√(Ĩ_P/χ), the width of the near-singular peak at θ = π for χ → 1,
//! k_m → 0); a violation inside a cell needs an interior minimum, i.e. a sign change − → + of
//! g' on the cell; its value is estimated by the cubic Hermite interpolant, and unless that is
//! clearly positive (> 10 % of the smaller end value) the minimum is located by Brent on g'
//! and checked; crossings are refined by Brent. The assumption is only that g' changes sign
//! at most once per cell, which the grid guarantees for these trig polynomials over Ĩ_P^k.
//!
//! The evaluation uses one `sin_cos` of (θ − θ0)/2 per point, no heap allocation.

use crate::mechanics::energy::rolling_kinetic;
use crate::mechanics::friction::friction_ratio;
use crate::mechanics::liftoff::{free_normal_acceleration, liftoff_slope};
use crate::mechanics::Ramp;
pub use crate::modes::rolling::events::ContactEvent;
use crate::modes::rolling::events::{liftoff_at_start, violated_at_start, StartValues, Watched};
use crate::modes::rolling::{force_slopes, forces, torque, torque_slope};
use crate::ode::hermite::{hermite_min, hermite_root};
use crate::ode::roots::{brent, newton_bracketed};
use std::f64::consts::{FRAC_PI_2, TAU};

/// Samples per turn of the scanning grid.
pub const SAMPLES_PER_TURN: f64 = 24.0;

// Indices of the tracked constraint functions.
/// Index of g = F_y (normal force, must stay > 0).
pub const G_FY: usize = 0;
/// Index of g = M+ = μ_s F_y − F_x (friction margin, must stay ≥ 0).
pub const G_MPLUS: usize = 1;
/// Index of g = M− = μ_s F_y + F_x (friction margin, must stay ≥ 0).
pub const G_MMINUS: usize = 2;
/// Index of g = −L (no lift-off yet while > 0).
pub const G_NOLIFT: usize = 3;
/// Index of g = E, the kinetic energy ½Ĩ_P θ̇² (must stay > 0).
pub const G_ENERGY: usize = 4;
const NG: usize = 5;

/// Uniform scan steps between direct `sin_cos` evaluations (the others rotate the previous
/// half-angle sin/cos, re-anchored every ROTATIONS + 1 samples): ≤ 1.2e-15 absolute error,
/// about the rounding of θ itself beyond one turn (ulp(2π) = 8.9e-16). Seven rotations
/// halve the direct calls of three (2–3 % of a map) for 0.6e-15 more.
const ROTATIONS: u32 = 7;

/// Everything along the rolling path at one θ.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathPoint {
    /// The angle θ (rad).
    pub theta: f64,
    /// sin θ.
    pub sin_t: f64,
    /// cos θ.
    pub cos_t: f64,
    /// θ̇² (2E/Ĩ_P).
    pub omega_sq: f64,
    /// θ̈.
    pub omega_dot: f64,
    /// Contact force F_x (along the ramp).
    pub fx: f64,
    /// Contact force F_y (normal to the ramp).
    pub fy: f64,
    /// dF_x/dθ along the path.
    pub dfx: f64,
    /// dF_y/dθ along the path.
    pub dfy: f64,
    /// The lift-off function χθ̇² cos θ − cos α.
    pub lift: f64,
    /// `g[k]` for the constraint functions (see the `G_*` indices).
    pub g: [f64; NG],
    /// `dg[k]`/dθ for the constraint functions.
    pub dg: [f64; NG],
}

impl PathPoint {
    /// |F_x|/F_y, +∞ where F_y ≤ 0.
    #[inline]
    pub fn ratio(&self) -> f64 {
        friction_ratio(self.fx, self.fy)
    }

    /// Sign test of d(|F_x|/F_y)/dθ > 0 without division (F_y > 0 assumed).
    #[inline]
    fn ratio_rising(&self) -> bool {
        self.fx.signum() * self.dfx * self.fy - self.fx.abs() * self.dfy > 0.0
    }

    #[inline]
    fn ratio_derivative(&self) -> f64 {
        (self.fx.signum() * self.dfx * self.fy - self.fx.abs() * self.dfy) / (self.fy * self.fy)
    }
}

/// The precomputed rolling path from (θ0, θ̇0) with static friction μ_s.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct RollingPath {
    ramp: Ramp,
    chi: f64,
    sin_a: f64,
    cos_a: f64,
    theta0: f64,
    s0: f64,
    c0: f64,
    sa0: f64,
    ca0: f64,
    k0: f64,
    mu_s: f64,
    /// Ĩ_P at or above which the grid step is certainly the uniform 2π/24 ([`Self::step`]).
    ip_uniform: f64,
}

/// The outcome of a scan along the rolling path.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct PathScan {
    /// The event that stopped the scan (`End` if none).
    pub event: ContactEvent,
    /// The state where the scan stopped (the event, or the end).
    pub at: PathPoint,
    /// The largest |F_x|/F_y on [θ0, θ_event] (∞ if F_y reached 0).
    pub max_ratio: f64,
    /// Where `max_ratio` is reached (rad).
    pub theta_max_ratio: f64,
    /// The smallest F_y on [θ0, θ_event].
    pub min_fy: f64,
    /// Where `min_fy` is reached (rad).
    pub theta_min_fy: f64,
    /// Function evaluations used (a cost measure).
    pub evaluations: u32,
}

/// Which constraints a scan watches.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Watch {
    /// Watch F_y > 0.
    pub normal_force: bool,
    /// Watch the two friction margins M± ≥ 0.
    pub friction: bool,
    /// Watch the paper's lift-off (L reaching 0 from below).
    pub liftoff: bool,
    /// Refine the reported extrema (max friction ratio, min F_y) to full precision by Brent on
    /// their derivative; otherwise they are the best sample or cubic-Hermite cell estimate
    /// (relative error ~1e-4). Costs ~2 × 10 evaluations per scan.
    pub refine_extrema: bool,
    /// Grid step multiplier (1 = the rigorous grid). Only for cheap auxiliary scans of the
    /// smooth lift-off function (e.g. to name a failure reason), never for the path checks.
    pub coarseness: u8,
}

impl Watch {
    /// Every constraint, refined extrema, the rigorous grid.
    pub const ALL: Watch = Watch {
        normal_force: true,
        friction: true,
        liftoff: true,
        refine_extrema: true,
        coarseness: 1,
    };

    /// The paper's lift-off alone (and the body stopping, always watched), no extrema, on a
    /// grid `coarseness` times the rigorous one: what the lift-off search after a slip watches.
    pub const fn liftoff_only(coarseness: u8) -> Watch {
        Watch {
            normal_force: false,
            friction: false,
            liftoff: true,
            refine_extrema: false,
            coarseness,
        }
    }

    #[inline]
    fn active(&self, k: usize) -> bool {
        match k {
            G_FY => self.normal_force,
            G_MPLUS | G_MMINUS => self.friction,
            G_NOLIFT => self.liftoff,
            _ => true, // the body stopping is always watched
        }
    }
}

/// Violation test; NaN counts as a violation (never silently passes). Margins may touch 0.
#[inline]
fn violated(k: usize, g: f64) -> bool {
    if k == G_MPLUS || k == G_MMINUS {
        g.is_nan() || g < 0.0
    } else {
        g.is_nan() || g <= 0.0
    }
}

/// (sin(h/2), 1 − cos(h/2)) for the rotation of half-angles by h/2 in the increment form
/// s' = s + (c sin − s (1 − cos)), c' = c − (s sin + c (1 − cos)): ~½ ulp per step.
#[inline]
fn rotation(h: f64) -> (f64, f64) {
    let (s4, c4) = crate::trig::sin_cos(0.25 * h);
    (2.0 * s4 * c4, 2.0 * s4 * s4)
}

/// True if g_k certainly stays unviolated on the cell [a, b] by the tests of
/// `first_violation` (not violated at b, and no interior minimum, or one whose cubic-Hermite
/// estimate is clearly positive: > 10 % of the smaller end value).
#[inline(always)]
fn clear(k: usize, a: &PathPoint, b: &PathPoint) -> bool {
    clear_values(k, a.g[k], a.dg[k], b.g[k], b.dg[k], b.theta - a.theta)
}

/// [`clear`] from g_k and g_k' at the ends of a cell of width h.
#[inline(always)]
fn clear_values(k: usize, ga: f64, da: f64, gb: f64, db: f64, h: f64) -> bool {
    if violated(k, gb) {
        return false;
    }
    if da < 0.0 && db > 0.0 {
        let (_, est) = hermite_min(ga, h * da, gb, h * db);
        est > 0.1 * ga.min(gb)
    } else {
        true
    }
}

/// The running extremum of a tracked quantity (for reporting): the best sample, and the cell
/// whose interior extremum (Hermite estimate) is best, refined at the end, with the runner-up
/// cell, refined too when the two estimates are a near tie.
#[derive(Clone, Copy)]
struct Extremum {
    value: f64,
    theta: f64,
    cell_est: f64,
    cell_theta: f64,
    cell: Option<(f64, f64)>,
    /// A bound on the error of `cell_est` (see [`Extremum::offer`]).
    cell_err: f64,
    runner_est: f64,
    runner: Option<(f64, f64)>,
    runner_err: f64,
    /// +1 for a running minimum, −1 for a maximum.
    sense: f64,
}

/// Cell estimates closer than this (relative) are a near tie: the Hermite estimate's error
/// (~1e-3 relative on the 2π/24 grid) could order them wrongly, e.g. the minima of F_y on
/// successive turns, which differ by little at small α.
const NEAR_TIE: f64 = 0.05;

impl Extremum {
    fn start(value: f64, theta: f64, worst: f64) -> Self {
        Self {
            value,
            theta,
            cell_est: worst,
            cell_theta: f64::NAN,
            cell: None,
            cell_err: 0.0,
            runner_est: worst,
            runner: None,
            runner_err: 0.0,
            sense: worst.signum(),
        }
    }

    /// A cell [lo, hi] whose interior extremum is estimated at `est` (at θ = `at`); the
    /// earlier cell wins ties. The runner-up kept is the latest cell
    /// in a near tie with the best: a cell cut short by the event has a more accurate
    /// estimate than the full cells before it, whose errors share a sign.
    ///
    /// `spread` is the cell's scale of variation, |g_b − g_a| + h(|g_a'| + |g_b'|). The
    /// Hermite estimate of an extremum errs by ~h⁴|g''''|/384 against a spread ~h²|g''|, i.e.
    /// by ≲ (k h)²/384 ≈ 2e-3 of the spread for the few harmonics k ≤ 3 of these functions on
    /// the grid (finer where Ĩ_P is small); NEAR_TIE × spread bounds it with a wide margin.
    #[inline]
    fn offer(&mut self, est: f64, at: f64, cell: (f64, f64), spread: f64) {
        let err = NEAR_TIE * spread;
        if self.sense * (est - self.cell_est) < 0.0 {
            if self.cell.is_some() {
                (self.runner, self.runner_est, self.runner_err) =
                    (self.cell, self.cell_est, self.cell_err);
            }
            (self.cell, self.cell_est, self.cell_theta, self.cell_err) = (Some(cell), est, at, err);
        } else {
            (self.runner, self.runner_est, self.runner_err) = (Some(cell), est, err);
        }
    }

    /// True if a cell estimated at `est` (error ≤ `err`) could beat the best sample.
    #[inline]
    fn could_beat(&self, est: f64, err: f64) -> bool {
        self.sense * (est - self.value) < err
    }

    /// The cells to refine, in θ order: the best, and the runner-up if it is a near tie;
    /// a cell whose estimate cannot beat the best sample by its error bound is left out (its
    /// refinement would not change the result).
    fn cells_to_refine(&self) -> [Option<(f64, f64)>; 2] {
        let best = self
            .cell
            .filter(|_| self.could_beat(self.cell_est, self.cell_err));
        let runner = self.runner.filter(|_| {
            (self.runner_est - self.cell_est).abs() <= NEAR_TIE * self.cell_est.abs()
                && self.could_beat(self.runner_est, self.runner_err)
        });
        match (best, runner) {
            (Some(c), Some(r)) if r.0 < c.0 => [Some(r), Some(c)],
            // Both in θ order, or the one that is left first.
            (c, r) => [c.or(r), c.and(r)],
        }
    }
}

impl Extremum {
    /// A sample value for a running minimum (the earlier sample wins ties).
    #[inline]
    fn sample(&mut self, value: f64, theta: f64) {
        if value < self.value {
            (self.value, self.theta) = (value, theta);
        }
    }

    /// A sample value for a running maximum (the earlier sample wins ties).
    #[inline]
    fn sample_max(&mut self, value: f64, theta: f64) {
        if value > self.value {
            (self.value, self.theta) = (value, theta);
        }
    }
}

/// Scans spanning at least this many turns try to skip turns ([`RollingPath::skip_turns`]).
const SKIP_MIN_TURNS: f64 = 6.0;
/// The turn whose samples estimate how many turns stay clean (turn 1 is the start's).
const SKIP_RECORD_TURN: f64 = 2.0;
/// The scan restarts this many turns, plus this share of the estimated clean turns, before
/// the first turn estimated to violate (samples miss the minima between them).
const SKIP_MARGIN_TURNS: f64 = 1.0;
const SKIP_MARGIN_SHARE: f64 = 0.1;

/// What a scan watches and how it steps, fixed for one scan.
struct Grid {
    act: [bool; NG],
    theta_end: f64,
    coarseness: f64,
    /// The rigorous grid (coarseness 1): only its scans skip turns.
    rigorous: bool,
    /// The uniform step: [`RollingPath::step`] away from the singular peak, times the
    /// coarseness.
    h_uni: f64,
    /// [`rotation`] of `h_uni`.
    sh: f64,
    vh: f64,
    /// A generous cap on cells (the floor step keeps progress finite anyway).
    max_cells: u64,
}

impl Grid {
    fn new(theta_start: f64, theta_end: f64, watch: Watch) -> Self {
        let c = watch.coarseness.max(1);
        let coarseness = c as f64;
        let h_uni = TAU / SAMPLES_PER_TURN * coarseness;
        // The rotations of the two grids in use are computed once per process.
        static ROTATIONS_1_3: std::sync::LazyLock<[(f64, f64); 2]> =
            std::sync::LazyLock::new(|| [1.0, 3.0].map(|c| rotation(TAU / SAMPLES_PER_TURN * c)));
        let (sh, vh) = match c {
            1 => ROTATIONS_1_3[0],
            3 => ROTATIONS_1_3[1],
            _ => rotation(h_uni),
        };
        Self {
            act: [0, 1, 2, 3, 4].map(|k| watch.active(k)),
            theta_end,
            coarseness,
            rigorous: c == 1,
            h_uni,
            sh,
            vh,
            max_cells: ((theta_end - theta_start) / (TAU / SAMPLES_PER_TURN) * 64.0 + 1e5) as u64,
        }
    }
}

/// A scan's state between cells: the cell start, the half-angle sin/cos of its sample
/// (advanced by rotation on uniform steps), the running extrema and the cost so far.
#[derive(Clone, Copy)]
struct Cursor {
    /// Two slots for the cell ends, used alternately (no copy of the points); `ia` is the
    /// cell start.
    pts: [PathPoint; 2],
    ia: usize,
    su: f64,
    cu: f64,
    rotated: u32,
    cells: u64,
    evals: u32,
    min_fy: Extremum,
    max_r: Extremum,
}

impl Cursor {
    /// A cursor at `p0`, whose half-angle sin/cos are (su, cu).
    fn start(p0: PathPoint, (su, cu): (f64, f64), min_fy: Extremum, max_r: Extremum) -> Self {
        Self {
            pts: [p0, p0],
            ia: 0,
            su,
            cu,
            rotated: 0,
            cells: 0,
            evals: 1,
            min_fy,
            max_r,
        }
    }
}

/// The rolling state at one θ ([`RollingPath::state_half`]).
struct State {
    s: f64,
    c: f64,
    /// The kinetic energy E.
    e: f64,
    sin_at: f64,
    cos_at: f64,
    /// 1/Ĩ_P.
    inv_ip: f64,
    /// θ̇².
    w: f64,
    /// χθ̇².
    chi_w2: f64,
    /// θ̈.
    acc: f64,
}

/// What the lift-off scan of one window found ([`RollingPath::window_liftoff`]).
#[derive(Debug, Clone, Copy, PartialEq)]
enum WindowLift {
    /// No lift-off in the window.
    Clean,
    /// The first lift-off, located.
    At(f64),
    /// A lift-off in a cell whose exact angle does not matter to the caller.
    Within,
}

/// The order in which simultaneous events are resolved (the shared catalogue's): lift-off,
/// normal force, friction, energy.
const TIE_ORDER: [usize; NG] = [G_NOLIFT, G_FY, G_MPLUS, G_MMINUS, G_ENERGY];

/// The position of constraint k in [`TIE_ORDER`].
#[inline]
fn tie_rank(k: usize) -> usize {
    TIE_ORDER.iter().position(|&o| o == k).unwrap_or(NG)
}

/// Why [`RollingPath::advance`] returned.
enum Stop {
    /// A watched constraint is violated at this point (the first one on the path).
    Event(ContactEvent, PathPoint),
    /// The scan reached its end (or its cell cap) with no event.
    End,
    /// A cell ended at or after the requested angle, with no event.
    Reached,
}

impl RollingPath {
    /// A path on the ramp `r` from (θ0, θ̇0); μ_s is used by the friction margins.
    pub fn new(r: &Ramp, theta0: f64, omega0: f64, mu_s: f64) -> Self {
        let (s0, c0) = crate::trig::sin_cos(theta0);
        let (sa0, ca0) = r.shifted(s0, c0);
        let k0 = 0.5 * r.contact_inertia(c0) * omega0 * omega0;
        // ¼√(Ĩ_P/χ) ≥ h_max ⇔ Ĩ_P ≥ 16 h_max² χ; the factor 1 + 1e-12 absorbs the rounding of
        // both sides, so Ĩ_P ≥ ip_uniform gives the step the square root would give, bit for bit.
        let hmax = TAU / SAMPLES_PER_TURN;
        let ip_uniform = 16.0 * hmax * hmax * r.body.chi * (1.0 + 1e-12);
        Self {
            ramp: *r,
            chi: r.body.chi,
            sin_a: r.sin_a,
            cos_a: r.cos_a,
            theta0,
            s0,
            c0,
            sa0,
            ca0,
            k0,
            mu_s,
            ip_uniform,
        }
    }

    /// θ0 of the path.
    pub fn theta0(&self) -> f64 {
        self.theta0
    }

    /// The available kinetic energy E(θ) at θ (θ̇² = 2E/Ĩ_P).
    #[inline]
    pub fn energy(&self, theta: f64) -> f64 {
        let u = 0.5 * (theta - self.theta0);
        let (su, cu) = crate::trig::sin_cos(u);
        let sin_mid = self.sa0 * cu + self.ca0 * su;
        rolling_kinetic(
            self.k0,
            theta - self.theta0,
            self.sin_a,
            self.chi,
            sin_mid,
            su,
        )
    }

    /// All path quantities at the start θ0 (no `sin_cos`: the half angle is 0).
    #[inline]
    pub fn start(&self) -> PathPoint {
        self.eval_half(self.theta0, 0.0, 1.0)
    }

    /// All path quantities at θ: one `sin_cos`, no allocation.
    #[inline]
    pub fn eval(&self, theta: f64) -> PathPoint {
        let (su, cu) = crate::trig::sin_cos(0.5 * (theta - self.theta0));
        self.eval_half(theta, su, cu)
    }

    /// The rolling state at θ given (su, cu) = sin_cos((θ − θ0)/2): what every path quantity
    /// is built from (one place, so the full and the lift-only evaluations agree bit for bit).
    #[inline(always)]
    fn state_half(&self, theta: f64, su: f64, cu: f64) -> State {
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        let d = theta - self.theta0;
        let sd = 2.0 * su * cu;
        let cd = (cu - su) * (cu + su);
        let s = self.s0 * cd + self.c0 * sd;
        let c = self.c0 * cd - self.s0 * sd;
        // E = K0 + ΔE(θ), sin(α + θ0 + u) by the addition theorem from (su, cu).
        let e = rolling_kinetic(self.k0, d, r.sin_a, chi, self.sa0 * cu + self.ca0 * su, su);
        let (sin_at, cos_at) = r.shifted(s, c);
        let inv_ip = 1.0 / r.contact_inertia(c);
        let w = 2.0 * e * inv_ip;
        let chi_w2 = chi * w;
        let acc = torque(chi, chi_w2, s, sin_at, r.sin_a) * inv_ip;
        State {
            s,
            c,
            e,
            sin_at,
            cos_at,
            inv_ip,
            w,
            chi_w2,
            acc,
        }
    }

    /// [`Self::eval`] given (su, cu) = sin_cos((θ − θ0)/2).
    #[inline]
    fn eval_half(&self, theta: f64, su: f64, cu: f64) -> PathPoint {
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        let State {
            s,
            c,
            e,
            sin_at,
            cos_at,
            inv_ip,
            w,
            chi_w2,
            acc,
        } = self.state_half(theta, su, cu);
        let de = r.sin_a + chi * sin_at;
        let dacc = torque_slope(chi, w, acc, s, c, cos_at) * inv_ip;
        let (fx, fy) = forces(r, chi_w2, s, c, acc);
        let (dfx, dfy) = force_slopes(chi, chi_w2, s, c, acc, dacc);
        let lift = free_normal_acceleration(chi_w2, c, r.cos_a);
        let dlift = liftoff_slope(chi, chi_w2, acc, s, c);
        let mu = self.mu_s;
        PathPoint {
            theta,
            sin_t: s,
            cos_t: c,
            omega_sq: w,
            omega_dot: acc,
            fx,
            fy,
            dfx,
            dfy,
            lift,
            g: [fy, mu * fy - fx, mu * fy + fx, -lift, e],
            dg: [dfy, mu * dfy - dfx, mu * dfy + dfx, -dlift, de],
        }
    }

    /// (g, g', cos θ) of g = −L alone at θ, given its half-angle sin/cos: the values
    /// [`Self::eval_half`] gives, bit for bit, for a fraction of its work.
    #[inline(always)]
    fn no_lift_half(&self, theta: f64, su: f64, cu: f64) -> (f64, f64, f64) {
        let chi = self.chi;
        let st = self.state_half(theta, su, cu);
        let lift = free_normal_acceleration(st.chi_w2, st.c, self.cos_a);
        let dlift = liftoff_slope(chi, st.chi_w2, st.acc, st.s, st.c);
        (-lift, -dlift, st.c)
    }

    /// Grid step at a point: ≤ 2π/24, and ≤ ¼√(Ĩ_P/χ) near the singular peak.
    #[inline]
    fn step(&self, p: &PathPoint) -> f64 {
        self.step_at(p.theta, p.cos_t)
    }

    /// [`Self::step`] at θ with cos θ = `cos_t`.
    #[inline]
    fn step_at(&self, theta: f64, cos_t: f64) -> f64 {
        let hmax = TAU / SAMPLES_PER_TURN;
        let ip = self.ramp.contact_inertia(cos_t);
        if ip >= self.ip_uniform {
            return hmax; // what the test below gives, without its square root and division
        }
        let h = 0.25 * (ip / self.chi).sqrt();
        let floor = 1e-9 * (1.0 + theta.abs());
        if h < hmax {
            h.max(floor)
        } else {
            hmax
        }
    }

    /// Root of g_k on [lo, hi] with g_k(lo) not violated and g_k(hi) violated.
    fn crossing(&self, k: usize, lo: &PathPoint, hi: &PathPoint, evals: &mut u32) -> f64 {
        let (fa, fb) = (lo.g[k], hi.g[k]);
        if !fb.is_finite() {
            // Refine a non-finite end by bisection on "violated".
            let (mut a, mut b) = (lo.theta, hi.theta);
            for _ in 0..200 {
                let m = 0.5 * (a + b);
                if m <= a || m >= b {
                    break;
                }
                *evals += 1;
                if violated(k, self.eval(m).g[k]) {
                    b = m;
                } else {
                    a = m;
                }
            }
            return b;
        }
        // Newton on the analytic slope g_k', from the root of the cell's cubic Hermite
        // interpolant (error ~h⁴): 2.3 evaluations on average where Brent from the bracket
        // alone needed six or seven.
        let h = hi.theta - lo.theta;
        let x0 = lo.theta + h * hermite_root(fa, h * lo.dg[k], fb, h * hi.dg[k]);
        let mut n = 0u32;
        let r = newton_bracketed(
            |t| {
                n += 1;
                let p = self.eval(t);
                (p.g[k], p.dg[k])
            },
            lo.theta,
            hi.theta,
            fa,
            fb,
            x0,
            4.0 * f64::EPSILON,
            200,
        );
        *evals += n;
        match r {
            Ok(r) => r.hi.min(r.x.max(r.lo)),
            Err(_) => hi.theta,
        }
    }

    /// The point where dg_k changes sign − → + on [lo, hi] (a minimum of g_k).
    fn min_location(&self, k: usize, lo: &PathPoint, hi: &PathPoint, evals: &mut u32) -> PathPoint {
        let mut n = 0u32;
        let r = brent(
            |t| {
                n += 1;
                self.eval(t).dg[k]
            },
            lo.theta,
            hi.theta,
            lo.dg[k],
            hi.dg[k],
            0.0,
            4.0 * f64::EPSILON,
            200,
        );
        *evals += n + 1;
        let x = r.map(|r| r.x).unwrap_or(0.5 * (lo.theta + hi.theta));
        self.eval(x)
    }

    /// The first θ in (a, b] where g_k is violated, given it is not violated at a.
    fn first_violation(
        &self,
        k: usize,
        a: &PathPoint,
        b: &PathPoint,
        evals: &mut u32,
    ) -> Option<f64> {
        let (ga, da, gb, db) = (a.g[k], a.dg[k], b.g[k], b.dg[k]);
        let vb = violated(k, gb);
        if da < 0.0 && db > 0.0 {
            if !vb {
                let h = b.theta - a.theta;
                let (_, est) = hermite_min(ga, h * da, gb, h * db);
                if est > 0.1 * ga.min(gb) {
                    return None;
                }
            }
            let m = self.min_location(k, a, b, evals);
            if violated(k, m.g[k]) {
                return Some(self.crossing(k, a, &m, evals));
            }
            if vb {
                return Some(self.crossing(k, &m, b, evals));
            }
            None
        } else if vb {
            Some(self.crossing(k, a, b, evals))
        } else {
            None
        }
    }

    /// Scans the rolling path from θ0 to `theta_end` and stops at the first violated watched
    /// constraint (ties resolved in the order lift-off, normal force, friction, energy).
    pub fn scan(&self, theta_end: f64, watch: Watch) -> PathScan {
        self.scan_from(self.theta0, theta_end, watch)
    }

    /// The paper's lift-off after θ_start: the angle where `scan_from(θ_start, θ_end, w)`
    /// with `w` watching only lift-off and energy (no extrema, grid coarseness `coarseness`)
    /// stops at a lift-off, None if it stops otherwise or not at all. Only the parts of each
    /// turn where L = χθ̇² cos θ − cos α can reach 0 are visited.
    /// Where E > 0 is guaranteed from θ_start on ([`Self::energy_stays_positive`]) and
    /// cos α > 0, L < 0 wherever cos θ < c_min = cos α (Ĩ_C + 1)/(2χ E_ub), with
    /// E_ub = K0 + (θ − θ0) sin α + χ(cos(α + θ0) + 1) at the window's end (Ĩ_P ≥ Ĩ_C + 1 where
    /// cos θ ≥ 0): so only |θ − 2πm| ≤ acos c_min is scanned, whole turns are skipped while
    /// c_min ≥ 1, and within a window only L is evaluated ([`Self::window_liftoff`]).
    /// Elsewhere (no such guarantee) it is the plain scan.
    ///
    /// `matters(lo, hi)` says whether the caller needs the angle when the lift-off is known to
    /// lie in the grid cell [lo, hi]; if not, the root is not located and the result is None,
    /// as when there is none (after a slip only a lift-off in a green window counts).
    pub fn liftoff_after(
        &self,
        theta_start: f64,
        theta_end: f64,
        coarseness: u8,
        matters: impl Fn(f64, f64) -> bool,
    ) -> Option<f64> {
        let watch = Watch::liftoff_only(coarseness);
        let plain = || {
            let sc = self.scan_from(theta_start, theta_end, watch);
            (sc.event == ContactEvent::Liftoff).then_some(sc.at.theta)
        };
        let chi = self.chi;
        let guaranteed = self.cos_a > 0.0
            && self.sin_a > 0.0
            && chi > 0.0
            && self.energy_stays_positive(theta_start);
        if !guaranteed || theta_end <= theta_start || theta_end.is_nan() {
            return plain();
        }
        // L < 0 on window m while 2χ E_ub(2πm + π/2) ≤ cos α (Ĩ_C + 1) (with a margin).
        let need = self.cos_a * (self.ramp.body.ic + 1.0) / (2.0 * chi) * (1.0 - 1e-9);
        let e_ub =
            |theta: f64| self.k0 + (theta - self.theta0) * self.sin_a + chi * (self.ca0 + 1.0);
        // First window that can hold L ≥ 0: θ_hi = 2πm + π/2 with E_ub(θ_hi) > need.
        let theta_need = self.theta0 + (need - e_ub(self.theta0)) / self.sin_a;
        let m_start = ((theta_start + FRAC_PI_2) / TAU).floor();
        let m_need = ((theta_need - FRAC_PI_2) / TAU).floor();
        let mut m = m_start.max(m_need);
        // The window of turn m, and whether it is whole (not cut by θ_start or θ_end).
        let window = |m: f64| {
            let centre = TAU * m;
            let c_min = need / e_ub(centre + FRAC_PI_2);
            (c_min < 1.0).then(|| {
                let beta = crate::trig::acos(c_min);
                let (lo, hi) = (centre - beta, centre + beta);
                let whole = lo > theta_start && hi < theta_end;
                (lo.max(theta_start), hi.min(theta_end), whole)
            })
        };
        let grid = Grid::new(theta_start, theta_end, watch);
        let mut tried_skip = false;
        loop {
            let centre = TAU * m;
            if centre - FRAC_PI_2 >= theta_end {
                return None;
            }
            if let Some((lo, hi, whole)) = window(m) {
                if lo < hi {
                    match self.window_liftoff(lo, hi, &grid, &matters) {
                        WindowLift::Clean => {}
                        WindowLift::Within => return None,
                        // An event at a window start contradicts the bound (rounding): fall
                        // back to the plain scan.
                        WindowLift::At(x) if lo > theta_start && x <= lo => return plain(),
                        WindowLift::At(x) => return Some(x),
                    }
                    if whole && !tried_skip {
                        tried_skip = true;
                        if let Some(t) = self.skip_windows(m, &window, &grid, theta_end) {
                            // Nearer the lift-off, a new estimate is better: skip again.
                            m = t;
                            tried_skip = false;
                        }
                    }
                }
            }
            m += 1.0;
        }
    }

    /// True if E > 0 on (θ_start, ∞) is certain (sin α > 0 assumed). First the bound without
    /// trigonometry, E ≥ K0 + (θ − θ0) sin α + χ(cos(α + θ0) − 1), which rises with θ; where
    /// it is not yet positive (a slip soon after the start), the exact lowest value: E at
    /// θ_start (or E = 0 there and rising, as at a slip at the start from rest) and at the
    /// first minimum of E after it ([`Ramp::energy_minimum_after`]), with a margin far above
    /// the rounding of E. One turn later E is larger by 2π sin α at every phase, so no later
    /// minimum is lower.
    fn energy_stays_positive(&self, theta_start: f64) -> bool {
        let chi = self.chi;
        let e_low = self.k0 + (theta_start - self.theta0) * self.sin_a + chi * (self.ca0 - 1.0);
        if e_low > 0.0 {
            return true;
        }
        let margin =
            |theta: f64| 1e-12 * (self.k0 + (theta - self.theta0).abs() * self.sin_a + 2.0 * chi);
        let p = self.eval(theta_start);
        let (e, de) = (p.g[G_ENERGY], p.dg[G_ENERGY]);
        let start = e > margin(theta_start) || (e >= 0.0 && de > 1e-12 * (self.sin_a + chi));
        start
            && self
                .ramp
                .energy_minimum_after(theta_start)
                .is_none_or(|t| self.energy(t) > margin(t))
    }

    /// The first lift-off on [lo, hi] (−L violated; at lo itself by the start test of
    /// [`violated_at_start`]), by the grid and the cell tests of [`Self::advance`] with only
    /// −L evaluated: the angle `scan_from(lo, hi, w)` finds where E > 0 is guaranteed, so that
    /// E, watched there too, cannot end the scan. Only a cell that is not clear is evaluated in
    /// full, to locate the root as the scan does, and only if `matters` for its cell.
    fn window_liftoff(
        &self,
        lo: f64,
        hi: f64,
        grid: &Grid,
        matters: &impl Fn(f64, f64) -> bool,
    ) -> WindowLift {
        let (mut su, mut cu) = if lo == self.theta0 {
            (0.0, 1.0)
        } else {
            crate::trig::sin_cos(0.5 * (lo - self.theta0))
        };
        let (mut ga, mut da, mut ca) = self.no_lift_half(lo, su, cu);
        if liftoff_at_start(-ga, -da) {
            return WindowLift::At(lo);
        }
        let (mut ta, mut rotated, mut cells) = (lo, 0u32, 0u64);
        let mut evals = 0u32;
        loop {
            cells += 1;
            let h = self.step_at(ta, ca) * grid.coarseness;
            let tb = (ta + h).min(hi);
            let (sa, ca_half) = (su, cu);
            if h == grid.h_uni && tb == ta + h && rotated < ROTATIONS {
                (su, cu) = (
                    su + (cu * grid.sh - su * grid.vh),
                    cu - (su * grid.sh + cu * grid.vh),
                );
                rotated += 1;
            } else {
                (su, cu) = crate::trig::sin_cos(0.5 * (tb - self.theta0));
                rotated = 0;
            }
            let (gb, db, cb) = self.no_lift_half(tb, su, cu);
            if !clear_values(G_NOLIFT, ga, da, gb, db, tb - ta) {
                // Violated at tb (and not at ta): the lift-off is in this cell.
                if violated(G_NOLIFT, gb) && !matters(ta, tb) {
                    return WindowLift::Within;
                }
                let pa = self.eval_half(ta, sa, ca_half);
                let pb = self.eval_half(tb, su, cu);
                if let Some(x) = self.first_violation(G_NOLIFT, &pa, &pb, &mut evals) {
                    return WindowLift::At(x);
                }
            }
            if tb >= hi || cells > grid.max_cells {
                return WindowLift::Clean;
            }
            (ta, ga, da, ca) = (tb, gb, db, cb);
        }
    }

    /// Skips the lift-off windows after the clean whole window of turn m, as
    /// [`Self::skip_turns`] skips turns: −L is affine in the turn index at a fixed phase, and
    /// the windows only widen with m. Turn m is clean on the window of a later turn T (inside
    /// its own window by the scan, outside by the bound on L), so if the window of T is
    /// clean, −L > 0 on it at every turn in between, and every window in between lies inside
    /// it. T is a margin before the lift-off turn estimated from L at 2πm one turn apart, and
    /// not after the last window that ends before θ_end. If window T holds a lift-off, the
    /// clean windows from m on are still consecutive, so the last clean one before T is found
    /// by bisection (a few window scans where window by window took up to 10⁶).
    /// Returns the window skipped to, None to go on window by window.
    fn skip_windows(
        &self,
        m: f64,
        window: &impl Fn(f64) -> Option<(f64, f64, bool)>,
        grid: &Grid,
        theta_end: f64,
    ) -> Option<f64> {
        let centre = TAU * m;
        let (l0, l1) = (self.eval(centre).lift, self.eval(centre + TAU).lift);
        let more = -l0 / (l1 - l0); // turns until L(2πm') ≥ 0 (L is maximal near 2πm')
                                    // A window ends by 2πm' + π/2; one more turn of margin for the rounding.
        let last = ((theta_end - FRAC_PI_2) / TAU).floor() - 1.0;
        let target = (m + more - SKIP_MARGIN_TURNS - SKIP_MARGIN_SHARE * more)
            .floor()
            .min(last);
        if !(l0 < 0.0 && l1 > l0 && target >= m + 3.0) {
            return None;
        }
        if let Some(t) = self.clean_window(target, window, grid) {
            return Some(t);
        }
        let last = self.last_clean_window((m, target), window, grid);
        (last > m).then_some(last)
    }

    /// The last clean whole window before `dirty`, given that window `clean` is clean and
    /// window `dirty` is not (or not whole), by bisection: the clean windows from `clean` on
    /// are consecutive (see [`Self::skip_windows`]).
    fn last_clean_window(
        &self,
        (clean, dirty): (f64, f64),
        window: &impl Fn(f64) -> Option<(f64, f64, bool)>,
        grid: &Grid,
    ) -> f64 {
        last_clean((clean, dirty), |m| {
            self.clean_window(m, window, grid).is_some()
        })
    }

    /// `target` if its window is whole and clean (the proof that the windows before it hold
    /// no lift-off, given a clean whole window earlier).
    fn clean_window(
        &self,
        target: f64,
        window: &impl Fn(f64) -> Option<(f64, f64, bool)>,
        grid: &Grid,
    ) -> Option<f64> {
        let (lo, hi, whole) = window(target)?;
        let clean = whole && self.window_liftoff(lo, hi, grid, &|_, _| false) == WindowLift::Clean;
        clean.then_some(target)
    }

    /// As [`Self::scan`], but starting at θ_start ≥ θ0 on the same path (e.g. to continue
    /// past an event); the extrema are then over [θ_start, θ_event].
    ///
    /// Long scans on the rigorous grid skip turns that provably hold no event (see
    /// [`Self::skip_turns`]); every other scan visits every cell.
    pub fn scan_from(&self, theta_start: f64, theta_end: f64, watch: Watch) -> PathScan {
        self.scan_cells(theta_start, theta_end, watch, true)
    }

    /// [`Self::scan_from`], with or without skipping turns.
    fn scan_cells(&self, theta_start: f64, theta_end: f64, watch: Watch, skip: bool) -> PathScan {
        // At θ0 itself the half angle is 0: (sin, cos) = (0, 1) exactly, without a call.
        let half = if theta_start == self.theta0 {
            (0.0, 1.0)
        } else {
            crate::trig::sin_cos(0.5 * (theta_start - self.theta0))
        };
        let p0 = self.eval_half(theta_start, half.0, half.1);
        let min_fy = Extremum::start(p0.fy, p0.theta, f64::INFINITY);
        let max_r = Extremum::start(p0.ratio(), p0.theta, f64::NEG_INFINITY);
        // Violations at the start itself (the check shared with the ODE route).
        let start = StartValues {
            lift: p0.lift,
            lift_slope: -p0.dg[G_NOLIFT],
            fx: p0.fx,
            fy: p0.fy,
            kinetic: p0.g[G_ENERGY],
            kinetic_slope: p0.dg[G_ENERGY],
        };
        let watched = Watched {
            liftoff: watch.liftoff,
            normal_force: watch.normal_force,
            friction: watch.friction,
        };
        if let Some(event) = violated_at_start(watched, self.mu_s, &start) {
            return self.finish(event, p0, min_fy, max_r, 1, watch.refine_extrema);
        }
        let grid = Grid::new(theta_start, theta_end, watch);
        let mut cur = Cursor::start(p0, half, min_fy, max_r);
        let long = theta_end - theta_start >= SKIP_MIN_TURNS * TAU;
        let stop = if !skip || !grid.rigorous || !long {
            self.advance(&mut cur, &grid, f64::INFINITY, |_, _, _| {})
        } else {
            self.skip_turns(&mut cur, &grid, theta_start)
        };
        let (event, at) = match stop {
            Stop::Event(event, at) => (event, at),
            Stop::End | Stop::Reached => (ContactEvent::End, cur.pts[cur.ia]),
        };
        let Cursor {
            min_fy,
            max_r,
            evals,
            ..
        } = cur;
        self.finish(event, at, min_fy, max_r, evals, watch.refine_extrema)
    }

    /// Runs the scan from `theta_start` to the end, skipping whole turns that provably hold
    /// no event.
    ///
    /// At a fixed phase, one turn later only E changes, by 2π sin α (E(θ + 2π) = E(θ) +
    /// 2π sin α), and every tracked g_k (F_y, M±, −L, E) is affine in E there: so g_k at a
    /// fixed phase is affine in the turn index m, and min over a turn of g_k is a minimum of
    /// affine functions of m, i.e. concave in m. A concave function positive at turns R and
    /// T is positive on every turn in between: if the rigorous scan finds turns R and T clean,
    /// so is every turn between them, with no need to visit them. The same holds for the
    /// reported extrema: F_y is affine and |F_x|/F_y monotone in m at each phase (F_y > 0
    /// throughout), so their extreme values over turns R…T lie on turn R or turn T.
    ///
    /// Turn R = `SKIP_RECORD_TURN` is scanned as usual while each sample estimates, by the
    /// affine law, how many more turns its g_k stay positive. The scan then restarts at turn
    /// T, a margin before the earliest estimate. If turn T is clean, the event (or the end)
    /// found from there is the true first one; if not, the cursor is put back and the scan
    /// continues cell by cell from the end of turn R, exactly as without the skip.
    fn skip_turns(&self, cur: &mut Cursor, grid: &Grid, theta_start: f64) -> Stop {
        let turn_start = |m: f64| theta_start + TAU * (m - 1.0);
        let noop = |_: &PathPoint, _: f64, _: f64| {};
        let mut r = SKIP_RECORD_TURN;
        match self.advance(cur, grid, turn_start(r), noop) {
            Stop::Reached => {}
            stop => return stop,
        }
        // The last turn that ends before θ_end (with a margin for the rounding of turn_start).
        let whole = ((grid.theta_end - theta_start) / TAU * (1.0 - 1e-12)).floor();
        loop {
            let mut more = f64::INFINITY;
            let record = |p: &PathPoint, su: f64, cu: f64| {
                more = more.min(self.turns_left(p, su, cu, &grid.act));
            };
            match self.advance(cur, grid, turn_start(r + 1.0), record) {
                Stop::Reached => {}
                stop => return stop,
            }
            let estimate = r + more.floor() + 1.0; // the first turn estimated to violate
            let target = (estimate - SKIP_MARGIN_TURNS - SKIP_MARGIN_SHARE * more)
                .floor()
                .min(whole);
            if target.is_nan() || target < r + 3.0 {
                return self.advance(cur, grid, f64::INFINITY, noop);
            }
            let saved = *cur;
            let t_skip = turn_start(target);
            if self.restart(cur, grid, t_skip) {
                match self.advance(cur, grid, t_skip + TAU, noop) {
                    // Turn T is clean: nearer the event, record the next turn and skip again
                    // (each estimate leaves a margin of a tenth of its turns).
                    Stop::Reached => {
                        r = target + 1.0;
                        continue;
                    }
                    Stop::End => return Stop::End,
                    Stop::Event(e, p) if p.theta >= t_skip + TAU => return Stop::Event(e, p),
                    Stop::Event(..) => {} // not proven: below
                }
            }
            return self.bisect_turns(cur, grid, &saved, (r, target), turn_start);
        }
    }

    /// The scan when turn `clean` is clean (the cursor `saved` at its end) and turn `dirty`
    /// is not (or its first sample is violated): the first event lies in the turns between.
    /// The clean turns from `clean` on are consecutive (each constraint's minimum over a turn
    /// is concave in the turn index), so the last clean one is found by bisection, each probe
    /// a rigorous scan of one turn (a failed probe's state is dropped, its work counts); the
    /// scan then goes on cell by cell from its end. Without it, an estimate off by a few per
    /// cent of 10⁵ turns cost milliseconds of cells.
    fn bisect_turns(
        &self,
        cur: &mut Cursor,
        grid: &Grid,
        saved: &Cursor,
        (clean, dirty): (f64, f64),
        turn_start: impl Fn(f64) -> f64,
    ) -> Stop {
        let restore = |cur: &mut Cursor, to: &Cursor| {
            let evals = cur.evals;
            *cur = *to;
            cur.evals = evals;
        };
        restore(cur, saved);
        let noop = |_: &PathPoint, _: f64, _: f64| {};
        last_clean((clean, dirty), |m| {
            let (before, t) = (*cur, turn_start(m));
            let probe_clean = self.restart(cur, grid, t)
                && matches!(self.advance(cur, grid, t + TAU, noop), Stop::Reached);
            if !probe_clean {
                restore(cur, &before);
            }
            probe_clean
        });
        self.advance(cur, grid, f64::INFINITY, noop)
    }

    /// Estimated whole turns after the one of `p` before a watched g_k at the phase of `p`
    /// becomes violated (∞ if none decreases): one turn later g_k changes by
    /// d_k = g_k(θ + 2π) − g_k(θ), evaluated at the same phase (half-angle u + π: no
    /// `sin_cos`), and g_k + j d_k ≤ 0 from j = g_k/(−d_k) on.
    #[inline]
    fn turns_left(&self, p: &PathPoint, su: f64, cu: f64, act: &[bool; NG]) -> f64 {
        let q = self.eval_half(p.theta + TAU, -su, -cu);
        let mut j = f64::INFINITY;
        for (k, &on) in act.iter().enumerate() {
            let d = q.g[k] - p.g[k];
            if on && d < 0.0 {
                j = j.min(p.g[k] / -d);
            }
        }
        // NaN (a NaN sample) must not hide a decrease elsewhere, and makes no skip.
        if j.is_nan() {
            0.0
        } else {
            j
        }
    }

    /// Moves the cursor to a fresh grid starting at θ (after skipped turns): the sample there
    /// counts for the extrema. False if a watched constraint is violated (or NaN) there.
    fn restart(&self, cur: &mut Cursor, grid: &Grid, theta: f64) -> bool {
        let (su, cu) = crate::trig::sin_cos(0.5 * (theta - self.theta0));
        let p = self.eval_half(theta, su, cu);
        cur.evals += 1;
        if (0..NG).any(|k| grid.act[k] && violated(k, p.g[k])) {
            return false;
        }
        cur.min_fy.sample(p.fy, p.theta);
        cur.max_r.sample_max(p.ratio(), p.theta);
        cur.ia = 0;
        cur.pts[0] = p;
        (cur.su, cur.cu, cur.rotated) = (su, cu, 0);
        true
    }

    /// Advances the cursor cell by cell until an event, the end of the scan, or a cell ending
    /// at or after `until` (`Stop::Reached`; the cursor then starts the next cell). `observe`
    /// sees every new sample with its half-angle (sin, cos) of (θ − θ0)/2.
    #[inline(always)]
    fn advance(
        &self,
        cur: &mut Cursor,
        grid: &Grid,
        until: f64,
        mut observe: impl FnMut(&PathPoint, f64, f64),
    ) -> Stop {
        let (act, theta_end, h_uni) = (&grid.act, grid.theta_end, grid.h_uni);
        loop {
            cur.cells += 1;
            let ia = cur.ia;
            let ib = ia ^ 1;
            let ta = cur.pts[ia].theta;
            let h = self.step(&cur.pts[ia]) * grid.coarseness;
            let tb = (ta + h).min(theta_end);
            // Rotation by h/2 where the step is the uniform one, re-anchored on a direct
            // sin_cos every ROTATIONS + 1 samples (error a few ulp).
            let (mut su, mut cu) = (cur.su, cur.cu);
            if h == h_uni && tb == ta + h && cur.rotated < ROTATIONS {
                (su, cu) = (
                    su + (cu * grid.sh - su * grid.vh),
                    cu - (su * grid.sh + cu * grid.vh),
                );
                cur.rotated += 1;
            } else {
                (su, cu) = crate::trig::sin_cos(0.5 * (tb - self.theta0));
                cur.rotated = 0;
            }
            (cur.su, cur.cu) = (su, cu);
            cur.pts[ib] = self.eval_half(tb, su, cu);
            cur.evals += 1;
            let (pa, pb) = (&cur.pts[ia], &cur.pts[ib]);
            observe(pb, su, cu);
            // Cheap filter: a constraint needs a closer look only if it is violated at the
            // cell end or has an interior minimum (g' from − to +) whose cubic-Hermite
            // estimate is not clearly positive (exactly the cases `first_violation` handles
            // with more than this test).
            let mut look = false;
            for (k, &on) in act.iter().enumerate() {
                look |= on && !clear(k, pa, pb);
            }
            if look {
                if let Some((k, px)) = self.first_event(act, pa, pb, &mut cur.evals) {
                    track(pa, &px, &mut cur.min_fy, &mut cur.max_r);
                    return Stop::Event(event_of(k), px);
                }
            }
            track(pa, pb, &mut cur.min_fy, &mut cur.max_r);
            cur.ia = ib;
            if tb >= theta_end || cur.cells > grid.max_cells {
                return Stop::End;
            }
            if tb >= until {
                return Stop::Reached;
            }
        }
    }

    /// The first violation on the cell [a, b] of a watched constraint that is not clear there:
    /// the constraint and the point, None if there is none after all.
    ///
    /// Constraints are examined in tie order ([`TIE_ORDER`]); after a first violation at bx
    /// only an earlier one can win, so the next ones are examined on [θa, bx] (usually no root
    /// search: the point at bx is known). Where the cubic-Hermite roots say clearly which
    /// constraint crosses first ([`Self::leader`]), that one is located first, so the others
    /// need no root search of their own; the tie rule keeps the result of the plain order.
    fn first_event(
        &self,
        act: &[bool; NG],
        pa: &PathPoint,
        pb: &PathPoint,
        evals: &mut u32,
    ) -> Option<(usize, PathPoint)> {
        let Some(lead) = self.leader(act, pa, pb) else {
            return self.first_event_from(None, act, pa, pb, evals);
        };
        let found = self.first_event_from(Some(lead), act, pa, pb, evals);
        // A constraint earlier in tie order that is not violated at the event could still
        // cross within the tie tolerance after it (which the plain order would give to it):
        // then the plain order decides. Where g_k > 2 tol |g_k'| it cannot (g smooth).
        let near_tie = |(k, px): &(usize, PathPoint)| {
            let tol = 1e-12 * (1.0 + px.theta.abs());
            TIE_ORDER[..tie_rank(*k)].iter().any(|&j| {
                // False for NaN: then it is a near tie too.
                let away = px.g[j] > 2.0 * tol * px.dg[j].abs();
                act[j] && !clear(j, pa, pb) && !away
            })
        };
        match found {
            Some(f) if near_tie(&f) => self.first_event_from(None, act, pa, pb, evals),
            found => found,
        }
    }

    /// [`Self::first_event`] with `lead` examined first, then the others in tie order.
    fn first_event_from(
        &self,
        lead: Option<usize>,
        act: &[bool; NG],
        pa: &PathPoint,
        pb: &PathPoint,
        evals: &mut u32,
    ) -> Option<(usize, PathPoint)> {
        let rest = TIE_ORDER.into_iter().filter(|&k| Some(k) != lead);
        // The earliest violation so far, with its constraint and the point there.
        let mut best: Option<(f64, usize, PathPoint)> = None;
        for k in lead.into_iter().chain(rest) {
            if !act[k] || clear(k, pa, pb) {
                continue;
            }
            let end = best.as_ref().map_or(pb, |(_, _, px)| px);
            let Some(x) = self.first_violation(k, pa, end, evals) else {
                continue;
            };
            // Near-ties go to the earlier constraint in the tie order (at Ĩ_CM = 0 the
            // margins vanish with F_y: that is a loss of normal force).
            let wins = best.as_ref().is_none_or(|&(bx, bk, _)| {
                x < bx - 1e-12 * (1.0 + bx.abs()) || (x <= bx && tie_rank(k) < tie_rank(bk))
            });
            if wins {
                *evals += 1;
                best = Some((x, k, self.eval(x)));
            }
        }
        best.map(|(_, k, px)| (k, px))
    }

    /// The constraint to locate first on an event cell, when that is not simply the first
    /// in tie order: every constraint that is not clear is violated at b (a plain sign change),
    /// and one's cubic-Hermite root is earlier than every other's by 1 % of the cell (the
    /// estimates err by ≲ 1e-4 of it). A wrong guess costs root searches, never the result.
    fn leader(&self, act: &[bool; NG], pa: &PathPoint, pb: &PathPoint) -> Option<usize> {
        let h = pb.theta - pa.theta;
        let (mut first, mut t_first, mut t_second, mut count) =
            (None, f64::INFINITY, f64::INFINITY, 0);
        for k in TIE_ORDER {
            if !act[k] || clear(k, pa, pb) {
                continue;
            }
            if !violated(k, pb.g[k]) || violated(k, pa.g[k]) {
                return None; // an interior minimum, or NaN: the plain order
            }
            let t = hermite_root(pa.g[k], h * pa.dg[k], pb.g[k], h * pb.dg[k]);
            count += 1;
            if t < t_first {
                (t_second, t_first, first) = (t_first, t, Some(k));
            } else if t < t_second {
                t_second = t;
            }
        }
        let in_order = TIE_ORDER.into_iter().find(|&k| act[k] && !clear(k, pa, pb));
        (count > 1 && t_first + 0.01 < t_second && first != in_order).then_some(first?)
    }

    fn finish(
        &self,
        event: ContactEvent,
        at: PathPoint,
        min_fy: Extremum,
        max_r: Extremum,
        mut evals: u32,
        refine: bool,
    ) -> PathScan {
        // Refine the reported extrema inside their cells (Brent on the derivative).
        let mut min_fy = min_fy;
        let mut max_r = max_r;
        if !refine {
            // Cheap estimates: the cell's cubic Hermite extremum where it beats the samples.
            if min_fy.cell.is_some() && min_fy.cell_est < min_fy.value {
                min_fy.value = min_fy.cell_est;
                min_fy.theta = min_fy.cell_theta;
            }
            if max_r.cell.is_some() && max_r.cell_est > max_r.value {
                max_r.value = max_r.cell_est;
                max_r.theta = max_r.cell_theta;
            }
            min_fy.cell = None;
            max_r.cell = None;
        }
        for (lo, hi) in min_fy.cells_to_refine().into_iter().flatten() {
            let (pl, ph) = (self.eval(lo), self.eval(hi));
            let m = self.min_location(G_FY, &pl, &ph, &mut evals);
            if m.fy < min_fy.value {
                min_fy.value = m.fy;
                min_fy.theta = m.theta;
            }
        }
        for (lo, hi) in max_r.cells_to_refine().into_iter().flatten() {
            let (pl, ph) = (self.eval(lo), self.eval(hi));
            let (dl, dh) = (pl.ratio_derivative(), ph.ratio_derivative());
            if dl > 0.0 && dh < 0.0 {
                let mut n = 0u32;
                if let Ok(r) = brent(
                    |t| {
                        n += 1;
                        self.eval(t).ratio_derivative()
                    },
                    lo,
                    hi,
                    dl,
                    dh,
                    0.0,
                    4.0 * f64::EPSILON,
                    200,
                ) {
                    let p = self.eval(r.x);
                    if p.ratio() > max_r.value {
                        max_r.value = p.ratio();
                        max_r.theta = p.theta;
                    }
                }
                evals += n + 1;
            }
        }
        PathScan {
            event,
            at,
            max_ratio: max_r.value,
            theta_max_ratio: max_r.theta,
            min_fy: min_fy.value,
            theta_min_fy: min_fy.theta,
            evaluations: evals,
        }
    }
}

/// The last turn (or window) m in [clean, dirty) with `is_clean(m)`, given that `clean` is
/// clean and `dirty` is not, and that the clean ones from `clean` on are consecutive: by
/// bisection on the integers, `is_clean` asked about log₂(dirty − clean) times, in
/// increasing order of the clean answers (a skip may keep the state of the last clean probe).
fn last_clean((clean, dirty): (f64, f64), mut is_clean: impl FnMut(f64) -> bool) -> f64 {
    let (mut lo, mut hi) = (clean, dirty);
    while hi - lo > 1.0 {
        let mid = (0.5 * (lo + hi)).floor();
        if is_clean(mid) {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

fn event_of(k: usize) -> ContactEvent {
    match k {
        G_FY => ContactEvent::NormalForce,
        G_MPLUS | G_MMINUS => ContactEvent::Slip,
        G_NOLIFT => ContactEvent::Liftoff,
        _ => ContactEvent::RocksBack,
    }
}

/// Updates the reported extrema with the cell [a, b]: end values, and an interior extremum
/// (derivative sign change) estimated by the cubic Hermite interpolant, refined at the end.
#[inline]
fn track(a: &PathPoint, b: &PathPoint, min_fy: &mut Extremum, max_r: &mut Extremum) {
    let h = b.theta - a.theta;
    if b.fy < min_fy.value {
        min_fy.value = b.fy;
        min_fy.theta = b.theta;
    }
    let (da, db) = (a.dg[G_FY], b.dg[G_FY]);
    if da < 0.0 && db > 0.0 {
        let (t, est) = hermite_min(a.fy, h * da, b.fy, h * db);
        let spread = (b.fy - a.fy).abs() + h * (da.abs() + db.abs());
        min_fy.offer(est, a.theta + t * h, (a.theta, b.theta), spread);
    }
    let rb = b.ratio();
    if rb > max_r.value {
        max_r.value = rb;
        max_r.theta = b.theta;
    }
    if a.fy > 0.0
        && b.fy > 0.0
        && a.fx.signum() == b.fx.signum()
        && a.ratio_rising()
        && !b.ratio_rising()
    {
        let (ra, rda, rdb) = (a.ratio(), a.ratio_derivative(), b.ratio_derivative());
        if rda > 0.0 && rdb < 0.0 {
            let (t, est) = hermite_min(-ra, -h * rda, -rb, -h * rdb);
            let spread = (rb - ra).abs() + h * (rda.abs() + rdb.abs());
            max_r.offer(-est, a.theta + t * h, (a.theta, b.theta), spread);
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::Cylinder;

    fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
        Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
    }

    #[test]
    fn path_point_agrees_with_rolling_and_derivatives() {
        for &(chi, km, a, th0, w0) in &[
            (0.3, 0.2, 25.0, 0.0, 0.0),
            (0.7, 0.05, 50.0, 1.0, 0.5),
            (0.9, 0.02, 10.0, -0.3, 2.0),
        ] {
            let r = ramp(chi, km, a);
            let p = RollingPath::new(&r, th0, w0, 0.8);
            for i in 1..40 {
                let th = th0 + 0.31 * i as f64;
                let q = p.eval(th);
                let w2 = r.omega_sq(th0, w0, th);
                assert!((q.omega_sq - w2).abs() < 1e-12 * (1.0 + w2));
                let k = r.kinematics(th, w2.sqrt());
                let tol = 1e-12 * (1.0 + w2);
                assert!(
                    (q.fx - k.fx).abs() < tol && (q.fy - k.fy).abs() < tol,
                    "{th}"
                );
                let ip = r.contact_inertia(th.cos());
                assert!((q.omega_dot - k.omega_dot).abs() < tol * (1.0 + 1.0 / ip));
                let hh = 1e-6;
                let (qp, qm) = (p.eval(th + hh), p.eval(th - hh));
                assert!(
                    ((qp.omega_sq - qm.omega_sq) / (2.0 * hh) - 2.0 * q.omega_dot).abs()
                        < 1e-6 * (1.0 + q.omega_dot.abs())
                );
                for kk in 0..NG {
                    let fd = (qp.g[kk] - qm.g[kk]) / (2.0 * hh);
                    assert!(
                        (fd - q.dg[kk]).abs() < 1e-6 * (1.0 + fd.abs()),
                        "{kk} {fd} {}",
                        q.dg[kk]
                    );
                }
            }
        }
    }

    #[test]
    fn uniform_step_shortcut_gives_the_square_root_rule_bit_for_bit() {
        // The step rule as it was: ¼√(Ĩ_P/χ) when below 2π/24 (with a floor), else 2π/24.
        let reference = |p: &RollingPath, q: &PathPoint| {
            let hmax = TAU / SAMPLES_PER_TURN;
            let h = 0.25 * (p.ramp.contact_inertia(q.cos_t) / p.chi).sqrt();
            let floor = 1e-9 * (1.0 + q.theta.abs());
            if h < hmax {
                h.max(floor)
            } else {
                hmax
            }
        };
        let mut near = 0;
        for &(chi, km) in &[(0.9, 0.02), (0.7, 0.1), (0.5, 0.2), (0.99, 0.0), (0.3, 0.0)] {
            let r = ramp(chi, km, 20.0);
            let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
            for i in 0..20_000 {
                let q = p.eval(TAU * i as f64 / 20_000.0);
                assert_eq!(p.step(&q).to_bits(), reference(&p, &q).to_bits());
            }
            // Where Ĩ_P crosses the threshold: cos θ on a fine grid of ulps around it.
            let c_star = (p.ip_uniform - r.body.ic - 1.0) / (2.0 * chi);
            if c_star.abs() < 1.0 {
                near += 1;
                let mut q = p.eval(1.0);
                for k in -2000i64..=2000 {
                    q.cos_t = f64::from_bits((c_star.to_bits() as i64 + k) as u64);
                    assert_eq!(p.step(&q).to_bits(), reference(&p, &q).to_bits(), "{k}");
                }
            }
        }
        assert!(near >= 3, "{near}: the threshold was not crossed");
    }

    #[test]
    fn rotated_half_angles_stay_within_1_5e_15() {
        // The scan advances sin/cos of (θ − θ0)/2 by ROTATIONS rotations between direct
        // evaluations; check the worst error against sin_cos over many starts (in θ ∈ [−8, 8]
        // so that the rounding of θ itself stays below 5e-16). Measured: 1.17e-15 for seven
        // rotations (7.2e-16 for three).
        {
            let h = TAU / SAMPLES_PER_TURN;
            let (sh, vh) = rotation(h);
            let mut worst = 0.0f64;
            for i in 0..20_000 {
                let t0 = 8e-4 * i as f64 - 8.0;
                let (mut su, mut cu) = crate::trig::sin_cos(0.5 * t0);
                let mut t = t0;
                for _ in 0..ROTATIONS {
                    (su, cu) = (su + (cu * sh - su * vh), cu - (su * sh + cu * vh));
                    t += h;
                    let (s, c) = crate::trig::sin_cos(0.5 * t);
                    worst = worst.max((su - s).abs()).max((cu - c).abs());
                }
            }
            assert!(worst < 1.5e-15, "{worst}");
            println!("h = {h}: worst {worst:e}");
        }
    }

    /// xorshift64*: a uniform in [0, 1) (reproducible test points).
    fn uniform(s: &mut u64) -> f64 {
        *s ^= *s >> 12;
        *s ^= *s << 25;
        *s ^= *s >> 27;
        (s.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
    }

    #[test]
    fn every_constraint_is_affine_in_the_turn_index_at_a_fixed_phase() {
        // The law the turn skip rests on, checked against direct evaluations m turns later
        // (an independent route: E(θ + 2πm) through `sin_cos` of the full angle).
        let mut s = 7u64;
        for _ in 0..300 {
            let (chi, km) = (0.01 + 0.98 * uniform(&mut s), 0.5 * uniform(&mut s));
            let r = ramp(chi, km * (1.0 - chi), 0.01 + 20.0 * uniform(&mut s));
            let (th0, w0) = (6.0 * uniform(&mut s) - 3.0, 2.0 * uniform(&mut s));
            let p = RollingPath::new(&r, th0, w0, 0.3 + uniform(&mut s));
            let th = th0 + 0.1 + 6.0 * uniform(&mut s);
            let (su, cu) = crate::trig::sin_cos(0.5 * (th - th0));
            let (a, b) = (p.eval_half(th, su, cu), p.eval_half(th + TAU, -su, -cu));
            for m in [1.0, 2.0, 7.0, 40.0] {
                let q = p.eval(th + TAU * m);
                for k in 0..NG {
                    let lin = a.g[k] + m * (b.g[k] - a.g[k]);
                    let scale = 1.0 + a.g[k].abs() + m * (b.g[k] - a.g[k]).abs();
                    assert!(
                        (q.g[k] - lin).abs() < 1e-11 * scale,
                        "{k} {m} {} {lin}",
                        q.g[k]
                    );
                }
            }
        }
    }

    /// The extrema of F_y (min) and |F_x|/F_y (max) on [a, b] by brute force: 48 samples a
    /// turn, then a 2000-point grid around every sample that is a local extremum.
    fn brute_extrema(p: &RollingPath, a: f64, b: f64) -> (f64, f64) {
        let n = ((b - a) / TAU * 48.0).ceil().max(2.0) as usize;
        let h = (b - a) / n as f64;
        let pts: Vec<PathPoint> = (0..=n).map(|i| p.eval(a + h * i as f64)).collect();
        let best = |f: &dyn Fn(&PathPoint) -> f64| {
            let v: Vec<f64> = pts.iter().map(f).collect();
            let mut m = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
            for i in 0..=n {
                let left = i == 0 || v[i] >= v[i - 1];
                let right = i == n || v[i] >= v[i + 1];
                if left && right {
                    let c = a + h * i as f64;
                    for j in 0..=2000 {
                        let t = (c + h * (j as f64 / 1000.0 - 1.0)).clamp(a, b);
                        m = m.max(f(&p.eval(t)));
                    }
                }
            }
            m
        };
        (-best(&|q| -q.fy), best(&|q| q.ratio()))
    }

    #[test]
    fn turn_skip_finds_the_event_and_extrema_of_the_full_scan() {
        // Long paths (small α, from rest or not, each watch of the routes): the scan that
        // skips turns must find the event of the cell-by-cell scan, and the extrema over the
        // whole path (brute force), while doing much less work.
        let mut s = 20_261_124u64;
        let (mut far, mut evals_skip, mut evals_full) = (0, 0u64, 0u64);
        let watches = [
            Watch::ALL,
            Watch {
                liftoff: false,
                ..Watch::ALL
            },
            Watch {
                normal_force: false,
                friction: false,
                refine_extrema: false,
                ..Watch::ALL
            },
        ];
        for i in 0..300 {
            let chi = 0.001 + 0.998 * uniform(&mut s);
            let km = uniform(&mut s) * (1.0 - chi);
            let alpha = 0.2 * uniform(&mut s).powi(3) + 1e-6;
            let r = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap();
            let (th0, w0) = if i % 2 == 0 {
                (0.0, 0.0)
            } else {
                (4.0 * uniform(&mut s) - 2.0, uniform(&mut s))
            };
            let p = RollingPath::new(&r, th0, w0, 0.5 + 2.0 * uniform(&mut s));
            let end = th0 + TAU * (6.0 + 150.0 * uniform(&mut s));
            let w = watches[i % 3];
            let (a, b) = (
                p.scan_cells(th0, end, w, true),
                p.scan_cells(th0, end, w, false),
            );
            let at = format!(
                "chi {chi} km {km} alpha {alpha} th0 {th0} w0 {w0} watch {}",
                i % 3
            );
            assert_eq!(a.event, b.event, "{at}");
            let (ta, tb) = (a.at.theta, b.at.theta);
            assert!(
                (ta - tb).abs() <= 1e-13 * tb.abs().max(1.0),
                "{ta} {tb} {at}"
            );
            if w.normal_force && a.min_fy > 0.0 {
                let (min_fy, max_ratio) = brute_extrema(&p, th0, ta);
                let (m, r) = (a.min_fy, a.max_ratio);
                // Reported: values on the path, at least as good as every brute-force sample.
                let tol = 1e-11 * (1.0 + m.abs() + r.abs());
                assert!(
                    m <= min_fy + tol,
                    "{m} {min_fy} (full scan {}) {at}",
                    b.min_fy
                );
                assert!(
                    r >= max_ratio - tol,
                    "{r} {max_ratio} (full {}) {at}",
                    b.max_ratio
                );
                for (x, f) in [(a.theta_min_fy, m), (a.theta_max_ratio, r)] {
                    assert!(x >= th0 && x <= ta, "{x} {at}");
                    let q = p.eval(x);
                    assert!(f == q.fy || f == q.ratio(), "{f} {x} {at}");
                }
            }
            if tb > th0 + 10.0 * TAU {
                far += 1;
            }
            evals_skip += a.evaluations as u64;
            evals_full += b.evaluations as u64;
        }
        assert!(far > 100, "{far} paths ran past 10 turns");
        assert!(
            (evals_skip as f64) < 0.3 * evals_full as f64,
            "{evals_skip} {evals_full}"
        );
    }

    #[test]
    fn event_angles_are_the_roots_of_their_constraints_to_the_last_bits() {
        // The crossings are found by Newton on the analytic slope; bisection on the sign of
        // the violated constraint (to the last bit) is the independent route. The two must
        // agree to within the root's conditioning: a few ulp, plus the noise of g over its
        // slope.
        use crate::ode::roots::bisect;
        let mut s = 20_261_125u64;
        let (mut checked, mut close) = (0, 0);
        for i in 0..2000 {
            let chi = 0.001 + 0.998 * uniform(&mut s);
            let km = uniform(&mut s) * (1.0 - chi);
            let alpha = FRAC_PI_2 * uniform(&mut s);
            let r = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap();
            let (th0, w0) = if i % 2 == 0 {
                (0.0, 0.0)
            } else {
                (4.0 * uniform(&mut s) - 2.0, uniform(&mut s))
            };
            let p = RollingPath::new(&r, th0, w0, 0.2 + 1.5 * uniform(&mut s));
            let sc = p.scan(th0 + 8.0 * TAU, Watch::ALL);
            let k = match sc.event {
                ContactEvent::Liftoff => G_NOLIFT,
                ContactEvent::NormalForce => G_FY,
                ContactEvent::Slip if sc.at.fx > 0.0 => G_MPLUS,
                ContactEvent::Slip => G_MMINUS,
                _ => continue,
            };
            let x = sc.at.theta;
            if x <= th0 + 1e-6 {
                continue; // at the start: no crossing
            }
            let g = |t: f64| p.eval(t).g[k];
            let (lo, hi) = (x - 1e-7 * (1.0 + x), x + 1e-7 * (1.0 + x));
            let (glo, ghi) = (g(lo), g(hi));
            if !(glo > 0.0 && ghi < 0.0) {
                continue; // a tangential or multiple root: no sign change to bisect
            }
            let b = bisect(g, lo, hi, glo, ghi).unwrap().x;
            let q = p.eval(x);
            let noise = 1e-15 * (1.0 + q.g[k].abs() + q.fy.abs() + q.fx.abs() + q.lift.abs());
            let tol = 8.0 * f64::EPSILON * x.abs() + noise / q.dg[k].abs();
            assert!(
                (x - b).abs() <= tol,
                "{x} vs bisection {b}: chi {chi} km {km} alpha {alpha} th0 {th0} w0 {w0} k {k}"
            );
            if (x - b).abs() <= 4.0 * f64::EPSILON * x.abs() {
                close += 1;
            }
            checked += 1;
        }
        assert!(checked > 1000, "{checked} crossings checked");
        // Most roots are well conditioned: there the two routes agree to 4 ε|θ| (Newton
        // extrapolates through the rounding noise of g, bisection follows its sign, so where
        // the noise over the slope exceeds a few ulp they differ within that bound).
        assert!(close as f64 > 0.85 * checked as f64, "{close} of {checked}");
    }

    #[test]
    fn a_window_skip_is_refused_when_the_target_window_holds_the_liftoff() {
        let w = Watch::liftoff_only(3);
        let r = ramp(0.7, 0.1, 0.05);
        let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
        let lift = p.scan_cells(0.0, 4000.0, w, false);
        assert_eq!(lift.event, ContactEvent::Liftoff);
        let n = (lift.at.theta / TAU).round();
        let window = |m: f64| Some((TAU * m - 0.5, TAU * m + 0.5, true));
        let grid = Grid::new(0.0, 4000.0, w);
        assert!(p.clean_window(n, &window, &grid).is_none());
        assert_eq!(p.clean_window(n - 1.0, &window, &grid), Some(n - 1.0));
        let cut = |m: f64| Some((TAU * m - 0.5, TAU * m + 0.5, false));
        assert!(p.clean_window(n - 1.0, &cut, &grid).is_none());
    }

    /// The bisections behind the skips: from a clean turn (window) and a later one that is not
    /// clean, the last clean one is found, and the scan from there finds the cell-by-cell
    /// scan's event; the lift-off windows likewise.
    #[test]
    fn bisection_finds_the_last_clean_turn_and_window() {
        let noop = |_: &PathPoint, _: f64, _: f64| {};
        let mut probes = 0;
        for &(chi, km, a) in &[(0.05, 0.5, 0.06), (0.5, 0.2, 0.02), (0.3, 0.35, 0.1)] {
            let r = ramp(chi, km, a);
            let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
            let end = 3000.0 * TAU;
            let full = p.scan_cells(0.0, end, Watch::ALL, false);
            assert_ne!(full.event, ContactEvent::End, "{chi} {km} {a}");
            let event_turn = (full.at.theta / TAU).floor() + 1.0; // turns counted from 1
            assert!(event_turn > 20.0, "{chi} {km} {a}: {event_turn}");
            // The cursor at the end of turn 2, as `skip_turns` leaves it before a skip.
            let grid = Grid::new(0.0, end, Watch::ALL);
            let p0 = p.start();
            let min_fy = Extremum::start(p0.fy, p0.theta, f64::INFINITY);
            let max_r = Extremum::start(p0.ratio(), p0.theta, f64::NEG_INFINITY);
            let mut cur = Cursor::start(p0, (0.0, 1.0), min_fy, max_r);
            let turn_start = |m: f64| TAU * (m - 1.0);
            assert!(matches!(
                p.advance(&mut cur, &grid, turn_start(3.0), noop),
                Stop::Reached
            ));
            for dirty in [event_turn, event_turn + 1.0, event_turn + 700.0] {
                let saved = cur;
                let mut c = cur;
                let Stop::Event(e, at) =
                    p.bisect_turns(&mut c, &grid, &saved, (2.0, dirty), turn_start)
                else {
                    panic!("{chi} {km} {a}: no event");
                };
                assert_eq!(e, full.event);
                let t = full.at.theta;
                assert!((at.theta - t).abs() <= 1e-12 * t, "{} {t}", at.theta);
                // The probes cost a few turns, not the turns before the event.
                assert!(
                    c.cells < 24 * 40 + cur.cells,
                    "{} cells",
                    c.cells - cur.cells
                );
                probes += 1;
            }
            // Lift-off windows: the first window of the lift-off, by the plain scan.
            let w = Watch::liftoff_only(3);
            let lift = p.scan_cells(0.0, end, w, false);
            assert_eq!(lift.event, ContactEvent::Liftoff);
            let n = (lift.at.theta / TAU).round();
            let window = |m: f64| Some((TAU * m - 0.5, TAU * m + 0.5, true));
            let grid = Grid::new(0.0, end, w);
            assert!(n > 10.0);
            for dirty in [n, n + 1.0, n + 300.0] {
                assert_eq!(p.last_clean_window((1.0, dirty), &window, &grid), n - 1.0);
            }
        }
        assert_eq!(probes, 9);
    }

    /// Points that once took up to 1.5 s (a slip or lift-off search over 10⁴–10⁶ turns at tiny
    /// α): the scan to the first event takes a few turns' evaluations, and the lift-off
    /// search after it finds the plain scan's lift-off (where that scan is affordable here).
    #[test]
    fn tiny_angles_take_few_evaluations() {
        use crate::jarm::decision::{point_ramp, search_end};
        use crate::jarm::JarmOptions;
        let o = JarmOptions {
            max_turns: 1_000_000,
            ..JarmOptions::default()
        };
        for &(a, chi, km) in &[(1e-9, 0.99, 0.0), (3.2e-8, 0.81, 0.15), (1e-3, 0.05, 0.5)] {
            let r = point_ramp(a, chi, km, 1.0, &o).unwrap();
            let (end, _) = search_end(&r, &o).unwrap();
            let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
            let s = p.scan(end, Watch::ALL);
            assert_eq!(s.event, ContactEvent::Slip, "{a}");
            assert!(s.evaluations < 3000, "{a}: {} evaluations", s.evaluations);
            let th = s.at.theta;
            if end - th < 1e5 {
                let plain = p.scan_cells(th, end, Watch::liftoff_only(3), false);
                let fast = p.liftoff_after(th, end, 3, |_, _| true);
                assert_eq!(fast.is_some(), plain.event == ContactEvent::Liftoff, "{a}");
                if let Some(x) = fast {
                    assert!((x - plain.at.theta).abs() <= 1e-12 * x.abs(), "{a}");
                }
            }
        }
    }

    #[test]
    fn window_liftoff_gives_the_scans_angle_bit_for_bit() {
        // On windows where E > 0 holds, the lift-only loop must stop exactly where the full
        // scan watching lift-off and energy stops: same grid, same values, same root.
        let mut s = 20261124u64;
        let (mut found, mut clean) = (0, 0);
        for _ in 0..3000 {
            let alpha = 0.02 + 1.5 * uniform(&mut s);
            let chi = 0.001 + 0.999 * uniform(&mut s);
            let km = (1.0 - chi) * uniform(&mut s);
            let r = ramp(chi, km, alpha.to_degrees());
            let (th0, w0) = if uniform(&mut s) < 0.5 {
                (0.0, 0.0)
            } else {
                (6.0 * uniform(&mut s) - 3.0, 2.0 * uniform(&mut s))
            };
            let p = RollingPath::new(&r, th0, w0, 1.0);
            let m = (th0 / TAU).ceil() + (6.0 * uniform(&mut s)).floor();
            let half = 1.5 * uniform(&mut s).powi(3) + 0.01;
            let (lo, hi) = ((TAU * m - half).max(th0), TAU * m + half);
            let coarseness = if uniform(&mut s) < 0.5 { 1 } else { 3 };
            let w = Watch::liftoff_only(coarseness);
            // Skip windows where the energy could vanish (the loop assumes it cannot).
            let e_low = p.k0 + (lo - th0) * p.sin_a + chi * (p.ca0 - 1.0);
            if e_low <= 0.0 {
                continue;
            }
            let full = p.scan_cells(lo, hi, w, false);
            let fast = p.window_liftoff(lo, hi, &Grid::new(lo, hi, w), &|_, _| true);
            match fast {
                WindowLift::At(x) => {
                    assert_eq!(full.event, ContactEvent::Liftoff, "{alpha} {chi} {km} {m}");
                    assert_eq!(x.to_bits(), full.at.theta.to_bits());
                    found += 1;
                }
                WindowLift::Clean => {
                    assert_eq!(full.event, ContactEvent::End, "{alpha} {chi} {km} {m}");
                    clean += 1;
                }
                WindowLift::Within => panic!("every cell matters here"),
            }
        }
        assert!(found > 300 && clean > 300, "{found} {clean}");
    }

    #[test]
    fn liftoff_scan_by_windows_agrees_with_plain_scan() {
        let w = Watch::liftoff_only(1);
        let (mut found, mut far) = (0, 0);
        for &(chi, km, a) in &[
            (0.15, 0.02, 40.0),
            (0.5, 0.4, 30.0),
            (0.9, 0.05, 2.0),
            (0.05, 0.3, 0.9),
            (0.99, 0.0, 30.0),
            (0.3, 0.1, 89.0),
            // Lift-off after hundreds of turns: the windows in between are skipped.
            (0.7, 0.1, 0.05),
            (0.3, 0.2, 0.02),
        ] {
            let r = ramp(chi, km, a);
            for &(th0, w0) in &[(0.0, 0.0), (1.0, 0.3), (-2.0, 1.5)] {
                let p = RollingPath::new(&r, th0, w0, 1.0);
                for i in 0..12 {
                    let start = th0 + 0.7 * i as f64;
                    let end = th0 + if a < 0.1 { 4000.0 } else { 400.0 };
                    let a1 = p.scan_cells(start, end, w, false);
                    let a2 = p.liftoff_after(start, end, 1, |_, _| true);
                    let lifts = a1.event == ContactEvent::Liftoff;
                    assert_eq!(lifts, a2.is_some(), "{chi} {km} {a} {th0} {start}");
                    if let Some(t2) = a2 {
                        found += 1;
                        far += (a1.at.theta > start + 100.0 * TAU) as u32;
                        let t1 = a1.at.theta;
                        assert!((t1 - t2).abs() <= 1e-13 * t1.abs().max(1.0), "{t1} {t2}");
                    }
                }
            }
        }
        assert!(found > 100 && far >= 20, "{found} {far}");
    }

    /// The exact energy test that lets a lift-off search after an early slip go by windows:
    /// it holds exactly where E stays positive (checked on a fine sampling of three turns),
    /// and the windowed search then agrees with the plain scan, including where the body
    /// rocks back first (E reaching 0 ends the plain scan: no lift-off).
    #[test]
    fn early_slip_lift_off_search_is_exact_where_energy_stays_positive() {
        let w = Watch::liftoff_only(3);
        let mut s = 7u64;
        let (mut exact, mut rocks, mut windowed) = (0, 0, 0);
        for _ in 0..4000 {
            let alpha = 1e-3 + (FRAC_PI_2 - 2e-3) * uniform(&mut s);
            let chi = 0.02 + 0.97 * uniform(&mut s);
            let r = ramp(chi, uniform(&mut s) * (1.0 - chi), alpha.to_degrees());
            let th0 = TAU * (uniform(&mut s) - 0.5);
            let w0 = if uniform(&mut s) < 0.3 {
                0.0
            } else {
                0.6 * uniform(&mut s)
            };
            let p = RollingPath::new(&r, th0, w0, 1.0);
            let start = th0 + 0.8 * uniform(&mut s);
            let e_low = p.k0 + (start - th0) * r.sin_a + chi * (p.ca0 - 1.0);
            if e_low > 0.0 || p.energy(start) < 0.0 {
                continue; // the cheap bound decides, or the path never gets here
            }
            // The lowest E on (start, start + 3 turns], sampled.
            let lowest = (1..=30_000)
                .map(|i| p.energy(start + 3.0 * TAU * i as f64 / 30_000.0))
                .fold(f64::INFINITY, f64::min);
            let positive = p.energy_stays_positive(start);
            if positive {
                assert!(lowest > 0.0, "{alpha} {chi} {th0} {w0} {start}: {lowest}");
                exact += 1;
            } else if lowest > 1e-6 {
                panic!("E stays positive but the test failed: {alpha} {chi} {th0} {w0} {start}");
            }
            let end = start + 60.0;
            let plain = p.scan_cells(start, end, w, false);
            rocks += (plain.event == ContactEvent::RocksBack) as u32;
            let fast = p.liftoff_after(start, end, 3, |_, _| true);
            assert_eq!(
                fast.is_some(),
                plain.event == ContactEvent::Liftoff,
                "{alpha} {chi} {th0} {w0} {start}"
            );
            if let Some(x) = fast {
                let t = plain.at.theta;
                assert!((x - t).abs() <= 1e-13 * t.abs().max(1.0), "{x} {t}");
                windowed += positive as u32;
            }
        }
        assert!(
            exact > 300 && rocks > 100 && windowed > 200,
            "{exact} {rocks} {windowed}"
        );
    }

    /// The paper's FxL2 and FyL2, typed exactly as printed (g = M = 1).
    fn fx_l2(alpha: f64, chi: f64, gamma: f64, th: f64) -> f64 {
        use std::f64::consts::PI;
        let (sa, ca) = crate::trig::sin_cos(alpha);
        let pg = PI * gamma;
        -1.0 / (4.0 * chi * (2.0 * pg + th.cos() - 1.0).powi(2))
            * (sa
                * (16.0 * PI * PI * gamma * gamma * chi - 16.0 * pg * chi - 4.0 * pg - chi * chi
                    + 3.0 * chi
                    + 2.0
                    + 2.0 * pg * chi * chi
                    + 2.0 * (-1.0 + (-3.0 + 6.0 * pg) * chi) * th.cos()
                    + chi * (2.0 * th).cos()
                    - 2.0 * th * th.sin()
                    - 4.0 * th * chi * th.sin()
                    + 8.0 * pg * th * chi * th.sin()
                    + th * chi * (2.0 * th).sin())
                + chi
                    * (2.0 * ca * (-1.0 - 2.0 * chi + 4.0 * pg * chi + chi * th.cos()) * th.sin()
                        - (-2.0 + 4.0 * pg + chi) * (alpha + th).sin()
                        - chi
                            * ((-3.0 + 6.0 * pg) * (alpha + 2.0 * th).sin()
                                + (alpha + 3.0 * th).sin())))
    }

    fn fy_l2(alpha: f64, chi: f64, gamma: f64, th: f64) -> f64 {
        use std::f64::consts::PI;
        let (sa, ca) = crate::trig::sin_cos(alpha);
        let pg = PI * gamma;
        1.0 / (4.0 * (2.0 * pg + th.cos() - 1.0).powi(2))
            * (ca
                * (6.0 - 16.0 * pg + 16.0 * PI * PI * gamma * gamma - 4.0 * chi
                    + 2.0 * pg * chi
                    + (-8.0 - 8.0 * pg * (-2.0 + chi) + 7.0 * chi) * th.cos()
                    + (2.0 - 4.0 * chi + 6.0 * pg * chi) * (2.0 * th).cos()
                    + chi * (3.0 * th).cos())
                - sa * (3.0 * th + 4.0 * (-1.0 + 2.0 * pg) * th * th.cos() + th * (2.0 * th).cos()
                    - 2.0 * th.sin()
                    + 4.0 * pg * th.sin()
                    + 3.0 * chi * th.sin()
                    + (2.0 * th).sin()
                    - 3.0 * chi * (2.0 * th).sin()
                    + 6.0 * pg * chi * (2.0 * th).sin()
                    + chi * (3.0 * th).sin()))
    }

    #[test]
    fn forces_match_the_papers_fxl2_fyl2() {
        for &(chi, km, a) in &[
            (0.15, 0.02, 40.0),
            (0.5, 0.4, 30.0),
            (0.8, 0.1, 12.0),
            (0.05, 0.9, 80.0),
        ] {
            let r = ramp(chi, km, a);
            let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
            let gamma = r.body.gamma();
            for i in 1..200 {
                let th = 0.05 * i as f64;
                let q = p.eval(th);
                let (fx, fy) = (
                    fx_l2(r.alpha, chi, gamma, th),
                    fy_l2(r.alpha, chi, gamma, th),
                );
                assert!(
                    (q.fx - fx).abs() < 1e-10 * (1.0 + fx.abs()),
                    "{chi} {th}: {} {fx}",
                    q.fx
                );
                assert!(
                    (q.fy - fy).abs() < 1e-10 * (1.0 + fy.abs()),
                    "{chi} {th}: {} {fy}",
                    q.fy
                );
            }
        }
    }

    /// Brute force: the first violation on a dense grid of 1e5 points.
    fn brute(p: &RollingPath, theta_end: f64, watch: Watch) -> Option<(f64, usize)> {
        let n = 100_000;
        for i in 0..=n {
            let th = p.theta0() + (theta_end - p.theta0()) * i as f64 / n as f64;
            let q = p.eval(th);
            for &k in &[G_NOLIFT, G_FY, G_MPLUS, G_MMINUS, G_ENERGY] {
                if watch.active(k) && i > 0 && violated(k, q.g[k]) {
                    return Some((th, k));
                }
            }
        }
        None
    }

    #[test]
    fn scan_agrees_with_dense_sampling() {
        let mut checked = 0;
        for &(chi, km, a, mu) in &[
            (0.15, 0.02, 40.0, 1.0),
            (0.5, 0.4, 30.0, 1.0),
            (0.3, 0.1, 20.0, 0.7),
            (0.9, 0.05, 15.0, 1.0),
            (0.6, 0.3, 60.0, 2.0),
            (0.05, 0.2, 80.0, 1.0),
            (0.99, 0.0, 30.0, 5.0),
            (0.4, 0.5, 8.0, 0.5),
        ] {
            let r = ramp(chi, km, a);
            let p = RollingPath::new(&r, 0.0, 0.0, mu);
            let end = 4.0 * TAU;
            let s = p.scan(end, Watch::ALL);
            let b = brute(&p, end, Watch::ALL);
            match (s.event, b) {
                (ContactEvent::End, None) => {}
                (ev, Some((th, k))) => {
                    assert_eq!(ev, event_of(k), "{chi} {km} {a}");
                    assert!(
                        s.at.theta <= th && th - s.at.theta < 1e-3,
                        "{} {th}",
                        s.at.theta
                    );
                    checked += 1;
                }
                (ev, None) => panic!("{ev:?} but brute force found nothing"),
            }
            // Reported extrema against dense sampling on [0, θ_event].
            let n = 100_000;
            let (mut mr, mut mf) = (0.0f64, f64::INFINITY);
            for i in 0..=n {
                let q = p.eval(s.at.theta * i as f64 / n as f64);
                mr = mr.max(q.ratio());
                mf = mf.min(q.fy);
            }
            assert!(
                s.min_fy <= mf + 1e-12 && mf - s.min_fy < 1e-8,
                "{} {mf}",
                s.min_fy
            );
            if mr.is_finite() {
                assert!(
                    s.max_ratio >= mr - 1e-12 && s.max_ratio - mr < 1e-6,
                    "{} {mr}",
                    s.max_ratio
                );
            }
        }
        assert!(checked >= 6);
    }

    #[test]
    fn reference_slip_near_316_degrees() {
        let r = ramp(0.5, 0.4, 30.0);
        let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
        let s = p.scan(2.0 * TAU, Watch::ALL);
        assert_eq!(s.event, ContactEvent::Slip);
        assert!(
            (s.at.theta.to_degrees() - 316.47).abs() < 0.01,
            "{}",
            s.at.theta.to_degrees()
        );
        assert!((s.at.ratio() - 1.0).abs() < 1e-9);
    }

    #[test]
    fn thin_violation_between_samples_is_found() {
        // Choose μ_s just below the interior maximum of the friction ratio on the path, so
        // that the margin dips below 0 on a sliver much thinner than the grid step.
        let r = ramp(0.3, 0.1, 20.0);
        let big = RollingPath::new(&r, 0.0, 0.0, 1e6);
        let w = Watch {
            normal_force: true,
            friction: false,
            ..Watch::ALL
        };
        let s = big.scan(4.0 * TAU, w);
        // Find an interior local maximum of the ratio well before the event.
        let (mut best, mut th_best) = (0.0, 0.0);
        let n = 200_000;
        for i in 1..n {
            let th = 0.8 * s.at.theta * i as f64 / n as f64;
            let q = big.eval(th);
            if q.ratio() > best {
                best = q.ratio();
                th_best = th;
            }
        }
        assert!(th_best > 0.1 && th_best < 0.79 * s.at.theta, "{th_best}");
        let mu = best * (1.0 - 1e-9);
        let p = RollingPath::new(&r, 0.0, 0.0, mu);
        let sc = p.scan(4.0 * TAU, Watch::ALL);
        assert_eq!(sc.event, ContactEvent::Slip);
        assert!(
            (sc.at.theta - th_best).abs() < 1e-3,
            "{} {th_best}",
            sc.at.theta
        );
        // The violation is thinner than the grid step by orders of magnitude.
        let width = {
            let (mut lo, mut hi) = (th_best, th_best);
            while p.eval(lo).g[G_MPLUS].min(p.eval(lo).g[G_MMINUS]) < 0.0 {
                lo -= 1e-7;
            }
            while p.eval(hi).g[G_MPLUS].min(p.eval(hi).g[G_MMINUS]) < 0.0 {
                hi += 1e-7;
            }
            hi - lo
        };
        assert!(width < 1e-3, "{width}");
    }
}

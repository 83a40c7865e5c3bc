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
//! stops and rocks back).
//!
//! The evaluation uses one `sin_cos` of (θ − θ0)/2 per point, no heap allocation.
//!
//! The module holds the path's public types and its evaluation; the scan is in its parts:
//! - `scan`: the grid and the scan cell by cell;
//! - `events`: the first event on a cell (crossings, minima, the tie order);
//! - `extremum`: the reported extrema, tracked and refined;
//! - `skip`: skipping whole turns that provably hold no event, and the bisection behind it;
//! - `liftoff`: the lift-off search after a slip, window by window.

use crate::jarm::decision::Extrema;
use crate::mechanics::energy::rolling_kinetic;
use crate::mechanics::friction::friction_ratio;
use crate::mechanics::liftoff::{free_normal_acceleration, liftoff_slope};
use crate::mechanics::Ramp;
pub use crate::modes::rolling::events::ContactEvent;
use crate::modes::rolling::{force_slopes, forces, torque, torque_slope};
use std::f64::consts::TAU;

mod events;
mod extremum;
mod liftoff;
mod scan;
mod skip;
#[cfg(test)]
mod tests;

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
    /// The event that stopped the scan (`ThetaLimit` if none: the end of the search).
    pub event: ContactEvent,
    /// The state where the scan stopped (the event, or the end).
    pub at: PathPoint,
    /// The largest |F_x|/F_y (∞ if F_y reached 0) and the smallest F_y on [θ0, θ_event],
    /// and where.
    pub extrema: Extrema,
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

    /// The available kinetic energy E(θ) at θ (θ̇² = 2E/Ĩ_P).
    #[inline]
    pub fn energy(&self, theta: f64) -> f64 {
        let u = 0.5 * (theta - self.theta0);
        let (su, cu) = crate::trig::sin_cos(u);
        let sin_mid = self.sa0 * cu + self.ca0 * su;
        rolling_kinetic(
            self.k0,
            theta - self.theta0,
            self.ramp.sin_a,
            self.ramp.body.chi,
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
        let chi = self.ramp.body.chi;
        let st = self.state_half(theta, su, cu);
        let lift = free_normal_acceleration(st.chi_w2, st.c, self.ramp.cos_a);
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
        let h = 0.25 * (ip / self.ramp.body.chi).sqrt();
        let floor = 1e-9 * (1.0 + theta.abs());
        if h < hmax {
            h.max(floor)
        } else {
            hmax
        }
    }
}

//! Classification of one point (α, χ, k_m, μ_s): does the cylinder jump after pure rolling
//! (a JARM), and if not, why. Start from rest at θ0 = 0 by default, or any (θ0, θ̇0 ≥ 0).
//!
//! First-jump semantics: the body leaves at the FIRST θ where the lift-off rule holds; every
//! path condition is checked on the way there, and the first thing that happens decides.
//!
//! Two lift-off rules ([`Rule`]):
//! - `Paper`: lift-off at the first rising zero θ_L of L = χθ̇² cos θ − cos α. JARM iff the
//!   path keeps F_y > 0 and μ_s F_y − |F_x| ≥ 0 on [θ0, θ_L), θ_L lies in a green window
//!   2πn − α < θ_L < 2πn with F_y,J > 0, and μ(θ_L) ≤ μ_s (Eq. ineq2).
//! - `NormalForce` (classical unilateral contact): keep rolling until F_y = 0 or the rolling
//!   branch needs |F_x| = μ_s F_y. There, if sliding is inconsistent — L ≥ 0 (the sliding
//!   normal force Ĩ_CM(cos α − χθ̇² cos θ)/D would be ≤ 0), or D ≤ 0 (Painlevé), or Ĩ_CM = 0 —
//!   with K = χ sin θ − σ μ_k (1 + χ cos θ), D = Ĩ_CM + χ K sin θ, μ_k = μ_s, σ = sign F_x —
//!   the body goes straight to flight: a JARM with θ_J there. Otherwise it slips first.
//!
//! Search bound: at θ = 2πn the normal force is −L(2πn), and L(2πn) > 0 from turn
//! n* = min{n : n tan α > γ} on (from rest; the general start shifts the threshold), so under
//! either rule something happens by 2πn*; searches never go further. n* > `max_turns` gives
//! `TurnLimit` if nothing happened within `max_turns` turns.
//!
//! Turn of an event: n = round(θ/2π) (a lift-off needs cos θ > 0, so this is unambiguous).

use crate::body::Cylinder;
use crate::jump_point::{green_turn, jump_forces, mu};
use crate::path::{PathEvent, PathScan, RollingPath, Watch};
use crate::rolling::Rolling;
pub use crate::rule::Rule;
use std::f64::consts::{FRAC_PI_2, PI, TAU};

/// Why a point is or is not a JARM. `#[repr(u8)]` with stable values (the bridge exports them).
#[repr(u8)]
#[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
pub enum Reason {
    /// 0: jump after pure rolling.
    Jarm = 0,
    /// 1: no lift-off (on the requested turn n, or ever: α = 0, χ = 0, or the path passes turn
    /// n without event).
    NoRoot = 1,
    /// 2: the lift-off rule held earlier: on an earlier turn than the requested n, or at the
    /// start itself (e.g. α = π/2 from rest, where F_y = 0 at θ0).
    LiftoffEarlier = 2,
    /// 3: the normal force reached 0 before lift-off (or F_y,J ≤ 0 at it).
    NormalForceLost = 3,
    /// 4: the rolling branch needs more than μ_s of friction before lift-off (and the paper's
    /// jump-point test ineq2 alone would not have caught it), or slip is consistent there under
    /// the `NormalForce` rule.
    SlipBefore = 4,
    /// 5: friction fails on the final approach: the paper's lift-off point that follows is in
    /// the green window but needs μ(θ_J) > μ_s (Eq. ineq2 fails). Paper rule only.
    SlipAtJump = 5,
    /// 6: θ̇² returns to 0 before any event: the body stops and rolls back (not possible from
    /// rest at θ0 = 0 with α > 0; see `from_rest::rock_back_angle`).
    RocksBack = 6,
    /// 7: nothing happened within `max_turns` turns and n* > `max_turns`.
    TurnLimit = 7,
    /// 8: a parameter is NaN or out of range.
    InvalidParams = 8,
}

impl Reason {
    /// All reasons, indexed by code.
    pub const ALL: [Reason; 9] = [
        Reason::Jarm,
        Reason::NoRoot,
        Reason::LiftoffEarlier,
        Reason::NormalForceLost,
        Reason::SlipBefore,
        Reason::SlipAtJump,
        Reason::RocksBack,
        Reason::TurnLimit,
        Reason::InvalidParams,
    ];

    /// The numeric code.
    pub fn code(self) -> u8 {
        self as u8
    }

    /// The reason for a code, if valid.
    pub fn from_code(code: u8) -> Option<Reason> {
        Reason::ALL.get(code as usize).copied()
    }

    /// A short snake_case name.
    pub fn name(self) -> &'static str {
        match self {
            Reason::Jarm => "jarm",
            Reason::NoRoot => "no_root",
            Reason::LiftoffEarlier => "liftoff_earlier",
            Reason::NormalForceLost => "normal_force_lost",
            Reason::SlipBefore => "slip_before",
            Reason::SlipAtJump => "slip_at_jump",
            Reason::RocksBack => "rocks_back",
            Reason::TurnLimit => "turn_limit",
            Reason::InvalidParams => "invalid_params",
        }
    }
}

/// Options of a classification.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JarmOptions {
    pub rule: Rule,
    /// Required turn n ≥ 1, or 0 for automatic (the first jump, whatever its turn).
    pub n: u32,
    /// Turn cap of the search.
    pub max_turns: u32,
    /// Initial angle θ0 and angular velocity θ̇0 ≥ 0 (default: rest at 0).
    pub theta0: f64,
    pub omega0: f64,
    /// Refine the reported path extrema (max friction ratio, min F_y) to full precision
    /// (default); if false they are cell estimates (relative error ~1e-4) and the map is
    /// faster. The classification itself does not depend on it.
    pub refine_extrema: bool,
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
        }
    }
}

/// The classification of one point. Angles in radians (absolute θ); NaN where not applicable.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JarmResult {
    pub is_jarm: bool,
    pub reason: Reason,
    /// Turn of the jump (JARM), of the earlier lift-off (LiftoffEarlier) or of the event
    /// that decided (others); 0 if none.
    pub n: u32,
    /// Lift-off angle: the JARM's, the earlier one (LiftoffEarlier), or the paper's root
    /// after a friction failure (SlipAtJump); NaN otherwise.
    pub theta_j: f64,
    /// Where the deciding failure happened (NaN for a JARM).
    pub theta_event: f64,
    /// Forces at the jump (JARM only; NaN otherwise).
    pub fx_j: f64,
    pub fy_j: f64,
    /// The largest |F_x|/F_y and the smallest F_y on the rolling path [θ0, θ_event or θ_J].
    pub max_ratio: f64,
    pub theta_max_ratio: f64,
    pub min_fy: f64,
    pub theta_min_fy: f64,
}

impl JarmResult {
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

    /// A result carrying the path extrema: the largest |F_x|/F_y and the smallest F_y, with
    /// the angles where they occur (shared by both routes).
    pub(crate) fn with_extrema(reason: Reason, max_ratio: (f64, f64), min_fy: (f64, f64)) -> Self {
        let mut r = Self::new(reason);
        (r.max_ratio, r.theta_max_ratio) = max_ratio;
        (r.min_fy, r.theta_min_fy) = min_fy;
        r
    }

    fn with_scan(reason: Reason, s: &PathScan) -> Self {
        Self::with_extrema(
            reason,
            (s.max_ratio, s.theta_max_ratio),
            (s.min_fy, s.theta_min_fy),
        )
    }
}

/// round(θ/2π), clamped to u32.
#[inline]
pub(crate) fn turn_of(theta: f64) -> u32 {
    let n = (theta / TAU).round();
    if n <= 0.0 {
        0
    } else if n >= u32::MAX as f64 {
        u32::MAX
    } else {
        n as u32
    }
}

/// Parameter check without allocation; returns the body on success.
#[inline]
pub(crate) fn valid_body(
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    o: &JarmOptions,
) -> Option<Cylinder> {
    let ok = alpha.is_finite()
        && (0.0..=FRAC_PI_2).contains(&alpha)
        && chi.is_finite()
        && (0.0..=1.0).contains(&chi)
        && km.is_finite()
        && km >= 0.0
        && km <= 1.0 - chi + 4.0 * f64::EPSILON
        && mu_s.is_finite()
        && mu_s >= 0.0
        && o.theta0.is_finite()
        && o.omega0.is_finite()
        && o.omega0 >= 0.0
        && o.max_turns >= 1;
    if ok {
        Cylinder::new(chi, km).ok()
    } else {
        None
    }
}

/// The turn bound n*: the smallest n with 2πn > θ0 and L(2πn) > 0 along rolling from
/// (θ0, θ̇0); None if it does not exist (α = 0 or χ = 0). Capped at max_turns + 1.
pub(crate) fn turn_bound(r: &Rolling, theta0: f64, omega0: f64, max_turns: u32) -> Option<u32> {
    let chi = r.body.chi;
    if chi == 0.0 || r.sin_a == 0.0 {
        return None;
    }
    let cap = max_turns as u64 + 1;
    let n_lo = ((theta0 / TAU).floor() + 1.0).max(1.0);
    if n_lo > cap as f64 {
        return Some(cap as u32);
    }
    // L(2πn) > 0 ⇔ 2πn sin α > R with
    // R = cos α Ĩ_P(0)/(2χ) − K0 + θ0 sin α − χ(cos(α + θ0) − cos α).
    let k0 = 0.5 * r.contact_inertia(theta0.cos()) * omega0 * omega0;
    let ip0 = r.body.ic + 1.0 + 2.0 * chi;
    let rhs = r.cos_a * ip0 / (2.0 * chi) - k0 + theta0 * r.sin_a
        - chi * ((r.alpha + theta0).cos() - r.cos_a);
    let per = TAU * r.sin_a;
    let guess = (rhs / per).floor() + 1.0;
    let mut n = guess.max(n_lo).min(cap as f64) as u64;
    while n > n_lo as u64 && (n - 1) as f64 * per > rhs {
        n -= 1;
    }
    while n < cap && n as f64 * per <= rhs {
        n += 1;
    }
    Some(n as u32)
}

/// Classifies one point. Never panics; invalid parameters give `InvalidParams`.
pub fn classify(alpha: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> JarmResult {
    let Some(body) = valid_body(alpha, chi, km, mu_s, o) else {
        return JarmResult::new(Reason::InvalidParams);
    };
    let Ok(r) = Rolling::new(body, alpha) else {
        return JarmResult::new(Reason::InvalidParams);
    };
    let path = RollingPath::new(&r, o.theta0, o.omega0, mu_s);
    // An equilibrium start (θ̇0 = 0 and θ̈0 = 0, e.g. α = 0 from rest): nothing ever happens.
    if o.omega0 == 0.0 {
        let p0 = path.eval(o.theta0);
        if p0.omega_dot == 0.0 && p0.fy > 0.0 && mu_s * p0.fy >= p0.fx.abs() {
            return JarmResult::new(Reason::NoRoot);
        }
    }
    // Where to stop looking.
    let (mut theta_end, end_reason) = match turn_bound(&r, o.theta0, o.omega0, o.max_turns) {
        None => (o.theta0 + TAU, Reason::NoRoot), // α = 0 or χ = 0: periodic, one turn suffices
        Some(n) if n > o.max_turns => (TAU * o.max_turns as f64, Reason::TurnLimit),
        Some(n) => (TAU * n as f64, Reason::NoRoot),
    };
    if o.n > 0 {
        let lim = TAU * o.n as f64 + PI;
        if lim < theta_end {
            theta_end = lim;
        }
    }
    if theta_end <= o.theta0 {
        return JarmResult::new(Reason::NoRoot);
    }
    let watch = Watch {
        normal_force: true,
        friction: true,
        liftoff: o.rule == Rule::Paper,
        energy: true,
        refine_extrema: o.refine_extrema,
        coarseness: 1,
    };
    let s = path.scan(theta_end, watch);
    let th = s.at.theta;
    let at_start = th <= o.theta0;
    let mut res = match (o.rule, s.event) {
        (_, PathEvent::End) => JarmResult::with_scan(end_reason, &s),
        (_, PathEvent::RocksBack) => {
            let mut x = JarmResult::with_scan(Reason::RocksBack, &s);
            x.theta_event = th;
            x
        }
        (Rule::Paper, PathEvent::Liftoff) => {
            if at_start {
                liftoff_earlier(&s, th)
            } else {
                let jf = jump_forces(&body, alpha, th);
                let green = green_turn(alpha, th);
                if green.is_none() || jf.fy <= 0.0 {
                    failure(Reason::NormalForceLost, &s, th)
                } else if mu(&body, th) > mu_s {
                    let mut x = failure(Reason::SlipAtJump, &s, th);
                    x.theta_j = th;
                    x
                } else {
                    let mut x = JarmResult::with_scan(Reason::Jarm, &s);
                    x.n = green.unwrap_or(0);
                    x.theta_j = th;
                    x.fx_j = jf.fx;
                    x.fy_j = jf.fy;
                    x
                }
            }
        }
        (Rule::Paper, PathEvent::NormalForce) => failure(Reason::NormalForceLost, &s, th),
        (Rule::Paper, PathEvent::Slip) => {
            // Continue along rolling to the paper's lift-off point: if it is in a green
            // window and ineq2 fails there, the jump-point test alone rejects the point.
            // Only the parts of each turn where L can reach 0 are scanned.
            let lift = path.scan_liftoff_from(th, theta_end.max(th), 3);
            let tl = lift.at.theta;
            if lift.event == PathEvent::Liftoff
                && green_turn(alpha, tl).is_some()
                && mu(&body, tl) > mu_s
            {
                let mut x = failure(Reason::SlipAtJump, &s, th);
                x.theta_j = tl;
                x
            } else {
                failure(Reason::SlipBefore, &s, th)
            }
        }
        (Rule::NormalForce, PathEvent::NormalForce) => {
            if at_start {
                liftoff_earlier(&s, th)
            } else {
                jarm_at(&s)
            }
        }
        (Rule::NormalForce, PathEvent::Slip) => {
            let p = &s.at;
            let sigma = if p.fx < 0.0 { -1.0 } else { 1.0 };
            let k = chi * p.sin_t - sigma * mu_s * (1.0 + chi * p.cos_t);
            let d = body.icm + chi * k * p.sin_t;
            let flight = p.fx == 0.0 || body.icm == 0.0 || p.lift >= 0.0 || d <= 0.0;
            if !flight {
                failure(Reason::SlipBefore, &s, th)
            } else if at_start {
                liftoff_earlier(&s, th)
            } else {
                jarm_at(&s)
            }
        }
        (Rule::NormalForce, PathEvent::Liftoff) => jarm_at(&s), // not watched
    };
    if o.n > 0 {
        res = restrict_to_turn(res, o.n);
    }
    res
}

fn failure(reason: Reason, s: &PathScan, th: f64) -> JarmResult {
    let mut x = JarmResult::with_scan(reason, s);
    x.theta_event = th;
    x.n = turn_of(th);
    x
}

fn liftoff_earlier(s: &PathScan, th: f64) -> JarmResult {
    let mut x = JarmResult::with_scan(Reason::LiftoffEarlier, s);
    x.theta_j = th;
    x.theta_event = th;
    x.n = turn_of(th);
    x
}

fn jarm_at(s: &PathScan) -> JarmResult {
    let mut x = JarmResult::with_scan(Reason::Jarm, s);
    x.theta_j = s.at.theta;
    x.n = turn_of(s.at.theta);
    x.fx_j = s.at.fx;
    x.fy_j = s.at.fy;
    x
}

/// First-jump semantics for a requested turn n.
pub(crate) fn restrict_to_turn(mut res: JarmResult, n: u32) -> JarmResult {
    match res.reason {
        Reason::Jarm if res.n == n => res,
        Reason::Jarm if res.n < n => {
            res.reason = Reason::LiftoffEarlier;
            res.is_jarm = false;
            res.theta_event = res.theta_j;
            res
        }
        Reason::Jarm => {
            res.reason = Reason::NoRoot;
            res.is_jarm = false;
            res
        }
        Reason::NormalForceLost | Reason::SlipBefore | Reason::SlipAtJump | Reason::RocksBack
            if res.n > n =>
        {
            res.reason = Reason::NoRoot;
            res
        }
        _ => res,
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn c(a_deg: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> JarmResult {
        classify(a_deg.to_radians(), chi, km, mu_s, o)
    }

    #[test]
    fn reason_codes_are_stable() {
        for (i, r) in Reason::ALL.iter().enumerate() {
            assert_eq!(r.code() as usize, i);
            assert_eq!(Reason::from_code(i as u8), Some(*r));
        }
        assert_eq!(Reason::from_code(9), None);
    }

    #[test]
    fn reference_jarm() {
        let o = JarmOptions::default();
        let r = c(40.0, 0.15, 0.02, 1.0, &o);
        assert_eq!(r.reason, Reason::Jarm);
        assert_eq!(r.n, 1);
        assert!((r.theta_j.to_degrees() - 334.344).abs() < 1e-3);
        assert!((r.fy_j - 0.01543).abs() < 1e-5 && (r.fx_j + 0.00516).abs() < 1e-5);
        // The paper's θ_{n,J} by bisection agrees.
        let ramp = Rolling::new(Cylinder::new(0.15, 0.02).unwrap(), 40f64.to_radians()).unwrap();
        let t = crate::from_rest::theta_nj(&ramp, 1).unwrap();
        assert!((t - r.theta_j).abs() < 1e-12);
        // The max friction ratio on the path is at the jump: μ(θ_J).
        assert!(r.max_ratio <= 1.0);
        // Explicit n.
        assert_eq!(
            c(40.0, 0.15, 0.02, 1.0, &JarmOptions { n: 1, ..o }).reason,
            Reason::Jarm
        );
        assert_eq!(
            c(40.0, 0.15, 0.02, 1.0, &JarmOptions { n: 2, ..o }).reason,
            Reason::LiftoffEarlier
        );
        // Classical rule: also a JARM, later lift-off.
        let k = c(
            40.0,
            0.15,
            0.02,
            1.0,
            &JarmOptions {
                rule: Rule::NormalForce,
                ..o
            },
        );
        assert_eq!(k.reason, Reason::Jarm);
        assert!(k.theta_j > r.theta_j && (k.theta_j - r.theta_j).to_degrees() < 2.0);
    }

    #[test]
    fn reference_slip() {
        let o = JarmOptions::default();
        let r = c(30.0, 0.5, 0.4, 1.0, &o);
        assert!(!r.is_jarm);
        assert!(matches!(r.reason, Reason::SlipAtJump | Reason::SlipBefore));
        assert!((r.theta_event.to_degrees() - 316.47).abs() < 0.01);
        // The paper's lift-off on this path (≈ 325.5°) lies before the green window
        // (330°, 360°): JtaC1 fails, so the jump-point test has nothing to reject; the path
        // test catches the slip.
        assert_eq!(r.reason, Reason::SlipBefore);
        let ramp = Rolling::new(Cylinder::new(0.5, 0.4).unwrap(), 30f64.to_radians()).unwrap();
        assert!(crate::from_rest::jtac1(&ramp, 1) > 0.0);
        // Same body at 40°: the lift-off is in the window and needs μ > 1 (μ_s,min = 1.39).
        let r = c(40.0, 0.5, 0.4, 1.0, &o);
        assert!(!r.is_jarm, "{r:?}");
        let k = c(
            30.0,
            0.5,
            0.4,
            1.0,
            &JarmOptions {
                rule: Rule::NormalForce,
                ..o
            },
        );
        assert!(!k.is_jarm);
    }

    #[test]
    fn invalid_params_never_panic() {
        let o = JarmOptions::default();
        for &(a, chi, km, mu) in &[
            (f64::NAN, 0.1, 0.1, 1.0),
            (-0.1, 0.1, 0.1, 1.0),
            (1.6, 0.1, 0.1, 1.0),
            (0.5, 1.1, 0.0, 1.0),
            (0.5, 0.5, 0.6, 1.0),
            (0.5, 0.5, 0.1, -1.0),
            (0.5, 0.5, 0.1, f64::NAN),
            (0.5, 0.5, -0.1, 1.0),
        ] {
            assert_eq!(classify(a, chi, km, mu, &o).reason, Reason::InvalidParams);
        }
        let bad = JarmOptions { omega0: -1.0, ..o };
        assert_eq!(
            classify(0.5, 0.1, 0.1, 1.0, &bad).reason,
            Reason::InvalidParams
        );
    }

    #[test]
    fn limits() {
        let o = JarmOptions::default();
        // α = 0: never a JARM (at rest: an equilibrium).
        for &(chi, km) in &[(0.3, 0.2), (0.0, 0.5), (1.0, 0.0), (0.5, 0.0)] {
            assert!(!classify(0.0, chi, km, 1.0, &o).is_jarm);
            assert!(!classify(0.0, chi, km, 1.0, &JarmOptions { omega0: 1.0, ..o }).is_jarm);
        }
        // χ = 0: no lift-off; slips at the start if μ_s < k_m tan α/(1 + k_m).
        assert_eq!(classify(0.5, 0.0, 0.3, 1.0, &o).reason, Reason::NoRoot);
        assert_eq!(classify(1.5, 0.0, 0.9, 0.1, &o).reason, Reason::SlipBefore);
        // α = π/2 from rest: F_y = 0 at the start.
        let r = classify(FRAC_PI_2, 0.3, 0.2, 1.0, &o);
        assert!(!r.is_jarm, "{r:?}");
        // χ = 1, k_m = 0 (Ĩ_CM = 0): F_x = χ sin θ F_y/(1 + χ cos θ), so the friction ratio is
        // |tan(θ/2)| (diverging at the singular θ = π) and margins vanish with F_y.
        let r = classify(0.5, 1.0, 0.0, 1.0, &o);
        assert_eq!(r.reason, Reason::NormalForceLost, "{r:?}");
        assert!((0.5 * r.theta_event).tan() < 1.0);
        let r = classify(0.5, 1.0, 0.0, 0.3, &o);
        assert_eq!(r.reason, Reason::SlipBefore, "{r:?}");
        assert!(((0.5 * r.theta_event).tan() - 0.3).abs() < 1e-9);
        let r = classify(0.5, 1.0, 0.0, 1e6, &o);
        assert!(!r.is_jarm && r.theta_event < PI, "{r:?}");
        // Tiny α: many turns, bounded, or the turn cap.
        let r = classify(1e-4, 0.3, 0.2, 1.0, &JarmOptions { max_turns: 10, ..o });
        assert_eq!(r.reason, Reason::TurnLimit);
    }

    #[test]
    fn monotone_in_mu_s_and_alpha_zero() {
        let o = JarmOptions::default();
        let mus = [0.3, 0.5, 0.7, 1.0, 1.5, 2.5, 5.0];
        let mut jarms = 0;
        for i in 1..=30 {
            let a = 90.0 * i as f64 / 31.0;
            for j in 1..=12 {
                let chi = j as f64 / 13.0;
                for l in 0..5 {
                    let km = (1.0 - chi) * l as f64 / 5.0;
                    let mut was = false;
                    for &m in &mus {
                        let r = c(a, chi, km, m, &o);
                        if was {
                            assert!(r.is_jarm, "{a} {chi} {km} {m}: {r:?}");
                        }
                        was = r.is_jarm;
                        jarms += r.is_jarm as u32;
                    }
                }
            }
        }
        assert!(jarms > 0);
    }

    #[test]
    fn rules_agree_away_from_boundaries() {
        // Classification agrees; θ_J differs by < ~2°. Points whose decisive margins are
        // within a hair of the boundary (μ_s ± 2 %) are skipped.
        let o = JarmOptions::default();
        let k = JarmOptions {
            rule: Rule::NormalForce,
            ..o
        };
        let (mut agree, mut both, mut skipped, mut max_dth) = (0, 0, 0, 0.0f64);
        for i in 1..=40 {
            let a = 90.0 * i as f64 / 41.0;
            for j in 1..=15 {
                let chi = j as f64 / 16.0;
                // k_m = 0 (Ĩ_CM = 0) is a boundary where the rules differ: see below.
                for l in 1..6 {
                    let km = (1.0 - chi) * l as f64 / 6.0;
                    let p = c(a, chi, km, 1.0, &o);
                    let lo = c(a, chi, km, 0.98, &o);
                    let hi = c(a, chi, km, 1.02, &o);
                    if lo.is_jarm != hi.is_jarm {
                        skipped += 1;
                        continue;
                    }
                    let q = c(a, chi, km, 1.0, &k);
                    assert_eq!(p.is_jarm, q.is_jarm, "{a} {chi} {km}: {p:?} {q:?}");
                    agree += 1;
                    if p.is_jarm {
                        both += 1;
                        max_dth = max_dth.max((q.theta_j - p.theta_j).abs());
                        assert!(q.theta_j >= p.theta_j);
                    }
                }
            }
        }
        assert!(both > 0 && agree > 1000, "{agree} {both} {skipped}");
        assert!(max_dth.to_degrees() < 2.5, "{}", max_dth.to_degrees());
    }

    #[test]
    fn turns_and_overlaps_from_rest() {
        // Each point has at most one n (first-jump semantics); find which n occur.
        let o = JarmOptions::default();
        let mut seen = [0u32; 8];
        for i in 1..=60 {
            let a = 30.0 * i as f64 / 61.0;
            for j in 1..=20 {
                let chi = 0.3 * j as f64 / 21.0;
                for l in 0..4 {
                    let km = (1.0 - chi) * l as f64 / 4.0;
                    let r = c(a, chi, km, 1.0, &o);
                    if r.is_jarm {
                        seen[(r.n as usize).min(7)] += 1;
                        for n in 1..6 {
                            let e = c(a, chi, km, 1.0, &JarmOptions { n, ..o });
                            assert_eq!(e.is_jarm, n == r.n);
                        }
                    }
                }
            }
        }
        assert!(seen[1] > 0, "{seen:?}");
    }
}

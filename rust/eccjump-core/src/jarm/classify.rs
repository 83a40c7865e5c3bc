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

use crate::jarm::decision::{decide, point_ramp, search_end, Case, EventPoint, Extrema, Found};
use crate::jarm::jump_point::may_be_green;
use crate::jarm::path::{PathScan, RollingPath, Watch};
use crate::jarm::result::{JarmOptions, JarmResult, Reason};
use crate::mechanics::Rule;
use crate::modes::rolling::events::equilibrium_start;

impl PathScan {
    /// The scan's outcome for the shared decision tree.
    fn found(&self, theta0: f64) -> Found {
        let p = &self.at;
        Found {
            event: self.event,
            at_start: p.theta <= theta0,
            at: EventPoint {
                theta: p.theta,
                sin_t: p.sin_t,
                cos_t: p.cos_t,
                fx: p.fx,
                fy: p.fy,
                lift: p.lift,
            },
            extrema: Extrema {
                max_ratio: self.max_ratio,
                theta_max_ratio: self.theta_max_ratio,
                min_fy: self.min_fy,
                theta_min_fy: self.theta_min_fy,
            },
        }
    }
}

/// Classifies one point. Never panics; invalid parameters give `InvalidParams`.
pub fn classify(alpha: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> JarmResult {
    let Some(r) = point_ramp(alpha, chi, km, mu_s, o) else {
        return JarmResult::new(Reason::InvalidParams);
    };
    let path = RollingPath::new(&r, o.theta0, o.omega0, mu_s);
    let p0 = path.start();
    if equilibrium_start(o.omega0, p0.omega_dot, p0.fx, p0.fy, mu_s) {
        return JarmResult::new(Reason::NoRoot);
    }
    let Some((theta_end, end_reason)) = search_end(&r, o) else {
        return JarmResult::new(Reason::NoRoot);
    };
    let watch = Watch {
        normal_force: true,
        friction: true,
        liftoff: o.rule == Rule::Paper,
        refine_extrema: o.refine_extrema,
        coarseness: 1,
    };
    let s = path.scan(theta_end, watch);
    let case = Case {
        body: &r.body,
        alpha,
        mu_s,
        rule: o.rule,
        end_reason,
        stop_at_slip: o.stop_at_slip,
    };
    // After a slip (paper rule): only the parts of each turn where L can reach 0 are scanned.
    let th = s.at.theta;
    // Only a lift-off in a green window can make the slip `SlipAtJump`.
    let liftoff_after_slip = || {
        let green = |lo, hi| may_be_green(alpha, lo, hi);
        path.liftoff_after(th, theta_end.max(th), 3, green)
    };
    let res = decide(&case, &s.found(o.theta0), liftoff_after_slip);
    crate::jarm::decision::restrict_to_turn(res, o.n)
}

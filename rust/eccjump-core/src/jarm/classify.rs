//! Classification of one point (α, χ, k_m, μ_s) by the closed forms: does the cylinder jump
//! after pure rolling (a JARM), and if not, why. Start from rest at θ0 = 0 by default, or any
//! (θ0, θ̇0 ≥ 0). The two lift-off rules ([`Rule`]), the first-jump semantics (the first thing
//! that happens on the path decides), the search bound 2πn* and the turn of an event are as
//! `docs/jarm.md` ("Lift-off rules") states them: the rigorous path scan ([`crate::jarm::path`])
//! finds the first event, the jump-point formulas ([`crate::jarm::jump_point`]) test a lift-off,
//! and the decision tree shared with the ODE route ([`crate::jarm::decision`]) gives the verdict.

use crate::jarm::decision::{decide, point_ramp, search_end, Case, EventPoint, Found};
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
            extrema: self.extrema,
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

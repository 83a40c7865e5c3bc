//! The first event on a grid cell: where each watched constraint is first violated (its
//! crossing, or the minimum inside the cell), and which constraint wins (the tie order).

use super::scan::clear;
use super::{violated, ContactEvent, PathPoint, RollingPath, NG};
use super::{G_ENERGY, G_FY, G_MMINUS, G_MPLUS, G_NOLIFT};
use crate::ode::hermite::{hermite_min, hermite_root};
use crate::ode::roots::{brent, newton_bracketed};

/// The order in which simultaneous events are resolved (the shared catalogue's): lift-off,
/// normal force, friction, energy.
const TIE_ORDER: [usize; NG] = [G_NOLIFT, G_FY, G_MPLUS, G_MMINUS, G_ENERGY];

/// The position of constraint k in [`TIE_ORDER`].
#[inline]
fn tie_rank(k: usize) -> usize {
    TIE_ORDER.iter().position(|&o| o == k).unwrap_or(NG)
}

pub(super) fn event_of(k: usize) -> ContactEvent {
    match k {
        G_FY => ContactEvent::NormalForce,
        G_MPLUS | G_MMINUS => ContactEvent::Slip,
        G_NOLIFT => ContactEvent::Liftoff,
        _ => ContactEvent::RocksBack,
    }
}

impl RollingPath {
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
    pub(super) fn min_location(
        &self,
        k: usize,
        lo: &PathPoint,
        hi: &PathPoint,
        evals: &mut u32,
    ) -> PathPoint {
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
    pub(super) fn first_violation(
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

    /// The first violation on the cell [a, b] of a watched constraint that is not clear there:
    /// the constraint and the point, None if there is none after all.
    ///
    /// Constraints are examined in tie order ([`TIE_ORDER`]); after a first violation at bx
    /// only an earlier one can win, so the next ones are examined on [θa, bx] (usually no root
    /// search: the point at bx is known). Where the cubic-Hermite roots say clearly which
    /// constraint crosses first ([`Self::leader`]), that one is located first, so the others
    /// need no root search of their own; the tie rule keeps the result of the plain order.
    pub(super) fn first_event(
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
}

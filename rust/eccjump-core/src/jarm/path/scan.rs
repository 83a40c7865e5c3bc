//! The scan along the rolling path, cell by cell.
//!
//! "A thin violation between sample points must not be missed": the functions and their
//! analytic derivatives are sampled on a grid of ≤ 2π/24 (`SAMPLES_PER_TURN`; finer where
//! Ĩ_P is small: step ≤ ¼√(Ĩ_P/χ), the width of the near-singular peak at θ = π for χ → 1,
//! k_m → 0); a violation inside a cell needs an interior minimum, i.e. a sign change − → + of
//! g' on the cell; its value is estimated by the cubic Hermite interpolant, and unless that is
//! clearly positive (> 10 % of the smaller end value) the minimum is located by Brent on g'
//! and checked; crossings are refined by Brent. The assumption is only that g' changes sign
//! at most once per cell, which the grid guarantees for these trig polynomials over Ĩ_P^k.

use super::events::event_of;
use super::extremum::{track, Extremum};
use super::skip::SKIP_MIN_TURNS;
use super::{violated, PathPoint, PathScan, RollingPath, Watch, NG, SAMPLES_PER_TURN};
use super::{ContactEvent, G_ENERGY, G_NOLIFT};
use crate::modes::rolling::events::{violated_at_start, StartValues, Watched};
use crate::ode::hermite::hermite_min;
use std::f64::consts::TAU;

/// Uniform scan steps between direct `sin_cos` evaluations (the others rotate the previous
/// half-angle sin/cos, re-anchored every ROTATIONS + 1 samples): ≤ 1.2e-15 absolute error,
/// about the rounding of θ itself beyond one turn (ulp(2π) = 8.9e-16). Seven rotations
/// halve the direct calls of three (2–3 % of a map) for 0.6e-15 more.
pub(super) const ROTATIONS: u32 = 7;

/// (sin(h/2), 1 − cos(h/2)) for the rotation of half-angles by h/2 in the increment form
/// s' = s + (c sin − s (1 − cos)), c' = c − (s sin + c (1 − cos)): ~½ ulp per step.
#[inline]
pub(super) fn rotation(h: f64) -> (f64, f64) {
    let (s4, c4) = crate::trig::sin_cos(0.25 * h);
    (2.0 * s4 * c4, 2.0 * s4 * s4)
}

/// True if g_k certainly stays unviolated on the cell [a, b] by the tests of
/// `first_violation` (not violated at b, and no interior minimum, or one whose cubic-Hermite
/// estimate is clearly positive: > 10 % of the smaller end value).
#[inline(always)]
pub(super) fn clear(k: usize, a: &PathPoint, b: &PathPoint) -> bool {
    clear_values(k, a.g[k], a.dg[k], b.g[k], b.dg[k], b.theta - a.theta)
}

/// [`clear`] from g_k and g_k' at the ends of a cell of width h.
#[inline(always)]
pub(super) fn clear_values(k: usize, ga: f64, da: f64, gb: f64, db: f64, h: f64) -> bool {
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

/// What a scan watches and how it steps, fixed for one scan.
pub(super) struct Grid {
    pub(super) act: [bool; NG],
    pub(super) theta_end: f64,
    pub(super) coarseness: f64,
    /// The rigorous grid (coarseness 1): only its scans skip turns.
    rigorous: bool,
    /// The uniform step: [`RollingPath::step`] away from the singular peak, times the
    /// coarseness.
    pub(super) h_uni: f64,
    /// [`rotation`] of `h_uni`.
    pub(super) sh: f64,
    pub(super) vh: f64,
    /// A generous cap on cells (the floor step keeps progress finite anyway).
    pub(super) max_cells: u64,
}

impl Grid {
    pub(super) fn new(theta_start: f64, theta_end: f64, watch: Watch) -> Self {
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
pub(super) struct Cursor {
    /// Two slots for the cell ends, used alternately (no copy of the points); `ia` is the
    /// cell start.
    pub(super) pts: [PathPoint; 2],
    pub(super) ia: usize,
    pub(super) su: f64,
    pub(super) cu: f64,
    pub(super) rotated: u32,
    pub(super) cells: u64,
    pub(super) evals: u32,
    pub(super) min_fy: Extremum,
    pub(super) max_r: Extremum,
}

impl Cursor {
    /// A cursor at `p0`, whose half-angle sin/cos are (su, cu).
    pub(super) fn start(
        p0: PathPoint,
        (su, cu): (f64, f64),
        min_fy: Extremum,
        max_r: Extremum,
    ) -> Self {
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

/// Why [`RollingPath::advance`] returned.
pub(super) enum Stop {
    /// A watched constraint is violated at this point (the first one on the path).
    Event(ContactEvent, PathPoint),
    /// The scan reached its end (or its cell cap) with no event.
    End,
    /// A cell ended at or after the requested angle, with no event.
    Reached,
}

impl RollingPath {
    /// Scans the rolling path from θ0 to `theta_end` and stops at the first violated watched
    /// constraint (ties resolved in the order lift-off, normal force, friction, energy).
    pub fn scan(&self, theta_end: f64, watch: Watch) -> PathScan {
        self.scan_from(self.theta0, theta_end, watch)
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
    pub(super) fn scan_cells(
        &self,
        theta_start: f64,
        theta_end: f64,
        watch: Watch,
        skip: bool,
    ) -> PathScan {
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
            Stop::End | Stop::Reached => (ContactEvent::ThetaLimit, cur.pts[cur.ia]),
        };
        let Cursor {
            min_fy,
            max_r,
            evals,
            ..
        } = cur;
        self.finish(event, at, min_fy, max_r, evals, watch.refine_extrema)
    }

    /// Advances the cursor cell by cell until an event, the end of the scan, or a cell ending
    /// at or after `until` (`Stop::Reached`; the cursor then starts the next cell). `observe`
    /// sees every new sample with its half-angle (sin, cos) of (θ − θ0)/2.
    #[inline(always)]
    pub(super) fn advance(
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
}

//! The paper's lift-off after a slip: the search visits only the windows of each turn where
//! L can reach 0, skipping the windows that provably hold none.

use super::scan::{clear_values, Grid, ROTATIONS};
use super::skip::{last_clean, SKIP_MARGIN_SHARE, SKIP_MARGIN_TURNS};
use super::{violated, ContactEvent, RollingPath, Watch, G_ENERGY, G_NOLIFT};
use crate::modes::rolling::events::liftoff_at_start;
use std::f64::consts::{FRAC_PI_2, TAU};

/// What the lift-off scan of one window found ([`RollingPath::window_liftoff`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub(super) enum WindowLift {
    /// No lift-off in the window.
    Clean,
    /// The first lift-off, located.
    At(f64),
    /// A lift-off in a cell whose exact angle does not matter to the caller.
    Within,
}

impl RollingPath {
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
        let chi = self.ramp.body.chi;
        let guaranteed = self.ramp.cos_a > 0.0
            && self.ramp.sin_a > 0.0
            && chi > 0.0
            && self.energy_stays_positive(theta_start);
        if !guaranteed || theta_end <= theta_start || theta_end.is_nan() {
            return plain();
        }
        // L < 0 on window m while 2χ E_ub(2πm + π/2) ≤ cos α (Ĩ_C + 1) (with a margin).
        let need = self.ramp.cos_a * (self.ramp.body.ic + 1.0) / (2.0 * chi) * (1.0 - 1e-9);
        let e_ub =
            |theta: f64| self.k0 + (theta - self.theta0) * self.ramp.sin_a + chi * (self.ca0 + 1.0);
        // First window that can hold L ≥ 0: θ_hi = 2πm + π/2 with E_ub(θ_hi) > need.
        let theta_need = self.theta0 + (need - e_ub(self.theta0)) / self.ramp.sin_a;
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
    ///
    /// [`Ramp::energy_minimum_after`]: crate::mechanics::Ramp::energy_minimum_after
    pub(super) fn energy_stays_positive(&self, theta_start: f64) -> bool {
        let chi = self.ramp.body.chi;
        let e_low =
            self.k0 + (theta_start - self.theta0) * self.ramp.sin_a + chi * (self.ca0 - 1.0);
        if e_low > 0.0 {
            return true;
        }
        let margin = |theta: f64| {
            1e-12 * (self.k0 + (theta - self.theta0).abs() * self.ramp.sin_a + 2.0 * chi)
        };
        let p = self.eval(theta_start);
        let (e, de) = (p.g[G_ENERGY], p.dg[G_ENERGY]);
        let start = e > margin(theta_start) || (e >= 0.0 && de > 1e-12 * (self.ramp.sin_a + chi));
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
    ///
    /// [`violated_at_start`]: crate::modes::rolling::events::violated_at_start
    pub(super) fn window_liftoff(
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
    pub(super) fn last_clean_window(
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
    pub(super) fn clean_window(
        &self,
        target: f64,
        window: &impl Fn(f64) -> Option<(f64, f64, bool)>,
        grid: &Grid,
    ) -> Option<f64> {
        let (lo, hi, whole) = window(target)?;
        let clean = whole && self.window_liftoff(lo, hi, grid, &|_, _| false) == WindowLift::Clean;
        clean.then_some(target)
    }
}

//! Skipping whole turns of a long scan that provably hold no event, and the bisection
//! behind the skips (of turns here, of lift-off windows in [`super::liftoff`]).

use super::scan::{Cursor, Grid, Stop};
use super::{violated, PathPoint, RollingPath, NG};
use std::f64::consts::TAU;

/// Scans spanning at least this many turns try to skip turns ([`RollingPath::skip_turns`]).
pub(super) const SKIP_MIN_TURNS: f64 = 6.0;
/// The turn whose samples estimate how many turns stay clean (turn 1 is the start's).
const SKIP_RECORD_TURN: f64 = 2.0;
/// The scan restarts this many turns, plus this share of the estimated clean turns, before
/// the first turn estimated to violate (samples miss the minima between them).
pub(super) const SKIP_MARGIN_TURNS: f64 = 1.0;
pub(super) const SKIP_MARGIN_SHARE: f64 = 0.1;

impl RollingPath {
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
    pub(super) fn skip_turns(&self, cur: &mut Cursor, grid: &Grid, theta_start: f64) -> Stop {
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
    pub(super) fn bisect_turns(
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
}

/// The last turn (or window) m in [clean, dirty) with `is_clean(m)`, given that `clean` is
/// clean and `dirty` is not, and that the clean ones from `clean` on are consecutive: by
/// bisection on the integers, `is_clean` asked about log₂(dirty − clean) times, in
/// increasing order of the clean answers (a skip may keep the state of the last clean probe).
pub(super) fn last_clean((clean, dirty): (f64, f64), mut is_clean: impl FnMut(f64) -> bool) -> f64 {
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

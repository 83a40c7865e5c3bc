//! The reported extrema of a scan (the smallest F_y, the largest |F_x|/F_y): tracked cell
//! by cell, refined in their cells at the end.

use super::{ContactEvent, Extrema, PathPoint, PathScan, RollingPath, G_FY};
use crate::ode::hermite::hermite_min;
use crate::ode::roots::brent;

/// The running extremum of a tracked quantity (for reporting): the best sample, and the cell
/// whose interior extremum (Hermite estimate) is best, refined at the end, with the runner-up
/// cell, refined too when the two estimates are a near tie.
#[derive(Clone, Copy)]
pub(super) struct Extremum {
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
    pub(super) fn start(value: f64, theta: f64, worst: f64) -> Self {
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
    pub(super) fn sample(&mut self, value: f64, theta: f64) {
        if value < self.value {
            (self.value, self.theta) = (value, theta);
        }
    }

    /// A sample value for a running maximum (the earlier sample wins ties).
    #[inline]
    pub(super) fn sample_max(&mut self, value: f64, theta: f64) {
        if value > self.value {
            (self.value, self.theta) = (value, theta);
        }
    }
}

/// Updates the reported extrema with the cell [a, b]: end values, and an interior extremum
/// (derivative sign change) estimated by the cubic Hermite interpolant, refined at the end.
#[inline]
pub(super) fn track(a: &PathPoint, b: &PathPoint, min_fy: &mut Extremum, max_r: &mut Extremum) {
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

impl RollingPath {
    pub(super) fn finish(
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
            extrema: Extrema {
                max_ratio: max_r.value,
                theta_max_ratio: max_r.theta,
                min_fy: min_fy.value,
                theta_min_fy: min_fy.theta,
            },
            evaluations: evals,
        }
    }
}

//! Event functions g_k(t, y): their specs, and location of their zeros on the dense output.

use super::{DenseStep, State};
use crate::ode::roots;

/// Which zero crossings of g count.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Direction {
    /// Any sign change.
    Any,
    /// g goes from negative to positive.
    Rising,
    /// g goes from positive to negative.
    Falling,
}

/// How an event behaves when it is met.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct EventSpec {
    /// Which zero crossings count.
    pub direction: Direction,
    /// A terminal event stops the integration at its root.
    pub terminal: bool,
}

/// A set of event functions, evaluated by index (no boxing, no allocation).
pub trait EventFunctions<const N: usize> {
    /// Number of event functions.
    fn count(&self) -> usize;
    /// Direction and terminality of event k.
    fn spec(&self, k: usize) -> EventSpec;
    /// g_k(t, y).
    fn value(&self, k: usize, t: f64, y: &State<N>) -> f64;
    /// g_first, g_first+1, … at one point, into `out`. Override it when the events share
    /// work (trigonometry of the state, say): the step scan calls this at every sample.
    #[inline]
    fn values(&self, first: usize, t: f64, y: &State<N>, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = self.value(first + i, t, y);
        }
    }
    /// Bounds D_first, D_first+1, … on how much each event function can change within the
    /// step `dense`, into `out`: any D_k ≥ L_k |h| + 4 δ_k, where L_k bounds
    /// |d/dt g_k(t, y(t))| along the dense output y(t) over the whole step and δ_k bounds
    /// the error of a computed g_k there (rounding of g_k and of y(t), and the difference
    /// between the exact step end and the interpolant at σ = 1).
    ///
    /// The step scan uses them to skip the interior samples: if the computed values at
    /// the step ends have one sign and |g_a| + |g_b| > D_k, then the exact g_k stays
    /// above δ_k in magnitude throughout the step (it cannot fall faster than L_k from
    /// either end), so every computed interior sample has that same sign and cannot show
    /// a crossing. The default, +∞, never skips.
    #[inline]
    fn change_bounds(&self, first: usize, dense: &DenseStep<N>, out: &mut [f64]) {
        let _ = (first, dense);
        out.fill(f64::INFINITY);
    }
}

/// Events evaluated together per sample in the step scan (a stack buffer; more events
/// are handled in chunks of this size).
pub const EVENT_CHUNK: usize = 8;

/// The empty event set.
pub struct NoEvents;

impl<const N: usize> EventFunctions<N> for NoEvents {
    fn count(&self) -> usize {
        0
    }
    fn spec(&self, _k: usize) -> EventSpec {
        unreachable!("NoEvents has no events")
    }
    fn value(&self, _k: usize, _t: f64, _y: &State<N>) -> f64 {
        unreachable!("NoEvents has no events")
    }
}

// ---------------------------------------------------------------------------------------
// Detection and location of event zeros within one accepted step.
//
// Each step is cut into `samples + 1` sub-intervals by equally spaced interior points of
// the dense output; a crossing of event k is a sign change of g_k over a sub-interval.
// Zeros are attributed to the sub-interval they END: a crossing needs a strictly nonzero
// g at the left end. Hence a zero exactly at a sample or step boundary is reported once
// (by the interval it closes), and a zero at the very start t0 is never reported.
//
// Nothing is stored per event (the number of events is only known at run time and the
// loop must not allocate): a first pass walks each event's samples to find the earliest
// sub-interval with any crossing — the common "nothing happens" case costs
// samples + 2 evaluations of each g. Only when something crosses, a second pass sweeps
// the sub-intervals in time order from there, re-evaluating g at their ends (the same
// points, hence the same values), and locates the roots with Brent's method.
// ---------------------------------------------------------------------------------------

/// Does the change of g from `a` to `b` (in the order of integration) count as a
/// crossing for `direction`? The left value must be nonzero (see above).
#[inline]
pub fn crosses(direction: Direction, a: f64, b: f64) -> bool {
    let rising = a < 0.0 && b >= 0.0;
    let falling = a > 0.0 && b <= 0.0;
    match direction {
        Direction::Any => rising || falling,
        Direction::Rising => rising,
        Direction::Falling => falling,
    }
}

/// An event function returned NaN or ±inf while the step was scanned.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct NonFiniteEvent;

/// An event met within a step.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct EventHit<const N: usize> {
    /// Index k of the event function.
    pub index: usize,
    /// Time of the root.
    pub t: f64,
    /// State at the root (from the dense output).
    pub y: State<N>,
}

/// The event values at the end of the last scanned step, which are the values at the
/// start of the next step (the same t and y, bit for bit), so the scan reuses them
/// instead of evaluating the events again. Kept only when all events fit in one chunk;
/// reused only when t and y match exactly.
#[derive(Debug, Clone, Copy)]
pub struct EventCarry<const N: usize> {
    t: f64,
    y: State<N>,
    g: [f64; EVENT_CHUNK],
    valid: bool,
}

impl<const N: usize> Default for EventCarry<N> {
    fn default() -> Self {
        Self {
            t: 0.0,
            y: State::<N>::zeros(),
            g: [0.0; EVENT_CHUNK],
            valid: false,
        }
    }
}

impl<const N: usize> EventCarry<N> {
    #[inline]
    fn matches(&self, t: f64, y: &State<N>) -> bool {
        self.valid
            && self.t.to_bits() == t.to_bits()
            && self
                .y
                .iter()
                .zip(y.iter())
                .all(|(a, b)| a.to_bits() == b.to_bits())
    }
}

/// Can the interior samples of a step be skipped for an event, given its computed values
/// at the step ends and its change bound (see [`EventFunctions::change_bounds`])? Both
/// ends finite, of one strict sign, and further from zero together than g can travel.
#[inline]
fn no_zero_inside(ga: f64, gb: f64, bound: f64) -> bool {
    let same_sign = (ga > 0.0 && gb > 0.0) || (ga < 0.0 && gb < 0.0);
    // A NaN bound compares false: no skip. The relative slack covers the rounding of
    // the bound itself and of the sum.
    same_sign && ga.is_finite() && gb.is_finite() && ga.abs() + gb.abs() > bound * (1.0 + 1e-9)
}

/// The sample points of one accepted step: its two ends (exact states) and `samples`
/// equally spaced interior points of the dense output.
struct StepSamples<'a, const N: usize> {
    dense: &'a DenseStep<N>,
    t_new: f64,
    y_new: &'a State<N>,
    samples: usize,
}

impl<const N: usize> StepSamples<'_, N> {
    /// Sample point j = 0..=samples + 1 (0 is the step start, samples + 1 its end).
    #[inline]
    fn point(&self, j: usize) -> (f64, State<N>) {
        if j == 0 {
            (self.dense.t_old, self.dense.y_old)
        } else if j > self.samples {
            (self.t_new, *self.y_new)
        } else {
            let t = self.dense.t_old + self.dense.h * (j as f64 / (self.samples + 1) as f64);
            (t, self.dense.eval(t))
        }
    }

    /// The state at a located root time (exact at the step end).
    #[inline]
    fn state_at(&self, t: f64) -> State<N> {
        if t == self.t_new {
            *self.y_new
        } else {
            self.dense.eval(t)
        }
    }
}

#[inline]
fn checked(g: f64) -> Result<f64, NonFiniteEvent> {
    if g.is_finite() {
        Ok(g)
    } else {
        Err(NonFiniteEvent)
    }
}

#[inline]
fn check_all(g: &[f64]) -> Result<(), NonFiniteEvent> {
    if g.iter().all(|v| v.is_finite()) {
        Ok(())
    } else {
        Err(NonFiniteEvent)
    }
}

/// Locates the zero of g_k on the sub-interval [ta, tb] (in integration order) where
/// g goes from ga to gb, to within ~4ε|t|. Returns the end of Brent's final bracket on
/// the far side of the crossing, so that g at the reported point has already changed
/// sign (or is zero): restarting the integration there does not find the same event.
fn locate<E: EventFunctions<N>, const N: usize>(
    events: &E,
    k: usize,
    dense: &DenseStep<N>,
    (ta, ga): (f64, f64),
    (tb, gb): (f64, f64),
) -> Result<f64, NonFiniteEvent> {
    let mut bad = false;
    let g = |t: f64| {
        let v = events.value(k, t, &dense.eval(t));
        bad |= !v.is_finite();
        v
    };
    let xtol = 4.0 * f64::EPSILON * ta.abs().max(tb.abs());
    let rtol = 4.0 * f64::EPSILON;
    let root = match roots::brent(g, ta, tb, ga, gb, xtol, rtol, 200) {
        Ok(r) => r,
        // Brent has a guaranteed bisection fallback; should it still not converge in
        // 200 iterations, bisect to the last bit, which always terminates.
        Err(_) if bad => return Err(NonFiniteEvent),
        Err(_) => {
            let g2 = |t: f64| {
                let v = events.value(k, t, &dense.eval(t));
                bad |= !v.is_finite();
                v
            };
            roots::bisect(g2, ta, tb, ga, gb).map_err(|_| NonFiniteEvent)?
        }
    };
    if bad {
        return Err(NonFiniteEvent);
    }
    Ok(if tb >= ta { root.hi } else { root.lo })
}

/// Finds the events of one accepted step (dense output `dense`, ending at (t_new, y_new))
/// and hands each to `report` in time order (ties by event index), stopping after the
/// first terminal one, which is returned. `carry` holds the end values of the previous
/// scanned step (start with `EventCarry::default()`).
pub fn scan_step<E: EventFunctions<N>, const N: usize>(
    events: &E,
    dense: &DenseStep<N>,
    t_new: f64,
    y_new: &State<N>,
    samples: usize,
    carry: &mut EventCarry<N>,
    mut report: impl FnMut(EventHit<N>),
) -> Result<Option<EventHit<N>>, NonFiniteEvent> {
    let n_events = events.count();
    if n_events == 0 {
        return Ok(None);
    }
    let pts = StepSamples {
        dense,
        t_new,
        y_new,
        samples,
    };
    let last = samples + 1;

    // Pass 1: the earliest sub-interval (ending at sample j_first) with any crossing.
    // All events of a chunk are evaluated together at each sample, so the dense output
    // and any shared work of the event functions are computed once per sample. The
    // start values come from the previous step's end when possible; the end values are
    // evaluated first (they are carried to the next step) and, when the events' change
    // bounds prove that no sample inside the step can show a crossing, the interior
    // samples are skipped. The end values are checked for finiteness only where they are
    // used, as the plain walk would.
    let carry_all = n_events <= EVENT_CHUNK;
    let mut j_first = usize::MAX;
    let mut g_a = [0.0; EVENT_CHUNK];
    let mut g_b = [0.0; EVENT_CHUNK];
    let mut g_end = [0.0; EVENT_CHUNK];
    let mut bound = [0.0; EVENT_CHUNK];
    for first in (0..n_events).step_by(EVENT_CHUNK) {
        let m = (n_events - first).min(EVENT_CHUNK);
        let (t, y) = pts.point(0);
        if carry_all && carry.matches(t, &y) {
            g_a[..m].copy_from_slice(&carry.g[..m]);
        } else {
            events.values(first, t, &y, &mut g_a[..m]);
        }
        check_all(&g_a[..m])?;
        events.values(first, t_new, y_new, &mut g_end[..m]);
        if carry_all {
            *carry = EventCarry {
                t: t_new,
                y: *y_new,
                g: g_end,
                valid: true,
            };
        }
        // Only sub-intervals before the earliest crossing found so far can matter.
        let limit = last.min(j_first.saturating_sub(1));
        if limit == 0 {
            continue;
        }
        if samples > 0 {
            events.change_bounds(first, dense, &mut bound[..m]);
            if (0..m).all(|i| no_zero_inside(g_a[i], g_end[i], bound[i])) {
                continue;
            }
        }
        for j in 1..=limit {
            if j == last {
                g_b = g_end;
            } else {
                let (t, y) = pts.point(j);
                events.values(first, t, &y, &mut g_b[..m]);
            }
            check_all(&g_b[..m])?;
            let any = (0..m).any(|i| crosses(events.spec(first + i).direction, g_a[i], g_b[i]));
            if any {
                j_first = j;
                break;
            }
            g_a = g_b;
        }
    }
    if j_first == usize::MAX {
        return Ok(None);
    }

    // Pass 2: sweep the sub-intervals in time order. Within one sub-interval several
    // events may cross; they are reported in order of (time, index) by repeatedly
    // picking the smallest one after the previous report (no buffer needed; more than
    // one crossing in a sub-interval is rare, so the quadratic cost is irrelevant).
    let forward = dense.h >= 0.0;
    let later = |a: (f64, usize), b: (f64, usize)| -> bool {
        // Is a strictly after b in integration order (ties broken by index)?
        if a.0 == b.0 {
            a.1 > b.1
        } else {
            (a.0 > b.0) == forward
        }
    };
    for j in j_first..=last {
        let (ta, ya) = pts.point(j - 1);
        let (tb, yb) = pts.point(j);
        let mut prev: Option<(f64, usize)> = None;
        loop {
            let mut best: Option<(f64, usize)> = None;
            for k in 0..n_events {
                let dir = events.spec(k).direction;
                let ga = checked(events.value(k, ta, &ya))?;
                let gb = checked(events.value(k, tb, &yb))?;
                if !crosses(dir, ga, gb) {
                    continue;
                }
                let t = locate(events, k, dense, (ta, ga), (tb, gb))?;
                let cand = (t, k);
                if prev.is_none_or(|p| later(cand, p)) && best.is_none_or(|b| later(b, cand)) {
                    best = Some(cand);
                }
            }
            let Some((t, k)) = best else { break };
            let hit = EventHit {
                index: k,
                t,
                y: pts.state_at(t),
            };
            report(hit);
            if events.spec(k).terminal {
                return Ok(Some(hit));
            }
            prev = best;
        }
    }
    Ok(None)
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn crossings_need_a_nonzero_left_value() {
        use Direction::*;
        assert!(crosses(Rising, -1.0, 1.0) && crosses(Rising, -1.0, 0.0));
        assert!(!crosses(Rising, 0.0, 1.0) && !crosses(Rising, 1.0, -1.0));
        assert!(crosses(Falling, 1.0, -1.0) && crosses(Falling, 1.0, 0.0));
        assert!(!crosses(Falling, 0.0, -1.0) && !crosses(Falling, -1.0, 1.0));
        assert!(crosses(Any, 1.0, -1.0) && crosses(Any, -1.0, 1.0));
        assert!(!crosses(Any, 0.0, 0.0) && !crosses(Any, 1.0, 2.0));
    }
}

//! Event functions g_k(t, y): their specs, and location of their zeros on the dense output.

use super::{DenseStep, SinCos, State, StepEnds};
use crate::ode::hermite::hermite_min;
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

/// A set of event functions, evaluated by index (no boxing, no allocation): what the
/// solver needs to find their zeros. Bounds that let it skip work are apart
/// ([`EventBounds`], offered through [`Self::bounds`]), as scipy keeps its events apart
/// from its solvers.
pub trait EventFunctions<const N: usize> {
    /// Whether [`Self::slopes`] gives slopes: the scan makes the dip test only then.
    const HAS_SLOPES: bool = false;
    /// Number of event functions.
    fn count(&self) -> usize;
    /// Direction and terminality of event k.
    fn spec(&self, k: usize) -> EventSpec;
    /// g_first, g_first+1, … at one point, into `out` (one value for a root search). The
    /// step scan calls it for all events at every sample, so events that share work
    /// (trigonometry of the state, say) do it once.
    fn values(&self, first: usize, t: f64, y: &State<N>, out: &mut [f64]);
    /// [`Self::values`] at a state whose y[0] has the sine and cosine `trig`, if known
    /// (handed on from the right-hand side: [`crate::ode::OdeSystem::rhs_with_trig`]), for
    /// events that need them. The scan asks so at each step's end. By default `trig` is
    /// not used.
    #[inline]
    fn values_at(&self, first: usize, t: f64, y: &State<N>, trig: Option<SinCos>, out: &mut [f64]) {
        let _ = trig;
        self.values(first, t, y, out);
    }
    /// dg_first/dt, dg_first+1/dt, … along the solution at one point, into `out` (as
    /// [`Self::values`]), for the dip test of the step scan: where g_k has one sign at two
    /// neighbouring samples but its slope turns between them (towards zero, then away),
    /// the extremum between them is located and, if it reaches the other side, counts as a
    /// crossing. Without it a dip narrower than the sample spacing (a grazing event) is
    /// missed. NaN, the default: no dip test for that event.
    #[inline]
    fn slopes(&self, first: usize, t: f64, y: &State<N>, out: &mut [f64]) {
        let _ = (first, t, y);
        out.fill(f64::NAN);
    }
    /// The events' change bounds, if they have any: the solver skips work they prove
    /// idle (quiet steps, skipped samples and dip tests). None, the default: the scan
    /// walks every sample of every step.
    #[inline]
    fn bounds(&self) -> Option<&impl EventBounds<N>> {
        None::<&NoBounds>
    }
}

/// Bounds on how much event functions can change within a step (see [`Change`]), which
/// let the solver skip work where they prove that no event can occur. Optional: the same
/// events are found without them, at more cost.
///
/// Both methods are given `end_trig`, the sine and cosine of y[0] at the step's end if the
/// right-hand side computed them there ([`crate::ode::OdeSystem::rhs_with_trig`]): bounds
/// on the trigonometry along the step may start from them.
pub trait EventBounds<const N: usize> {
    /// Bounds on how much each event function g_first, g_first+1, … can change within the
    /// step `dense`, into `out`.
    fn change_bounds(
        &self,
        first: usize,
        dense: &DenseStep<N>,
        end_trig: Option<SinCos>,
        out: &mut [Change],
    );
    /// Bounds as [`Self::change_bounds`], from the step's ends alone (before its dense
    /// output is built), meant to hold along the dense output whatever it turns out to be
    /// (computed along an interpolant of the ends, widened by an estimate of how far the
    /// dense output can stray from it): a step they clear of events needs no dense output
    /// ([`quiet_step`]). Without `bends` the bends may be left +∞ (not computed), but the
    /// rates and slacks must be the same bits as with them: [`quiet_step`] tries them
    /// alone first, as most steps far from events need no more. The default,
    /// [`Change::ANY`], never skips.
    #[inline]
    fn change_bounds_ends(
        &self,
        first: usize,
        ends: &StepEnds<N>,
        bends: bool,
        end_trig: Option<SinCos>,
        out: &mut [Change],
    ) {
        let _ = (first, ends, bends, end_trig);
        out.fill(Change::ANY);
    }
}

/// No change bounds: the type of [`EventFunctions::bounds`] for events without any.
pub struct NoBounds;

impl<const N: usize> EventBounds<N> for NoBounds {
    fn change_bounds(&self, _: usize, _: &DenseStep<N>, _: Option<SinCos>, out: &mut [Change]) {
        out.fill(Change::ANY);
    }
}

/// g_k at one point.
#[inline]
fn value_of<E: EventFunctions<N>, const N: usize>(
    events: &E,
    k: usize,
    t: f64,
    y: &State<N>,
) -> f64 {
    let mut out = [0.0];
    events.values(k, t, y, &mut out);
    out[0]
}

/// dg_k/dt at one point.
#[inline]
fn slope_of<E: EventFunctions<N>, const N: usize>(
    events: &E,
    k: usize,
    t: f64,
    y: &State<N>,
) -> f64 {
    let mut out = [f64::NAN];
    events.slopes(k, t, y, &mut out);
    out[0]
}

/// Is an accepted step free of events by its ends alone
/// ([`EventBounds::change_bounds_ends`]: every event's values at both ends of one strict
/// sign, further from zero than it can travel or bend within the step)? Then its dense
/// output is not needed for the scan, and the step end's values go to `carry` for the
/// next step, as [`scan_step`] leaves them. False (and `carry` untouched) whenever in
/// doubt: more events than one chunk, a non-finite value, or a bound that does not hold;
/// `end_trig` is the sine and cosine of y_new[0], if known.
/// [`scan_step`] then scans the step on its dense output, as always. The bounds without
/// their bends come first; the bends only when the rates alone do not clear the step (the
/// same verdict as the whole bounds at once: the rates are the same bits).
pub fn quiet_step<E: EventFunctions<N>, const N: usize>(
    events: &E,
    ends: &StepEnds<N>,
    end_trig: Option<SinCos>,
    carry: &mut EventCarry<N>,
) -> bool {
    let m = events.count();
    if m == 0 || m > EVENT_CHUNK {
        return m == 0;
    }
    let Some(bounds) = events.bounds() else {
        return false;
    };
    let mut g_a = [0.0; EVENT_CHUNK];
    let mut g_b = [0.0; EVENT_CHUNK];
    let mut bound = [Change::ANY; EVENT_CHUNK];
    bounds.change_bounds_ends(0, ends, false, end_trig, &mut bound[..m]);
    if bound[..m].iter().any(|b| b.slack == f64::INFINITY) {
        return false;
    }
    if carry.matches(ends.t_old, &ends.y_old) {
        g_a[..m].copy_from_slice(&carry.g[..m]);
    } else {
        events.values(0, ends.t_old, &ends.y_old, &mut g_a[..m]);
    }
    let t_new = ends.t_new;
    events.values_at(0, t_new, &ends.y_new, end_trig, &mut g_b[..m]);
    let clear = |bound: &[Change]| (0..m).all(|i| no_zero_inside(g_a[i], g_b[i], &bound[i], 1.0));
    if !clear(&bound[..m]) {
        if bound[..m].iter().all(|b| b.bend < f64::INFINITY) {
            return false; // the bends were there already
        }
        bounds.change_bounds_ends(0, ends, true, end_trig, &mut bound[..m]);
        if !clear(&bound[..m]) {
            return false;
        }
    }
    *carry = EventCarry {
        t: t_new,
        y: ends.y_new,
        g: g_b,
        valid: true,
    };
    true
}

/// How much an event function g can change within one step, along the dense output y(t):
/// - `rate` ≥ L |h|, where L bounds |d/dt g(t, y(t))| over the whole step;
/// - `bend` ≥ M |h|²/8, where M bounds |d²/dt² φ(t, y(t))| over the step for g = φ
///   (`smooth`), or for each φ_i of g = min_i φ_i (a kink where two meet: the slip margin
///   μF_y − |F_x| = min(μF_y − F_x, μF_y + F_x)); +∞ if unknown;
/// - `slack` ≥ 4δ, where δ bounds the error of a computed g there (rounding of g and of
///   y(t), and the difference between the exact step end and the interpolant at σ = 1).
///
/// The step scan uses them to skip work: if the computed values of g at the ends of a part
/// of the step (the whole step, or one cell between two samples) have one sign and either
/// - |g_a| + |g_b| > (the part's share of `rate`) + `slack` (g cannot fall faster than L
///   from either end), or
/// - min(g_a, g_b) > (the part's share of `bend`, squared) + `slack` (g positive: each φ_i
///   stays above its chord, which is above min(g_a, g_b), by at most M λ²|h|²/8 for a part
///   λ of the step), or max(g_a, g_b) < −(the same) (g negative and smooth),
///
/// then the exact g stays above δ in magnitude throughout the part, so every computed value
/// inside has that same sign: no sample inside the step can show a crossing, or no dip
/// inside the cell can reach the other side.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Change {
    /// ≥ L |h|.
    pub rate: f64,
    /// ≥ 4δ.
    pub slack: f64,
    /// ≥ M |h|²/8.
    pub bend: f64,
    /// g itself is smooth: `bend` holds above its chord too, not only below.
    pub smooth: bool,
}

impl Change {
    /// Of a constant: no change at all.
    pub const NONE: Change = Change {
        rate: 0.0,
        slack: 0.0,
        bend: 0.0,
        smooth: true,
    };
    /// Unknown: anything may happen (never skips).
    pub const ANY: Change = Change {
        rate: 0.0,
        slack: f64::INFINITY,
        bend: f64::INFINITY,
        smooth: false,
    };

    /// The bound by the rate over a part `share` (≥ 0) of the step.
    #[inline]
    pub fn over(self, share: f64) -> f64 {
        self.rate * share + self.slack
    }

    /// The bound by the bend over a part `share` (≥ 0) of the step.
    #[inline]
    pub fn bend_over(self, share: f64) -> f64 {
        self.bend * (share * share) + self.slack
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
    fn values(&self, _first: usize, _t: f64, _y: &State<N>, _out: &mut [f64]) {
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

/// What a part of a step between two computed times may exceed its nominal share of the
/// step by: a few ulps of t (in their rounding), as a share of h. Negligible unless the
/// step is tiny against t (a step of 1e-11 at t = 3.7 is 1.5e-3 of a 64th of it).
#[inline]
pub(crate) fn time_slack(t_old: f64, h: f64) -> f64 {
    (t_old.abs() + h.abs()) / h.abs() * f64::EPSILON * 16.0
}

/// Can the inside of a step (or of a part `share` of it, a cell) be skipped for an event,
/// given its computed values at the ends and its change bound (see [`Change`])? Both ends
/// finite, of one strict sign, and further from zero than g can travel or bend.
#[inline]
fn no_zero_inside(ga: f64, gb: f64, change: &Change, share: f64) -> bool {
    let same_sign = (ga > 0.0 && gb > 0.0) || (ga < 0.0 && gb < 0.0);
    if !(same_sign && ga.is_finite() && gb.is_finite()) {
        return false;
    }
    // A NaN bound compares false: no skip. The relative slack covers the rounding of
    // the bounds themselves and of the sum.
    let margin = 1.0 + 1e-9;
    let bend = change.bend_over(share) * margin;
    ga.abs() + gb.abs() > change.over(share) * margin
        || if ga > 0.0 {
            ga.min(gb) > bend
        } else {
            change.smooth && -ga.max(gb) > bend
        }
}

/// The sample points of one accepted step: its two ends (exact states) and `samples`
/// equally spaced interior points of the dense output.
struct StepSamples<'a, const N: usize> {
    dense: &'a DenseStep<N>,
    t_new: f64,
    y_new: &'a State<N>,
    /// sin and cos of y_new[0], if known.
    trig_new: Option<SinCos>,
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
        let v = value_of(events, k, t, &dense.eval(t));
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
                let v = value_of(events, k, t, &dense.eval(t));
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

/// A dip is located only where the cubic-Hermite extremum of its cell comes within this
/// share of the cell's spread |g_b − g_a| + |h|(|g_a'| + |g_b'|) of zero. The interpolant errs
/// by ~(θ-width of the cell)⁴/384 of the spread: ≲ 1e-6 for the ≲ 0.2 rad of a sample cell.
const DIP_SCREEN: f64 = 0.01;

/// A dip of g_k inside the sub-interval [ta, tb] (in integration order), where g_k has one
/// sign at both ends or starts at exactly 0 (no crossing there) and slopes sa, sb: None unless the slope turns
/// towards zero then away (an extremum inside) and the extremum, located by Brent on the
/// slope along the dense output, reaches the other side. Then g_k crosses twice, into the
/// other side and back; the result is the bracket ((t, g), (t, g)) of the crossing that
/// counts for the event's direction, the first one if both do. A cheap screen first
/// ([`DIP_SCREEN`]).
#[allow(clippy::type_complexity)] // two (t, g) ends
fn dip<E: EventFunctions<N>, const N: usize>(
    events: &E,
    k: usize,
    dense: &DenseStep<N>,
    (ta, ga, sa): (f64, f64, f64),
    (tb, gb, sb): (f64, f64, f64),
) -> Result<Option<((f64, f64), (f64, f64))>, NonFiniteEvent> {
    // σ = +1 looks for a minimum (g positive at both ends), σ = −1 for a maximum; the slopes
    // are per unit of time, h < 0 when integrating backwards.
    // A g that starts the cell at exactly 0 counts as on the side its slope leaves 0 for:
    // if it ends the cell back on the other side, it went out and came back across 0
    // within the cell (a slip that starts at v = 0 and returns to it), which the sign
    // test, needing a nonzero left value, cannot see.
    let h = tb - ta;
    let (ma, mb) = (h * sa, h * sb);
    let sigma = if ga >= 0.0 && gb > 0.0 && ma < 0.0 && mb > 0.0 {
        1.0
    } else if ga <= 0.0 && gb < 0.0 && ma > 0.0 && mb < 0.0 {
        -1.0
    } else {
        return Ok(None);
    };
    let (_, est) = hermite_min(sigma * ga, sigma * ma, sigma * gb, sigma * mb);
    let spread = (gb - ga).abs() + ma.abs() + mb.abs();
    if est > DIP_SCREEN * spread {
        return Ok(None);
    }
    let mut bad = false;
    let slope = |t: f64| {
        let v = slope_of(events, k, t, &dense.eval(t));
        bad |= !v.is_finite();
        v
    };
    let xtol = 4.0 * f64::EPSILON * ta.abs().max(tb.abs());
    let at = match roots::brent(slope, ta, tb, sa, sb, xtol, 4.0 * f64::EPSILON, 200) {
        Ok(r) => r.x,
        Err(_) if bad => return Err(NonFiniteEvent),
        Err(_) => return Ok(None),
    };
    let g = checked(value_of(events, k, at, &dense.eval(at)))?;
    let direction = events.spec(k).direction;
    Ok(if crosses(direction, ga, g) {
        Some(((ta, ga), (at, g)))
    } else if crosses(direction, g, gb) {
        Some(((at, g), (tb, gb)))
    } else {
        None
    })
}

/// Finds the events of one accepted step (dense output `dense`, ending at (t_new, y_new),
/// where y_new[0] has the sine and cosine `trig_new` if known) and hands each to `report`
/// in time order (ties by event index), stopping after the first terminal one, which is
/// returned. `carry` holds the end values of the previous scanned step (start with
/// `EventCarry::default()`).
pub fn scan_step<E: EventFunctions<N>, const N: usize>(
    events: &E,
    dense: &DenseStep<N>,
    (t_new, y_new, trig_new): (f64, &State<N>, Option<SinCos>),
    samples: usize,
    carry: &mut EventCarry<N>,
    report: impl FnMut(EventHit<N>),
) -> Result<Option<EventHit<N>>, NonFiniteEvent> {
    if events.count() == 0 {
        return Ok(None);
    }
    let pts = StepSamples {
        dense,
        t_new,
        y_new,
        trig_new,
        samples,
    };
    match first_crossing(events, &pts, carry)? {
        Some(j_first) => report_crossings(events, &pts, j_first, report),
        None => Ok(None),
    }
}

/// Pass 1 of [`scan_step`]: the earliest sub-interval (ending at sample j) with any
/// crossing. All events of a chunk are evaluated together at each sample, so the dense
/// output and any shared work of the event functions are computed once per sample. The
/// start values come from the previous step's end when possible; the end values are
/// evaluated first (they are carried to the next step) and, when the events' change bounds
/// prove that no sample inside the step can show a crossing, the interior samples are
/// skipped. The end values are checked for finiteness only where they are used, as the
/// plain walk would.
#[inline(always)]
fn first_crossing<E: EventFunctions<N>, const N: usize>(
    events: &E,
    pts: &StepSamples<'_, N>,
    carry: &mut EventCarry<N>,
) -> Result<Option<usize>, NonFiniteEvent> {
    let n_events = events.count();
    let carry_all = n_events <= EVENT_CHUNK;
    let mut j_first = None;
    for first in (0..n_events).step_by(EVENT_CHUNK) {
        let m = (n_events - first).min(EVENT_CHUNK);
        let mut g_a = [0.0; EVENT_CHUNK];
        let (t, y) = pts.point(0);
        if carry_all && carry.matches(t, &y) {
            g_a[..m].copy_from_slice(&carry.g[..m]);
        } else {
            events.values(first, t, &y, &mut g_a[..m]);
        }
        check_all(&g_a[..m])?;
        let mut g_end = [0.0; EVENT_CHUNK];
        events.values_at(first, pts.t_new, pts.y_new, pts.trig_new, &mut g_end[..m]);
        if carry_all {
            *carry = EventCarry {
                t: pts.t_new,
                y: *pts.y_new,
                g: g_end,
                valid: true,
            };
        }
        // Only sub-intervals before the earliest crossing found so far can matter.
        let limit = (pts.samples + 1).min(j_first.map_or(usize::MAX, |j: usize| j - 1));
        if limit > 0 {
            let chunk = first..first + m;
            j_first = walk_samples(events, pts, chunk, limit, g_a, &g_end)?.or(j_first);
        }
    }
    Ok(j_first)
}

/// The earliest sub-interval, up to the one ending at sample `limit`, where an event of
/// `chunk` crosses (or dips across) zero, from their values `g_a` at the step's start and
/// `g_end` at its end: none when their change bounds prove that no sample inside the step
/// can show a crossing; else the samples in order, with the dip test in the cells where
/// the bounds allow a dip.
#[inline(always)]
fn walk_samples<E: EventFunctions<N>, const N: usize>(
    events: &E,
    pts: &StepSamples<'_, N>,
    chunk: std::ops::Range<usize>,
    limit: usize,
    mut g_a: [f64; EVENT_CHUNK],
    g_end: &[f64; EVENT_CHUNK],
) -> Result<Option<usize>, NonFiniteEvent> {
    let (first, m) = (chunk.start, chunk.len());
    let (dense, samples) = (pts.dense, pts.samples);
    // Without bounds (or with no interior samples) nothing is skipped.
    let mut bound = [Change::ANY; EVENT_CHUNK];
    if let Some(bounds) = events.bounds().filter(|_| samples > 0) {
        bounds.change_bounds(first, dense, pts.trig_new, &mut bound[..m]);
        if (0..m).all(|i| no_zero_inside(g_a[i], g_end[i], &bound[i], 1.0)) {
            return Ok(None);
        }
    }
    let cell = 1.0 / (samples + 1) as f64 + time_slack(dense.t_old, dense.h);
    // The dip test needs slopes, computed only at the ends of cells where g_k could reach
    // zero at all (see `Change`).
    let may_dip =
        |i: usize, ga: f64, gb: f64| samples == 0 || !no_zero_inside(ga, gb, &bound[i], cell);
    let mut g_b = [0.0; EVENT_CHUNK];
    let mut s_a = [f64::NAN; EVENT_CHUNK];
    let mut s_b = [f64::NAN; EVENT_CHUNK];
    let mut s_a_at = usize::MAX; // the sample whose slopes s_a holds
    for j in 1..=limit {
        let (t, y) = pts.point(j);
        if j == samples + 1 {
            g_b = *g_end;
        } else {
            events.values(first, t, &y, &mut g_b[..m]);
        }
        check_all(&g_b[..m])?;
        if (0..m).any(|i| crosses(events.spec(first + i).direction, g_a[i], g_b[i])) {
            return Ok(Some(j));
        }
        if E::HAS_SLOPES && (0..m).any(|i| may_dip(i, g_a[i], g_b[i])) {
            let (ta, ya) = pts.point(j - 1);
            if s_a_at != j - 1 {
                events.slopes(first, ta, &ya, &mut s_a[..m]);
            }
            events.slopes(first, t, &y, &mut s_b[..m]);
            let mut found = false;
            for i in (0..m).filter(|&i| may_dip(i, g_a[i], g_b[i])) {
                let a = (ta, g_a[i], s_a[i]);
                found |= dip(events, first + i, dense, a, (t, g_b[i], s_b[i]))?.is_some();
            }
            if found {
                return Ok(Some(j));
            }
            (s_a, s_a_at) = (s_b, j);
        }
        g_a = g_b;
    }
    Ok(None)
}

/// Pass 2 of [`scan_step`]: the sub-intervals from the one ending at sample `j_first` on,
/// in time order. Within one sub-interval several events may cross; they are reported in
/// order of (time, index) by repeatedly picking the earliest one after the previous report
/// (no buffer needed; more than one crossing in a sub-interval is rare, so the quadratic
/// cost is irrelevant).
fn report_crossings<E: EventFunctions<N>, const N: usize>(
    events: &E,
    pts: &StepSamples<'_, N>,
    j_first: usize,
    mut report: impl FnMut(EventHit<N>),
) -> Result<Option<EventHit<N>>, NonFiniteEvent> {
    for j in j_first..=pts.samples + 1 {
        let (a, b) = (pts.point(j - 1), pts.point(j));
        let mut prev = None;
        while let Some((t, k)) = next_crossing(events, pts.dense, &a, &b, prev)? {
            let hit = EventHit {
                index: k,
                t,
                y: pts.state_at(t),
            };
            report(hit);
            if events.spec(k).terminal {
                return Ok(Some(hit));
            }
            prev = Some((t, k));
        }
    }
    Ok(None)
}

/// The earliest crossing (t, k) inside the sub-interval from `a` to `b` after `prev` in
/// integration order (ties broken by index), located. The events' values (and, for the
/// dip test, slopes) at the sub-interval's ends come a chunk at a time, as in pass 1: one
/// evaluation of the shared work per point, not one per event.
fn next_crossing<E: EventFunctions<N>, const N: usize>(
    events: &E,
    dense: &DenseStep<N>,
    (ta, ya): &(f64, State<N>),
    (tb, yb): &(f64, State<N>),
    prev: Option<(f64, usize)>,
) -> Result<Option<(f64, usize)>, NonFiniteEvent> {
    let (ta, tb) = (*ta, *tb);
    let forward = dense.h >= 0.0;
    let later = |a: (f64, usize), b: (f64, usize)| -> bool {
        // Is a strictly after b in integration order (ties broken by index)?
        if a.0 == b.0 {
            a.1 > b.1
        } else {
            (a.0 > b.0) == forward
        }
    };
    let n_events = events.count();
    let mut best: Option<(f64, usize)> = None;
    for first in (0..n_events).step_by(EVENT_CHUNK) {
        let m = (n_events - first).min(EVENT_CHUNK);
        let (mut g_a, mut g_b) = ([0.0; EVENT_CHUNK], [0.0; EVENT_CHUNK]);
        events.values(first, ta, ya, &mut g_a[..m]);
        events.values(first, tb, yb, &mut g_b[..m]);
        check_all(&g_a[..m])?;
        check_all(&g_b[..m])?;
        let mut slopes: Option<([f64; EVENT_CHUNK], [f64; EVENT_CHUNK])> = None;
        for i in 0..m {
            let k = first + i;
            let (ga, gb) = (g_a[i], g_b[i]);
            // The part of [ta, tb] where g_k changes sign: all of it, or one side of a
            // dip's extremum.
            let (lo, hi) = if crosses(events.spec(k).direction, ga, gb) {
                ((ta, ga), (tb, gb))
            } else if E::HAS_SLOPES {
                let (s_a, s_b) = *slopes.get_or_insert_with(|| {
                    let (mut s_a, mut s_b) = ([f64::NAN; EVENT_CHUNK], [f64::NAN; EVENT_CHUNK]);
                    events.slopes(first, ta, ya, &mut s_a[..m]);
                    events.slopes(first, tb, yb, &mut s_b[..m]);
                    (s_a, s_b)
                });
                match dip(events, k, dense, (ta, ga, s_a[i]), (tb, gb, s_b[i]))? {
                    Some(bracket) => bracket,
                    None => continue,
                }
            } else {
                continue;
            };
            let cand = (locate(events, k, dense, lo, hi)?, k);
            if prev.is_none_or(|p| later(cand, p)) && best.is_none_or(|b| later(b, cand)) {
                best = Some(cand);
            }
        }
    }
    Ok(best)
}

/// For tests: the change bounds `b` of a step from `t_old` over `h` hold between every two
/// of 33 equally spaced points of it a power of two of cells apart (`g(t)`: the events'
/// values there), each pair by its share of the step (with the times' rounding:
/// [`time_slack`]): by the rate ([`Change::over`]) between the two, and by the bend
/// ([`Change::bend_over`]) at every point between them, which stays above the lower of
/// the two values less the bend (and, for a smooth g, below the higher plus the bend); the
/// failures described.
#[cfg(test)]
pub(crate) fn check_change_bounds<const K: usize>(
    t_old: f64,
    h: f64,
    g: impl Fn(f64) -> [f64; K],
    b: &[Change; K],
) -> Result<(), String> {
    let values: Vec<[f64; K]> = (0..=32).map(|i| g(t_old + h * (i as f64 / 32.0))).collect();
    for (i, gi) in values.iter().enumerate() {
        for (j, gj) in values.iter().enumerate().skip(i + 1) {
            if !(j - i).is_power_of_two() {
                continue;
            }
            let share = (j - i) as f64 / 32.0 + time_slack(t_old, h);
            for k in 0..K {
                let (ga, gb, bound) = (gi[k], gj[k], b[k]);
                if (gb - ga).abs() > bound.over(share) {
                    return Err(format!("event {k}, points {i}, {j}: {ga}, {gb}, {bound:?}"));
                }
                let bend = bound.bend_over(share);
                for (l, gl) in values.iter().enumerate().take(j).skip(i + 1) {
                    let below = gl[k] < ga.min(gb) - bend;
                    let above = bound.smooth && gl[k] > ga.max(gb) + bend;
                    if below || above {
                        let g = gl[k];
                        return Err(format!(
                            "event {k}, points {i}, {l}, {j}: {ga}, {g}, {gb}, {bound:?}"
                        ));
                    }
                }
            }
        }
    }
    Ok(())
}

/// Events without change bounds, for tests: the scan walks every interior sample of every
/// step (and makes the dip test in every cell), the reference the skipping must match.
#[cfg(test)]
pub struct WalkAll<'a, E>(pub &'a E);

#[cfg(test)]
impl<E: EventFunctions<N>, const N: usize> EventFunctions<N> for WalkAll<'_, E> {
    const HAS_SLOPES: bool = E::HAS_SLOPES;
    fn count(&self) -> usize {
        self.0.count()
    }
    fn spec(&self, k: usize) -> EventSpec {
        self.0.spec(k)
    }
    fn values(&self, first: usize, t: f64, y: &State<N>, out: &mut [f64]) {
        self.0.values(first, t, y, out)
    }
    fn slopes(&self, first: usize, t: f64, y: &State<N>, out: &mut [f64]) {
        self.0.slopes(first, t, y, out)
    }
}

#[cfg(test)]
mod tests;

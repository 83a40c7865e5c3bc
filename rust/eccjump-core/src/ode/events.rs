//! Event functions g_k(t, y): their specs, and location of their zeros on the dense output.

use super::{DenseStep, State, StepEnds};

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
pub trait EventBounds<const N: usize> {
    /// Bounds on how much each event function g_first, g_first+1, … can change within the
    /// step `dense`, into `out`.
    fn change_bounds(&self, first: usize, dense: &DenseStep<N>, out: &mut [Change]);
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
        out: &mut [Change],
    ) {
        let _ = (first, ends, bends);
        out.fill(Change::ANY);
    }
}

/// No change bounds: the type of [`EventFunctions::bounds`] for events without any.
pub struct NoBounds;

impl<const N: usize> EventBounds<N> for NoBounds {
    fn change_bounds(&self, _first: usize, _dense: &DenseStep<N>, out: &mut [Change]) {
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
/// [`scan_step`] then scans the step on its dense output, as always. The bounds without
/// their bends come first; the bends only when the rates alone do not clear the step (the
/// same verdict as the whole bounds at once: the rates are the same bits).
pub fn quiet_step<E: EventFunctions<N>, const N: usize>(
    events: &E,
    ends: &StepEnds<N>,
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
    bounds.change_bounds_ends(0, ends, false, &mut bound[..m]);
    if bound[..m].iter().any(|b| b.slack == f64::INFINITY) {
        return false;
    }
    if carry.matches(ends.t_old, &ends.y_old) {
        g_a[..m].copy_from_slice(&carry.g[..m]);
    } else {
        events.values(0, ends.t_old, &ends.y_old, &mut g_a[..m]);
    }
    let t_new = ends.t_new;
    events.values(0, t_new, &ends.y_new, &mut g_b[..m]);
    let clear = |bound: &[Change]| (0..m).all(|i| no_zero_inside(g_a[i], g_b[i], &bound[i], 1.0));
    if !clear(&bound[..m]) {
        if bound[..m].iter().all(|b| b.bend < f64::INFINITY) {
            return false; // the bends were there already
        }
        bounds.change_bounds_ends(0, ends, true, &mut bound[..m]);
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

mod scan;
pub use scan::{crosses, scan_step, EventHit, NonFiniteEvent};

#[cfg(test)]
mod tests;

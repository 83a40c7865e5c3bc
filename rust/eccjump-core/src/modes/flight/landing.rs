//! The landing: the first τ > 0 at which the gap g(τ) = b(τ) − 1 of a flight returns to 0.
//!
//! The gap is a parabola minus a sinusoid: it can dip to 0 and rise again between any two
//! samples, so sampling alone may miss a touch. The search is rigorous instead, with
//! |g''| ≤ M = cos α + χθ̇² and |g'''| ≤ M3 = χ|θ̇|³ ([`Flight::gap_bounds`]):
//! - an interval [a, b] holds no zero if lower bounds of g from its left end (g(a) + g'(a)s
//!   − ½Ms², or g(a) + g'(a)s + ½g''(a)s² − M3 s³/6 where g, g', g'' ≥ 0, which clears
//!   intervals growing with τ right after a lift-off, where g ~ τ³) and from its right end
//!   (the same with s → −s) are positive on pieces that cover it;
//! - an interval with g(a) > 0 ≥ g(b) on which g' provably keeps its sign (g'(a) + Mh < 0 or
//!   g'(b) + Mh < 0) holds exactly one zero, found by Brent's method;
//! - anything else is halved, the left half searched first.
//!
//! Right after a lift-off the gap starts at 0 (and, under the paper's rule, so do its first
//! two derivatives); the start is cleared with the gap's Taylor polynomial to third order and
//! the bound χθ̇⁴ on its fourth derivative. Beyond [`Flight::fall_bound`] the gap is
//! certainly negative, which bounds the search.

use crate::modes::flight::Flight;
use crate::ode::roots::brent;

/// Evaluations of the gap a landing search may use: far beyond any flight met in practice
/// (a few hundred), it only guards against a pathological near-graze.
pub const MAX_EVALUATIONS: usize = 100_000;

/// The result of a landing search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Landing {
    /// The gap returns to 0 at τ.
    At(f64),
    /// The gap does not become positive after τ = 0: the body cannot fly from this state.
    Immediate,
    /// No touch before τ_end.
    None,
    /// The search used up [`MAX_EVALUATIONS`].
    Undecided,
}

struct Search<'a> {
    flight: &'a Flight,
    m: f64,
    m3: f64,
    evaluations: usize,
}

/// The gap, its rate and its curvature at one time.
type Sample = (f64, f64, f64, f64);

/// The length s > 0 up to which g + d s − ½Ms² stays positive (g > 0).
fn clear_quadratic(g: f64, d: f64, m: f64) -> f64 {
    if m > 0.0 {
        // The positive root of ½Ms² − d s − g, in the form without cancellation.
        let disc = (d * d + 2.0 * m * g).sqrt();
        if d >= 0.0 {
            (d + disc) / m
        } else {
            2.0 * g / (disc - d)
        }
    } else if d >= 0.0 {
        f64::INFINITY
    } else {
        g / -d
    }
}

/// The length s > 0 up to which g + d s + ½c s² − (M3/6) s³ stays positive, for g > 0 and
/// d, c ≥ 0, to 1e-3 relative (the lower end is returned). The cubic p has exactly one
/// positive root r (one sign change in its coefficients); beyond c/M3 it is concave, and
/// r > c/M3 (p(c/M3) > 0), so Newton's method from any s > r descends monotonically onto r
/// from above. The answer is 0.999 times that limit, once p is confirmed positive there: a
/// positive p at s > 0 puts s below r, so the whole (0, s] is clear. Should the check fail
/// (rounding near a double root), bisection between 0 and the Newton point decides.
fn clear_cubic(g: f64, d: f64, c: f64, m3: f64) -> f64 {
    if !(d >= 0.0 && c >= 0.0) {
        return 0.0;
    }
    if m3 <= 0.0 {
        return f64::INFINITY;
    }
    let p = |s: f64| g + s * (d + s * (0.5 * c - s * m3 / 6.0));
    let dp = |s: f64| d + s * (c - 0.5 * m3 * s);
    // Each term of p alone is below M3 s³/6 beyond this point, so p < 0 there.
    let mut hi = crate::trig::cbrt(6.0 * g / m3)
        .max(3.0 * c / m3)
        .max((6.0 * d / m3).sqrt())
        * 2.0;
    if !(hi.is_finite() && hi > 0.0) {
        return 0.0;
    }
    while p(hi) > 0.0 {
        hi *= 2.0;
    }
    for _ in 0..60 {
        let step = p(hi) / dp(hi);
        // p ≤ 0 and p' < 0 beyond r: the step is ≥ 0 (NaN or a sign slip ends the loop).
        if step.is_nan() || step < 0.0 {
            break;
        }
        hi -= step;
        if step <= 1e-4 * hi {
            break;
        }
    }
    let lo = hi * 0.999;
    if lo > 0.0 && p(lo) > 0.0 {
        return lo;
    }
    let mut lo = 0.0;
    while hi - lo > 1e-3 * hi {
        let mid = 0.5 * (lo + hi);
        if p(mid) > 0.0 {
            lo = mid;
        } else {
            hi = mid;
        }
    }
    lo
}

impl Search<'_> {
    fn eval(&mut self, tau: f64) -> Sample {
        self.evaluations += 1;
        let (g, d, c) = self.flight.gap_derivatives(tau);
        (tau, g, d, c)
    }

    /// How far from a point with g > 0 and rate d (along the search) g is provably positive.
    fn clear(&self, g: f64, d: f64, c: f64) -> f64 {
        clear_quadratic(g, d, self.m).max(clear_cubic(g, d, c, self.m3))
    }

    /// The first zero in (a, b], given g, g', g'' at both ends and g(a) > 0.
    fn first_zero(&mut self, a: Sample, b: Sample) -> Result<Option<f64>, ()> {
        let ((ta, ga, da, ca), (tb, gb, db, cb)) = (a, b);
        let h = tb - ta;
        if gb <= 0.0 {
            let slope_up = (da + self.m * h).min(db + self.m * h);
            if slope_up < 0.0 || h <= 4.0 * f64::EPSILON * tb.abs() {
                return Ok(Some(self.locate(ta, ga, tb, gb)));
            }
        } else {
            // A relative margin covers the rounding of g, g' and the bounds. The quadratic
            // bounds are tried first: they are cheap and usually enough.
            let covers = |left: f64, right: f64| left + right >= h * (1.0 + 1e-12);
            let (left, right) = (
                clear_quadratic(ga, da, self.m),
                clear_quadratic(gb, -db, self.m),
            );
            if covers(left, right)
                || h <= 4.0 * f64::EPSILON * tb.abs()
                || covers(self.clear(ga, da, ca), self.clear(gb, -db, cb))
            {
                return Ok(None);
            }
        }
        if self.evaluations >= MAX_EVALUATIONS {
            return Err(());
        }
        let mid = self.eval(ta + 0.5 * h);
        if mid.1 <= 0.0 {
            // A zero lies in (a, m]: the first one is there.
            return self.first_zero(a, mid);
        }
        match self.first_zero(a, mid)? {
            Some(t) => Ok(Some(t)),
            None => self.first_zero(mid, b),
        }
    }

    /// The zero of g in (a, b] with g(a) > 0 ≥ g(b), by Brent's method.
    fn locate(&mut self, ta: f64, ga: f64, tb: f64, gb: f64) -> f64 {
        let f = self.flight;
        match brent(|t| f.gap(t).0, ta, tb, ga, gb, 0.0, 4.0 * f64::EPSILON, 200) {
            Ok(root) => {
                self.evaluations += root.evaluations;
                root.x
            }
            Err(_) => tb,
        }
    }
}

impl Flight {
    /// The first return of the gap to 0 in (0, τ_end] (see the module notes).
    pub fn landing(&self, tau_end: f64) -> Landing {
        let (m, m3) = self.gap_bounds();
        let mut search = Search {
            flight: self,
            m,
            m3,
            evaluations: 0,
        };
        let end = tau_end.min(self.fall_bound() * (1.0 + 1e-9) + 1e-12);
        if end.is_nan() || end <= 0.0 {
            return Landing::None;
        }
        let g0 = self.start.b - 1.0;
        let start = if g0 > 0.0 {
            search.eval(0.0)
        } else {
            match self.clear_start(end) {
                Some(s) => {
                    let first = search.eval(s);
                    if first.1 <= 0.0 {
                        return Landing::Immediate;
                    }
                    first
                }
                None if self.gap_is_identically_zero() => return Landing::None,
                None => return Landing::Immediate,
            }
        };
        let last = search.eval(end);
        match search.first_zero(start, last) {
            Ok(Some(t)) => Landing::At(t),
            Ok(None) => Landing::None,
            Err(()) => Landing::Undecided,
        }
    }

    /// On a vertical ramp, a flight without spin that starts touching with ḃ = 0 slides
    /// down the wall with the gap exactly 0: it never lands.
    fn gap_is_identically_zero(&self) -> bool {
        let ([c1, c2, c3], m4) = self.taylor();
        self.start.b == 1.0 && c1 == 0.0 && c2 == 0.0 && c3 == 0.0 && m4 == 0.0
    }

    /// A τ ∈ (0, end] up to which the gap, starting at 0, is provably positive, or None if
    /// its leading Taylor coefficient is not positive. With the cubic's coefficients c_j (of
    /// τ^(j+1)), c_k the first nonzero one, and M4 ≥ |g⁗|, the gap is at least
    /// τ^(k+1) P(τ), P(τ) = c_k + … + c_2 τ^(2−k) − (M4/24) τ^(3−k), so it is positive up
    /// to any s with P > 0 on (0, s]. Each coefficient of P is first moved towards −∞ by a
    /// relative 1e-12 (for the rounding of the gap and of the coefficients); then the
    /// minimum of that polynomial over [0, s] (at 0, s or a stationary point) is checked,
    /// for s = end (at most 1) halved until it holds.
    ///
    /// A lift-off from slipping starts with g, g' and g'' all (nearly) 0 and g⁗ bounded:
    /// the whole polynomial, not only its leading term, clears the start at once. (The
    /// leading term alone, a rounding-sized ḃ0, cleared only ~1e-14 and left the search to
    /// double its way out: ~50 evaluations of the gap.)
    fn clear_start(&self, end: f64) -> Option<f64> {
        let (c, m4) = self.taylor();
        let k = c.iter().position(|&x| x != 0.0)?;
        if c[k].is_nan() || c[k] <= 0.0 {
            return None;
        }
        let mut p = [0.0; 4];
        for (j, &cj) in c.iter().enumerate().skip(k) {
            p[j - k] = cj;
        }
        p[3 - k] = -m4 / 24.0;
        let p = p.map(|x| x - 1e-12 * x.abs());
        let value = |s: f64| p[0] + s * (p[1] + s * (p[2] + s * p[3]));
        // The stationary points of P: the roots of p1 + 2 p2 σ + 3 p3 σ² (NaN: none).
        let (qa, qb, qc) = (3.0 * p[3], 2.0 * p[2], p[1]);
        let stationary = if qa != 0.0 {
            let disc = qb * qb - 4.0 * qa * qc;
            if disc >= 0.0 {
                // Without cancellation: q = −(b + sign(b)√disc)/2, roots q/a and c/q.
                let q = -0.5 * (qb + qb.signum() * disc.sqrt());
                [q / qa, if q != 0.0 { qc / q } else { f64::NAN }]
            } else {
                [f64::NAN; 2]
            }
        } else if qb != 0.0 {
            [-qc / qb, f64::NAN]
        } else {
            [f64::NAN; 2]
        };
        let positive_up_to = |s: f64| {
            value(s) > 0.0
                && stationary
                    .iter()
                    .all(|&r| !(r > 0.0 && r < s) || value(r) > 0.0)
        };
        let mut s = end.min(1.0);
        for _ in 0..1100 {
            if s > 0.0 && positive_up_to(s) {
                return Some(s);
            }
            s *= 0.5;
        }
        None
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{BodyState, Cylinder, Ramp};

    fn ramp(chi: f64, km: f64, alpha: f64) -> Ramp {
        Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap()
    }

    /// The first sign change of the gap on a fine grid (a brute-force reference).
    fn brute(f: &Flight, end: f64, n: usize) -> Option<f64> {
        let mut prev = f.gap(end / n as f64).0;
        for i in 2..=n {
            let t = end * i as f64 / n as f64;
            let g = f.gap(t).0;
            if prev > 0.0 && g <= 0.0 {
                return Some(t);
            }
            prev = g;
        }
        None
    }

    #[test]
    fn clear_cubic_is_just_below_the_positive_root() {
        let mut rng = crate::testing::Lcg(99);
        let mut next = || rng.next();
        let mut scale = || 10f64.powf(12.0 * next() - 6.0);
        for i in 0..20_000 {
            let (g, m3) = (scale(), scale());
            // Some with d = 0 or c = 0 (just after a lift-off).
            let d = if i % 3 == 0 { 0.0 } else { scale() };
            let c = if i % 5 == 0 { 0.0 } else { scale() };
            let p = |s: f64| g + s * (d + s * (0.5 * c - s * m3 / 6.0));
            // The root by plain bisection to the last bits.
            let (mut lo, mut hi) = (0.0, 1.0);
            while p(hi) > 0.0 {
                hi *= 2.0;
            }
            for _ in 0..200 {
                let mid = 0.5 * (lo + hi);
                if p(mid) > 0.0 {
                    lo = mid;
                } else {
                    hi = mid;
                }
            }
            let s = clear_cubic(g, d, c, m3);
            assert!(
                s > 0.0 && p(s) > 0.0 && s <= lo,
                "{g} {d} {c} {m3}: {s} {lo}"
            );
            assert!(s >= 0.998 * lo, "{g} {d} {c} {m3}: {s} {lo}");
        }
        // Outside its preconditions it clears nothing, and without M3 everything.
        assert_eq!(clear_cubic(1.0, -1.0, 1.0, 1.0), 0.0);
        assert_eq!(clear_cubic(1.0, 1.0, 1.0, 0.0), f64::INFINITY);
    }

    #[test]
    fn a_thrown_body_lands_where_brute_force_says() {
        let mut rng = crate::testing::Lcg(12345);
        let mut next = || rng.next();
        let mut landed = 0;
        for _ in 0..300 {
            let r = ramp(0.05 + 0.9 * next(), 0.02 + 0.03 * next(), 1.4 * next());
            let f = Flight::new(
                r,
                BodyState {
                    theta: std::f64::consts::TAU * next(),
                    omega: 6.0 * (next() - 0.5),
                    l: 0.0,
                    ldot: next(),
                    b: 1.0,
                    bdot: 0.5 * next() + 1e-3,
                },
            );
            let end = 20.0;
            let reference = brute(&f, end, 400_000);
            match f.landing(end) {
                Landing::At(t) => {
                    landed += 1;
                    let b = reference.expect("a landing brute force does not see");
                    assert!(t <= b + 1e-12 && t > b - 2.0 * end / 400_000.0, "{t} {b}");
                    assert!(f.gap(t).0.abs() < 1e-12);
                }
                other => assert!(reference.is_none(), "{other:?}"),
            }
        }
        assert!(landed > 250);
    }

    #[test]
    fn a_dip_between_samples_is_found() {
        // A fast spin on a shallow arc: the gap dips below 0 for a moment long before the
        // parabola comes down.
        let r = ramp(0.5, 0.3, 0.1);
        // The centre of mass starts below C (θ0 = π) and swings over it within π/40 while
        // C's height dips by 2χ = 1, more than the throw lifts it.
        let f = Flight::new(
            r,
            BodyState {
                theta: std::f64::consts::PI,
                omega: 40.0,
                l: 0.0,
                ldot: 0.0,
                b: 1.0 + 1e-3,
                bdot: 12.0,
            },
        );
        match f.landing(100.0) {
            Landing::At(t) => {
                let b = brute(&f, 1.0, 2_000_000).unwrap();
                assert!((t - b).abs() < 1e-6, "{t} {b}");
                assert!(t < 0.1);
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn a_liftoff_from_slipping_is_cleared_by_the_whole_taylor_polynomial() {
        // Leaving a slip at F_y = 0: b̈ = 0 at the start, and ḃ0 is a rounding-sized
        // number. The start is cleared far beyond the ~1e-14 its leading term alone gives,
        // and the landing is where brute force finds it.
        let r = ramp(0.5, 0.4, 30f64.to_radians());
        let theta = 5.8_f64;
        let omega = (r.cos_a / (r.body.chi * theta.cos())).sqrt();
        let mut start = BodyState::rolling(theta, omega, theta);
        start.ldot = 1.7;
        start.bdot = 2.5e-29;
        let f = Flight::new(r, start);
        let ([c1, c2, c3], _) = f.taylor();
        assert!(c1 == 2.5e-29 && c2 == 0.0 && c3 > 0.0);
        let s = f.clear_start(100.0).unwrap();
        assert!(s > 1e-2, "{s}");
        // The gap is positive up there (checked on a fine grid) ...
        assert!((1..=1000).all(|i| f.gap(s * i as f64 / 1000.0).0 > 0.0));
        // ... and the landing is the brute-force one.
        match f.landing(100.0) {
            Landing::At(t) => {
                let b = brute(&f, 4.0, 400_000).unwrap();
                assert!(t <= b + 1e-12 && t > b - 2.0 * 4.0 / 400_000.0, "{t} {b}");
            }
            other => panic!("{other:?}"),
        }
    }

    #[test]
    fn after_the_papers_liftoff_the_start_is_cleared() {
        // At the paper's lift-off the gap and its first two derivatives vanish.
        let r = ramp(0.15, 0.02, 40f64.to_radians());
        let theta = 5.8_f64;
        let omega = (r.cos_a / (r.body.chi * theta.cos())).sqrt();
        let f = Flight::new(r, BodyState::rolling(theta, omega, theta));
        let ([c1, c2, c3], _) = f.taylor();
        assert_eq!(c1, 0.0);
        assert!(c2.abs() < 1e-16 && c3 > 0.0);
        match f.landing(100.0) {
            Landing::At(t) => assert!(t > 1e-3 && f.gap(0.5 * t).0 > 0.0),
            other => panic!("{other:?}"),
        }
        // Rolling into the ramp is not a flight.
        let g = Flight::new(r, BodyState::rolling(0.3, 0.1, 0.3));
        assert_eq!(g.landing(100.0), Landing::Immediate);
        // Sliding down a vertical wall without spin never lands.
        let w = Ramp::new(
            Cylinder::new(0.2, 0.1).unwrap(),
            std::f64::consts::FRAC_PI_2,
        )
        .unwrap();
        let h = Flight::new(w, BodyState::rolling(0.0, 0.0, 0.0));
        assert_eq!(h.landing(10.0), Landing::None);
    }
}

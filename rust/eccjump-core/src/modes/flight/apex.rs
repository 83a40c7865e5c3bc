//! The apex of a flight: the largest gap g = b − 1 over [0, τ_end].
//!
//! In flight the gap is a concave parabola minus a sinusoid (module [`super`]):
//!
//!   g(τ) = Q(τ) − χ cos θ(τ),  Q(τ) = (b0 − 1 + χ cos θ0) + (ḃ0 − χθ̇ sin θ0) τ − ½ cos α τ²
//!
//! (Q is the height of the centre of mass above the ramp, less 1). So g lies within χ of Q,
//! and its largest value lies where Q ≥ max Q − 2χ: an interval around the parabola's top,
//! a few turns long at most however long the flight. That interval is sampled at 16 points
//! per half turn of spin (at least 32), every sample interval in which ḃ falls through 0
//! holds a local maximum, refined by Brent's method, and the apex is the largest of the
//! samples and these maxima. A fixed number of samples over the whole flight would miss the
//! highest hump of a long, fast-spinning one (the tests found one 0.08 R too low).

use super::Flight;
use crate::ode::roots::brent;

/// The samples of a stretch of flight `span` long: 16 per half turn of spin, at least 32, at
/// most 4096 (the apex search, and the points a run records of a flight).
pub fn samples(omega: f64, span: f64) -> usize {
    let turns = omega.abs() * span / std::f64::consts::PI;
    // max and min, not clamp: a NaN gives the fewest samples, not none.
    32.0f64.max(16.0 * turns).min(4096.0) as usize
}

impl Flight {
    /// The largest gap b − 1 over [0, τ_end] (τ_end ≥ 0).
    pub fn apex(&self, tau_end: f64) -> f64 {
        let (lo, hi) = self.apex_window(tau_end);
        let n = samples(self.start.omega, hi - lo);
        let at = |i: usize| {
            if i == n {
                hi
            } else {
                lo + (hi - lo) * i as f64 / n as f64
            }
        };
        let rate = |t: f64| self.gap(t).1;
        let mut prev = (lo, self.gap(lo));
        let mut top = prev.1 .0;
        for i in 1..=n {
            let t = at(i);
            let here = self.gap(t);
            top = top.max(here.0);
            let (da, db) = (prev.1 .1, here.1);
            if da > 0.0 && db < 0.0 {
                if let Ok(root) = brent(rate, prev.0, t, da, db, 0.0, 4.0 * f64::EPSILON, 200) {
                    top = top.max(self.gap(root.x).0);
                }
            }
            prev = (t, here);
        }
        top
    }

    /// The part [lo, hi] of [0, τ_end] where Q ≥ max Q − 2χ, widened by a relative 1e-9 for
    /// the rounding of its ends; all of [0, τ_end] on a vertical ramp (Q is then linear).
    fn apex_window(&self, tau_end: f64) -> (f64, f64) {
        let s = &self.start;
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        if r.cos_a <= 0.0 {
            return (0.0, tau_end);
        }
        // Q(τ) = Q(τ_v) − ½ cos α (τ − τ_v)², its top at τ_v.
        let vy = s.bdot - chi * s.omega * self.sin0;
        let tau_v = vy / r.cos_a;
        let drop = |t: f64| 0.5 * r.cos_a * (t - tau_v) * (t - tau_v);
        // max Q on [0, τ_end] is Q(τ_v) − drop(τ_c); Q ≥ it − 2χ where drop ≤ drop(τ_c) + 2χ.
        let tau_c = tau_v.clamp(0.0, tau_end);
        let reach = ((drop(tau_c) + 2.0 * chi) * 2.0 / r.cos_a).sqrt() * (1.0 + 1e-9) + 1e-12;
        let lo = (tau_v - reach).max(0.0);
        let hi = (tau_v + reach).min(tau_end);
        if lo < hi {
            (lo, hi)
        } else {
            (tau_c, tau_c)
        }
    }
}

#[cfg(test)]
mod tests {
    use crate::mechanics::{BodyState, Cylinder, Ramp};
    use crate::modes::flight::Flight;

    /// The largest gap on a grid of `n` + 1 times and the bound M h²/8 on how far below the
    /// true largest it can be.
    fn grid_best(f: &Flight, tau_end: f64, n: usize) -> (f64, f64) {
        let best = (0..=n)
            .map(|i| f.gap(tau_end * i as f64 / n as f64).0)
            .fold(f64::NEG_INFINITY, f64::max);
        let h = tau_end / n as f64;
        (best, f.gap_bounds().0 * h * h / 8.0)
    }

    #[test]
    fn apex_is_the_largest_gap_of_long_fast_flights() {
        let mut rng = crate::testing::Lcg(17);
        for _ in 0..300 {
            let chi = 0.05 + 0.9 * rng.next();
            let km = (1.0 - chi) * (0.05 + 0.9 * rng.next());
            let alpha = 1.5 * rng.next();
            let r = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap();
            let start = BodyState {
                theta: 20.0 * rng.next() - 10.0,
                omega: 80.0 * rng.next() - 40.0,
                l: 0.0,
                ldot: 2.0 * rng.next(),
                b: 1.0 + 2.0 * rng.next(),
                bdot: 6.0 * rng.next() - 1.0,
            };
            let f = Flight::new(r, start);
            let tau_end = 10.0 * rng.next();
            let apex = f.apex(tau_end);
            let (best, slack) = grid_best(&f, tau_end, 200_000);
            assert!(
                apex >= best - 1e-12 && apex <= best + slack + 1e-12,
                "apex {apex} against {best} ± {slack}: {start:?}, tau_end {tau_end}"
            );
        }
    }
}

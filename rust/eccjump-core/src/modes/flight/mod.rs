//! Flight (no contact, F = 0): θ̇ is constant and the centre of mass falls freely, so the
//! motion is known exactly. With u = θ̇τ/2 the time since lift-off τ enters only through
//!
//!   l(τ) = l0 + l̇0 τ + ½ sin α τ² + χ[2 sin θ0 sin² u + cos θ0 (2u − sin 2u)]
//!   b(τ) = b0 + ḃ0 τ − ½ cos α τ² + χ[2 cos θ0 sin² u − sin θ0 (2u − sin 2u)]
//!
//! (C = CM − χ(sin θ, cos θ) with the CM on its parabola), written so that the gap b − 1
//! keeps its full relative accuracy as τ → 0, where it starts at 0 after a lift-off. The
//! landing (the first return of the gap to 0) is found in [`landing`].

pub mod apex;
pub mod landing;

use crate::mechanics::{BodyState, Ramp};

/// (−1)^(k+1)/(2k+1)! for k = 1…10: (x − sin x)/x³ = 1/3! − x²/5! + x⁴/7! − … in powers of
/// x². Its terms fall below 1e-19 of the first for |x| < 1.
const X_MINUS_SIN_SERIES: [f64; 10] = {
    let mut c = [0.0; 10];
    let mut factorial = 6.0;
    let mut k = 0;
    while k < 10 {
        c[k] = if k % 2 == 0 { 1.0 } else { -1.0 } / factorial;
        factorial *= ((2 * k + 4) * (2 * k + 5)) as f64;
        k += 1;
    }
    c
};

/// 2u − sin 2u for x = 2u, given sin x: accurate in relative terms for small x (its Taylor
/// series up to x²¹/21!, by Horner in x² with constant coefficients, below |x| = 1; x − sin x
/// above, where cancellation costs at most a few ulps).
#[inline]
pub fn x_minus_sin(x: f64, sin_x: f64) -> f64 {
    if x.abs() >= 1.0 {
        return x - sin_x;
    }
    let x2 = x * x;
    let c = &X_MINUS_SIN_SERIES;
    let mut acc = c[9];
    for &ck in c[..9].iter().rev() {
        acc = acc * x2 + ck;
    }
    x * x2 * acc
}

/// 1 − cos x given sin x and cos x, without cancellation: sin²x / (1 + cos x) where cos x >
/// 0 (small x), 1 − cos x where it is ≥ 1. One `sin_cos` serves both this and the flight's
/// other terms (2 sin²(x/2) would cost a second one).
#[inline]
pub fn one_minus_cos(sin_x: f64, cos_x: f64) -> f64 {
    if cos_x > 0.0 {
        sin_x * sin_x / (1.0 + cos_x)
    } else {
        1.0 - cos_x
    }
}

/// The rotation x = θ̇τ since lift-off and what the flight's formulas need of it.
struct Turn {
    x: f64,
    sin_x: f64,
    cos_x: f64,
    /// 2 sin²(x/2) = 1 − cos x, without cancellation.
    one_minus_cos: f64,
    /// x − sin x, accurate for small x.
    x_minus_sin: f64,
}

impl Turn {
    #[inline]
    fn new(omega: f64, tau: f64) -> Self {
        let x = omega * tau;
        let (sin_x, cos_x) = crate::trig::sin_cos(x);
        Self {
            x,
            sin_x,
            cos_x,
            one_minus_cos: one_minus_cos(sin_x, cos_x),
            x_minus_sin: x_minus_sin(x, sin_x),
        }
    }
}

/// A flight from its start state: the exact state at any time since lift-off.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Flight {
    /// The body on its ramp.
    pub ramp: Ramp,
    /// The state at lift-off (τ = 0).
    pub start: BodyState,
    /// sin θ0, cos θ0.
    sin0: f64,
    cos0: f64,
}

impl Flight {
    /// The flight that starts in `start`.
    pub fn new(ramp: Ramp, start: BodyState) -> Self {
        let (sin0, cos0) = crate::trig::sin_cos(start.theta);
        Self {
            ramp,
            start,
            sin0,
            cos0,
        }
    }

    /// The state τ after lift-off.
    pub fn state(&self, tau: f64) -> BodyState {
        let s = &self.start;
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        let u = Turn::new(s.omega, tau);
        let (gap, bdot, _) = self.gap_of(tau, &u);
        BodyState {
            theta: s.theta + u.x,
            omega: s.omega,
            l: s.l
                + s.ldot * tau
                + 0.5 * r.sin_a * tau * tau
                + chi * (self.sin0 * u.one_minus_cos + self.cos0 * u.x_minus_sin),
            ldot: s.ldot
                + r.sin_a * tau
                + chi * s.omega * (self.sin0 * u.sin_x + self.cos0 * (1.0 - u.cos_x)),
            b: 1.0 + gap,
            bdot,
        }
    }

    /// The gap b − 1 and its rate ḃ at τ.
    #[inline]
    pub fn gap(&self, tau: f64) -> (f64, f64) {
        let (g, d, _) = self.gap_derivatives(tau);
        (g, d)
    }

    /// The gap b − 1, ḃ and b̈ = χθ̇² cos θ − cos α at τ.
    #[inline]
    pub fn gap_derivatives(&self, tau: f64) -> (f64, f64, f64) {
        self.gap_of(tau, &Turn::new(self.start.omega, tau))
    }

    /// [`Self::gap_derivatives`] with the rotation since lift-off already evaluated.
    #[inline]
    fn gap_of(&self, tau: f64, u: &Turn) -> (f64, f64, f64) {
        let s = &self.start;
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        let cos_t = self.cos0 * u.cos_x - self.sin0 * u.sin_x;
        (
            (s.b - 1.0) + s.bdot * tau - 0.5 * r.cos_a * tau * tau
                + chi * (self.cos0 * u.one_minus_cos - self.sin0 * u.x_minus_sin),
            s.bdot - r.cos_a * tau
                + chi * s.omega * (self.cos0 * u.sin_x - self.sin0 * (1.0 - u.cos_x)),
            chi * s.omega * s.omega * cos_t - r.cos_a,
        )
    }

    /// Bounds on |b̈| = |χθ̇² cos θ − cos α| and on |b⃛| = |χθ̇³ sin θ| over the whole flight.
    pub fn gap_bounds(&self) -> (f64, f64) {
        let (chi, w) = (self.ramp.body.chi, self.start.omega.abs());
        (self.ramp.cos_a + chi * w * w, chi * w * w * w)
    }

    /// The time τ_p after which the gap is certainly negative: C is below the CM by at most
    /// χ, so b − 1 ≤ y_CM(τ) + χ − 1, a parabola. ∞ on a vertical ramp (cos α = 0).
    pub fn fall_bound(&self) -> f64 {
        let s = &self.start;
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        if r.cos_a <= 0.0 {
            return f64::INFINITY;
        }
        let vy = s.bdot - chi * self.sin0 * s.omega;
        let h = s.b + chi * self.cos0 + chi - 1.0;
        (vy + (vy * vy + 2.0 * r.cos_a * h.max(0.0)).sqrt()) / r.cos_a
    }

    /// The gap's Taylor coefficients at τ = 0, (ḃ0, L0/2, −χθ̇³ sin θ0/6), and a bound on
    /// its fourth derivative, χθ̇⁴. L0/2 is set to 0 where it is below the rounding of its
    /// terms: after a lift-off at L = 0 its computed sign means nothing.
    pub fn taylor(&self) -> ([f64; 3], f64) {
        let s = &self.start;
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        let w = s.omega;
        let (spin, weight) = (chi * w * w * self.cos0, r.cos_a);
        let mut c2 = 0.5 * (spin - weight);
        if c2.abs() <= 4.0 * f64::EPSILON * (spin.abs() + weight) {
            c2 = 0.0;
        }
        (
            [s.bdot, c2, -chi * w * w * w * self.sin0 / 6.0],
            chi * w * w * w * w,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{Constraint, Cylinder};

    fn flight() -> Flight {
        let r = Ramp::new(Cylinder::new(0.4, 0.2).unwrap(), 0.5).unwrap();
        Flight::new(
            r,
            BodyState {
                theta: 5.8,
                omega: 2.3,
                l: 1.0,
                ldot: 2.1,
                b: 1.0,
                bdot: 0.05,
            },
        )
    }

    #[test]
    fn x_minus_sin_is_accurate() {
        for &x in &[1e-8, 1e-3, 0.3, 0.99, 1.0, 2.5, -0.7] {
            let series_free = x - f64::sin(x);
            let v = x_minus_sin(x, f64::sin(x));
            if x.abs() > 0.1 {
                assert!((v - series_free).abs() < 1e-15, "{x}");
            }
            // Against the first two terms, exact enough for tiny x.
            if x.abs() < 1e-3 {
                let t = x * x * x / 6.0 - x.powi(5) / 120.0;
                assert!((v - t).abs() <= 1e-15 * t.abs());
            }
        }
    }

    #[test]
    fn x_minus_sin_is_its_series_summed_term_by_term() {
        // An independent summation: the terms x^(2k+1)/(2k+1)!, each from the one before,
        // added from the smallest up; the two agree to a few roundings in relative terms.
        for i in 1..2000 {
            let x = (i as f64 / 2000.0) * if i % 2 == 0 { 1.0 } else { -1.0 };
            let mut terms = [0.0; 12];
            let mut t = x * x * x / 6.0;
            for (k, term) in terms.iter_mut().enumerate() {
                *term = t;
                t *= -x * x / (((2 * k + 4) * (2 * k + 5)) as f64);
            }
            let reference: f64 = terms.iter().rev().sum();
            let v = x_minus_sin(x, f64::sin(x));
            assert!(
                (v - reference).abs() <= 4.0 * f64::EPSILON * reference.abs(),
                "{x}"
            );
        }
    }

    #[test]
    fn one_minus_cos_is_accurate() {
        // Against 2 sin²(x/2), which has no cancellation anywhere, in relative terms.
        let mut rng = crate::testing::Lcg(11);
        for i in 0..20_000 {
            let scale = [1e-9, 1e-4, 0.5, 3.0, 40.0][i % 5];
            let x = (2.0 * rng.next() - 1.0) * scale;
            let (s, c) = crate::trig::sin_cos(x);
            let half = f64::sin(0.5 * x);
            let reference = 2.0 * half * half;
            let v = one_minus_cos(s, c);
            assert!(
                (v - reference).abs() <= 4.0 * f64::EPSILON * reference,
                "{x}: {v} against {reference}"
            );
        }
    }

    #[test]
    fn state_is_free_fall_with_constant_spin() {
        // The exact flight against Newton–Euler with F = 0, by finite differences of the
        // closed form, and the centre of mass on its parabola.
        let f = flight();
        let chi = f.ramp.body.chi;
        let h = 1e-4;
        for &tau in &[0.0, 0.3, 1.1] {
            let (a, m, p) = (f.state(tau), f.state(tau - h), f.state(tau + h));
            let ne = f
                .ramp
                .newton_euler(a.theta, a.omega, Constraint::Free)
                .unwrap();
            assert!(((p.l - m.l) / (2.0 * h) - a.ldot).abs() < 1e-7);
            assert!(((p.b - m.b) / (2.0 * h) - a.bdot).abs() < 1e-7);
            assert!(((p.ldot - m.ldot) / (2.0 * h) - ne.l_dd).abs() < 1e-7);
            assert!(((p.bdot - m.bdot) / (2.0 * h) - ne.b_dd).abs() < 1e-7);
            let x = a.l + chi * a.theta.sin();
            let x0 = f.start.l + chi * f.start.theta.sin();
            let vx0 = f.start.ldot + chi * f.start.theta.cos() * f.start.omega;
            assert!((x - (x0 + vx0 * tau + 0.5 * f.ramp.sin_a * tau * tau)).abs() < 1e-13);
            let (g, gd) = f.gap(tau);
            assert!((g - (a.b - 1.0)).abs() < 1e-15 && gd == a.bdot);
        }
        // Energy is conserved in flight.
        let e0 = f.ramp.energy_of(&f.start);
        assert!((f.ramp.energy_of(&f.state(0.9)) - e0).abs() < 1e-13);
    }
}

//! Flight (no contact, F = 0): θ̇ is constant and the centre of mass falls freely, so the
//! motion is known exactly. With u = θ̇τ/2 the time since lift-off τ enters only through
//!
//!   l(τ) = l0 + l̇0 τ + ½ sin α τ² + χ[2 sin θ0 sin² u + cos θ0 (2u − sin 2u)]
//!   b(τ) = b0 + ḃ0 τ − ½ cos α τ² + χ[2 cos θ0 sin² u − sin θ0 (2u − sin 2u)]
//!
//! (C = CM − χ(sin θ, cos θ) with the CM on its parabola), written so that the gap b − 1
//! keeps its full relative accuracy as τ → 0, where it starts at 0 after a lift-off. The
//! landing (the first return of the gap to 0) is found in [`landing`].

pub mod landing;

use crate::mechanics::{BodyState, Ramp};

/// 2u − sin 2u for x = 2u, accurate in relative terms for small x (its Taylor series,
/// alternating, up to x²¹/21!, below |x| = 1; direct above, where cancellation costs at
/// most a few ulps).
#[inline]
pub fn x_minus_sin(x: f64) -> f64 {
    if x.abs() >= 1.0 {
        return x - crate::trig::sin(x);
    }
    // x³/3! − x⁵/5! + … by Horner in x²: term ratio −x²/((2k+2)(2k+3)).
    let x2 = x * x;
    let mut acc = 0.0;
    for k in (1..=10).rev() {
        // The coefficient of x^(2k+1) is (−1)^(k+1)/(2k+1)!; Horner from the top.
        let n = (2 * k + 2) as f64 * (2 * k + 3) as f64;
        acc = 1.0 - x2 * acc / n;
    }
    x * x2 / 6.0 * acc
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
        let x = s.omega * tau;
        let (sin_x, cos_x) = crate::trig::sin_cos(x);
        let half = crate::trig::sin(0.5 * x);
        let (sq, xs) = (2.0 * half * half, x_minus_sin(x));
        let (gap, bdot) = self.gap(tau);
        BodyState {
            theta: s.theta + x,
            omega: s.omega,
            l: s.l
                + s.ldot * tau
                + 0.5 * r.sin_a * tau * tau
                + chi * (self.sin0 * sq + self.cos0 * xs),
            ldot: s.ldot
                + r.sin_a * tau
                + chi * s.omega * (self.sin0 * sin_x + self.cos0 * (1.0 - cos_x)),
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
        let s = &self.start;
        let (r, chi) = (&self.ramp, self.ramp.body.chi);
        let x = s.omega * tau;
        let (sin_x, cos_x) = crate::trig::sin_cos(x);
        let half = crate::trig::sin(0.5 * x);
        let (sq, xs) = (2.0 * half * half, x_minus_sin(x));
        let cos_t = self.cos0 * cos_x - self.sin0 * sin_x;
        (
            (s.b - 1.0) + s.bdot * tau - 0.5 * r.cos_a * tau * tau
                + chi * (self.cos0 * sq - self.sin0 * xs),
            s.bdot - r.cos_a * tau
                + chi * s.omega * (self.cos0 * sin_x - self.sin0 * (1.0 - cos_x)),
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
            let v = x_minus_sin(x);
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

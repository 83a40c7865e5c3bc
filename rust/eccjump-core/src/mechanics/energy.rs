//! Mechanical energy, in units of M g R, and its one consequence used everywhere along pure
//! rolling: θ̇² as a function of θ.
//!
//! With the centre of mass at (l + χ sin θ, b + χ cos θ) in ramp coordinates and gravity
//! (sin α, −cos α), the energy of any state is
//!
//!   E = ½[(l̇ + χ cos θ θ̇)² + (ḃ − χ sin θ θ̇)²] + ½ Ĩ_CM θ̇² − (l + χ sin θ) sin α + (b + χ cos θ) cos α.
//!
//! In pure rolling (l̇ = θ̇, b = 1, ḃ = 0) the kinetic part is ½ Ĩ_P(θ) θ̇² with
//! Ĩ_P = Ĩ_C + 1 + 2χ cos θ, and conservation of E from (θ0, θ̇0) gives
//!
//!   ½ Ĩ_P(θ) θ̇² = K0 + ΔE(θ),   K0 = ½ Ĩ_P(θ0) θ̇0²,
//!   ΔE(θ) = (θ − θ0) sin α + χ[cos(α + θ0) − cos(α + θ)] = d sin α + 2χ sin(α + θ0 + u) sin u,
//!
//! with d = θ − θ0, u = d/2 (the product form avoids cancellation at small d).

use crate::mechanics::ramp::Ramp;
use crate::mechanics::state::BodyState;
use crate::trig::{asin, cos, sin};
use std::f64::consts::TAU;

/// K0 + ΔE(θ): the kinetic energy ½ Ĩ_P θ̇² available at θ along pure rolling, given
/// d = θ − θ0, sin(α + θ0 + d/2) and sin(d/2) (computed by the caller, each in the way its
/// kernel can afford). θ̇² = 2 (K0 + ΔE)/Ĩ_P(θ).
#[inline(always)]
pub fn rolling_kinetic(k0: f64, d: f64, sin_a: f64, chi: f64, sin_mid: f64, sin_half: f64) -> f64 {
    k0 + d * sin_a + 2.0 * chi * sin_mid * sin_half
}

impl Ramp {
    /// The mechanical energy of a state, per M g R.
    pub fn energy_of(&self, s: &BodyState) -> f64 {
        self.energy_of_trig(s, crate::trig::sin_cos(s.theta))
    }

    /// [`Ramp::energy_of`] with (sin θ, cos θ) of the state already known (a recorded
    /// point whose trigonometry the integrator has just computed).
    #[inline]
    pub fn energy_of_trig(&self, st: &BodyState, (s, c): (f64, f64)) -> f64 {
        let chi = self.body.chi;
        let omega = st.omega;
        let (vx, vy) = (st.ldot + chi * c * omega, st.bdot - chi * s * omega);
        let height = -(st.l + chi * s) * self.sin_a + (st.b + chi * c) * self.cos_a;
        0.5 * (vx * vx + vy * vy) + 0.5 * self.body.icm * omega * omega + height
    }

    /// Where the rolling energy turns, as arcsin(sin α/χ): along pure rolling
    /// dE/dθ = sin α + χ sin(α + θ) vanishes where sin(α + θ) = −sin α/χ, a minimum at
    /// α + θ ≡ −arcsin(sin α/χ) and a maximum at α + θ ≡ π + arcsin(sin α/χ) (mod 2π).
    /// None where χ ≤ sin α: then dE/dθ ≥ 0 and E never decreases.
    pub fn energy_turn_offset(&self) -> Option<f64> {
        let chi = self.body.chi;
        (chi > self.sin_a).then(|| asin(self.sin_a / chi))
    }

    /// The first angle after θ where the rolling energy has a minimum,
    /// 2πm − α − arcsin(sin α/χ) (see [`Ramp::energy_turn_offset`]); one turn later E is
    /// larger by 2π sin α at every phase, so this is the lowest minimum after θ. None where
    /// E never decreases (χ ≤ sin α) or θ is not finite.
    pub fn energy_minimum_after(&self, theta: f64) -> Option<f64> {
        let asn = self.energy_turn_offset()?;
        let at = |m: f64| TAU * m - self.alpha - asn;
        let mut m = ((theta + self.alpha + asn) / TAU).floor() + 1.0;
        // The quotient's rounding can put m one off near a minimum: the first one after θ.
        if at(m - 1.0) > theta {
            m -= 1.0;
        } else if at(m) <= theta {
            m += 1.0;
        }
        theta.is_finite().then(|| at(m))
    }

    /// θ̇² at θ along pure rolling from (θ0, θ̇0), by conservation of energy.
    pub fn omega_sq(&self, theta0: f64, omega0: f64, theta: f64) -> f64 {
        let d = theta - theta0;
        let k0 = 0.5 * self.contact_inertia(cos(theta0)) * omega0 * omega0;
        let sin_mid = sin(self.alpha + 0.5 * (theta + theta0));
        let gain = rolling_kinetic(0.0, d, self.sin_a, self.body.chi, sin_mid, sin(0.5 * d));
        2.0 * (k0 + gain) / self.contact_inertia(cos(theta))
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::Cylinder;

    #[test]
    fn rolling_kinetic_energy_is_half_the_contact_inertia() {
        let r = Ramp::new(Cylinder::new(0.45, 0.3).unwrap(), 0.4).unwrap();
        let (th, w) = (2.2f64, 1.3f64);
        let kinetic = r.rolling_energy(th, w) - r.rolling_energy(th, 0.0);
        assert!((kinetic - 0.5 * r.contact_inertia(th.cos()) * w * w).abs() < 1e-14);
    }

    #[test]
    fn energy_minimum_after_is_the_next_minimum_of_the_rolling_energy() {
        use std::f64::consts::PI;
        for &(chi, alpha) in &[(0.9, 0.2), (0.5, 0.45), (0.999, 1.5), (0.3, 0.01)] {
            let r = Ramp::new(Cylinder::new(chi, 0.5 * (1.0 - chi)).unwrap(), alpha).unwrap();
            // E(θ) from rest up to a constant: θ sin α − χ cos(α + θ), sampled finely.
            let e = |t: f64| t * r.sin_a - chi * (alpha + t).cos();
            for &theta in &[-7.0, -0.3, 0.0, 0.4, 3.0, 40.0] {
                let m = r.energy_minimum_after(theta).unwrap();
                assert!(m > theta && m <= theta + TAU, "{chi} {alpha} {theta}: {m}");
                // A minimum: E' = 0 and E'' > 0 there.
                assert!((r.sin_a + chi * (alpha + m).sin()).abs() < 1e-12);
                assert!((alpha + m).cos() > 0.0);
                // The lowest value of E on (θ, θ + 4π] that is not at θ itself.
                let lowest = (1..=40_000)
                    .map(|i| theta + 4.0 * PI * i as f64 / 40_000.0)
                    .map(e)
                    .fold(f64::INFINITY, f64::min);
                assert!(e(m) <= lowest + 1e-9 || e(theta + 1e-9) <= e(m));
            }
        }
        // χ ≤ sin α: E never decreases, no minimum.
        let r = Ramp::new(Cylinder::new(0.2, 0.1).unwrap(), 0.5).unwrap();
        assert_eq!(r.energy_minimum_after(0.0), None);
        let r = Ramp::new(Cylinder::new(0.9, 0.1).unwrap(), 0.5).unwrap();
        assert_eq!(r.energy_minimum_after(f64::NAN), None);
    }

    #[test]
    fn omega_sq_is_energy_conservation() {
        let r = Ramp::new(Cylinder::new(0.5, 0.4).unwrap(), 30f64.to_radians()).unwrap();
        let (th0, w0, th) = (0.4, 0.3, 3.7);
        let w = r.omega_sq(th0, w0, th).sqrt();
        assert!((r.rolling_energy(th, w) - r.rolling_energy(th0, w0)).abs() < 1e-14);
    }
}

//! Pure rolling (contact, no slip: b = 1, l̇ = θ̇), in units g = R = M = 1.
//!
//! Newton–Euler for the cylinder (see `../shared/physics.md`):
//!
//!   θ̈ (Ĩ_C + 1 + 2χ cos θ) = χ θ̇² sin θ + χ sin(α + θ) + sin α          (roll-eq)
//!   F_x = −sin α − χ θ̇² sin θ + (1 + χ cos θ) θ̈                          (Njump)
//!   F_y =  cos α − χ θ̇² cos θ − χ θ̈ sin θ
//!
//! Ĩ_C + 1 + 2χ cos θ is the moment of inertia about the contact point; it vanishes only
//! for χ = 1, k_m = 0 at θ = π, the one singular point of the rolling equation.

use crate::body::Cylinder;
use crate::error::{check_range, Result};
use std::f64::consts::FRAC_PI_2;

/// A body on a ramp of angle α ∈ [0, π/2], with the trigonometry of α precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Rolling {
    pub body: Cylinder,
    pub alpha: f64,
    pub sin_a: f64,
    pub cos_a: f64,
}

/// The mechanical state in contact: angle θ and angular velocity θ̇ = l̇.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    pub theta: f64,
    pub omega: f64,
    pub omega_dot: f64,
    /// Friction force along the ramp (x points down the ramp), per M g.
    pub fx: f64,
    /// Normal force, per M g.
    pub fy: f64,
    /// cos θ, kept for callers that need more functions of the same state.
    pub cos_theta: f64,
}

impl Rolling {
    pub fn new(body: Cylinder, alpha: f64) -> Result<Self> {
        check_range("alpha", alpha, 0.0, FRAC_PI_2)?;
        // cos(π/2) in floating point is 6e-17, not 0: keep it exact at the end point.
        let cos_a = if alpha == FRAC_PI_2 { 0.0 } else { alpha.cos() };
        Ok(Self {
            body,
            alpha,
            sin_a: alpha.sin(),
            cos_a,
        })
    }

    /// Ĩ_P(θ) = Ĩ_C + 1 + 2χ cos θ, the moment of inertia about the contact point.
    #[inline]
    pub fn contact_inertia(&self, cos_t: f64) -> f64 {
        self.body.ic + 1.0 + 2.0 * self.body.chi * cos_t
    }

    /// θ̈ from the rolling equation (roll-eq).
    #[inline]
    pub fn omega_dot(&self, theta: f64, omega: f64) -> f64 {
        let (s, c) = theta.sin_cos();
        self.omega_dot_sc(s, c, omega)
    }

    /// θ̈ from the rolling equation, given s = sin θ and c = cos θ.
    #[inline]
    pub fn omega_dot_sc(&self, s: f64, c: f64, omega: f64) -> f64 {
        let chi = self.body.chi;
        // sin(α + θ) = sin α cos θ + cos α sin θ, reusing the one sin_cos of θ.
        let sin_at = self.sin_a * c + self.cos_a * s;
        (chi * omega * omega * s + chi * sin_at + self.sin_a) / self.contact_inertia(c)
    }

    /// θ̈ and the contact forces at (θ, θ̇).
    #[inline]
    pub fn kinematics(&self, theta: f64, omega: f64) -> Kinematics {
        let (s, c) = theta.sin_cos();
        self.kinematics_sc(theta, omega, s, c)
    }

    /// [`Rolling::kinematics`] given s = sin θ and c = cos θ.
    #[inline]
    pub fn kinematics_sc(&self, theta: f64, omega: f64, s: f64, c: f64) -> Kinematics {
        let chi = self.body.chi;
        let acc = self.omega_dot_sc(s, c, omega);
        let w2 = omega * omega;
        Kinematics {
            theta,
            omega,
            omega_dot: acc,
            fx: -self.sin_a - chi * w2 * s + (1.0 + chi * c) * acc,
            fy: self.cos_a - chi * w2 * c - chi * acc * s,
            cos_theta: c,
        }
    }

    /// The paper's lift-off function b̈_free = χ θ̇² cos θ − cos α: the normal acceleration
    /// the centre C would have if the contact were released. Its rising zero is the
    /// paper's jump condition (Eq. jumpcondition).
    #[inline]
    pub fn liftoff_function(&self, theta: f64, omega: f64) -> f64 {
        self.body.chi * omega * omega * theta.cos() - self.cos_a
    }

    /// Mechanical energy per M g R: ½ Ĩ_P(θ) θ̇² + height of the centre of mass, measured
    /// with the rolled distance l = θ (any constant offset cancels in differences).
    pub fn energy(&self, theta: f64, omega: f64) -> f64 {
        let chi = self.body.chi;
        let (s, c) = theta.sin_cos();
        let height = -(theta + chi * s) * self.sin_a + chi * c * self.cos_a;
        0.5 * self.contact_inertia(c) * omega * omega + height
    }

    /// θ̇² along pure rolling from (θ0, θ̇0), by conservation of energy:
    ///   ½ Ĩ_P(θ) θ̇² = ½ Ĩ_P(θ0) θ̇0² + (θ − θ0) sin α + χ [cos(α + θ0) − cos(α + θ)].
    /// The bracket is written as 2 sin(α + (θ + θ0)/2) sin((θ − θ0)/2) to avoid cancellation.
    pub fn omega_sq(&self, theta0: f64, omega0: f64, theta: f64) -> f64 {
        let chi = self.body.chi;
        let drop = (theta - theta0) * self.sin_a
            + 2.0
                * chi
                * (self.alpha + 0.5 * (theta + theta0)).sin()
                * (0.5 * (theta - theta0)).sin();
        let kinetic0 = 0.5 * self.contact_inertia(theta0.cos()) * omega0 * omega0;
        2.0 * (kinetic0 + drop) / self.contact_inertia(theta.cos())
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Rolling {
        Rolling::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
    }

    #[test]
    fn forces_satisfy_the_torque_balance_about_the_centre_of_mass() {
        // I_CM θ̈ = χ sin θ F_y − (1 + χ cos θ) F_x  (paper Eq. theta-eq with b = 1).
        let r = ramp(0.4, 0.3, 25.0);
        for &(th, w) in &[(0.3, 0.2), (2.0, 1.5), (4.0, -0.7), (5.9, 3.0)] {
            let k = r.kinematics(th, w);
            let rhs = r.body.chi * th.sin() * k.fy - (1.0 + r.body.chi * th.cos()) * k.fx;
            assert!((r.body.icm * k.omega_dot - rhs).abs() < 1e-14);
        }
    }

    #[test]
    fn energy_derivative_vanishes() {
        // dE/dt = ∂E/∂θ θ̇ + ∂E/∂θ̇ θ̈ = 0 along the rolling equation (finite differences).
        let r = ramp(0.6, 0.2, 35.0);
        let (th, w) = (1.1, 0.8);
        let h = 1e-6;
        let de_dth = (r.energy(th + h, w) - r.energy(th - h, w)) / (2.0 * h);
        let de_dw = (r.energy(th, w + h) - r.energy(th, w - h)) / (2.0 * h);
        assert!((de_dth * w + de_dw * r.omega_dot(th, w)).abs() < 1e-8);
    }

    #[test]
    fn omega_sq_is_energy_conservation() {
        let r = ramp(0.5, 0.4, 30.0);
        let (th0, w0, th) = (0.4, 0.3, 3.7);
        let w = r.omega_sq(th0, w0, th).sqrt();
        assert!((r.energy(th, w) - r.energy(th0, w0)).abs() < 1e-14);
    }

    #[test]
    fn vertical_ramp_has_exact_zero_cosine() {
        let r = ramp(0.2, 0.1, 90.0);
        assert_eq!(r.cos_a, 0.0);
        assert!(Rolling::new(Cylinder::new(0.2, 0.1).unwrap(), 1.6).is_err());
    }
}

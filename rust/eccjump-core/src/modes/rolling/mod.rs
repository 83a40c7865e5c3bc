//! Pure rolling (contact, no slip: b = 1, l̇ = θ̇): Newton–Euler
//! ([`crate::mechanics::newton_euler`]) with l̈ = θ̈ and b̈ = 0 gives, in units g = R = M = 1,
//!
//!   θ̈ (Ĩ_C + 1 + 2χ cos θ) = χ θ̇² sin θ + χ sin(α + θ) + sin α          (roll-eq)
//!   F_x = −sin α − χ θ̇² sin θ + (1 + χ cos θ) θ̈                          (Njump)
//!   F_y =  cos α − χ θ̇² cos θ − χ θ̈ sin θ
//!
//! and, differentiating along the path (w = θ̇², a = θ̈, dw/dθ = 2a),
//!
//!   a' Ĩ_P = χ (4 a sin θ + w cos θ + cos(α + θ)),
//!   F_x' = −3χ a sin θ − χ w cos θ + (1 + χ cos θ) a',   F_y' = −3χ a cos θ + χ w sin θ − χ a' sin θ.
//!
//! The formulas are written once, as the functions below, and used by the rolling ODE
//! ([`Kinematics`], the run in [`run`]) and by the closed-form path scan
//! ([`crate::jarm::path`]); they are tested against the general form.

pub mod bounds;
pub mod events;
pub mod ode;
pub mod run;
pub mod solution;
pub(crate) mod track;

use crate::mechanics::liftoff::{free_normal_acceleration, liftoff_slope};
use crate::mechanics::Ramp;
use crate::trig::SinCos;

/// The numerator of roll-eq, χθ̇² sin θ + χ sin(α + θ) + sin α, given χθ̇², sin θ and
/// sin(α + θ): θ̈ = this / Ĩ_P(θ).
#[inline(always)]
pub fn torque(chi: f64, chi_w2: f64, sin_t: f64, sin_at: f64, sin_a: f64) -> f64 {
    chi_w2 * sin_t + chi * sin_at + sin_a
}

/// The contact force (F_x, F_y) of pure rolling at θ̈ = `acc`, given χθ̇², sin θ, cos θ.
#[inline(always)]
pub fn forces(r: &Ramp, chi_w2: f64, sin_t: f64, cos_t: f64, acc: f64) -> (f64, f64) {
    let chi = r.body.chi;
    (
        -r.sin_a - chi_w2 * sin_t + (1.0 + chi * cos_t) * acc,
        r.cos_a - chi_w2 * cos_t - chi * acc * sin_t,
    )
}

/// Ĩ_P times dθ̈/dθ along the rolling path: χ(4 a sin θ + w cos θ + cos(α + θ)).
#[inline(always)]
pub fn torque_slope(chi: f64, w: f64, acc: f64, sin_t: f64, cos_t: f64, cos_at: f64) -> f64 {
    chi * (4.0 * acc * sin_t + w * cos_t + cos_at)
}

/// (dF_x/dθ, dF_y/dθ) along the rolling path, given θ̈ = `acc` and dθ̈/dθ = `dacc`.
#[inline(always)]
pub fn force_slopes(
    chi: f64,
    chi_w2: f64,
    sin_t: f64,
    cos_t: f64,
    acc: f64,
    dacc: f64,
) -> (f64, f64) {
    (
        -3.0 * chi * acc * sin_t - chi_w2 * cos_t + (1.0 + chi * cos_t) * dacc,
        -3.0 * chi * acc * cos_t + chi_w2 * sin_t - chi * dacc * sin_t,
    )
}

/// The state of pure rolling at one instant, with everything the events need.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Kinematics {
    /// θ.
    pub theta: f64,
    /// θ̇.
    pub omega: f64,
    /// θ̈ from roll-eq.
    pub omega_dot: f64,
    /// Friction force along the ramp (x points down the ramp), per M g.
    pub fx: f64,
    /// Normal force, per M g.
    pub fy: f64,
    /// sin θ and cos θ, kept for callers that need more functions of the same state.
    pub sin_theta: f64,
    /// cos θ.
    pub cos_theta: f64,
    /// The lift-off function χθ̇² cos θ − cos α.
    pub lift: f64,
}

impl Ramp {
    /// θ̈ from the rolling equation, given s = sin θ and c = cos θ.
    #[inline]
    pub fn omega_dot_sc(&self, s: f64, c: f64, omega: f64) -> f64 {
        let chi = self.body.chi;
        let (sin_at, _) = self.shifted(s, c);
        torque(chi, chi * omega * omega, s, sin_at, self.sin_a) / self.contact_inertia(c)
    }

    /// θ̈, the contact forces and the lift-off function of pure rolling at (θ, θ̇).
    #[inline]
    pub fn kinematics(&self, theta: f64, omega: f64) -> Kinematics {
        self.kinematics_at(theta, omega, None)
    }

    /// [`Ramp::kinematics`], with sin θ and cos θ from `trig` when it is of this θ
    /// ([`SinCos::at`]).
    #[inline]
    pub fn kinematics_at(&self, theta: f64, omega: f64, trig: Option<SinCos>) -> Kinematics {
        let (s, c) = SinCos::at(theta, trig);
        // χθ̇² is rounded as (χθ̇)θ̇ in θ̈ and L and as χ(θ̇²) in the forces, as this kernel
        // always has: every route's results stay bit-identical to earlier versions.
        let chi = self.body.chi;
        let (chi_w2, chi_w2_forces) = (chi * omega * omega, chi * (omega * omega));
        let (sin_at, _) = self.shifted(s, c);
        let acc = torque(chi, chi_w2, s, sin_at, self.sin_a) / self.contact_inertia(c);
        let (fx, fy) = forces(self, chi_w2_forces, s, c, acc);
        Kinematics {
            theta,
            omega,
            omega_dot: acc,
            fx,
            fy,
            sin_theta: s,
            cos_theta: c,
            lift: free_normal_acceleration(chi_w2, c, self.cos_a),
        }
    }

    /// The kinematics at θ along pure rolling from (θ0, θ̇0 ≥ 0), with θ̇ from energy
    /// conservation ([`Ramp::omega_sq`], clamped at 0 where the body cannot reach θ).
    pub fn kinematics_along(&self, theta0: f64, omega0: f64, theta: f64) -> Kinematics {
        self.kinematics(theta, self.omega_sq(theta0, omega0, theta).max(0.0).sqrt())
    }

    /// (dF_x/dθ, dF_y/dθ) along pure rolling at the state `q`.
    pub fn force_slopes(&self, q: &Kinematics) -> (f64, f64) {
        let chi = self.body.chi;
        let (s, c) = (q.sin_theta, q.cos_theta);
        let w = q.omega * q.omega;
        let (_, cos_at) = self.shifted(s, c);
        let dacc = torque_slope(chi, w, q.omega_dot, s, c, cos_at) / self.contact_inertia(c);
        force_slopes(chi, chi * w, s, c, q.omega_dot, dacc)
    }

    /// The rates d/dt of the contact functions at the state `q` of a rolling solution: θ̇
    /// times their derivatives along rolling (the chain rule, with θ̈ from roll-eq, which the
    /// solution obeys). What the event scans of the rolling run and of the ODE route need to
    /// find a dip between two samples.
    pub fn contact_rates(&self, q: &Kinematics) -> ContactRates {
        let chi = self.body.chi;
        let (dfx, dfy) = self.force_slopes(q);
        let w = q.omega;
        let dlift = liftoff_slope(chi, chi * (w * w), q.omega_dot, q.sin_theta, q.cos_theta);
        ContactRates {
            fx: w * dfx,
            fy: w * dfy,
            lift: w * dlift,
        }
    }
}

/// dF_x/dt, dF_y/dt and dL/dt along a rolling solution ([`Ramp::contact_rates`]).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactRates {
    /// dF_x/dt.
    pub fx: f64,
    /// dF_y/dt.
    pub fy: f64,
    /// dL/dt of the lift-off function L = χθ̇² cos θ − cos α.
    pub lift: f64,
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{Constraint, Cylinder};

    fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
        Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
    }

    #[test]
    fn fast_path_is_the_general_newton_euler() {
        for &(chi, km, a) in &[
            (0.4, 0.3, 25.0),
            (0.15, 0.02, 40.0),
            (0.9, 0.05, 80.0),
            (0.0, 0.5, 10.0),
        ] {
            let r = ramp(chi, km, a);
            for &(th, w) in &[(0.3, 0.2), (2.0, 1.5), (4.0, -0.7), (5.9, 3.0)] {
                let k = r.kinematics(th, w);
                let g = r.newton_euler(th, w, Constraint::Ramp).unwrap();
                let tol = 1e-13 * (1.0 + w * w);
                assert!((k.omega_dot - g.theta_dd).abs() < tol, "{chi} {th}");
                assert!((k.fx - g.fx).abs() < tol && (k.fy - g.fy).abs() < tol);
            }
        }
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
        let de_dth = (r.rolling_energy(th + h, w) - r.rolling_energy(th - h, w)) / (2.0 * h);
        let de_dw = (r.rolling_energy(th, w + h) - r.rolling_energy(th, w - h)) / (2.0 * h);
        let (s, c) = crate::trig::sin_cos(th);
        assert!((de_dth * w + de_dw * r.omega_dot_sc(s, c, w)).abs() < 1e-8);
    }

    #[test]
    fn contact_rates_are_time_derivatives_along_the_rolling_equation() {
        // An independent route: d/dt g(θ, θ̇) = ∂g/∂θ θ̇ + ∂g/∂θ̇ θ̈ by finite differences of
        // the kinematics in θ and θ̇ separately, at states off any one path.
        let h = 1e-6;
        for &(chi, km, a) in &[(0.5, 0.2, 30.0), (0.9, 0.05, 70.0), (0.1, 0.6, 5.0)] {
            let r = ramp(chi, km, a);
            for &(th, w) in &[(0.5, 0.3), (2.0, 1.7), (3.5, -0.8), (5.0, 2.5)] {
                let q = r.kinematics(th, w);
                let rates = r.contact_rates(&q);
                let d = |f: &dyn Fn(&Kinematics) -> f64| {
                    let dth =
                        (f(&r.kinematics(th + h, w)) - f(&r.kinematics(th - h, w))) / (2.0 * h);
                    let dw =
                        (f(&r.kinematics(th, w + h)) - f(&r.kinematics(th, w - h))) / (2.0 * h);
                    dth * w + dw * q.omega_dot
                };
                let (fx, fy, lift) = (d(&|k| k.fx), d(&|k| k.fy), d(&|k| k.lift));
                assert!((rates.fx - fx).abs() < 1e-6 * (1.0 + fx.abs()), "{th} {w}");
                assert!((rates.fy - fy).abs() < 1e-6 * (1.0 + fy.abs()), "{th} {w}");
                assert!(
                    (rates.lift - lift).abs() < 1e-6 * (1.0 + lift.abs()),
                    "{th} {w}"
                );
            }
        }
    }

    #[test]
    fn force_slopes_are_derivatives_along_the_path() {
        let r = ramp(0.5, 0.2, 30.0);
        let (th0, w0) = (0.2, 0.4);
        let h = 1e-6;
        for &th in &[0.5, 2.0, 3.5, 5.0] {
            let q = r.kinematics_along(th0, w0, th);
            let (p, m) = (
                r.kinematics_along(th0, w0, th + h),
                r.kinematics_along(th0, w0, th - h),
            );
            let (dfx, dfy) = r.force_slopes(&q);
            assert!((dfx - (p.fx - m.fx) / (2.0 * h)).abs() < 1e-7);
            assert!((dfy - (p.fy - m.fy) / (2.0 * h)).abs() < 1e-7);
        }
    }
}

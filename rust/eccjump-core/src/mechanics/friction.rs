//! Coulomb friction at the contact: the friction ratio and margin of a contact force, and
//! sliding contact with its consistency (Painlevé) test.
//!
//! Sliding (b = 1, b̈ = 0, F_x = σ μ_k F_y with σ = −sign of the slip velocity) put into
//! Newton–Euler ([`crate::mechanics::newton_euler`]) gives, with B = cos α − χθ̇² cos θ
//! (= −L, minus the lift-off function),
//!
//!   K = χ sin θ − σ μ_k (1 + χ cos θ),   D = Ĩ_CM + χ K sin θ,
//!   θ̈ = K B/D,   F_y = Ĩ_CM B/D           (the paper's Eq. normalslip1).
//!
//! D ≤ 0 is the Painlevé case: no consistent sliding contact exists, and nothing may be
//! divided by D there.

use crate::mechanics::body::Cylinder;

/// The friction ratio |F_x|/F_y of a contact force; +∞ where F_y ≤ 0 (or is NaN).
#[inline(always)]
pub fn friction_ratio(fx: f64, fy: f64) -> f64 {
    if fy > 0.0 {
        fx.abs() / fy
    } else {
        f64::INFINITY
    }
}

/// The slip margin μ F_y − |F_x|: ≥ 0 inside the friction cone. A margin, not a ratio: it
/// stays finite as F_y → 0.
#[inline(always)]
pub fn slip_margin(mu: f64, fx: f64, fy: f64) -> f64 {
    mu * fy - fx.abs()
}

/// The rate of the slip margin, d(μ F_y − |F_x|) = μ dF_y − sign(F_x) dF_x, given the rates
/// (or derivatives) of the two forces.
#[inline(always)]
pub fn slip_margin_rate(mu: f64, fx: f64, dfx: f64, dfy: f64) -> f64 {
    mu * dfy - fx.signum() * dfx
}

/// Sliding contact at one angle: the coefficients K and D of the module notes.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Sliding {
    /// K = χ sin θ − σ μ_k (1 + χ cos θ).
    pub k: f64,
    /// D = Ĩ_CM + χ K sin θ; D ≤ 0 is the Painlevé case.
    pub d: f64,
}

impl Sliding {
    /// K and D for friction direction σ = ±1 and kinetic coefficient μ_k, given sin θ, cos θ.
    #[inline]
    pub fn new(body: &Cylinder, sin_t: f64, cos_t: f64, sigma: f64, mu_k: f64) -> Self {
        let chi = body.chi;
        let k = chi * sin_t - sigma * mu_k * (1.0 + chi * cos_t);
        Self {
            k,
            d: body.icm + chi * k * sin_t,
        }
    }
}

/// Slip onset from rolling under the classical rule: true if the body cannot slide and
/// goes to flight instead. Friction keeps its direction (σ = sign F_x, μ_k = μ_s); sliding is
/// inconsistent if F_x = 0, Ĩ_CM = 0, L ≥ 0 (the sliding normal force Ĩ_CM(−L)/D would be
/// ≤ 0) or D ≤ 0 (Painlevé).
#[inline]
pub fn slip_onset_flies(
    body: &Cylinder,
    sin_t: f64,
    cos_t: f64,
    fx: f64,
    lift: f64,
    mu_s: f64,
) -> bool {
    let sigma = if fx < 0.0 { -1.0 } else { 1.0 };
    let sliding = Sliding::new(body, sin_t, cos_t, sigma, mu_s);
    fx == 0.0 || body.icm == 0.0 || lift >= 0.0 || sliding.d <= 0.0
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::newton_euler::Constraint;
    use crate::mechanics::Ramp;

    #[test]
    fn sliding_closed_form_is_newton_euler() {
        for &(chi, km, a, th, w, sigma, mu) in &[
            (0.5, 0.4, 0.5, 5.5f64, 1.2f64, -1.0, 0.7),
            (0.3, 0.1, 1.0, 2.0, 0.4, 1.0, 0.3),
            (0.8, 0.05, 1.3, 4.6, 0.9, -1.0, 1.0),
        ] {
            let r = Ramp::new(Cylinder::new(chi, km).unwrap(), a).unwrap();
            let (s, c) = crate::trig::sin_cos(th);
            let sl = Sliding::new(&r.body, s, c, sigma, mu);
            let b = r.cos_a - chi * w * w * c;
            let ne = r.newton_euler(th, w, Constraint::Sliding { sigma, mu_k: mu });
            // θ̈ = K B/D and F_y = Ĩ_CM B/D where D > 0; Newton–Euler is singular elsewhere.
            if sl.d > 0.0 {
                let (acc, fy) = (sl.k * b / sl.d, r.body.icm * b / sl.d);
                let ne = ne.unwrap();
                assert!((acc - ne.theta_dd).abs() < 1e-12 && (fy - ne.fy).abs() < 1e-12);
            }
        }
    }

    #[test]
    fn ratio_and_margin() {
        assert_eq!(friction_ratio(-0.5, 1.0), 0.5);
        assert_eq!(friction_ratio(0.5, 0.0), f64::INFINITY);
        assert_eq!(friction_ratio(0.5, f64::NAN), f64::INFINITY);
        assert_eq!(slip_margin(1.0, -0.25, 0.5), 0.25);
    }
}

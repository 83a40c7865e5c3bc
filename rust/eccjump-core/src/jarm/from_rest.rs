//! Sec. 3.2 of the paper: the jump point for the start from rest, θ0 = 0, θ̇0 = 0.
//!
//! Energy conservation (see [`Ramp::omega_sq`]) gives along pure rolling from rest
//!
//!   θ̇² = 2E(θ)/Ĩ_P(θ),  E(θ) = θ sin α + χ(cos α − cos(α + θ)),  Ĩ_P = Ĩ_C + 1 + 2χ cos θ.
//!
//! With 2πγ + cos θ − 1 = Ĩ_P/(2χ) (γ = (Ĩ_C + 1 + 2χ)/(4πχ), Eq. dega2) the paper's
//! J(θ) (Eq. Jta) is exactly the lift-off function divided by cos α:
//!
//!   J(θ) = (χ θ̇² cos θ − cos α)/cos α.
//!
//! We compute lift-off as χθ̇² cos θ − cos α directly (J divides by cos α, bad at α = π/2).
//! At θ = 2πn: θ̇² = 4πn sin α/(Ĩ_C + 1 + 2χ), so J(2πn) = n tan α/γ − 1 (Eq. JtaC2) and
//! J(2πn) > 0 ⇔ n tan α > γ. At 2πn the normal force is F_y = −cos α J(2πn) < 0 then, so the
//! first lift-off (under either rule) happens by turn n* = min{n ≥ 1 : n tan α > γ}.
//!
//! Rocking back: E(0) = 0, E'(θ) = sin α + χ sin(α + θ). For χ > sin α, E has local minima at
//! α + θ = 2πk − arcsin(sin α/χ); the first, θ_m = 2π − α − arcsin(sin α/χ), is the lowest
//! (later ones are higher by 2πk sin α). If E(θ_m) ≤ 0 the body stops (θ̇² = 0) before θ_m
//! and rolls back: from rest it then oscillates between 0 and that turning point forever.

use crate::mechanics::energy::rolling_kinetic;
use crate::mechanics::liftoff::free_normal_acceleration;
use crate::mechanics::Ramp;
use crate::ode::roots::bisect;
use crate::trig::{cos, sin, tan};
use std::f64::consts::{PI, TAU};

/// The paper's J(θ) (Eq. Jta) as printed, with γ from the body. Infinite/NaN at α = π/2.
pub fn j_paper(r: &Ramp, theta: f64) -> f64 {
    let chi = r.body.chi;
    let gamma = r.body.gamma();
    let a = r.alpha;
    let (ca, ct) = (cos(a), cos(theta));
    -1.0 + (chi * ca - chi * cos(a + theta) + theta * sin(a)) * ct
        / ((2.0 * PI * gamma + ct - 1.0) * ca)
}

/// Eq. JtaC1 as printed: J(2πn − α).
pub fn jtac1(r: &Ramp, n: u32) -> f64 {
    let chi = r.body.chi;
    let gamma = r.body.gamma();
    let a = r.alpha;
    (chi * cos(a) + (TAU * n as f64 - a) * sin(a) - chi) / (cos(a) + 2.0 * PI * gamma - 1.0) - 1.0
}

/// Eq. JtaC2 as printed: J(2πn) = n tan α/γ − 1.
pub fn jtac2(r: &Ramp, n: u32) -> f64 {
    n as f64 * tan(r.alpha) / r.body.gamma() - 1.0
}

/// E(θ) = θ sin α + χ(cos α − cos(α + θ)) from rest at θ0 = 0, written without cancellation.
#[inline]
pub fn energy_drop(r: &Ramp, theta: f64) -> f64 {
    let (sin_mid, sin_half) = (sin(r.alpha + 0.5 * theta), sin(0.5 * theta));
    rolling_kinetic(0.0, theta, r.sin_a, r.body.chi, sin_mid, sin_half)
}

/// The lift-off function χθ̇² cos θ − cos α along pure rolling from (θ0, θ̇0).
pub fn liftoff_from(r: &Ramp, theta0: f64, omega0: f64, theta: f64) -> f64 {
    let chi_w2 = r.body.chi * r.omega_sq(theta0, omega0, theta);
    free_normal_acceleration(chi_w2, cos(theta), r.cos_a)
}

/// The lift-off function along pure rolling from rest at θ0 = 0 (= cos α · J(θ)).
pub fn liftoff(r: &Ramp, theta: f64) -> f64 {
    let ip = r.contact_inertia(cos(theta));
    free_normal_acceleration(
        r.body.chi * 2.0 * energy_drop(r, theta) / ip,
        cos(theta),
        r.cos_a,
    )
}

/// θ_{n,J}: the root of the lift-off function in [2πn − α, 2πn] (Eq. thetasoL2), by
/// bisection to the last bit. None if JtaC1/JtaC2 fail (no sign change − → + there).
/// This is the paper's root on turn n; whether the body gets there in pure rolling, or
/// lifts off earlier, is decided by [`crate::jarm`].
pub fn theta_nj(r: &Ramp, n: u32) -> Option<f64> {
    if n == 0 || r.body.chi == 0.0 {
        return None;
    }
    let hi = TAU * n as f64;
    let lo = hi - r.alpha;
    let (flo, fhi) = (liftoff(r, lo), liftoff(r, hi));
    if !(flo < 0.0 && fhi > 0.0) {
        return None;
    }
    bisect(|t| liftoff(r, t), lo, hi, flo, fhi)
        .ok()
        .map(|x| x.x)
}

/// From rest at θ0 = 0: the angle θ_r > 0 where θ̇² returns to 0 (the body rocks back),
/// if it does. Closed-form test of the lowest minimum of E, then bisection to the last bit.
///
/// For α > 0 this never happens: E(θ_m) = (2π − α − arcsin(sin α/χ)) sin α + χ cos α
/// − √(χ² − sin² α) > 0, because χ² cos² α − (χ² − sin² α) = sin² α (1 − χ²) ≥ 0 and
/// α + arcsin(sin α/χ) ≤ π. (Rocking back is possible for other starts, e.g. θ0 < 0 or
/// θ0 past the top; [`crate::jarm::path`] detects it for any start.) For α = 0 the start is an
/// equilibrium and Some(0) is returned.
pub fn rock_back_angle(r: &Ramp) -> Option<f64> {
    if r.sin_a == 0.0 {
        // α = 0 from rest at θ0 = 0 is an (unstable) equilibrium: it never moves.
        return Some(0.0);
    }
    // The lowest minimum of E after the start (none if E never decreases).
    let asn = r.energy_turn_offset()?;
    let theta_m = r.energy_minimum_after(0.0)?;
    let e_m = energy_drop(r, theta_m);
    if e_m > 0.0 {
        return None;
    }
    // E rises from 0 to its maximum at α + θ = π + arcsin(sin α/χ), then falls to E(θ_m) ≤ 0.
    let theta_max = PI + asn - r.alpha;
    let e_max = energy_drop(r, theta_max);
    if e_m == 0.0 {
        return Some(theta_m);
    }
    bisect(|t| energy_drop(r, t), theta_max, theta_m, e_max, e_m)
        .ok()
        .map(|x| x.x)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jarm::turns::turn_bound;
    use crate::mechanics::Cylinder;

    fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
        Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
    }

    /// n* from rest: the turn by which the first lift-off (or an earlier failure) must
    /// happen, None beyond `max_turns` ([`turn_bound`] from θ0 = θ̇0 = 0).
    fn first_turn_bound(r: &Ramp, max_turns: u32) -> Option<u32> {
        turn_bound(r, 0.0, 0.0, max_turns).filter(|&n| n <= max_turns)
    }

    #[test]
    fn j_is_the_liftoff_function_over_cos_alpha() {
        let r = ramp(0.3, 0.2, 35.0);
        for i in 1..100 {
            let th = 0.137 * i as f64;
            let l = liftoff(&r, th);
            assert!((j_paper(&r, th) - l / r.cos_a).abs() < 1e-12);
            assert!((liftoff_from(&r, 0.0, 0.0, th) - l).abs() < 1e-12);
        }
        for n in 1..5 {
            let a = r.alpha;
            assert!((jtac1(&r, n) - j_paper(&r, TAU * n as f64 - a)).abs() < 1e-12);
            assert!((jtac2(&r, n) - j_paper(&r, TAU * n as f64)).abs() < 1e-12);
        }
    }

    #[test]
    fn reference_jump_angle() {
        let r = ramp(0.15, 0.02, 40.0);
        let n = first_turn_bound(&r, 1000).unwrap();
        assert_eq!(n, 1);
        let th = theta_nj(&r, 1).unwrap();
        assert!(
            (th.to_degrees() - 334.344).abs() < 1e-3,
            "{}",
            th.to_degrees()
        );
        assert!(liftoff(&r, th).abs() < 1e-14);
        let j = crate::jarm::jump_point::jump_forces(&r.body, r.alpha, th);
        assert!((j.fy - 0.01543).abs() < 1e-5 && (j.fx + 0.00516).abs() < 1e-5);
    }

    #[test]
    fn turn_bound_matches_jtac2() {
        for &(chi, km, a) in &[
            (0.1, 0.3, 5.0),
            (0.5, 0.2, 1.0),
            (0.9, 0.0, 0.3),
            (0.05, 0.5, 89.0),
        ] {
            let r = ramp(chi, km, a);
            let n = first_turn_bound(&r, 1_000_000).unwrap();
            assert!(jtac2(&r, n) > 0.0);
            if n > 1 {
                assert!(jtac2(&r, n - 1) <= 0.0);
            }
        }
        assert!(first_turn_bound(&ramp(0.1, 0.3, 0.0), 1000).is_none());
        assert!(first_turn_bound(&ramp(0.01, 0.3, 0.01), 1000).is_none());
        assert_eq!(first_turn_bound(&ramp(0.3, 0.3, 90.0), 10), Some(1));
    }

    #[test]
    fn no_rocking_back_from_rest_at_zero() {
        // E(θ_m) = (2π − α − asin(sin α/χ)) sin α + χ cos α − √(χ² − sin² α) > 0 for α > 0:
        // from rest at θ0 = 0 the body always passes the next top. Checked densely too.
        for &(chi, a) in &[
            (0.8, 5.0),
            (0.99, 0.05),
            (0.999, 0.5),
            (0.5, 20.0),
            (1.0, 1e-3),
        ] {
            let r = ramp(chi, 0.0, a);
            assert!(rock_back_angle(&r).is_none());
            for i in 1..100_000 {
                assert!(energy_drop(&r, 3.0 * TAU * i as f64 / 100_000.0) > 0.0);
            }
        }
        assert_eq!(rock_back_angle(&ramp(0.5, 0.1, 0.0)), Some(0.0));
    }
}

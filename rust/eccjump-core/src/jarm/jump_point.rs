//! Sec. 3.1 of the paper: the forces at a jump point and the friction they need,
//! independent of the initial conditions.
//!
//! At a jump point of the paper's rule the lift-off function vanishes,
//! χ θ̇_J² cos θ_J = cos α, i.e. θ̇_J² = cos α/(χ cos θ_J) (needs cos θ_J > 0). Put into the
//! rolling equation (see [`crate::modes::rolling`]):
//!
//!   θ̈_J Ĩ_P = cos α tan θ_J + χ sin(α + θ_J) + sin α = sin(α + θ_J)(1 + χ cos θ_J)/cos θ_J,
//!
//! with Ĩ_P = Ĩ_C + 1 + 2χ cos θ_J (the paper's Njump3). Then, since cos α − χθ̇_J² cos θ_J = 0,
//!
//!   F_y,J = −χ θ̈_J sin θ_J = −χ (1 + χ cos θ_J) tan θ_J sin(α + θ_J)/Ĩ_P          (Njumpfn)
//!   F_x,J = −sin α − cos α tan θ_J + (1 + χ cos θ_J) θ̈_J
//!         = sin(α + θ_J)[(1 + χ cos θ_J)² − Ĩ_P]/(cos θ_J Ĩ_P)
//!         = −(Ĩ_C − χ² cos² θ_J) sin(α + θ_J)/(cos θ_J Ĩ_P)                        (jump6)
//!
//! and the signed ratio, in which sin(α + θ_J) cancels (so it does not depend on α):
//!
//!   μ(χ, k_m, θ_J) = −F_x,J/F_y,J = −(Ĩ_C − χ² cos² θ_J)/(χ sin θ_J (1 + χ cos θ_J))  (ineq2)
//!
//! μ equals the friction ratio |F_x,J|/F_y,J only where F_y,J > 0 and F_x,J < 0, i.e. in the
//! green window 2πn − α < θ_J < 2πn, where sin θ_J < 0. Below, angles in the window are
//! written relative to the turn: φ = θ_J − 2πn ∈ (−π/2, 0) (the window for α = π/2).
//!
//! Limits: for χ = 0 no jump point exists (the lift-off function is −cos α); we return
//! μ_s,min = +∞ and no θ_J range. For k_m = 0 (Ĩ_CM = 0, so Ĩ_C = χ²)
//! μ = −χ sin φ/(1 + χ cos φ) → 0 as φ → 0⁻: μ_s,min = 0, reached only at the window's end,
//! which is where the paper's α = 0 argument (μ diverges at θ_J = 2πn) fails.

use crate::mechanics::Cylinder;
use crate::ode::roots::bisect;
use std::f64::consts::{FRAC_PI_2, TAU};

/// Forces at a jump point of the paper's rule, per M g.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JumpForces {
    /// θ̇_J² = cos α/(χ cos θ_J).
    pub omega_sq: f64,
    /// θ̈_J (Njump3).
    pub omega_dot: f64,
    /// Friction force F_x,J (jump6).
    pub fx: f64,
    /// Normal force F_y,J (Njumpfn).
    pub fy: f64,
}

/// Forces at a jump point θ_J on a ramp of angle α. Valid only at a true jump point:
/// needs χ > 0 and cos θ_J > 0 (otherwise the fields are non-finite or meaningless).
pub fn jump_forces(body: &Cylinder, alpha: f64, theta_j: f64) -> JumpForces {
    let chi = body.chi;
    let (s, c) = crate::trig::sin_cos(theta_j);
    let (sa, ca) = crate::trig::sin_cos(alpha);
    let sin_at = sa * c + ca * s;
    let ip = body.ic + 1.0 + 2.0 * chi * c;
    let omega_dot = sin_at * (1.0 + chi * c) / (c * ip);
    JumpForces {
        omega_sq: ca / (chi * c),
        omega_dot,
        fx: -(body.ic - chi * chi * c * c) * sin_at / (c * ip),
        fy: -chi * (1.0 + chi * c) * (s / c) * sin_at / ip,
    }
}

/// μ(χ, k_m, θ_J) of Eq. (ineq2): the signed ratio −F_x,J/F_y,J. Periodic in θ_J; the friction
/// ratio only where sin θ_J < 0 (the green window). Infinite for χ = 0 (if Ĩ_C > 0).
pub fn mu(body: &Cylinder, theta_j: f64) -> f64 {
    let chi = body.chi;
    let (s, c) = crate::trig::sin_cos(theta_j);
    if chi == 0.0 {
        return if body.ic == 0.0 { 0.0 } else { f64::INFINITY };
    }
    if body.icm == 0.0 {
        // Ĩ_C − χ² cos² θ = χ² sin² θ: μ = −χ sin θ/(1 + χ cos θ), finite (→ 0) at sin θ = 0.
        return -chi * s / (1.0 + chi * c);
    }
    // Ĩ_C − χ² cos² θ = Ĩ_CM + χ² sin² θ, without cancellation.
    -(body.icm + chi * chi * s * s) / (chi * s * (1.0 + chi * c))
}

/// The green-interval test 2πn − α < θ_J < 2πn for some turn n ≥ 1; returns that n.
pub fn green_turn(alpha: f64, theta_j: f64) -> Option<u32> {
    if !(theta_j.is_finite() && alpha > 0.0) {
        return None;
    }
    let n = (theta_j / TAU).ceil();
    if n < 1.0 || n > u32::MAX as f64 {
        return None;
    }
    let end = TAU * n;
    if theta_j < end && theta_j > end - alpha {
        Some(n as u32)
    } else {
        None
    }
}

/// False only if no θ in [lo, hi] is in a green window 2πn − α < θ < 2πn (n ≥ 1), i.e. if
/// [`green_turn`] is None on the whole interval; the test keeps a margin of 1e-9 (1 + |θ|)
/// rad for the rounding of 2πn, so it may say true near a window's edge.
pub fn may_be_green(alpha: f64, lo: f64, hi: f64) -> bool {
    if !(lo.is_finite() && hi.is_finite() && alpha > 0.0) {
        return true;
    }
    let tol = 1e-9 * (1.0 + lo.abs().max(hi.abs()));
    // The first window ending after lo: its end 2πn > lo (n ≥ 1); the earlier ones end by lo.
    let n = ((lo - tol) / TAU).floor() + 1.0;
    TAU * n.max(1.0) - alpha < hi + tol
}

/// Sign of dμ/dφ on (−π/2, 0): with c = cos φ it is the sign of
///   f(c) = c/(1 − c²) − χ/(1 + χc) − 2χ²c/(Ĩ_C − χ²c²)      (d ln μ/dc; dc/dφ > 0 there).
/// Written with 1 − c² = sin² φ to keep precision near φ = 0.
fn dmu_sign_fn(body: &Cylinder, phi: f64) -> f64 {
    let chi = body.chi;
    let (s, c) = crate::trig::sin_cos(phi);
    let den = body.icm + chi * chi * s * s; // Ĩ_C − χ²c², exact-ish form
    c / (s * s) - chi / (1.0 + chi * c) - 2.0 * chi * chi * c / den
}

/// μ_s,min(χ, k_m): the smallest static friction coefficient for which some jump point in the
/// window (−π/2, 0) (relative to 2πn) needs no more friction than μ_s; returned with the
/// relative angle φ* where it is reached. χ = 0: (+∞, NaN); k_m = 0 (Ĩ_CM = 0): (0, 0).
///
/// Robust minimisation: the sign of dμ/dφ is scanned on 256 points of (−π/2, 0), every
/// sign change − → + is bisected to the last bit and the smallest μ among them is taken.
/// (At φ → −π/2⁺ the derivative is negative and at φ → 0⁻ positive, so a minimum is interior.)
pub fn mu_s_min(body: &Cylinder) -> (f64, f64) {
    if body.chi == 0.0 {
        return (f64::INFINITY, f64::NAN);
    }
    if body.icm == 0.0 {
        return (0.0, 0.0);
    }
    const N: usize = 256;
    let lo = -FRAC_PI_2;
    let grid = (1..N).map(|i| lo + FRAC_PI_2 * (i as f64) / (N as f64));
    let mut best = (f64::INFINITY, f64::NAN);
    let mut prev_phi = lo;
    let mut prev_f = dmu_sign_fn(body, lo);
    // The grid's last cell ends just below 0, where f → +∞.
    for phi in grid.chain([-f64::EPSILON * FRAC_PI_2]) {
        let f = dmu_sign_fn(body, phi);
        if prev_f < 0.0 && f >= 0.0 {
            if let Ok(r) = bisect(|p| dmu_sign_fn(body, p), prev_phi, phi, prev_f, f) {
                let m = mu(body, r.x);
                if m < best.0 {
                    best = (m, r.x);
                }
            }
        }
        prev_phi = phi;
        prev_f = f;
    }
    best
}

/// The jump angles allowed by friction: {φ ∈ (−π/2, 0) : μ(φ) ≤ μ_s} = [φ_min, φ_max]
/// relative to 2πn (θ_J,min = 2πn + φ_min, θ_J,max = 2πn + φ_max). None if μ_s < μ_s,min.
/// When μ_s ≥ μ(−π/2) = Ĩ_C/χ there is only one root and φ_min = −π/2 (no lower bound
/// from friction; the window's own bound 2πn − α applies). For Ĩ_CM = 0, φ_max = 0.
///
/// μ is unimodal on the window (one minimum; checked on a grid of (χ, k_m) in the tests),
/// so the set is one interval; its ends are bisected to the last bit.
pub fn theta_j_range(body: &Cylinder, mu_s: f64) -> Option<(f64, f64)> {
    let (m_min, phi_star) = mu_s_min(body);
    if mu_s.is_nan() || mu_s < m_min {
        return None;
    }
    let g = |p: f64| mu(body, p) - mu_s;
    let phi_max = if body.icm == 0.0 {
        0.0
    } else {
        let hi = -f64::EPSILON;
        bisect(g, phi_star, hi, g(phi_star), g(hi)).map_or(phi_star, |r| r.x)
    };
    let lo = -FRAC_PI_2;
    let phi_min = if g(lo) <= 0.0 {
        lo
    } else {
        let a = if body.icm == 0.0 { 0.0 } else { phi_star };
        bisect(g, lo, a, g(lo), g(a)).map_or(a, |r| r.x)
    };
    Some((phi_min, phi_max))
}

/// θ_J,min and θ_J,max as absolute angles on turn n.
pub fn theta_j_range_abs(body: &Cylinder, mu_s: f64, n: u32) -> Option<(f64, f64)> {
    theta_j_range(body, mu_s).map(|(a, b)| (TAU * n as f64 + a, TAU * n as f64 + b))
}

/// α_min(n) = 2πn − θ_J,max: the smallest ramp angle whose green window reaches a jump angle
/// friction allows. Independent of n (it equals −φ_max). None if μ_s < μ_s,min.
pub fn alpha_min(body: &Cylinder, mu_s: f64, n: u32) -> Option<f64> {
    theta_j_range_abs(body, mu_s, n).map(|(_, tmax)| TAU * n as f64 - tmax)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::Ramp;

    fn body(chi: f64, km: f64) -> Cylinder {
        Cylinder::new(chi, km).unwrap()
    }

    #[test]
    fn jump_forces_follow_from_the_rolling_equations() {
        // Put θ̇² = cos α/(χ cos θ) into Ramp::kinematics: an independent route.
        for &(chi, km, a_deg, th) in &[
            (0.15, 0.02, 40.0f64, 5.835f64),
            (0.5, 0.4, 30.0, -0.3),
            (0.8, 0.1, 70.0, 1.0),
            (0.3, 0.5, 10.0, 6.2),
        ] {
            let b = body(chi, km);
            let alpha: f64 = a_deg.to_radians();
            let r = Ramp::new(b, alpha).unwrap();
            let w2 = alpha.cos() / (chi * th.cos());
            let k = r.kinematics(th, w2.sqrt());
            let j = jump_forces(&b, alpha, th);
            assert!((k.fx - j.fx).abs() < 1e-12, "{} {}", k.fx, j.fx);
            assert!((k.fy - j.fy).abs() < 1e-12, "{} {}", k.fy, j.fy);
            assert!((k.omega_dot - j.omega_dot).abs() < 1e-12);
            // The paper's printed jump6 / Njumpfn / Njump3, typed as printed.
            let ic = km + chi * chi / (1.0 - km);
            let (s, c) = crate::trig::sin_cos(th);
            let sec = 1.0 / c;
            let den = km + chi * chi / (1.0 - km) + 1.0 + 2.0 * chi * c;
            let fx_p =
                -((km + chi * chi / (1.0 - km) - chi * chi * c * c) * sec * (alpha + th).sin())
                    / den;
            let fy_p = -(chi * (1.0 + chi * c) * th.tan() * (alpha + th).sin()) / den;
            let acc_p = (1.0 + chi * c) * sec * (alpha + th).sin() / den;
            assert!((fx_p - j.fx).abs() < 1e-12 && (fy_p - j.fy).abs() < 1e-12);
            assert!((acc_p - j.omega_dot).abs() < 1e-12);
            assert!((ic - b.ic).abs() < 1e-15);
            // Eq. ineq2 as printed.
            let mu_p = ((-km * km + km + chi * chi) / ((km - 1.0) * chi * chi) + c * c)
                / (s * (1.0 / chi + c));
            assert!((mu_p - mu(&b, th)).abs() < 1e-12 * mu_p.abs().max(1.0));
            assert!((mu(&b, th) + j.fx / j.fy).abs() < 1e-10 * mu_p.abs().max(1.0));
            let _ = s;
        }
    }

    #[test]
    fn signs_in_the_green_window() {
        let b = body(0.5, 0.4);
        let alpha = 0.6;
        for i in 1..50 {
            let th = TAU - alpha * i as f64 / 50.0;
            let j = jump_forces(&b, alpha, th);
            assert!(j.fy > 0.0 && j.fx < 0.0);
            assert!((mu(&b, th) - (-j.fx / j.fy)).abs() < 1e-12);
            assert_eq!(green_turn(alpha, th), Some(1));
        }
        // Grey region (cos θ > 0 but outside the window): F_y,J < 0.
        let th = TAU - alpha - 0.2;
        assert!(jump_forces(&b, alpha, th).fy < 0.0);
        assert_eq!(green_turn(alpha, th), None);
        assert_eq!(green_turn(alpha, 2.0 * TAU - 0.1), Some(2));
        assert_eq!(green_turn(alpha, TAU), None);
    }

    #[test]
    fn may_be_green_is_true_wherever_a_point_is_green() {
        let mut s = 7u64;
        let mut u = || {
            s ^= s << 13;
            s ^= s >> 7;
            s ^= s << 17;
            (s >> 11) as f64 / (1u64 << 53) as f64
        };
        let (mut no, mut yes) = (0, 0);
        for _ in 0..20_000 {
            let alpha = FRAC_PI_2 * u();
            let lo = 40.0 * u() - 5.0;
            let hi = lo + 1.2 * u() * u();
            let green =
                (0..=64).any(|i| green_turn(alpha, lo + (hi - lo) * i as f64 / 64.0).is_some());
            let may = may_be_green(alpha, lo, hi);
            assert!(may || !green, "{alpha} {lo} {hi}");
            if !may {
                no += 1;
            } else {
                yes += 1;
            }
        }
        assert!(no > 5_000 && yes > 2_000, "{no} {yes}");
        // The window edges themselves.
        assert!(may_be_green(0.5, TAU - 0.5 - 1e-3, TAU - 0.5 + 1e-3));
        assert!(!may_be_green(0.5, TAU - 0.5 - 0.2, TAU - 0.5 - 0.1));
        assert!(!may_be_green(0.5, TAU + 0.1, TAU + 0.2));
        assert!(may_be_green(0.5, TAU - 0.1, TAU + 0.1));
        assert!(may_be_green(0.5, 0.0, 100.0));
        assert!(may_be_green(f64::NAN, 1.0, 2.0));
    }

    #[test]
    fn mu_s_min_reference_and_dense_scan() {
        let b = body(0.5, 0.4);
        let (m, phi) = mu_s_min(&b);
        assert!((m - 1.3916).abs() < 5e-5, "{m}");
        // Dense scan cannot beat it.
        let mut dense = f64::INFINITY;
        for i in 1..200_000 {
            let p = -FRAC_PI_2 * i as f64 / 200_000.0;
            dense = dense.min(mu(&b, p));
        }
        assert!(m <= dense + 1e-15 && dense - m < 1e-9, "{m} {dense}");
        // A stationary point: μ(φ* ± h) ≥ μ(φ*).
        assert!(mu(&b, phi + 1e-6) >= m && mu(&b, phi - 1e-6) >= m);
    }

    #[test]
    fn mu_is_unimodal_on_the_window() {
        for i in 1..20 {
            let chi = i as f64 / 20.0;
            for j in 0..=10 {
                let km = (1.0 - chi) * j as f64 / 10.0;
                let b = body(chi, km);
                let mut changes = 0;
                let mut prev = dmu_sign_fn(&b, -FRAC_PI_2 + 1e-9);
                for k in 1..4000 {
                    let p = -FRAC_PI_2 + FRAC_PI_2 * k as f64 / 4000.0;
                    let f = dmu_sign_fn(&b, p);
                    if (f >= 0.0) != (prev >= 0.0) {
                        changes += 1;
                    }
                    prev = f;
                }
                assert!(changes <= 1, "chi {chi} km {km}: {changes}");
            }
        }
    }

    #[test]
    fn theta_j_range_and_alpha_min() {
        let b = body(0.5, 0.4);
        assert!(theta_j_range(&b, 1.3).is_none());
        let (lo, hi) = theta_j_range(&b, 1.5).unwrap();
        assert!(-FRAC_PI_2 < lo && lo < hi && hi < 0.0);
        assert!((mu(&b, lo) - 1.5).abs() < 1e-12 && (mu(&b, hi) - 1.5).abs() < 1e-12);
        // Large μ_s: one root only.
        let (lo, hi) = theta_j_range(&b, 5.0).unwrap();
        assert_eq!(lo, -FRAC_PI_2);
        assert!((mu(&b, hi) - 5.0).abs() < 1e-11);
        let am = alpha_min(&b, 5.0, 3).unwrap();
        assert!((am + hi).abs() < 1e-12);
        // k_m = 0: μ → 0 at the window's end, μ_s,min = 0.
        let b0 = body(0.6, 0.0);
        assert_eq!(mu_s_min(&b0).0, 0.0);
        assert!(mu(&b0, -1e-8) < 1e-7);
        let (lo, hi) = theta_j_range(&b0, 0.3).unwrap();
        assert_eq!(hi, 0.0);
        assert!((mu(&b0, lo) - 0.3).abs() < 1e-12);
        // χ = 0: no jump point.
        assert!(mu_s_min(&body(0.0, 0.5)).0.is_infinite());
        assert!(theta_j_range(&body(0.0, 0.5), 10.0).is_none());
    }
}

//! Turns along the rolling path: the turn of an angle and the search bound n*, shared by
//! both routes and the from-rest closed forms.
//!
//! At θ = 2πn the normal force of pure rolling is −L(2πn) (sin θ = 0 there), and along
//! rolling from (θ0, θ̇0) L(2πn) > 0 ⇔ 2πn sin α > R with
//!   R = cos α Ĩ_P(0)/(2χ) − K0 + θ0 sin α − χ(cos(α + θ0) − cos α),  K0 = ½Ĩ_P(θ0)θ̇0²,
//! (energy conservation, [`crate::mechanics::energy`]). So under either lift-off rule
//! something happens by the first such turn n*; searches never go further. From rest at 0
//! the condition reads n tan α > γ (the paper's Eq. JtaC2).

use crate::mechanics::Ramp;
use std::f64::consts::TAU;

/// The turn of an event at θ: round(θ/2π), at least 1 (an event in the first half turn is on
/// turn 1, not 0, which means "none"), clamped to u32. A paper lift-off needs cos θ > 0, so
/// its turn is unambiguous: 2πn − π/2 < θ_J < 2πn + π/2.
#[inline]
pub fn turn_of(theta: f64) -> u32 {
    let n = (theta / TAU).round();
    if n.is_nan() {
        0
    } else if n <= 1.0 {
        1
    } else if n >= u32::MAX as f64 {
        u32::MAX
    } else {
        n as u32
    }
}

/// The whole turns completed before θ0 (0 for θ0 < 2π): searches count `max_turns` from
/// there.
#[inline]
pub fn turns_before(theta0: f64) -> u64 {
    let k = (theta0 / TAU).floor();
    if k.is_nan() || k <= 0.0 {
        0
    } else {
        k.min(u32::MAX as f64) as u64
    }
}

/// The turn bound n*: the smallest n with 2πn > θ0 and L(2πn) > 0 along rolling from
/// (θ0, θ̇0); None if it does not exist (α = 0 or χ = 0). Capped at
/// [`turns_before`]`(θ0) + max_turns + 1`.
pub fn turn_bound(r: &Ramp, theta0: f64, omega0: f64, max_turns: u32) -> Option<u32> {
    let chi = r.body.chi;
    if chi == 0.0 || r.sin_a == 0.0 {
        return None;
    }
    let cap = (turns_before(theta0) + max_turns as u64 + 1).min(u32::MAX as u64);
    let n_lo = ((theta0 / TAU).floor() + 1.0).max(1.0);
    if n_lo > cap as f64 {
        return Some(cap as u32);
    }
    // From rest at θ0 = 0 (every map's default) both terms below are exactly 0: no `cos`.
    let k0 = if omega0 == 0.0 {
        0.0
    } else {
        let (_, c0) = crate::trig::sin_cos(theta0);
        0.5 * r.contact_inertia(c0) * omega0 * omega0
    };
    let shift = if theta0 == 0.0 {
        0.0
    } else {
        crate::trig::sin_cos(r.alpha + theta0).1 - r.cos_a
    };
    let ip0 = r.contact_inertia(1.0);
    let rhs = r.cos_a * ip0 / (2.0 * chi) - k0 + theta0 * r.sin_a - chi * shift;
    let per = TAU * r.sin_a;
    let guess = (rhs / per).floor() + 1.0;
    let mut n = guess.max(n_lo).min(cap as f64) as u64;
    while n > n_lo as u64 && (n - 1) as f64 * per > rhs {
        n -= 1;
    }
    while n < cap && n as f64 * per <= rhs {
        n += 1;
    }
    Some(n as u32)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::Cylinder;

    #[test]
    fn turn_bound_is_the_first_turn_with_negative_normal_force() {
        // Independent route: F_y(2πn) = −L(2πn) from the rolling kinematics along the path.
        for &(chi, km, a, th0, w0) in &[
            (0.1, 0.3, 5.0f64, 0.0, 0.0),
            (0.5, 0.2, 1.0, 0.0, 0.0),
            (0.3, 0.1, 3.0, 0.4, 0.3),
            (0.7, 0.05, 0.5, -1.0, 0.1),
        ] {
            let r = Ramp::new(Cylinder::new(chi, km).unwrap(), a.to_radians()).unwrap();
            let n = turn_bound(&r, th0, w0, 1_000_000).unwrap();
            let fy = |n: u32| r.kinematics_along(th0, w0, TAU * n as f64).fy;
            assert!(fy(n) < 0.0, "{chi} {a}");
            if n > 1 && TAU * (n - 1) as f64 > th0 {
                assert!(fy(n - 1) >= -1e-12);
            }
        }
    }
}

//! The derivatives against central differences of the classification itself (its own root
//! finder, an independent route to θ_J), and the flagged and trivial cases.

use super::*;
use crate::jarm::{classify, JarmResult, Reason};

/// The classification at p = (α, χ, k_m) with `o`.
fn classified(p: [f64; 3], mu_s: f64, o: &JarmOptions) -> JarmResult {
    classify(p[0], p[1], p[2], mu_s, o)
}

/// Central differences of (θ_J, F_x,J, F_y,J, −F_x,J/F_y,J) of the classification in p_i.
fn differences(p: [f64; 3], mu_s: f64, o: &JarmOptions, i: usize) -> [f64; 4] {
    let h = 1e-6;
    let at = |sign: f64| {
        let mut q = p;
        q[i] += sign * h;
        let r = classified(q, mu_s, o);
        assert_eq!(r.reason, Reason::Jarm, "{q:?}");
        [r.theta_j, r.fx_j, r.fy_j, -r.fx_j / r.fy_j]
    };
    let (up, down) = (at(1.0), at(-1.0));
    std::array::from_fn(|k| (up[k] - down[k]) / (2.0 * h))
}

fn check_against_differences(p: [f64; 3], mu_s: f64, o: &JarmOptions) {
    let r = classified(p, mu_s, o);
    assert_eq!(r.reason, Reason::Jarm);
    let d = jump_derivatives(p[0], p[1], p[2], mu_s, r.theta_j, o);
    assert!(!d.singular);
    for i in 0..3 {
        let fd = differences(p, mu_s, o, i);
        let exact = [d.theta_j[i], d.fx_j[i], d.fy_j[i], d.mu_j[i]];
        for (k, (x, y)) in exact.iter().zip(fd).enumerate() {
            assert!(
                (x - y).abs() <= 1e-6 * (1.0 + x.abs()),
                "{:?} p{i} field {k}: {x} vs {y}",
                o.rule
            );
        }
    }
}

#[test]
fn agree_with_differences_of_the_paper_rule_classification() {
    let o = JarmOptions::default();
    check_against_differences([40f64.to_radians(), 0.15, 0.02], 1.0, &o);
    check_against_differences([0.43035434364068176, 0.40227469606, 0.12416803289], 1.0, &o);
    let moving = JarmOptions {
        theta0: -0.4,
        omega0: 0.3,
        ..o
    };
    check_against_differences([40f64.to_radians(), 0.15, 0.02], 1.0, &moving);
}

#[test]
fn agree_with_differences_of_the_classical_rule_classification() {
    // Lift-off where the friction cone is reached and sliding is inconsistent.
    let o = JarmOptions {
        rule: Rule::NormalForce,
        ..JarmOptions::default()
    };
    check_against_differences(
        [1.307614733181189, 0.07753522892693436, 0.053726066545],
        1.0,
        &o,
    );
    check_against_differences(
        [0.6156081003127996, 0.20195344412356825, 0.0383714316],
        1.0,
        &o,
    );
}

#[test]
fn the_paper_rule_ratio_is_eq_ineq2_along_the_jump() {
    // At a root of L the rolling forces are the jump-point forces: μ_J is closed_form.mu.
    let (a, chi, km) = (40f64.to_radians(), 0.15, 0.02);
    let r = classify(a, chi, km, 1.0, &JarmOptions::default());
    let q = Rolling::at(r.theta_j, (a, chi, km), (0.0, 0.0));
    let body = crate::Cylinder::new(chi, km).unwrap();
    let mu = crate::jarm::jump_point::mu(&body, r.theta_j);
    assert!((-q.fx.v / q.fy.v - mu).abs() < 1e-12 * mu);
    assert!((q.fx.v - r.fx_j).abs() < 1e-14 && (q.fy.v - r.fy_j).abs() < 1e-14);
}

#[test]
fn a_tangent_lift_off_function_is_flagged() {
    // At a local maximum of L along rolling ∂L/∂θ = 0: fed as θ_J it must be flagged.
    let (a, chi, km) = (0.3, 0.5, 0.2);
    let slope = |t: f64| Rolling::at(t, (a, chi, km), (0.0, 0.0)).lift.d[0];
    let mut lo = (0..1000)
        .map(|i| 0.01 * i as f64)
        .find(|&t| slope(t) > 0.0 && slope(t + 0.01) <= 0.0)
        .expect("L has a maximum on the first turns");
    let mut hi = lo + 0.01;
    for _ in 0..100 {
        let mid = 0.5 * (lo + hi);
        if slope(mid) > 0.0 {
            lo = mid
        } else {
            hi = mid
        }
    }
    let o = JarmOptions::default();
    let d = jump_derivatives(a, chi, km, 1.0, lo, &o);
    assert!(d.singular && d.theta_j.iter().all(|x| x.is_nan()), "{d:?}");
    // A little off the maximum: finite.
    let d = jump_derivatives(a, chi, km, 1.0, lo - 1e-3, &o);
    assert!(!d.singular && d.theta_j.iter().all(|x| x.is_finite()));
}

#[test]
fn a_classical_tie_of_both_forces_at_zero_is_flagged() {
    // F_x = F_y = 0 together: the corner of the friction cone, where neither function alone
    // is the one that vanishes.
    let zero = Dual::variable(0.0, 0);
    let q = Rolling {
        omega_sq: Dual::constant(1.0),
        omega_dot: Dual::constant(0.5),
        lift: zero,
        fx: zero.scale(2.0),
        fy: zero.scale(-1.0),
    };
    assert!(vanishing(&q, Rule::NormalForce, 0.1, 1.0, 1e-12).is_none());
    assert!(vanishing(&q, Rule::Paper, 0.1, 1.0, 1e-12).is_some());
    // k_m = 0: the forces vanish together at every classical lift-off; F_y is the root.
    assert!(vanishing(&q, Rule::NormalForce, 0.0, 1.0, 1e-12)
        .is_some_and(|(_, g)| g == Root::NormalForce));
}

#[test]
fn classical_jumps_of_a_body_without_inertia_about_its_centre_of_mass() {
    // k_m = 0: F_x = F_y = 0 at the lift-off (not a tie); the α and χ slopes are those of
    // the classification (for k_m > 0 these points slip first, so k_m is left out).
    let o = JarmOptions {
        rule: Rule::NormalForce,
        ..JarmOptions::default()
    };
    let p = [0.6981317007977318, 0.27, 0.0];
    let r = classified(p, 1.0, &o);
    assert_eq!(r.reason, Reason::Jarm);
    assert!(r.fx_j.abs() < 1e-12 && r.fy_j.abs() < 1e-12);
    let d = jump_derivatives(p[0], p[1], p[2], 1.0, r.theta_j, &o);
    assert!(!d.singular && d.mu_j.iter().all(|x| x.is_nan()), "{d:?}");
    assert!(d.theta_j[2].is_nan(), "one-sided at k_m = 0: {d:?}");
    for i in 0..2 {
        let fd = differences_of_theta(p, 1.0, &o, i);
        assert!(
            (d.theta_j[i] - fd).abs() < 1e-6 * (1.0 + fd.abs()),
            "{i}: {d:?} {fd}"
        );
    }
}

fn differences_of_theta(p: [f64; 3], mu_s: f64, o: &JarmOptions, i: usize) -> f64 {
    let h = 1e-6;
    let (mut up, mut down) = (p, p);
    up[i] += h;
    down[i] -= h;
    (classified(up, mu_s, o).theta_j - classified(down, mu_s, o).theta_j) / (2.0 * h)
}

#[test]
fn a_lift_off_at_the_start_does_not_move() {
    // A start fast enough that L > 0 at θ0: LiftoffEarlier with θ_J = θ0 (also from a start
    // below 0, classified one turn up and shifted back).
    for theta0 in [0.0, 0.1 - TAU] {
        let o = JarmOptions {
            theta0,
            omega0: 3.0,
            ..JarmOptions::default()
        };
        let r = crate::jarm::classify_with(crate::jarm::Method::ClosedForm, 0.5, 0.3, 0.2, 1.0, &o);
        assert_eq!(r.reason, Reason::LiftoffEarlier);
        let d = jump_derivatives(0.5, 0.3, 0.2, 1.0, r.theta_j, &o);
        assert_eq!(d.theta_j, [0.0; 3]);
        assert!(!d.singular);
    }
}

#[test]
fn no_jump_or_invalid_point_has_nan_derivatives() {
    let o = JarmOptions::default();
    for d in [
        jump_derivatives(0.5, 0.3, 0.2, 1.0, f64::NAN, &o),
        jump_derivatives(0.5, 0.3, 0.9, 1.0, 5.9, &o), // k_m > 1 − χ
        jump_derivatives(f64::NAN, 0.3, 0.2, 1.0, 5.9, &o),
    ] {
        assert!(!d.singular);
        assert!(d
            .theta_j
            .iter()
            .chain(&d.fx_j)
            .chain(&d.mu_j)
            .all(|x| x.is_nan()));
    }
}

/// Central differences in α and χ only (k_m = 0 is the edge of the body's range).
fn differences_in_alpha_and_chi(p: [f64; 3], mu_s: f64, o: &JarmOptions) -> [[f64; 4]; 2] {
    [0, 1].map(|i| differences(p, mu_s, o, i))
}

#[test]
fn the_cone_decides_at_km_zero_under_the_classical_rule() {
    // Issue 46's reproducer: k_m = 0, the lift-off on the friction cone with F_y > 0. The
    // force points at the centre of mass, so F_x/F_y depends on θ and χ only: dθ_J/dα = 0.
    let o = JarmOptions {
        rule: Rule::NormalForce,
        ..JarmOptions::default()
    };
    let p = [0.14828865162181382, 0.47671855125849555, 0.0];
    let r = classified(p, 0.3, &o);
    assert_eq!(r.reason, Reason::Jarm);
    assert!(r.fy_j > 0.01, "{}", r.fy_j);
    let d = jump_derivatives(p[0], p[1], p[2], 0.3, r.theta_j, &o);
    assert!(!d.singular);
    for (i, fd) in differences_in_alpha_and_chi(p, 0.3, &o).iter().enumerate() {
        let exact = [d.theta_j[i], d.fx_j[i], d.fy_j[i], d.mu_j[i]];
        for (k, (x, y)) in exact.iter().zip(fd).enumerate() {
            assert!(
                (x - y).abs() <= 1e-6 * (1.0 + x.abs()),
                "p{i} field {k}: {x} vs {y}"
            );
        }
    }
    assert!(d.theta_j[0].abs() < 1e-9 && d.fy_j[0] < -0.5, "{d:?}");
    // μ_J = −σ μ_s on the cone: its derivatives are exactly 0.
    assert_eq!(d.mu_j[..2], [0.0, 0.0]);
    // The k_m column is one-sided at k_m = 0: NaN.
    for col in [d.theta_j, d.fx_j, d.fy_j, d.mu_j] {
        assert!(col[2].is_nan());
    }
}

#[test]
fn on_the_cone_the_ratio_does_not_move() {
    let o = JarmOptions {
        rule: Rule::NormalForce,
        ..JarmOptions::default()
    };
    for (p, mu_s) in [
        (
            [1.307614733181189, 0.07753522892693436, 0.053726066545],
            1.0,
        ),
        (
            [1.307614733181189, 0.07753522892693436, 0.053726066545],
            1e6,
        ),
    ] {
        let r = classified(p, mu_s, &o);
        let d = jump_derivatives(p[0], p[1], p[2], mu_s, r.theta_j, &o);
        if r.fy_j > 1e-9 {
            assert_eq!(d.mu_j, [0.0; 3], "{p:?} {mu_s}");
        } else {
            assert!(d.mu_j.iter().all(|m| m.is_nan()), "{p:?} {mu_s}");
        }
    }
}

//! Tests of `jarm::classify`, the closed-form route, through the public API.

use eccjump_core::jarm::path::RollingPath;
use eccjump_core::jarm::{classify, JarmOptions, JarmResult, Reason};
use eccjump_core::mechanics::{Cylinder, Ramp, Rule};
use std::f64::consts::{FRAC_PI_2, PI};

fn c(a_deg: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> JarmResult {
    classify(a_deg.to_radians(), chi, km, mu_s, o)
}

#[test]
fn reason_codes_are_stable() {
    for (i, r) in Reason::ALL.iter().enumerate() {
        assert_eq!(r.code() as usize, i);
        assert_eq!(Reason::from_code(i as u8), Some(*r));
    }
    assert_eq!(Reason::from_code(11), None);
}

#[test]
fn reference_jarm() {
    let o = JarmOptions::default();
    let r = c(40.0, 0.15, 0.02, 1.0, &o);
    assert_eq!(r.reason, Reason::Jarm);
    assert_eq!(r.n, 1);
    assert!((r.theta_j.to_degrees() - 334.344).abs() < 1e-3);
    assert!((r.fy_j - 0.01543).abs() < 1e-5 && (r.fx_j + 0.00516).abs() < 1e-5);
    // The paper's θ_{n,J} by bisection agrees.
    let ramp = Ramp::new(Cylinder::new(0.15, 0.02).unwrap(), 40f64.to_radians()).unwrap();
    let t = eccjump_core::jarm::from_rest::theta_nj(&ramp, 1).unwrap();
    assert!((t - r.theta_j).abs() < 1e-12);
    // The max friction ratio on the path is at the jump: μ(θ_J).
    assert!(r.max_ratio <= 1.0);
    // Explicit n.
    assert_eq!(
        c(40.0, 0.15, 0.02, 1.0, &JarmOptions { n: 1, ..o }).reason,
        Reason::Jarm
    );
    assert_eq!(
        c(40.0, 0.15, 0.02, 1.0, &JarmOptions { n: 2, ..o }).reason,
        Reason::LiftoffEarlier
    );
    // Classical rule: also a JARM, later lift-off.
    let k = c(
        40.0,
        0.15,
        0.02,
        1.0,
        &JarmOptions {
            rule: Rule::NormalForce,
            ..o
        },
    );
    assert_eq!(k.reason, Reason::Jarm);
    assert!(k.theta_j > r.theta_j && (k.theta_j - r.theta_j).to_degrees() < 2.0);
}

#[test]
fn reference_slip() {
    let o = JarmOptions::default();
    let r = c(30.0, 0.5, 0.4, 1.0, &o);
    assert!(!r.is_jarm);
    assert!(matches!(r.reason, Reason::SlipAtJump | Reason::SlipBefore));
    assert!((r.theta_event.to_degrees() - 316.47).abs() < 0.01);
    // The paper's lift-off on this path (≈ 325.5°) lies before the green window
    // (330°, 360°): JtaC1 fails, so the jump-point test has nothing to reject; the path
    // test catches the slip.
    assert_eq!(r.reason, Reason::SlipBefore);
    let ramp = Ramp::new(Cylinder::new(0.5, 0.4).unwrap(), 30f64.to_radians()).unwrap();
    assert!(eccjump_core::jarm::from_rest::jtac1(&ramp, 1) > 0.0);
    // Same body at 40°: the lift-off is in the window and needs μ > 1 (μ_s,min = 1.39).
    let r = c(40.0, 0.5, 0.4, 1.0, &o);
    assert!(!r.is_jarm, "{r:?}");
    let k = c(
        30.0,
        0.5,
        0.4,
        1.0,
        &JarmOptions {
            rule: Rule::NormalForce,
            ..o
        },
    );
    assert!(!k.is_jarm);
}

#[test]
fn invalid_params_never_panic() {
    let o = JarmOptions::default();
    for &(a, chi, km, mu) in &[
        (f64::NAN, 0.1, 0.1, 1.0),
        (-0.1, 0.1, 0.1, 1.0),
        (1.6, 0.1, 0.1, 1.0),
        (0.5, 1.1, 0.0, 1.0),
        (0.5, 0.5, 0.6, 1.0),
        (0.5, 0.5, 0.1, -1.0),
        (0.5, 0.5, 0.1, f64::NAN),
        (0.5, 0.5, -0.1, 1.0),
    ] {
        assert_eq!(classify(a, chi, km, mu, &o).reason, Reason::InvalidParams);
    }
    let bad = JarmOptions { omega0: -1.0, ..o };
    assert_eq!(
        classify(0.5, 0.1, 0.1, 1.0, &bad).reason,
        Reason::InvalidParams
    );
}

#[test]
fn limits() {
    let o = JarmOptions::default();
    // α = 0: never a JARM (at rest: an equilibrium).
    for &(chi, km) in &[(0.3, 0.2), (0.0, 0.5), (1.0, 0.0), (0.5, 0.0)] {
        assert!(!classify(0.0, chi, km, 1.0, &o).is_jarm);
        assert!(!classify(0.0, chi, km, 1.0, &JarmOptions { omega0: 1.0, ..o }).is_jarm);
    }
    // χ = 0: no lift-off; slips at the start if μ_s < k_m tan α/(1 + k_m).
    assert_eq!(classify(0.5, 0.0, 0.3, 1.0, &o).reason, Reason::NoRoot);
    assert_eq!(classify(1.5, 0.0, 0.9, 0.1, &o).reason, Reason::SlipBefore);
    // α = π/2 from rest: F_y = 0 at the start.
    let r = classify(FRAC_PI_2, 0.3, 0.2, 1.0, &o);
    assert!(!r.is_jarm, "{r:?}");
    // χ = 1, k_m = 0 (Ĩ_CM = 0): F_x = χ sin θ F_y/(1 + χ cos θ), so the friction ratio is
    // |tan(θ/2)| (diverging at the singular θ = π) and margins vanish with F_y.
    let r = classify(0.5, 1.0, 0.0, 1.0, &o);
    assert_eq!(r.reason, Reason::NormalForceLost, "{r:?}");
    assert!((0.5 * r.theta_event).tan() < 1.0);
    let r = classify(0.5, 1.0, 0.0, 0.3, &o);
    assert_eq!(r.reason, Reason::SlipBefore, "{r:?}");
    assert!(((0.5 * r.theta_event).tan() - 0.3).abs() < 1e-9);
    let r = classify(0.5, 1.0, 0.0, 1e6, &o);
    assert!(!r.is_jarm && r.theta_event < PI, "{r:?}");
    // Tiny α: many turns, bounded, or the turn cap.
    let r = classify(1e-4, 0.3, 0.2, 1.0, &JarmOptions { max_turns: 10, ..o });
    assert_eq!(r.reason, Reason::TurnLimit);
}

#[test]
fn at_k_m_zero_a_tie_of_slip_and_normal_force_is_a_loss_of_normal_force() {
    // Ĩ_CM = 0: F_x ∝ F_y, so the friction margins vanish with F_y, at the same angle. The
    // tie goes to the loss of normal force, whichever constraint the scan locates first
    // (34 points of the 100³ map once came out as slips here). A slip must be a slip
    // with F_y clearly positive.
    let o = JarmOptions {
        refine_extrema: false,
        ..JarmOptions::default()
    };
    let alpha = 0.015707963267948967;
    for chi in [0.565, 0.685] {
        assert_eq!(
            classify(alpha, chi, 0.0, 1.0, &o).reason,
            Reason::NormalForceLost
        );
    }
    let (mut lost, mut slips) = (0, 0);
    for i in 0..60 {
        let alpha = 0.0157 + 1.55 * i as f64 / 59.0;
        for j in 0..50 {
            let chi = (j as f64 + 0.5) / 50.0;
            let mu_s = if j % 2 == 0 { 1.0 } else { 0.3 };
            let r = classify(alpha, chi, 0.0, mu_s, &o);
            match r.reason {
                Reason::NormalForceLost => lost += 1,
                Reason::SlipBefore | Reason::SlipAtJump => {
                    slips += 1;
                    let ramp = Ramp::new(Cylinder::new(chi, 0.0).unwrap(), alpha).unwrap();
                    let p = RollingPath::new(&ramp, 0.0, 0.0, mu_s).eval(r.theta_event);
                    assert!(p.fy > 1e-9, "{alpha} {chi}: a slip at F_y = {}", p.fy);
                }
                _ => {}
            }
        }
    }
    assert!(lost > 100 && slips > 100, "{lost} {slips}");
}

#[test]
fn monotone_in_mu_s_and_alpha_zero() {
    let o = JarmOptions::default();
    let mus = [0.3, 0.5, 0.7, 1.0, 1.5, 2.5, 5.0];
    let mut jarms = 0;
    for i in 1..=30 {
        let a = 90.0 * i as f64 / 31.0;
        for j in 1..=12 {
            let chi = j as f64 / 13.0;
            for l in 0..5 {
                let km = (1.0 - chi) * l as f64 / 5.0;
                let mut was = false;
                for &m in &mus {
                    let r = c(a, chi, km, m, &o);
                    if was {
                        assert!(r.is_jarm, "{a} {chi} {km} {m}: {r:?}");
                    }
                    was = r.is_jarm;
                    jarms += r.is_jarm as u32;
                }
            }
        }
    }
    assert!(jarms > 0);
}

#[test]
fn rules_agree_away_from_boundaries() {
    // Classification agrees; θ_J differs by < ~2°. Points whose decisive margins are
    // within a hair of the boundary (μ_s ± 2 %) are skipped.
    let o = JarmOptions::default();
    let k = JarmOptions {
        rule: Rule::NormalForce,
        ..o
    };
    let (mut agree, mut both, mut skipped, mut max_dth) = (0, 0, 0, 0.0f64);
    for i in 1..=40 {
        let a = 90.0 * i as f64 / 41.0;
        for j in 1..=15 {
            let chi = j as f64 / 16.0;
            // k_m = 0 (Ĩ_CM = 0) is a boundary where the rules differ: see below.
            for l in 1..6 {
                let km = (1.0 - chi) * l as f64 / 6.0;
                let p = c(a, chi, km, 1.0, &o);
                let lo = c(a, chi, km, 0.98, &o);
                let hi = c(a, chi, km, 1.02, &o);
                if lo.is_jarm != hi.is_jarm {
                    skipped += 1;
                    continue;
                }
                let q = c(a, chi, km, 1.0, &k);
                assert_eq!(p.is_jarm, q.is_jarm, "{a} {chi} {km}: {p:?} {q:?}");
                agree += 1;
                if p.is_jarm {
                    both += 1;
                    max_dth = max_dth.max((q.theta_j - p.theta_j).abs());
                    assert!(q.theta_j >= p.theta_j);
                }
            }
        }
    }
    assert!(both > 0 && agree > 1000, "{agree} {both} {skipped}");
    assert!(max_dth.to_degrees() < 2.5, "{}", max_dth.to_degrees());
}

#[test]
fn turns_and_overlaps_from_rest() {
    // Each point has at most one n (first-jump semantics); find which n occur.
    let o = JarmOptions::default();
    let mut seen = [0u32; 8];
    for i in 1..=60 {
        let a = 30.0 * i as f64 / 61.0;
        for j in 1..=20 {
            let chi = 0.3 * j as f64 / 21.0;
            for l in 0..4 {
                let km = (1.0 - chi) * l as f64 / 4.0;
                let r = c(a, chi, km, 1.0, &o);
                if r.is_jarm {
                    seen[(r.n as usize).min(7)] += 1;
                    for n in 1..6 {
                        let e = c(a, chi, km, 1.0, &JarmOptions { n, ..o });
                        assert_eq!(e.is_jarm, n == r.n);
                    }
                }
            }
        }
    }
    assert!(seen[1] > 0, "{seen:?}");
}

//! Tests of `mechanics::impact` through the public API: the impulse against the laws of
//! mechanics (energy, momentum, the friction cone), small-step integration and textbook cases.

mod common;

use common::Lcg;
use eccjump_core::mechanics::impact::{impact, resolve, Ending, ImpactLaw, ImpactMatrix, Impulse};
use eccjump_core::mechanics::{BodyState, Cylinder, Ramp};
use eccjump_core::Error;
use std::f64::consts::TAU;

/// A random impact: body, angle, velocities (θ̇, l̇, ḃ) with ḃ < 0.
struct Case {
    body: Cylinder,
    theta: f64,
    omega: f64,
    ldot: f64,
    bdot: f64,
}

fn random_case(r: &mut Lcg) -> Case {
    let chi = r.next();
    let km = (1.0 - chi) * (1.0 - r.next()); // (0, 1 − χ]: Ĩ_CM > 0
    Case {
        body: Cylinder::new(chi, km).unwrap(),
        theta: TAU * r.next(),
        omega: 6.0 * r.next() - 3.0,
        ldot: 6.0 * r.next() - 3.0,
        bdot: -3.0 * (1.0 - r.next()),
    }
}

/// A random law, with the special values μ = 0, e = 0 and e = 1 among them.
fn random_law(r: &mut Lcg) -> ImpactLaw {
    let mu_s = [0.0, 0.05, 2.0 * r.next(), 2.0 * r.next()][(4.0 * r.next()) as usize];
    let e = [0.0, 1.0, r.next(), r.next()][(4.0 * r.next()) as usize];
    ImpactLaw {
        mu_s,
        mu_k: mu_s * [1.0, r.next()][(2.0 * r.next()) as usize],
        restitution: e,
    }
}

/// The kinetic energy by the general formula of `mechanics::energy` (l = 0, b = 1: the
/// potential part is the same before and after an impact and cancels).
fn kinetic(body: &Cylinder, theta: f64, omega: f64, ldot: f64, bdot: f64) -> f64 {
    let ramp = Ramp::new(*body, 0.0).unwrap();
    let moving = BodyState {
        bdot,
        ..BodyState::in_contact(theta, omega, 0.0, ldot)
    };
    ramp.energy_of(&moving) - ramp.energy_of(&BodyState::rolling(theta, 0.0, 0.0))
}

/// Angular momentum about the contact point P, from first principles:
/// (r_CM − P) × v_CM + Ĩ_CM ω_z with ω_z = −θ̇, r_CM − P = (χ sin θ, 1 + χ cos θ).
fn momentum_about_contact(body: &Cylinder, theta: f64, omega: f64, ldot: f64, bdot: f64) -> f64 {
    let (s, c) = eccjump_core::trig::sin_cos(theta);
    let (rx, ry) = (body.chi * s, 1.0 + body.chi * c);
    let (vx, vy) = (ldot + body.chi * c * omega, bdot - body.chi * s * omega);
    rx * vy - ry * vx - body.icm * omega
}

fn run(case: &Case, law: &ImpactLaw) -> (Impulse, (f64, f64, f64)) {
    let w = ImpactMatrix::new(&case.body, case.theta.sin(), case.theta.cos()).unwrap();
    let imp = resolve(&w, law, case.ldot - case.omega, case.bdot);
    let after = case
        .body
        .apply_impulse(case.theta, case.omega, case.ldot, case.bdot, imp.pt, imp.pn);
    (imp, after)
}

const N: usize = 20_000;

#[test]
fn w_matches_unit_impulses() {
    let mut r = Lcg(1);
    for _ in 0..1000 {
        let c = random_case(&mut r);
        let w = ImpactMatrix::new(&c.body, c.theta.sin(), c.theta.cos()).unwrap();
        let du = |pt, pn| {
            let (om, ld, bd) = c
                .body
                .apply_impulse(c.theta, c.omega, c.ldot, c.bdot, pt, pn);
            ((ld - om) - (c.ldot - c.omega), bd - c.bdot)
        };
        let (t1, n1) = du(1.0, 0.0);
        let (t2, n2) = du(0.0, 1.0);
        let scale = w.tt() + w.nn();
        for (got, want) in [(t1, w.tt()), (n1, w.tn()), (t2, w.tn()), (n2, w.nn())] {
            assert!((got - want).abs() <= 1e-12 * scale, "{got} vs {want}");
        }
        let det = w.tt() * w.nn() - w.tn() * w.tn();
        assert!((det - w.det()).abs() <= 1e-10 * scale * scale);
        assert!(w.tt() >= 1.0 && w.nn() >= 1.0 && w.det() >= 1.0);
    }
}

#[test]
fn kinetic_energy_never_increases() {
    let mut r = Lcg(2);
    for _ in 0..N {
        let (c, law) = (random_case(&mut r), random_law(&mut r));
        let (imp, (om, ld, bd)) = run(&c, &law);
        let before = kinetic(&c.body, c.theta, c.omega, c.ldot, c.bdot);
        let after = kinetic(&c.body, c.theta, om, ld, bd);
        assert!(
            after <= before * (1.0 + 1e-12),
            "{before} → {after}, {law:?} {imp:?}"
        );
        assert!(imp.compression_work <= 0.0 && imp.friction_work <= 0.0);
        assert!(imp.normal_work <= 1e-15 * before && imp.pn > 0.0);
    }
}

#[test]
fn energy_loss_equals_the_works_of_the_impulse() {
    let mut r = Lcg(3);
    for _ in 0..N {
        let (c, law) = (random_case(&mut r), random_law(&mut r));
        let (imp, (om, ld, bd)) = run(&c, &law);
        let before = kinetic(&c.body, c.theta, c.omega, c.ldot, c.bdot);
        let lost = before - kinetic(&c.body, c.theta, om, ld, bd);
        assert!(
            (lost + imp.normal_work + imp.friction_work).abs() <= 1e-11 * before,
            "{lost} vs {imp:?}"
        );
        // Stronge: the normal work is (1 − e²) times that of compression.
        let e2 = law.restitution * law.restitution;
        let want = (1.0 - e2) * imp.compression_work;
        assert!((imp.normal_work - want).abs() <= 1e-12 * before);
    }
}

#[test]
fn angular_momentum_about_the_contact_is_conserved() {
    let mut r = Lcg(4);
    for _ in 0..N {
        let (c, law) = (random_case(&mut r), random_law(&mut r));
        let (imp, (om, ld, bd)) = run(&c, &law);
        let l0 = momentum_about_contact(&c.body, c.theta, c.omega, c.ldot, c.bdot);
        let l1 = momentum_about_contact(&c.body, c.theta, om, ld, bd);
        let scale = 1.0 + c.omega.abs() + c.ldot.abs() + c.bdot.abs() + imp.pt.abs();
        assert!((l1 - l0).abs() <= 1e-12 * scale, "{l0} → {l1}");
    }
}

#[test]
fn frictionless_elastic_impact_conserves_energy() {
    let mut r = Lcg(5);
    let law = ImpactLaw {
        mu_s: 0.0,
        mu_k: 0.0,
        restitution: 1.0,
    };
    for _ in 0..N {
        let c = random_case(&mut r);
        let (imp, (om, ld, bd)) = run(&c, &law);
        let before = kinetic(&c.body, c.theta, c.omega, c.ldot, c.bdot);
        let after = kinetic(&c.body, c.theta, om, ld, bd);
        assert!((after - before).abs() <= 1e-12 * before);
        assert!(imp.un > 0.0 && imp.friction_work == 0.0 && imp.pt == 0.0);
    }
}

#[test]
fn plastic_impact_ends_with_zero_normal_velocity() {
    let mut r = Lcg(6);
    for _ in 0..N {
        let c = random_case(&mut r);
        let law = ImpactLaw {
            restitution: 0.0,
            ..random_law(&mut r)
        };
        let landing = impact(&c.body, &law, c.theta, c.omega, c.ldot, c.bdot).unwrap();
        let imp = landing.impulse;
        assert_eq!((imp.un, landing.bdot), (0.0, 0.0));
        assert_eq!(imp.normal_work, imp.compression_work);
        if imp.ending == Ending::Sticking {
            assert_eq!((imp.ut, landing.ldot - landing.omega), (0.0, 0.0));
        }
    }
}

#[test]
fn friction_impulse_lies_in_the_cone() {
    let mut r = Lcg(7);
    let mut stuck = 0;
    for _ in 0..N {
        let (c, law) = (random_case(&mut r), random_law(&mut r));
        let (imp, _) = run(&c, &law);
        assert!(imp.pt.abs() <= law.mu_s * imp.pn * (1.0 + 1e-12) + 1e-300);
        match imp.ending {
            Ending::Sticking => {
                stuck += 1;
                assert_eq!(imp.ut, 0.0);
            }
            // Sliding at the end: the last increments were kinetic friction against u_t.
            Ending::Sliding => assert!(imp.ut != 0.0 || law.mu_k == 0.0),
        }
    }
    assert!(stuck > N / 10 && stuck < N, "{stuck}");
}

/// Routh's method by brute force: small steps h in p with the same Coulomb rules, the
/// works summed by the midpoint rule, the phases ended where the sums cross. No closed
/// form of `resolve` is used; the error is O(h). `newton` ends the impact instead by
/// Newton's kinematic rule u_n = −e u_n0 (the law `resolve` does not offer).
fn stepped(w: &ImpactMatrix, law: &ImpactLaw, u0: (f64, f64), h: f64, newton: bool) -> [f64; 4] {
    let (ut0, un0) = u0;
    let e = law.restitution;
    let going = |compression: f64, work: f64, un: f64| {
        compression.is_nan()
            || if newton {
                un < -e * un0
            } else {
                work < (1.0 - e * e) * compression
            }
    };
    let (mut ut, mut un, mut pt, mut pn) = (ut0, un0, 0.0, 0.0);
    let lambda = -w.tn() / w.tt();
    let (mut compression, mut work) = (f64::NAN, 0.0);
    let mut stuck = ut0 == 0.0 && lambda.abs() <= law.mu_s;
    let mut steps = 0;
    while going(compression, work, un) {
        steps += 1;
        assert!(steps < 10_000_000, "the stepped impact does not end");
        let f = if stuck {
            lambda
        } else {
            -ut.signum() * law.mu_k
        };
        let (dut, dun) = ((w.tt() * f + w.tn()) * h, (w.tn() * f + w.nn()) * h);
        work += (un + 0.5 * dun) * h;
        (pt, pn, un) = (pt + f * h, pn + h, un + dun);
        if stuck {
            // u_t stays 0.
        } else if ut != 0.0 && (ut + dut) * ut <= 0.0 && lambda.abs() <= law.mu_s {
            (ut, stuck) = (0.0, true);
        } else {
            ut += dut;
        }
        if compression.is_nan() && un >= 0.0 {
            compression = work;
        }
    }
    [pt, pn, ut, un]
}

#[test]
fn matches_small_step_integration() {
    let (mut r, mut checked) = (Lcg(10), 0);
    for _ in 0..200 {
        let (c, law) = (random_case(&mut r), random_law(&mut r));
        let (imp, _) = run(&c, &law);
        let w = ImpactMatrix::new(&c.body, c.theta.sin(), c.theta.cos()).unwrap();
        let (ut0, un0) = (c.ldot - c.omega, c.bdot);
        // A step must move u by much less than |u0|: skip the stiffest bodies (tiny
        // Ĩ_CM), where that needs too many steps; they are few.
        let stiffness = imp.pn * (w.tt() + w.nn()) / (ut0.abs() + un0.abs());
        if stiffness > 100.0 {
            continue;
        }
        checked += 1;
        let h = imp.pn * 1e-5 / stiffness.max(1.0);
        let got = stepped(&w, &law, (ut0, un0), h, false);
        let want = [imp.pt, imp.pn, imp.ut, imp.un];
        let scale = [imp.pn, imp.pn, ut0.abs() + un0.abs(), ut0.abs() + un0.abs()];
        for i in 0..4 {
            let tol = 1e-4 * scale[i] * (1.0 + law.mu_s);
            assert!(
                (got[i] - want[i]).abs() <= tol,
                "{i}: {got:?} vs {want:?} {law:?}"
            );
        }
    }
    assert!(checked > 180, "{checked}");
}

#[test]
fn newton_restitution_can_create_energy() {
    // Why `resolve` offers only Stronge's law: with friction, ending the impact at
    // u_n = −e u_n0 can return more energy than came in (here e = 1), where the
    // energetic law never does (kinetic_energy_never_increases).
    let (mut r, mut worst) = (Lcg(11), 0.0f64);
    for _ in 0..300 {
        let c = random_case(&mut r);
        let mu = 2.0 * r.next();
        let law = ImpactLaw {
            mu_s: mu,
            mu_k: mu,
            restitution: 1.0,
        };
        let (imp, _) = run(&c, &law);
        let w = ImpactMatrix::new(&c.body, c.theta.sin(), c.theta.cos()).unwrap();
        let (ut0, un0) = (c.ldot - c.omega, c.bdot);
        let stiffness = imp.pn * (w.tt() + w.nn()) / (ut0.abs() + un0.abs());
        if stiffness > 100.0 {
            continue;
        }
        let h = imp.pn * 1e-4 / stiffness.max(1.0);
        let [pt, pn, ..] = stepped(&w, &law, (ut0, un0), h, true);
        let (om, ld, bd) = c
            .body
            .apply_impulse(c.theta, c.omega, c.ldot, c.bdot, pt, pn);
        let before = kinetic(&c.body, c.theta, c.omega, c.ldot, c.bdot);
        worst = worst.max(kinetic(&c.body, c.theta, om, ld, bd) / before);
    }
    eprintln!("Newton's rule, e = 1: the kinetic energy grows up to {worst:.3}x");
    assert!(worst > 1.05, "{worst}");
}

#[test]
fn centred_body_has_the_textbook_answer() {
    // χ = 0: W = diag(1 + 1/Ĩ, 1), no coupling; Ĩ = 0.5 gives W_tt = 3.
    let body = Cylinder::new(0.0, 0.5).unwrap();
    let w = ImpactMatrix::new(&body, 0.3f64.sin(), 0.3f64.cos()).unwrap();
    assert_eq!((w.tt(), w.tn(), w.nn()), (3.0, 0.0, 1.0));
    let law = ImpactLaw {
        mu_s: 0.2,
        mu_k: 0.2,
        restitution: 0.5,
    };
    // p = (1 + e)·1 = 1.5, P_t = −0.3, u_t = 1 − 3·0.3 = 0.1 (still sliding).
    let imp = resolve(&w, &law, 1.0, -1.0);
    let close = |a: f64, b: f64| (a - b).abs() < 1e-15;
    assert!(close(imp.pn, 1.5) && close(imp.pt, -0.3) && close(imp.ut, 0.1));
    assert!(close(imp.un, 0.5) && imp.ending == Ending::Sliding);
    // More friction: u_t reaches 0 at p = 1/(3μ) and sticks (λ = 0).
    let law = ImpactLaw {
        mu_s: 1.0,
        mu_k: 1.0,
        ..law
    };
    let imp = resolve(&w, &law, 1.0, -1.0);
    assert!(close(imp.pt, -1.0 / 3.0) && imp.ut == 0.0 && imp.ending == Ending::Sticking);
}

#[test]
fn infinite_friction_plastic_sticks_iff_normal_velocity_stays_nonpositive() {
    // As μ → ∞ a tangential impulse −u_t/W_tt at p = 0⁺ removes u_t and moves u_n by
    // −W_tn u_t/W_tt. If that leaves u_n ≤ 0 the impact ends sticking (rolling); if u_n
    // has reached 0 first, compression (and, for e = 0, the impact) ends while sliding.
    let law = ImpactLaw {
        mu_s: 1e9,
        mu_k: 1e9,
        restitution: 0.0,
    };
    let mut r = Lcg(8);
    let (mut sliding, mut counted) = (0, 0);
    for _ in 0..N {
        let c = random_case(&mut r);
        let (imp, _) = run(&c, &law);
        let w = ImpactMatrix::new(&c.body, c.theta.sin(), c.theta.cos()).unwrap();
        let (ut0, un0) = (c.ldot - c.omega, c.bdot);
        let un_removed = un0 - w.tn() / w.tt() * ut0;
        let scale = ut0.abs() + un0.abs();
        if un_removed.abs() < 1e-6 * scale {
            continue; // on the boundary the finite μ decides
        }
        counted += 1;
        let sticks = un_removed <= 0.0;
        assert_eq!(
            imp.ending == Ending::Sticking,
            sticks,
            "{un_removed} {imp:?}"
        );
        if !sticks {
            sliding += 1;
            assert!(imp.ut.abs() > 1e-7 * scale);
        }
        assert_eq!(imp.un, 0.0);
    }
    let fraction = sliding as f64 / counted as f64;
    eprintln!("mu = 1e9, e = 0: {sliding}/{counted} impacts end sliding ({fraction:.4})");
    assert!(fraction > 0.01 && fraction < 0.2, "{fraction}");
}

#[test]
fn extreme_friction_and_inertia_stay_finite() {
    let mut r = Lcg(9);
    for &km in &[1e-300, 1e-150, 1e-12, 0.5] {
        for &mu in &[0.0, 1.0, 1e12, 1e300, f64::MAX] {
            for &e in &[0.0, 0.5, 1.0] {
                for &v in &[1e-300, 1e-8, 1.0, 1e100] {
                    let body = Cylinder::new(0.5, km).unwrap();
                    let theta = TAU * r.next();
                    let (ut0, un0) = (v * (2.0 * r.next() - 1.0), -v * r.next() - 1e-320);
                    let w = ImpactMatrix::new(&body, theta.sin(), theta.cos()).unwrap();
                    let law = ImpactLaw {
                        mu_s: mu,
                        mu_k: mu,
                        restitution: e,
                    };
                    let imp = resolve(&w, &law, ut0, un0);
                    let all = [imp.pt, imp.pn, imp.ut, imp.un, imp.compression_work];
                    let works = [imp.normal_work, imp.friction_work];
                    assert!(all.iter().chain(&works).all(|x| x.is_finite()), "{imp:?}");
                    assert!(imp.friction_work <= 0.0 && imp.compression_work <= 0.0);
                    if e == 0.0 {
                        assert_eq!(imp.un, 0.0);
                    }
                }
            }
        }
    }
}

#[test]
fn no_impact_unless_approaching() {
    let body = Cylinder::new(0.3, 0.2).unwrap();
    let w = ImpactMatrix::new(&body, 0.5, 0.5f64.cos()).unwrap();
    let law = ImpactLaw {
        mu_s: 1.0,
        mu_k: 0.5,
        restitution: 0.5,
    };
    for (ut, un) in [(0.3, 0.0), (0.3, 1.0), (f64::NAN, -1.0), (0.1, f64::NAN)] {
        let imp = resolve(&w, &law, ut, un);
        assert_eq!((imp.pt, imp.pn, imp.normal_work), (0.0, 0.0, 0.0));
    }
    assert!(ImpactMatrix::new(&Cylinder::new(0.7, 0.0).unwrap(), 0.5, 0.5).is_none());
    assert!(ImpactMatrix::new(&Cylinder::new(1.0, 0.0).unwrap(), 0.0, -1.0).is_none());
}

#[test]
fn invalid_inputs_name_the_parameter() {
    let name = |e: Error| match e {
        Error::InvalidParameter { name, .. } => name,
        other => panic!("{other}"),
    };
    let law = |mu_s, mu_k, restitution| ImpactLaw {
        mu_s,
        mu_k,
        restitution,
    };
    assert_eq!(name(law(-1.0, 0.0, 0.5).validate().unwrap_err()), "mu_s");
    assert_eq!(
        name(law(f64::INFINITY, 0.0, 0.5).validate().unwrap_err()),
        "mu_s"
    );
    assert_eq!(name(law(0.5, 0.6, 0.5).validate().unwrap_err()), "mu_k");
    assert_eq!(
        name(law(0.5, 0.5, 1.5).validate().unwrap_err()),
        "restitution"
    );
    assert_eq!(
        name(law(0.5, 0.5, f64::NAN).validate().unwrap_err()),
        "restitution"
    );
    let ok = law(0.5, 0.4, 0.3);
    assert!(ok.validate().is_ok());
    let body = Cylinder::new(0.4, 0.3).unwrap();
    let bad = |th, om, ld, bd| name(impact(&body, &ok, th, om, ld, bd).unwrap_err());
    assert_eq!(bad(f64::NAN, 0.0, 0.0, -1.0), "theta");
    assert_eq!(bad(0.0, f64::INFINITY, 0.0, -1.0), "omega");
    assert_eq!(bad(0.0, 0.0, f64::NAN, -1.0), "ldot");
    assert_eq!(bad(0.0, 0.0, 0.0, f64::NEG_INFINITY), "bdot");
    let point = Cylinder::new(0.6, 0.0).unwrap();
    assert_eq!(
        name(impact(&point, &ok, 0.0, 0.0, 0.0, -1.0).unwrap_err()),
        "km"
    );
}

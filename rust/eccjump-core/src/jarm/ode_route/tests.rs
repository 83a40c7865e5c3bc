//! The unit tests of `ode_route.rs` (a child module, `#[cfg(test)] mod tests;` there, for the
//! private items they use).

use super::*;
use crate::jarm::classify;
use crate::jarm::Method;
use crate::maps::columns::JarmColumns;
use crate::maps::parallel::pool;
use crate::maps::region::classify_grid;
use crate::mechanics::Ramp;
use crate::modes::rolling::events::N_EVENTS;
use crate::ode::events::{check_change_bounds, WalkAll};
use crate::ode::pair::error_scale;
use crate::ode::{Change, EventBounds, EventFunctions, OdeSystem, Outcome, SinCos, StepEnds};
use std::f64::consts::FRAC_PI_2;

/// Never stop: the `stop` of a map that is not to be interrupted.
fn never() -> bool {
    false
}

const RTOL: f64 = 1e-10;
const ATOL: f64 = 1e-12;

fn ode(a: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> JarmResult {
    classify_ode(a, chi, km, mu_s, o, (RTOL, ATOL), ode::Integrator::Rk45)
}

/// The closed form's verdict is robust: a relative change of α by ±1e-6 keeps its reason.
fn robust(a: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions, reason: Reason) -> bool {
    [a * (1.0 - 1e-6), (a * (1.0 + 1e-6)).min(FRAC_PI_2)]
        .iter()
        .all(|&b| classify(b, chi, km, mu_s, o).reason == reason)
}

#[derive(Default, Debug)]
struct Stats {
    compared: usize,
    skipped: usize,
    jarms: usize,
    max_dtheta_j: f64,
    max_dtheta_j_paper: f64,
    max_dtheta_event: f64,
    bad: Vec<String>,
}

fn compare(a: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions, st: &mut Stats) {
    let c = classify(a, chi, km, mu_s, o);
    if !robust(a, chi, km, mu_s, o, c.reason) {
        st.skipped += 1;
        return;
    }
    st.compared += 1;
    let e = ode(a, chi, km, mu_s, o);
    let mut ok = e.reason == c.reason && e.n == c.n;
    if ok && c.reason == Reason::Jarm {
        st.jarms += 1;
        let d = (e.theta_j - c.theta_j).abs();
        st.max_dtheta_j = st.max_dtheta_j.max(d);
        if o.rule == Rule::Paper {
            st.max_dtheta_j_paper = st.max_dtheta_j_paper.max(d);
        }
        // The integrator controls the error of θ relative to |θ|, so long runs (many
        // turns at small α) carry an absolute error ~rtol·θ. Lift-off roots (Paper) are
        // steep; F_y roots (NormalForce) can be shallow (|F_y'| ~ 0.1 at k_m = 0), which
        // multiplies that error by ~10 (it converges with rtol: `shallow_roots_converge`).
        let tol =
            (1e-9 + 2.0 * RTOL * c.theta_j.abs()) * if o.rule == Rule::Paper { 1.0 } else { 20.0 };
        ok = d < tol;
    }
    if ok && !c.theta_event.is_nan() {
        let d = (e.theta_event - c.theta_event).abs();
        st.max_dtheta_event = st.max_dtheta_event.max(d);
        ok = d < 1e-7 + 5.0 * RTOL * c.theta_event.abs();
    }
    if !ok {
        st.bad.push(format!(
            "a={a:?} chi={chi:?} km={km:?} mu={mu_s} {:?} n={} th0={} w0={}: cf {:?} n{} thj {} the {} | ode {:?} n{} dthj {:.2e} dthe {:.2e}",
            o.rule, o.n, o.theta0, o.omega0, c.reason, c.n, c.theta_j, c.theta_event,
            e.reason, e.n, e.theta_j - c.theta_j, e.theta_event - c.theta_event
        ));
    }
}

/// Runs with all events on (and the continuation's set, without F_y and slip), to the
/// first terminal event: small and large α, a near-singular body, both rules.
fn bound_cases() -> Vec<(f64, f64, f64, f64, bool, bool)> {
    let mut v = Vec::new();
    for &(a, chi, km, mu_s) in &[
        (0.0157, 0.35, 0.3, 1.0),
        (0.0314, 0.75, 0.1, 1.0),
        (0.7, 0.15, 0.02, 1.0),
        (0.52, 0.5, 0.4, 1.0),
        (0.2, 0.3, 0.0, 1.0),
        (0.05, 0.95, 0.0, 50.0),
        (0.5, 1.0, 0.0, 1e6),
        (1.2, 0.9, 0.05, 0.3),
    ] {
        for (liftoff, forces) in [(true, true), (false, true), (true, false)] {
            v.push((a, chi, km, mu_s, liftoff, forces));
        }
    }
    v
}

fn events_for(ramp: &Ramp, mu_s: f64, liftoff: bool, forces: bool) -> ContactEvents {
    ContactEvents {
        ramp: *ramp,
        mu_s,
        theta_end: 400.0,
        watched: [liftoff, forces, forces, true, true],
        terminal: [true; N_EVENTS],
    }
}

/// Both kinds of bounds hold along every step's dense output, of every pair: those
/// from the dense output itself, with any anchor, and those from the step's ends alone
/// (which decide whether the dense output is made at all).
#[test]
fn change_bounds_bound_the_change_along_each_step() {
    let mut steps = 0;
    let mut quiet = 0;
    let cases = bound_cases().into_iter();
    for (pair, (a, chi, km, mu_s, liftoff, forces)) in ode::Integrator::ALL
        .into_iter()
        .flat_map(|p| cases.clone().map(move |c| (p, c)))
    {
        let so = SolverOptions {
            event_samples: 8,
            dense_every_step: true,
            method: pair,
            ..SolverOptions::default()
        };
        let r = Ramp::new(crate::mechanics::Cylinder::new(chi, km).unwrap(), a).unwrap();
        let ev = events_for(&r, mu_s, liftoff, forces);
        let check = events_for(&r, mu_s, liftoff, forces);
        ode::solve(&r, &ev, 0.0, State::<2>::zeros(), 1e300, &so, &mut |obs| {
            let Observation::Step { dense, t, y, trig } = obs else {
                return;
            };
            let dense = dense.expect("every step's dense output");
            steps += 1;
            let g = |t: f64, y: &State<2>| {
                let mut v = [0.0; N_EVENTS];
                check.values(0, t, y, &mut v);
                v
            };
            let t_new = dense.t_old + dense.h;
            let (th0, th1) = (dense.y_old[0], dense.eval(t_new)[0]);
            let mid = dense.eval(dense.t_old + 0.37 * dense.h)[0];
            let anchors = [
                None,
                trig,
                Some(SinCos::of(th0)),
                Some(SinCos::of(th1)),
                Some(SinCos::of(mid)),
            ];
            for anchor in anchors {
                let b = ev.change_bounds_near(dense, anchor);
                // The start as it is, not as the interpolant gives it.
                let at = |ti: f64| match ti == dense.t_old {
                    true => g(ti, &dense.y_old),
                    false => g(ti, &dense.eval(ti)),
                };
                if let Err(e) = check_change_bounds(dense.t_old, dense.h, at, &b) {
                    panic!("{a} {chi} {km} {e} anchor {anchor:?} at {t} {y:?}");
                }
                // From the ends of a whole step (not one cut at an event).
                if (t - t_new).abs() > 1e-12 * t.abs().max(1.0) {
                    continue;
                }
                let ends = StepEnds {
                    t_old: dense.t_old,
                    t_new: t,
                    h: dense.h,
                    y_old: dense.y_old,
                    f_old: r.rhs(dense.t_old, &dense.y_old),
                    y_new: *y,
                    f_new: r.rhs(t, y),
                    scale: error_scale(&dense.y_old, y, so.rtol, so.atol),
                };
                let mut b = [Change::NONE; N_EVENTS];
                check.change_bounds_ends(0, &ends, true, anchor, &mut b);
                if let Err(e) = check_change_bounds(dense.t_old, dense.h, at, &b) {
                    panic!("{pair:?} {a} {chi} {km} {e} ends, anchor {anchor:?} at {t}");
                }
                quiet += usize::from(ode::quiet_step(
                    &check,
                    &ends,
                    anchor,
                    &mut Default::default(),
                ));
            }
        });
    }
    assert!(steps > 4000, "{steps}");
    // The ends prove most steps quiet (5 anchors each).
    assert!(quiet > steps, "{quiet} of {steps}");
}

#[test]
fn skipping_interior_samples_changes_nothing() {
    let mut nfev = [[0; 2]; ode::Integrator::ALL.len()];
    for (a, chi, km, mu_s, liftoff, forces) in bound_cases() {
        for (samples, pair) in [4, 16]
            .into_iter()
            .flat_map(|s| ode::Integrator::ALL.map(|p| (s, p)))
        {
            let so = SolverOptions {
                event_samples: samples,
                method: pair,
                ..SolverOptions::default()
            };
            let r = Ramp::new(crate::mechanics::Cylinder::new(chi, km).unwrap(), a).unwrap();
            let run = |skip: bool| {
                let ev = events_for(&r, mu_s, liftoff, forces);
                let mut seen = Vec::new();
                let mut obs = |o: Observation<'_, 2>| {
                    if let Observation::Event { index, t, y } = o {
                        seen.push((index, t.to_bits(), y[0].to_bits(), y[1].to_bits()));
                    }
                };
                let y0 = State::<2>::zeros();
                let out = if skip {
                    ode::solve(&r, &ev, 0.0, y0, 1e300, &so, &mut obs)
                } else {
                    ode::solve(&r, &WalkAll(&ev), 0.0, y0, 1e300, &so, &mut obs)
                };
                (out, seen)
            };
            // The same steps, events and end; fewer evaluations where the dense output of
            // a step proven quiet from its ends is not made (the extra stages of DOP853
            // and Vern9).
            let (p, q) = (run(true), run(false));
            let same = |o: &Outcome<2>| (o.status, o.t, o.y, o.n_accepted, o.n_rejected);
            assert_eq!(same(&p.0), same(&q.0), "{a} {chi} {km} {pair:?}");
            assert_eq!(p.1, q.1);
            let i = pair as usize;
            nfev[i][0] += p.0.nfev;
            nfev[i][1] += q.0.nfev;
        }
    }
    assert_eq!(
        nfev[0][0], nfev[0][1],
        "RK45 always makes its (free) dense output"
    );
    for (i, pair) in ode::Integrator::ALL.into_iter().enumerate().skip(1) {
        assert!(10 * nfev[i][0] < 9 * nfev[i][1], "{pair:?}: {:?}", nfev[i]);
    }
}

#[test]
fn a_grazing_slip_after_930_turns_is_found_by_every_pair() {
    // The friction margin dips below 0 on turn 934 for a window narrower than the sample
    // spacing; sign sampling alone slipped one turn later (SLIP_BEFORE at 5875.087).
    let (a, chi, km) = (
        0.11715890776808541,
        0.001036140639499864,
        0.5957722237251039,
    );
    let o = JarmOptions::default();
    let c = classify(a, chi, km, 1.0, &o);
    assert_eq!((c.reason, c.n), (Reason::SlipAtJump, 934));
    for pair in ode::Integrator::ALL {
        let e = classify_ode(a, chi, km, 1.0, &o, (RTOL, ATOL), pair);
        assert_eq!((e.reason, e.n), (c.reason, c.n), "{pair:?}");
        assert!(
            (e.theta_event - c.theta_event).abs() < 1e-6,
            "{pair:?} {e:?}"
        );
    }
}

#[test]
fn agreement_grid() {
    let mut st = Stats::default();
    // 15 angles 6°..90°, plus small ones (many turns, narrow windows: more samples).
    let mut alphas: Vec<f64> = (1..=15).map(|i| FRAC_PI_2 * i as f64 / 15.0).collect();
    alphas.extend([1.0f64, 2.5].map(f64::to_radians));
    let chis = [0.0, 0.05, 0.15, 0.3, 0.5, 0.7, 0.9, 1.0];
    let fracs = [0.0, 0.25, 0.5, 0.75, 1.0];
    for &a in &alphas {
        for &chi in &chis {
            for &f in &fracs {
                let km = f * (1.0 - chi);
                for mu_s in [0.7, 1.0] {
                    for rule in [Rule::Paper, Rule::NormalForce] {
                        for n in [0, 1, 2] {
                            let o = JarmOptions {
                                rule,
                                n,
                                ..JarmOptions::default()
                            };
                            compare(a, chi, km, mu_s, &o, &mut st);
                        }
                    }
                }
            }
        }
    }
    report("grid from rest", &st);
}

fn report(what: &str, st: &Stats) {
    println!(
        "{what}: compared {} skipped {} jarms {} max dθ_J {:.2e} (Paper rule {:.2e}) \
         max dθ_event {:.2e} disagreements {}",
        st.compared,
        st.skipped,
        st.jarms,
        st.max_dtheta_j,
        st.max_dtheta_j_paper,
        st.max_dtheta_event,
        st.bad.len()
    );
    for b in st.bad.iter().take(50) {
        println!("{b}");
    }
    assert!(st.bad.is_empty(), "{what}");
}

#[test]
#[allow(clippy::excessive_precision)] // the reference digits, as published
fn reference_points() {
    let o = JarmOptions::default();
    let r = ode(40f64.to_radians(), 0.15, 0.02, 1.0, &o);
    assert_eq!(r.reason, Reason::Jarm, "{r:?}");
    assert_eq!(r.n, 1);
    // 30-digit reference: θ_J = 334.34383789184907...°.
    let want = 334.343_837_891_849_07f64.to_radians();
    assert!((r.theta_j - want).abs() < 1e-9, "{}", r.theta_j - want);
    assert!((r.fy_j - 0.01543).abs() < 1e-5 && (r.fx_j + 0.00516).abs() < 1e-5);
    assert!(r.max_ratio <= 1.0);
    let r = ode(30f64.to_radians(), 0.5, 0.4, 1.0, &o);
    assert_eq!(r.reason, Reason::SlipBefore, "{r:?}");
    let want = 316.471_677_233_046_156_45f64.to_radians();
    assert!(
        (r.theta_event - want).abs() < 1e-9,
        "{}",
        r.theta_event - want
    );
    // Explicit n and the classical rule, as the closed form.
    let a = 40f64.to_radians();
    for (n, reason) in [(1, Reason::Jarm), (2, Reason::LiftoffEarlier)] {
        assert_eq!(
            ode(a, 0.15, 0.02, 1.0, &JarmOptions { n, ..o }).reason,
            reason
        );
    }
    let k = JarmOptions {
        rule: Rule::NormalForce,
        ..o
    };
    let (p, q) = (
        ode(a, 0.15, 0.02, 1.0, &k),
        classify(a, 0.15, 0.02, 1.0, &k),
    );
    assert_eq!(p.reason, Reason::Jarm);
    assert!((p.theta_j - q.theta_j).abs() < 1e-9);
}

#[test]
fn shallow_roots_converge() {
    // A classical-rule jump at k_m = 0 where F_y' ≈ −0.096: the θ_J error follows rtol.
    let (a, chi) = (0.20943951023931953, 0.3);
    let k = JarmOptions {
        rule: Rule::NormalForce,
        ..JarmOptions::default()
    };
    let c = classify(a, chi, 0.0, 1.0, &k);
    let mut last = f64::INFINITY;
    for rtol in [1e-10, 1e-12] {
        let e = classify_ode(
            a,
            chi,
            0.0,
            1.0,
            &k,
            (rtol, 1e-2 * rtol),
            ode::Integrator::Rk45,
        );
        assert_eq!(e.reason, c.reason);
        let d = (e.theta_j - c.theta_j).abs();
        assert!(d < last && d < 1e4 * rtol, "{rtol} {d}");
        last = d;
    }
}

#[test]
fn other_initial_conditions_agree() {
    let mut st = Stats::default();
    for &(th0, w0) in &[(0.0, 0.5), (0.3, 0.0), (-0.5, 0.2), (2.0, 1.0), (5.5, 0.3)] {
        for i in 1..=8 {
            let a = FRAC_PI_2 * i as f64 / 8.5;
            for &chi in &[0.1, 0.3, 0.6, 0.9] {
                for &f in &[0.0, 0.3, 0.8] {
                    for rule in [Rule::Paper, Rule::NormalForce] {
                        let o = JarmOptions {
                            rule,
                            theta0: th0,
                            omega0: w0,
                            ..JarmOptions::default()
                        };
                        compare(a, chi, f * (1.0 - chi), 1.0, &o, &mut st);
                    }
                }
            }
        }
    }
    // Starts that roll back (uphill start against gravity on a gentle ramp).
    for &(a, chi, th0) in &[(0.05, 0.5, 3.5), (0.1, 0.8, 4.0), (0.02, 0.3, 3.3)] {
        let o = JarmOptions {
            theta0: th0,
            omega0: 0.0,
            ..JarmOptions::default()
        };
        compare(a, chi, 0.1, 1.0, &o, &mut st);
        assert_eq!(ode(a, chi, 0.1, 1.0, &o).reason, Reason::RocksBack);
    }
    report("other starts", &st);
}

#[test]
fn special_cases() {
    let o = JarmOptions::default();
    let k = JarmOptions {
        rule: Rule::NormalForce,
        ..o
    };
    for opts in [o, k] {
        // α = 0 from rest: equilibrium; with θ̇0 > 0 as the closed form.
        for &(chi, km) in &[(0.3, 0.2), (0.0, 0.5), (1.0, 0.0), (0.5, 0.0)] {
            assert_eq!(ode(0.0, chi, km, 1.0, &opts).reason, Reason::NoRoot);
            for w0 in [0.3, 1.0, 3.0] {
                let m = JarmOptions { omega0: w0, ..opts };
                let (e, c) = (ode(0.0, chi, km, 1.0, &m), classify(0.0, chi, km, 1.0, &m));
                assert_eq!(e.reason, c.reason, "{chi} {km} {w0}: {e:?} {c:?}");
                // The green window is empty at α = 0; under the classical rule a fast
                // spin can still lose F_y and fly (both routes agree on it).
                assert!(!e.is_jarm || opts.rule == Rule::NormalForce);
            }
        }
        // χ = 0: no lift-off, or slip at the start.
        for &(a, km, mu_s) in &[(0.5, 0.3, 1.0), (1.5, 0.9, 0.1), (1.0, 1.0, 1.0)] {
            let (e, c) = (
                ode(a, 0.0, km, mu_s, &opts),
                classify(a, 0.0, km, mu_s, &opts),
            );
            assert_eq!(e.reason, c.reason, "{a} {km}: {e:?} {c:?}");
        }
        // α = π/2 from rest: F_y = 0 at the start; χ = 1, k_m = 0 (singular at θ = π).
        for &(a, chi, km, mu_s) in &[
            (FRAC_PI_2, 0.3, 0.2, 1.0),
            (FRAC_PI_2, 1.0, 0.0, 1.0),
            (0.5, 1.0, 0.0, 1.0),
            (0.5, 1.0, 0.0, 0.3),
            (0.5, 1.0, 0.0, 1e6),
            (0.05, 1.0, 0.0, 1e6),
            (1e-3, 1.0, 0.0, 50.0),
        ] {
            let (e, c) = (
                ode(a, chi, km, mu_s, &opts),
                classify(a, chi, km, mu_s, &opts),
            );
            assert_eq!(e.reason, c.reason, "{a} {chi} {km} {mu_s}: {e:?} {c:?}");
            assert!((e.theta_event - c.theta_event).abs() < 1e-7 || c.theta_event.is_nan());
        }
        // The turn cap.
        let m = JarmOptions {
            max_turns: 10,
            ..opts
        };
        assert_eq!(ode(1e-4, 0.3, 0.2, 1.0, &m).reason, Reason::TurnLimit);
    }
    // Invalid input, including tolerances.
    for &(a, chi, km, mu_s) in &[
        (f64::NAN, 0.1, 0.1, 1.0),
        (-0.1, 0.1, 0.1, 1.0),
        (1.6, 0.1, 0.1, 1.0),
        (0.5, 1.1, 0.0, 1.0),
        (0.5, 0.5, 0.6, 1.0),
        (0.5, 0.5, 0.1, -1.0),
        (0.5, 0.5, -0.1, 1.0),
    ] {
        assert_eq!(ode(a, chi, km, mu_s, &o).reason, Reason::InvalidParams);
    }
    let bad = JarmOptions { omega0: -1.0, ..o };
    assert_eq!(ode(0.5, 0.1, 0.1, 1.0, &bad).reason, Reason::InvalidParams);
    for (rt, at) in [(0.0, 1e-12), (1e-10, f64::NAN), (f64::INFINITY, 1e-12)] {
        let r = classify_ode(0.5, 0.1, 0.1, 1.0, &o, (rt, at), ode::Integrator::Rk45);
        assert_eq!(r.reason, Reason::InvalidParams);
    }
}

#[test]
fn integrator_failure_is_no_physical_verdict() {
    // A step budget far too small for the many turns at α = 1°: the integrator stops with
    // MaxSteps, reported as SolverFailed at the last good θ, never as a slip or turn limit.
    let o = JarmOptions::default();
    let a = 1f64.to_radians();
    let ok = classify_ode(a, 0.3, 0.2, 1.0, &o, (RTOL, ATOL), ode::Integrator::Rk45);
    assert_ne!(ok.reason, Reason::SolverFailed);
    let how = Integration {
        tol: (RTOL, ATOL),
        pair: ode::Integrator::Rk45,
        steps_per_turn: 1,
    };
    let r = classify_ode_budget(a, 0.3, 0.2, 1.0, &o, how);
    assert_eq!(r.reason, Reason::SolverFailed, "{r:?}");
    assert!(!r.is_jarm && r.theta_event.is_finite() && r.theta_j.is_nan());
    assert!(r.theta_event < ok.theta_event.max(ok.theta_j));
}

#[test]
fn a_lane_batch_is_each_point_bit_for_bit() {
    // Random points (a few invalid, some at rest in equilibrium, some already past a
    // contact condition at the start), every pair, both rules, explicit turns, moving
    // starts, with and without the continuation after a slip.
    let mut rng = crate::testing::Lcg(11);
    let mut u = || rng.next();
    let points: Vec<(f64, f64, f64, f64, JarmOptions)> = (0..600)
        .map(|i| {
            let chi = 1e-3 + 0.999 * u();
            let km = (1.0 - chi) * u();
            let alpha = if i % 50 == 7 { -0.1 } else { 1.5 * u() + 0.02 };
            let o = JarmOptions {
                rule: if i % 2 == 0 {
                    Rule::Paper
                } else {
                    Rule::NormalForce
                },
                n: if i % 7 == 3 { 1 + (i % 3) as u32 } else { 0 },
                theta0: if i % 5 == 1 { 6.0 * u() } else { 0.0 },
                omega0: if i % 5 == 2 { 2.0 * u() } else { 0.0 },
                stop_at_slip: i % 3 == 0,
                ..JarmOptions::default()
            };
            (alpha, chi, km, 0.2 + 1.5 * u(), o)
        })
        .collect();
    // Then slips under the paper's rule without stop_at_slip to the very end: their
    // continuations to the lift-off are integrated after the last point has started.
    let paper = JarmOptions::default();
    let points: Vec<_> = (points.into_iter())
        .chain((0..80).map(|_| (0.3 + 0.9 * u(), 0.5, 0.1, 0.05 + 0.2 * u(), paper)))
        .collect();
    let bits = |r: &JarmResult| r.as_f64s().map(f64::to_bits);
    for pair in ode::Integrator::ALL {
        let mut out = vec![JarmResult::new(Reason::NoRoot); points.len()];
        classify_ode_batch(|i| points[i], (RTOL, ATOL), pair, &mut out, &never);
        let mut reasons = std::collections::BTreeSet::new();
        for (x, &(a, c, k, m, o)) in out.iter().zip(&points) {
            let want = classify_ode(a, c, k, m, &o, (RTOL, ATOL), pair);
            assert_eq!(bits(x), bits(&want), "{pair:?} {a} {c} {k} {m} {o:?}");
            reasons.insert(x.reason as u8);
        }
        // The batch met many kinds of ends, and the last points slipped.
        assert!(reasons.len() >= 6, "{reasons:?}");
        let slipped = |r: &JarmResult| matches!(r.reason, Reason::SlipBefore | Reason::SlipAtJump);
        assert!(out[out.len() - 10..].iter().all(slipped));
    }
}

#[test]
fn deterministic() {
    let bits = |r: &JarmResult| {
        [
            r.reason as u8 as u64,
            r.n as u64,
            r.theta_j.to_bits(),
            r.theta_event.to_bits(),
            r.fx_j.to_bits(),
            r.fy_j.to_bits(),
            r.max_ratio.to_bits(),
            r.theta_max_ratio.to_bits(),
            r.min_fy.to_bits(),
            r.theta_min_fy.to_bits(),
        ]
    };
    for &(a, chi, km) in &[(0.7, 0.15, 0.02), (0.52, 0.5, 0.4), (0.2, 0.3, 0.0)] {
        for rule in [Rule::Paper, Rule::NormalForce] {
            let o = JarmOptions {
                rule,
                ..JarmOptions::default()
            };
            let (p, q) = (ode(a, chi, km, 1.0, &o), ode(a, chi, km, 1.0, &o));
            assert_eq!(bits(&p), bits(&q));
        }
    }
    // Through the parallel map: any thread count gives the same bits.
    let (al, ch, fr) = grid(6);
    let m = Method::Ode {
        rtol: RTOL,
        atol: ATOL,
        pair: ode::Integrator::Rk45,
    };
    let o = JarmOptions::default();
    let mut r1 = JarmColumns::new(&pool(1).unwrap(), 216).unwrap();
    let mut r2 = r1.clone();
    classify_grid(&al, &ch, &fr, 1.0, m, &o, 1, &mut r1, &never).unwrap();
    classify_grid(&al, &ch, &fr, 1.0, m, &o, 2, &mut r2, &never).unwrap();
    let (r1, r2) = (r1.rows(), r2.rows());
    assert!(r1.iter().zip(&r2).all(|(p, q)| bits(p) == bits(q)));
}

/// CPU time of the process (user + system) from /proc/self/stat, in seconds (assumes
/// 100 clock ticks per second; NaN where /proc is unavailable). On a shared machine this
/// is the fairer measure of cost per point than wall time.
fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    // Fields after the parenthesised command name; utime and stime are fields 14 and 15.
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .map(|x| x.parse().unwrap_or(f64::NAN))
        .collect();
    if f.len() == 2 {
        (f[0] + f[1]) / 100.0
    } else {
        f64::NAN
    }
}

fn grid(n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let a = (1..=n).map(|i| FRAC_PI_2 * i as f64 / n as f64).collect();
    let c = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
    let f = (0..n).map(|i| i as f64 / n as f64).collect();
    (a, c, f)
}

/// Time per point of the ODE route; run with
/// `cargo test --release -p eccjump-core jarm::ode_route::tests::timing -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing() {
    let (a, c, f) = grid(20);
    let m = Method::Ode {
        rtol: RTOL,
        atol: ATOL,
        pair: ode::Integrator::Rk45,
    };
    let o = JarmOptions::default();
    let mut out = JarmColumns::new(&pool(1).unwrap(), 8000).unwrap();
    for nt in [1, 2] {
        let (t, cpu) = (std::time::Instant::now(), cpu_seconds());
        classify_grid(&a, &c, &f, 1.0, m, &o, nt, &mut out, &never).unwrap();
        let (dt, dcpu) = (t.elapsed().as_secs_f64(), cpu_seconds() - cpu);
        let jarm = out.is_jarm.iter().filter(|&&j| j).count();
        println!(
            "ODE route, {nt} thread(s): wall {:.1} us/point x threads, CPU {:.1} us/point \
             on 20^3 ({jarm} JARM)",
            dt * nt as f64 / 8000.0 * 1e6,
            dcpu / 8000.0 * 1e6
        );
    }
    let t = std::time::Instant::now();
    classify_grid(&a, &c, &f, 1.0, Method::ClosedForm, &o, 1, &mut out, &never).unwrap();
    let dt = t.elapsed().as_secs_f64();
    println!("closed form, 1 thread: {:.1} us/point", dt / 8000.0 * 1e6);
}

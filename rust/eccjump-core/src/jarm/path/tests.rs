//! The unit tests of the rolling path (`#[cfg(test)] mod tests` of [`super`]), with the
//! private items they check.

use super::events::event_of;
use super::extremum::Extremum;
use super::liftoff::WindowLift;
use super::scan::{rotation, Cursor, Grid, Stop, ROTATIONS};
use super::*;
use crate::mechanics::Cylinder;
use std::f64::consts::FRAC_PI_2;

fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
    Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
}

#[test]
fn path_point_agrees_with_rolling_and_derivatives() {
    for &(chi, km, a, th0, w0) in &[
        (0.3, 0.2, 25.0, 0.0, 0.0),
        (0.7, 0.05, 50.0, 1.0, 0.5),
        (0.9, 0.02, 10.0, -0.3, 2.0),
    ] {
        let r = ramp(chi, km, a);
        let p = RollingPath::new(&r, th0, w0, 0.8);
        for i in 1..40 {
            let th = th0 + 0.31 * i as f64;
            let q = p.eval(th);
            let w2 = r.omega_sq(th0, w0, th);
            assert!((q.omega_sq - w2).abs() < 1e-12 * (1.0 + w2));
            let k = r.kinematics(th, w2.sqrt());
            let tol = 1e-12 * (1.0 + w2);
            assert!(
                (q.fx - k.fx).abs() < tol && (q.fy - k.fy).abs() < tol,
                "{th}"
            );
            let ip = r.contact_inertia(th.cos());
            assert!((q.omega_dot - k.omega_dot).abs() < tol * (1.0 + 1.0 / ip));
            let hh = 1e-6;
            let (qp, qm) = (p.eval(th + hh), p.eval(th - hh));
            assert!(
                ((qp.omega_sq - qm.omega_sq) / (2.0 * hh) - 2.0 * q.omega_dot).abs()
                    < 1e-6 * (1.0 + q.omega_dot.abs())
            );
            for kk in 0..NG {
                let fd = (qp.g[kk] - qm.g[kk]) / (2.0 * hh);
                assert!(
                    (fd - q.dg[kk]).abs() < 1e-6 * (1.0 + fd.abs()),
                    "{kk} {fd} {}",
                    q.dg[kk]
                );
            }
        }
    }
}

#[test]
fn uniform_step_shortcut_gives_the_square_root_rule_bit_for_bit() {
    // The step rule as it was: ¼√(Ĩ_P/χ) when below 2π/24 (with a floor), else 2π/24.
    let reference = |p: &RollingPath, q: &PathPoint| {
        let hmax = TAU / SAMPLES_PER_TURN;
        let h = 0.25 * (p.ramp.contact_inertia(q.cos_t) / p.ramp.body.chi).sqrt();
        let floor = 1e-9 * (1.0 + q.theta.abs());
        if h < hmax {
            h.max(floor)
        } else {
            hmax
        }
    };
    let mut near = 0;
    for &(chi, km) in &[(0.9, 0.02), (0.7, 0.1), (0.5, 0.2), (0.99, 0.0), (0.3, 0.0)] {
        let r = ramp(chi, km, 20.0);
        let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
        for i in 0..20_000 {
            let q = p.eval(TAU * i as f64 / 20_000.0);
            assert_eq!(p.step(&q).to_bits(), reference(&p, &q).to_bits());
        }
        // Where Ĩ_P crosses the threshold: cos θ on a fine grid of ulps around it.
        let c_star = (p.ip_uniform - r.body.ic - 1.0) / (2.0 * chi);
        if c_star.abs() < 1.0 {
            near += 1;
            let mut q = p.eval(1.0);
            for k in -2000i64..=2000 {
                q.cos_t = f64::from_bits((c_star.to_bits() as i64 + k) as u64);
                assert_eq!(p.step(&q).to_bits(), reference(&p, &q).to_bits(), "{k}");
            }
        }
    }
    assert!(near >= 3, "{near}: the threshold was not crossed");
}

#[test]
fn rotated_half_angles_stay_within_1_5e_15() {
    // The scan advances sin/cos of (θ − θ0)/2 by ROTATIONS rotations between direct
    // evaluations; check the worst error against sin_cos over many starts (in θ ∈ [−8, 8]
    // so that the rounding of θ itself stays below 5e-16). Measured: 1.17e-15 for seven
    // rotations (7.2e-16 for three).
    {
        let h = TAU / SAMPLES_PER_TURN;
        let (sh, vh) = rotation(h);
        let mut worst = 0.0f64;
        for i in 0..20_000 {
            let t0 = 8e-4 * i as f64 - 8.0;
            let (mut su, mut cu) = crate::trig::sin_cos(0.5 * t0);
            let mut t = t0;
            for _ in 0..ROTATIONS {
                (su, cu) = (su + (cu * sh - su * vh), cu - (su * sh + cu * vh));
                t += h;
                let (s, c) = crate::trig::sin_cos(0.5 * t);
                worst = worst.max((su - s).abs()).max((cu - c).abs());
            }
        }
        assert!(worst < 1.5e-15, "{worst}");
        println!("h = {h}: worst {worst:e}");
    }
}

/// xorshift64*: a uniform in [0, 1) (reproducible test points).
fn uniform(s: &mut u64) -> f64 {
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    (s.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn every_constraint_is_affine_in_the_turn_index_at_a_fixed_phase() {
    // The law the turn skip rests on, checked against direct evaluations m turns later
    // (an independent route: E(θ + 2πm) through `sin_cos` of the full angle).
    let mut s = 7u64;
    for _ in 0..300 {
        let (chi, km) = (0.01 + 0.98 * uniform(&mut s), 0.5 * uniform(&mut s));
        let r = ramp(chi, km * (1.0 - chi), 0.01 + 20.0 * uniform(&mut s));
        let (th0, w0) = (6.0 * uniform(&mut s) - 3.0, 2.0 * uniform(&mut s));
        let p = RollingPath::new(&r, th0, w0, 0.3 + uniform(&mut s));
        let th = th0 + 0.1 + 6.0 * uniform(&mut s);
        let (su, cu) = crate::trig::sin_cos(0.5 * (th - th0));
        let (a, b) = (p.eval_half(th, su, cu), p.eval_half(th + TAU, -su, -cu));
        for m in [1.0, 2.0, 7.0, 40.0] {
            let q = p.eval(th + TAU * m);
            for k in 0..NG {
                let lin = a.g[k] + m * (b.g[k] - a.g[k]);
                let scale = 1.0 + a.g[k].abs() + m * (b.g[k] - a.g[k]).abs();
                assert!(
                    (q.g[k] - lin).abs() < 1e-11 * scale,
                    "{k} {m} {} {lin}",
                    q.g[k]
                );
            }
        }
    }
}

/// The extrema of F_y (min) and |F_x|/F_y (max) on [a, b] by brute force: 48 samples a
/// turn, then a 2000-point grid around every sample that is a local extremum.
fn brute_extrema(p: &RollingPath, a: f64, b: f64) -> (f64, f64) {
    let n = ((b - a) / TAU * 48.0).ceil().max(2.0) as usize;
    let h = (b - a) / n as f64;
    let pts: Vec<PathPoint> = (0..=n).map(|i| p.eval(a + h * i as f64)).collect();
    let best = |f: &dyn Fn(&PathPoint) -> f64| {
        let v: Vec<f64> = pts.iter().map(f).collect();
        let mut m = v.iter().copied().fold(f64::NEG_INFINITY, f64::max);
        for i in 0..=n {
            let left = i == 0 || v[i] >= v[i - 1];
            let right = i == n || v[i] >= v[i + 1];
            if left && right {
                let c = a + h * i as f64;
                for j in 0..=2000 {
                    let t = (c + h * (j as f64 / 1000.0 - 1.0)).clamp(a, b);
                    m = m.max(f(&p.eval(t)));
                }
            }
        }
        m
    };
    (-best(&|q| -q.fy), best(&|q| q.ratio()))
}

#[test]
fn turn_skip_finds_the_event_and_extrema_of_the_full_scan() {
    // Long paths (small α, from rest or not, each watch of the routes): the scan that
    // skips turns must find the event of the cell-by-cell scan, and the extrema over the
    // whole path (brute force), while doing much less work.
    let mut s = 20_261_124u64;
    let (mut far, mut evals_skip, mut evals_full) = (0, 0u64, 0u64);
    let watches = [
        Watch::ALL,
        Watch {
            liftoff: false,
            ..Watch::ALL
        },
        Watch {
            normal_force: false,
            friction: false,
            refine_extrema: false,
            ..Watch::ALL
        },
    ];
    for i in 0..300 {
        let chi = 0.001 + 0.998 * uniform(&mut s);
        let km = uniform(&mut s) * (1.0 - chi);
        let alpha = 0.2 * uniform(&mut s).powi(3) + 1e-6;
        let r = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap();
        let (th0, w0) = if i % 2 == 0 {
            (0.0, 0.0)
        } else {
            (4.0 * uniform(&mut s) - 2.0, uniform(&mut s))
        };
        let p = RollingPath::new(&r, th0, w0, 0.5 + 2.0 * uniform(&mut s));
        let end = th0 + TAU * (6.0 + 150.0 * uniform(&mut s));
        let w = watches[i % 3];
        let (a, b) = (
            p.scan_cells(th0, end, w, true),
            p.scan_cells(th0, end, w, false),
        );
        let at = format!(
            "chi {chi} km {km} alpha {alpha} th0 {th0} w0 {w0} watch {}",
            i % 3
        );
        assert_eq!(a.event, b.event, "{at}");
        let (ta, tb) = (a.at.theta, b.at.theta);
        assert!(
            (ta - tb).abs() <= 1e-13 * tb.abs().max(1.0),
            "{ta} {tb} {at}"
        );
        if w.normal_force && a.extrema.min_fy > 0.0 {
            let (min_fy, max_ratio) = brute_extrema(&p, th0, ta);
            let (m, r) = (a.extrema.min_fy, a.extrema.max_ratio);
            // Reported: values on the path, at least as good as every brute-force sample.
            let tol = 1e-11 * (1.0 + m.abs() + r.abs());
            assert!(
                m <= min_fy + tol,
                "{m} {min_fy} (full scan {}) {at}",
                b.extrema.min_fy
            );
            assert!(
                r >= max_ratio - tol,
                "{r} {max_ratio} (full {}) {at}",
                b.extrema.max_ratio
            );
            for (x, f) in [(a.extrema.theta_min_fy, m), (a.extrema.theta_max_ratio, r)] {
                assert!(x >= th0 && x <= ta, "{x} {at}");
                let q = p.eval(x);
                assert!(f == q.fy || f == q.ratio(), "{f} {x} {at}");
            }
        }
        if tb > th0 + 10.0 * TAU {
            far += 1;
        }
        evals_skip += a.evaluations as u64;
        evals_full += b.evaluations as u64;
    }
    assert!(far > 100, "{far} paths ran past 10 turns");
    assert!(
        (evals_skip as f64) < 0.3 * evals_full as f64,
        "{evals_skip} {evals_full}"
    );
}

#[test]
fn a_window_skip_is_refused_when_the_target_window_holds_the_liftoff() {
    let w = Watch::liftoff_only(3);
    let r = ramp(0.7, 0.1, 0.05);
    let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
    let lift = p.scan_cells(0.0, 4000.0, w, false);
    assert_eq!(lift.event, ContactEvent::Liftoff);
    let n = (lift.at.theta / TAU).round();
    let window = |m: f64| Some((TAU * m - 0.5, TAU * m + 0.5, true));
    let grid = Grid::new(0.0, 4000.0, w);
    assert!(p.clean_window(n, &window, &grid).is_none());
    assert_eq!(p.clean_window(n - 1.0, &window, &grid), Some(n - 1.0));
    let cut = |m: f64| Some((TAU * m - 0.5, TAU * m + 0.5, false));
    assert!(p.clean_window(n - 1.0, &cut, &grid).is_none());
}

/// The bisections behind the skips: from a clean turn (window) and a later one that is not
/// clean, the last clean one is found, and the scan from there finds the cell-by-cell
/// scan's event; the lift-off windows likewise.
#[test]
fn bisection_finds_the_last_clean_turn_and_window() {
    let noop = |_: &PathPoint, _: f64, _: f64| {};
    let mut probes = 0;
    for &(chi, km, a) in &[(0.05, 0.5, 0.06), (0.5, 0.2, 0.02), (0.3, 0.35, 0.1)] {
        let r = ramp(chi, km, a);
        let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
        let end = 3000.0 * TAU;
        let full = p.scan_cells(0.0, end, Watch::ALL, false);
        assert_ne!(full.event, ContactEvent::ThetaLimit, "{chi} {km} {a}");
        let event_turn = (full.at.theta / TAU).floor() + 1.0; // turns counted from 1
        assert!(event_turn > 20.0, "{chi} {km} {a}: {event_turn}");
        // The cursor at the end of turn 2, as `skip_turns` leaves it before a skip.
        let grid = Grid::new(0.0, end, Watch::ALL);
        let p0 = p.start();
        let min_fy = Extremum::start(p0.fy, p0.theta, f64::INFINITY);
        let max_r = Extremum::start(p0.ratio(), p0.theta, f64::NEG_INFINITY);
        let mut cur = Cursor::start(p0, (0.0, 1.0), min_fy, max_r);
        let turn_start = |m: f64| TAU * (m - 1.0);
        assert!(matches!(
            p.advance(&mut cur, &grid, turn_start(3.0), noop),
            Stop::Reached
        ));
        for dirty in [event_turn, event_turn + 1.0, event_turn + 700.0] {
            let saved = cur;
            let mut c = cur;
            let Stop::Event(e, at) =
                p.bisect_turns(&mut c, &grid, &saved, (2.0, dirty), turn_start)
            else {
                panic!("{chi} {km} {a}: no event");
            };
            assert_eq!(e, full.event);
            let t = full.at.theta;
            assert!((at.theta - t).abs() <= 1e-12 * t, "{} {t}", at.theta);
            // The probes cost a few turns, not the turns before the event.
            assert!(
                c.cells < 24 * 40 + cur.cells,
                "{} cells",
                c.cells - cur.cells
            );
            probes += 1;
        }
        // Lift-off windows: the first window of the lift-off, by the plain scan.
        let w = Watch::liftoff_only(3);
        let lift = p.scan_cells(0.0, end, w, false);
        assert_eq!(lift.event, ContactEvent::Liftoff);
        let n = (lift.at.theta / TAU).round();
        let window = |m: f64| Some((TAU * m - 0.5, TAU * m + 0.5, true));
        let grid = Grid::new(0.0, end, w);
        assert!(n > 10.0);
        for dirty in [n, n + 1.0, n + 300.0] {
            assert_eq!(p.last_clean_window((1.0, dirty), &window, &grid), n - 1.0);
        }
    }
    assert_eq!(probes, 9);
}

/// Points that once took up to 1.5 s (a slip or lift-off search over 10⁴–10⁶ turns at tiny
/// α): the scan to the first event takes a few turns' evaluations, and the lift-off
/// search after it finds the plain scan's lift-off (where that scan is affordable here).
#[test]
fn tiny_angles_take_few_evaluations() {
    use crate::jarm::decision::{point_ramp, search_end};
    use crate::jarm::JarmOptions;
    let o = JarmOptions {
        max_turns: 1_000_000,
        ..JarmOptions::default()
    };
    for &(a, chi, km) in &[(1e-9, 0.99, 0.0), (3.2e-8, 0.81, 0.15), (1e-3, 0.05, 0.5)] {
        let r = point_ramp(a, chi, km, 1.0, &o).unwrap();
        let (end, _) = search_end(&r, &o).unwrap();
        let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
        let s = p.scan(end, Watch::ALL);
        assert_eq!(s.event, ContactEvent::Slip, "{a}");
        assert!(s.evaluations < 3000, "{a}: {} evaluations", s.evaluations);
        let th = s.at.theta;
        if end - th < 1e5 {
            let plain = p.scan_cells(th, end, Watch::liftoff_only(3), false);
            let fast = p.liftoff_after(th, end, 3, |_, _| true);
            assert_eq!(fast.is_some(), plain.event == ContactEvent::Liftoff, "{a}");
            if let Some(x) = fast {
                assert!((x - plain.at.theta).abs() <= 1e-12 * x.abs(), "{a}");
            }
        }
    }
}

#[test]
fn window_liftoff_gives_the_scans_angle_bit_for_bit() {
    // On windows where E > 0 holds, the lift-only loop must stop exactly where the full
    // scan watching lift-off and energy stops: same grid, same values, same root.
    let mut s = 20261124u64;
    let (mut found, mut clean) = (0, 0);
    for _ in 0..3000 {
        let alpha = 0.02 + 1.5 * uniform(&mut s);
        let chi = 0.001 + 0.999 * uniform(&mut s);
        let km = (1.0 - chi) * uniform(&mut s);
        let r = ramp(chi, km, alpha.to_degrees());
        let (th0, w0) = if uniform(&mut s) < 0.5 {
            (0.0, 0.0)
        } else {
            (6.0 * uniform(&mut s) - 3.0, 2.0 * uniform(&mut s))
        };
        let p = RollingPath::new(&r, th0, w0, 1.0);
        let m = (th0 / TAU).ceil() + (6.0 * uniform(&mut s)).floor();
        let half = 1.5 * uniform(&mut s).powi(3) + 0.01;
        let (lo, hi) = ((TAU * m - half).max(th0), TAU * m + half);
        let coarseness = if uniform(&mut s) < 0.5 { 1 } else { 3 };
        let w = Watch::liftoff_only(coarseness);
        // Skip windows where the energy could vanish (the loop assumes it cannot).
        let e_low = p.k0 + (lo - th0) * p.ramp.sin_a + chi * (p.ca0 - 1.0);
        if e_low <= 0.0 {
            continue;
        }
        let full = p.scan_cells(lo, hi, w, false);
        let fast = p.window_liftoff(lo, hi, &Grid::new(lo, hi, w), &|_, _| true);
        match fast {
            WindowLift::At(x) => {
                assert_eq!(full.event, ContactEvent::Liftoff, "{alpha} {chi} {km} {m}");
                assert_eq!(x.to_bits(), full.at.theta.to_bits());
                found += 1;
            }
            WindowLift::Clean => {
                assert_eq!(
                    full.event,
                    ContactEvent::ThetaLimit,
                    "{alpha} {chi} {km} {m}"
                );
                clean += 1;
            }
            WindowLift::Within => panic!("every cell matters here"),
        }
    }
    assert!(found > 300 && clean > 300, "{found} {clean}");
}

#[test]
fn liftoff_scan_by_windows_agrees_with_plain_scan() {
    let w = Watch::liftoff_only(1);
    let (mut found, mut far) = (0, 0);
    for &(chi, km, a) in &[
        (0.15, 0.02, 40.0),
        (0.5, 0.4, 30.0),
        (0.9, 0.05, 2.0),
        (0.05, 0.3, 0.9),
        (0.99, 0.0, 30.0),
        (0.3, 0.1, 89.0),
        // Lift-off after hundreds of turns: the windows in between are skipped.
        (0.7, 0.1, 0.05),
        (0.3, 0.2, 0.02),
    ] {
        let r = ramp(chi, km, a);
        for &(th0, w0) in &[(0.0, 0.0), (1.0, 0.3), (-2.0, 1.5)] {
            let p = RollingPath::new(&r, th0, w0, 1.0);
            for i in 0..12 {
                let start = th0 + 0.7 * i as f64;
                let end = th0 + if a < 0.1 { 4000.0 } else { 400.0 };
                let a1 = p.scan_cells(start, end, w, false);
                let a2 = p.liftoff_after(start, end, 1, |_, _| true);
                let lifts = a1.event == ContactEvent::Liftoff;
                assert_eq!(lifts, a2.is_some(), "{chi} {km} {a} {th0} {start}");
                if let Some(t2) = a2 {
                    found += 1;
                    far += (a1.at.theta > start + 100.0 * TAU) as u32;
                    let t1 = a1.at.theta;
                    assert!((t1 - t2).abs() <= 1e-13 * t1.abs().max(1.0), "{t1} {t2}");
                }
            }
        }
    }
    assert!(found > 100 && far >= 20, "{found} {far}");
}

/// The exact energy test that lets a lift-off search after an early slip go by windows:
/// it holds exactly where E stays positive (checked on a fine sampling of three turns),
/// and the windowed search then agrees with the plain scan, including where the body
/// rocks back first (E reaching 0 ends the plain scan: no lift-off).
#[test]
fn early_slip_lift_off_search_is_exact_where_energy_stays_positive() {
    let w = Watch::liftoff_only(3);
    let mut s = 7u64;
    let (mut exact, mut rocks, mut windowed) = (0, 0, 0);
    for _ in 0..4000 {
        let alpha = 1e-3 + (FRAC_PI_2 - 2e-3) * uniform(&mut s);
        let chi = 0.02 + 0.97 * uniform(&mut s);
        let r = ramp(chi, uniform(&mut s) * (1.0 - chi), alpha.to_degrees());
        let th0 = TAU * (uniform(&mut s) - 0.5);
        let w0 = if uniform(&mut s) < 0.3 {
            0.0
        } else {
            0.6 * uniform(&mut s)
        };
        let p = RollingPath::new(&r, th0, w0, 1.0);
        let start = th0 + 0.8 * uniform(&mut s);
        let e_low = p.k0 + (start - th0) * r.sin_a + chi * (p.ca0 - 1.0);
        if e_low > 0.0 || p.energy(start) < 0.0 {
            continue; // the cheap bound decides, or the path never gets here
        }
        // The lowest E on (start, start + 3 turns], sampled.
        let lowest = (1..=30_000)
            .map(|i| p.energy(start + 3.0 * TAU * i as f64 / 30_000.0))
            .fold(f64::INFINITY, f64::min);
        let positive = p.energy_stays_positive(start);
        if positive {
            assert!(lowest > 0.0, "{alpha} {chi} {th0} {w0} {start}: {lowest}");
            exact += 1;
        } else if lowest > 1e-6 {
            panic!("E stays positive but the test failed: {alpha} {chi} {th0} {w0} {start}");
        }
        let end = start + 60.0;
        let plain = p.scan_cells(start, end, w, false);
        rocks += (plain.event == ContactEvent::RocksBack) as u32;
        let fast = p.liftoff_after(start, end, 3, |_, _| true);
        assert_eq!(
            fast.is_some(),
            plain.event == ContactEvent::Liftoff,
            "{alpha} {chi} {th0} {w0} {start}"
        );
        if let Some(x) = fast {
            let t = plain.at.theta;
            assert!((x - t).abs() <= 1e-13 * t.abs().max(1.0), "{x} {t}");
            windowed += positive as u32;
        }
    }
    assert!(
        exact > 300 && rocks > 100 && windowed > 200,
        "{exact} {rocks} {windowed}"
    );
}

/// Brute force: the first violation on a dense grid of 1e5 points.
fn brute(p: &RollingPath, theta_end: f64, watch: Watch) -> Option<(f64, usize)> {
    let n = 100_000;
    for i in 0..=n {
        let th = p.theta0 + (theta_end - p.theta0) * i as f64 / n as f64;
        let q = p.eval(th);
        for &k in &[G_NOLIFT, G_FY, G_MPLUS, G_MMINUS, G_ENERGY] {
            if watch.active(k) && i > 0 && violated(k, q.g[k]) {
                return Some((th, k));
            }
        }
    }
    None
}

#[test]
fn scan_agrees_with_dense_sampling() {
    let mut checked = 0;
    for &(chi, km, a, mu) in &[
        (0.15, 0.02, 40.0, 1.0),
        (0.5, 0.4, 30.0, 1.0),
        (0.3, 0.1, 20.0, 0.7),
        (0.9, 0.05, 15.0, 1.0),
        (0.6, 0.3, 60.0, 2.0),
        (0.05, 0.2, 80.0, 1.0),
        (0.99, 0.0, 30.0, 5.0),
        (0.4, 0.5, 8.0, 0.5),
    ] {
        let r = ramp(chi, km, a);
        let p = RollingPath::new(&r, 0.0, 0.0, mu);
        let end = 4.0 * TAU;
        let s = p.scan(end, Watch::ALL);
        let b = brute(&p, end, Watch::ALL);
        match (s.event, b) {
            (ContactEvent::ThetaLimit, None) => {}
            (ev, Some((th, k))) => {
                assert_eq!(ev, event_of(k), "{chi} {km} {a}");
                assert!(
                    s.at.theta <= th && th - s.at.theta < 1e-3,
                    "{} {th}",
                    s.at.theta
                );
                checked += 1;
            }
            (ev, None) => panic!("{ev:?} but brute force found nothing"),
        }
        // Reported extrema against dense sampling on [0, θ_event].
        let n = 100_000;
        let (mut mr, mut mf) = (0.0f64, f64::INFINITY);
        for i in 0..=n {
            let q = p.eval(s.at.theta * i as f64 / n as f64);
            mr = mr.max(q.ratio());
            mf = mf.min(q.fy);
        }
        assert!(
            s.extrema.min_fy <= mf + 1e-12 && mf - s.extrema.min_fy < 1e-8,
            "{} {mf}",
            s.extrema.min_fy
        );
        if mr.is_finite() {
            assert!(
                s.extrema.max_ratio >= mr - 1e-12 && s.extrema.max_ratio - mr < 1e-6,
                "{} {mr}",
                s.extrema.max_ratio
            );
        }
    }
    assert!(checked >= 6);
}

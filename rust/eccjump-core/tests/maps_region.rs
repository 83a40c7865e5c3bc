//! Tests of `maps::region` through the public API: grids and point lists classified in
//! parallel, bit for bit the same for any thread count and as point by point.

use eccjump_core::jarm::{classify, JarmOptions, JarmResult, Method};
use eccjump_core::maps::columns::JarmColumns;
use eccjump_core::maps::parallel::pool;
use eccjump_core::maps::region::{classify_grid, classify_points};
use std::f64::consts::FRAC_PI_2;

/// Never stop: the `stop` of a map that is not to be interrupted.
fn never() -> bool {
    false
}

/// Result columns for `len` points.
fn blank(len: usize) -> JarmColumns {
    JarmColumns::new(&pool(1).unwrap(), len).unwrap()
}

fn grid(n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
    let a = (1..=n).map(|i| FRAC_PI_2 * i as f64 / n as f64).collect();
    let c = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
    let f = (0..n).map(|i| i as f64 / n as f64).collect();
    (a, c, f)
}

fn run(n_threads: usize, a: &[f64], c: &[f64], f: &[f64]) -> Vec<JarmResult> {
    let mut out = blank(a.len() * c.len() * f.len());
    let o = JarmOptions::default();
    classify_grid(
        a,
        c,
        f,
        1.0,
        Method::ClosedForm,
        &o,
        n_threads,
        &mut out,
        &never,
    )
    .unwrap();
    out.rows()
}

fn bits(v: &[JarmResult]) -> Vec<(u8, u64, u64, u64)> {
    v.iter()
        .map(|r| {
            let b = (
                r.theta_j.to_bits(),
                r.max_ratio.to_bits(),
                r.min_fy.to_bits(),
            );
            (r.reason as u8, b.0, b.1, b.2)
        })
        .collect()
}

#[test]
fn bit_identical_for_any_thread_count_and_matches_single_points() {
    let (a, c, f) = grid(14);
    let r1 = run(1, &a, &c, &f);
    for nt in [2, 3, 0] {
        assert_eq!(bits(&run(nt, &a, &c, &f)), bits(&r1));
    }
    // Same as classify on each point, and as classify_points.
    let o = JarmOptions::default();
    let (mut pa, mut pc, mut pk) = (vec![], vec![], vec![]);
    for &x in &a {
        for &y in &c {
            for &z in &f {
                pa.push(x);
                pc.push(y);
                pk.push(z * (1.0 - y));
            }
        }
    }
    for (k, r) in r1.iter().enumerate() {
        assert_eq!(classify(pa[k], pc[k], pk[k], 1.0, &o).reason, r.reason);
    }
    let mut out = blank(pa.len());
    classify_points(
        &pa,
        &pc,
        &pk,
        &[1.0],
        &[0],
        Method::ClosedForm,
        &o,
        2,
        &mut out,
        &never,
    )
    .unwrap();
    assert_eq!(bits(&out.rows()), bits(&r1));
    // Wrong lengths are errors.
    let mut short = blank(3);
    let m = Method::ClosedForm;
    assert!(classify_grid(&a, &c, &f, 1.0, m, &o, 1, &mut short, &never).is_err());
    assert!(classify_points(&pa, &pc, &pk[1..], &[1.0], &[0], m, &o, 1, &mut out, &never).is_err());
}

/// Every 5th point of each axis of the timing grid (8000 points) on one thread: a small,
/// representative workload for instruction counts (`perf stat`, `valgrind --tool=callgrind`).
#[test]
#[ignore]
fn timing_sample() {
    let (a, c, f) = grid(100);
    let pick = |v: Vec<f64>| v.into_iter().skip(2).step_by(5).collect::<Vec<_>>();
    let (a, c, f) = (pick(a), pick(c), pick(f));
    let o = JarmOptions {
        refine_extrema: false,
        ..Default::default()
    };
    let mut out = blank(a.len() * c.len() * f.len());
    let t = std::time::Instant::now();
    for _ in 0..5 {
        classify_grid(&a, &c, &f, 1.0, Method::ClosedForm, &o, 1, &mut out, &never).unwrap();
    }
    let dt = t.elapsed().as_secs_f64() / 5.0;
    let jarm = out.is_jarm.iter().filter(|&&j| j).count();
    println!(
        "{} points: {:.2} us/point (1 thread), {jarm} JARM",
        out.len(),
        dt * 1e6 / out.len() as f64
    );
}

/// Snapshot of the 100³ timing grid (reason, n, θ_J, θ_event, max ratio, min F_y per
/// point), to check that an optimisation leaves every result unchanged. With
/// `ECCJUMP_SNAPSHOT=path` it writes the file if absent, else compares against it:
/// `cargo test --release -p eccjump-core maps::region::tests::snapshot -- --ignored --nocapture`.
#[test]
#[ignore]
fn snapshot() {
    let Ok(path) = std::env::var("ECCJUMP_SNAPSHOT") else {
        return;
    };
    let (a, c, f) = grid(100);
    let o = JarmOptions {
        refine_extrema: false,
        ..Default::default()
    };
    let mut out = blank(1_000_000);
    classify_grid(&a, &c, &f, 1.0, Method::ClosedForm, &o, 2, &mut out, &never).unwrap();
    let out = out.rows();
    let mut bytes = Vec::with_capacity(out.len() * 37);
    for r in &out {
        bytes.push(r.reason as u8);
        bytes.extend_from_slice(&r.n.to_le_bytes());
        for x in [r.theta_j, r.theta_event, r.max_ratio, r.min_fy] {
            bytes.extend_from_slice(&x.to_le_bytes());
        }
    }
    let Ok(old) = std::fs::read(&path) else {
        std::fs::write(&path, &bytes).unwrap();
        println!("wrote {path}");
        return;
    };
    assert_eq!(old.len(), bytes.len());
    // θ_J: relative difference; θ_event and the extrema (cell estimates, which may sit at
    // F_y ≈ 0, where the ratio flips between finite and ∞): relative to max(1, |x|, |y|).
    let diff = |i: usize, x: f64, y: f64| {
        if x == y || (x.is_nan() && y.is_nan()) {
            0.0
        } else {
            let floor = if i == 0 { 1e-300 } else { 1.0 };
            (x - y).abs() / x.abs().max(y.abs()).max(floor)
        }
    };
    let (mut worst, mut at, mut differ) = ([0.0f64; 4], [0usize; 4], [0usize; 4]);
    for (k, (o, n)) in old.chunks(37).zip(bytes.chunks(37)).enumerate() {
        assert_eq!(o[..5], n[..5], "point {k}: reason/n differ");
        for i in 0..4 {
            let g = |b: &[u8]| f64::from_le_bytes(b[5 + 8 * i..13 + 8 * i].try_into().unwrap());
            let d = diff(i, g(o), g(n));
            if d != 0.0 {
                differ[i] += 1;
            }
            // Finite against ∞ (or NaN) counts as a difference of 1.
            let d = if d.is_nan() { 1.0 } else { d.min(1.0) };
            if d > worst[i] {
                worst[i] = d;
                at[i] = k;
            }
        }
    }
    println!("same reason and n at all points; fields theta_j, theta_event, max_ratio, min_fy:");
    println!("  points differing: {differ:?}");
    println!(
        "  worst difference (θ_J relative, others relative to max(1, |x|)): {worst:?} at {at:?}"
    );
    assert!(worst[0] < 1e-12 && worst[1] < 1e-12, "{worst:?}");
}

/// The performance target: run with
/// `cargo test --release -p eccjump-core maps::region::tests::timing -- --ignored --nocapture`.
#[test]
#[ignore]
fn timing() {
    let (a, c, f) = grid(100);
    let o = JarmOptions {
        refine_extrema: false,
        ..Default::default()
    };
    let mut out = blank(1_000_000);
    for nt in [1, 2] {
        let t = std::time::Instant::now();
        classify_grid(
            &a,
            &c,
            &f,
            1.0,
            Method::ClosedForm,
            &o,
            nt,
            &mut out,
            &never,
        )
        .unwrap();
        let dt = t.elapsed().as_secs_f64();
        let jarm = out.is_jarm.iter().filter(|&&j| j).count();
        println!(
            "{nt} thread(s): {dt:.3} s for 1e6 points ({:.2} us/point/core), {jarm} JARM",
            dt * nt as f64
        );
    }
}

//! CPU cost of the ODE route per point, per Runge–Kutta pair, on the random
//! points (α ~ U(0, π/2), χ ~ U(1e-3, 1), k_m = u(1 − χ), μ_s = 1), one thread, and how
//! often the pairs agree on the reason. `cargo run --release -p eccjump-core --features profiling --example
//! ode_route_cost [points] [rk45|dop853|vern9|all] [stop]` (`stop`: `stop_at_slip`); each pair
//! point by point, then all points side by side (`classify_ode_batch`, the maps' way).
use eccjump_core::jarm::ode_route::classify_ode_batch;
use eccjump_core::jarm::{classify_ode, JarmOptions, JarmResult, Reason};
use eccjump_core::ode::Integrator;
use std::time::Instant;

/// A small deterministic generator (SplitMix64), so the points are the same every run.
fn uniform(state: &mut u64) -> f64 {
    *state = state.wrapping_add(0x9E37_79B9_7F4A_7C15);
    let mut z = *state;
    z = (z ^ (z >> 30)).wrapping_mul(0xBF58_476D_1CE4_E5B9);
    z = (z ^ (z >> 27)).wrapping_mul(0x94D0_49BB_1331_11EB);
    ((z ^ (z >> 31)) >> 11) as f64 / (1u64 << 53) as f64
}

fn main() {
    let n: usize = std::env::args()
        .nth(1)
        .and_then(|a| a.parse().ok())
        .unwrap_or(4000);
    let mut s = 20261123u64;
    let points: Vec<(f64, f64, f64)> = (0..n)
        .map(|_| {
            let a = uniform(&mut s) * std::f64::consts::FRAC_PI_2;
            let chi = 1e-3 + uniform(&mut s) * (1.0 - 1e-3);
            (a, chi, uniform(&mut s) * (1.0 - chi))
        })
        .filter(|p| p.0 > 0.0)
        .collect();
    let o = JarmOptions {
        stop_at_slip: std::env::args().nth(3).as_deref() == Some("stop"),
        ..JarmOptions::default()
    };
    let mut reasons = Vec::new();
    let pairs: Vec<Integrator> = match std::env::args().nth(2).as_deref() {
        Some("rk45") => vec![Integrator::Rk45],
        Some("dop853") => vec![Integrator::Dop853],
        Some("vern9") => vec![Integrator::Vern9],
        _ => Integrator::ALL.to_vec(),
    };
    for pair in pairs {
        let t0 = Instant::now();
        let r: Vec<_> = points
            .iter()
            .map(|&(a, chi, km)| classify_ode(a, chi, km, 1.0, &o, (1e-10, 1e-12), pair))
            .collect();
        let us = t0.elapsed().as_secs_f64() / points.len() as f64 * 1e6;
        let t0 = Instant::now();
        let mut batch = vec![JarmResult::new(Reason::NoRoot); points.len()];
        let point = |i: usize| {
            let (a, chi, km) = points[i];
            (a, chi, km, 1.0, o)
        };
        classify_ode_batch(point, (1e-10, 1e-12), pair, &mut batch, &|| false);
        let lanes = t0.elapsed().as_secs_f64() / points.len() as f64 * 1e6;
        let same = batch
            .iter()
            .zip(&r)
            .all(|(x, y)| x.as_f64s().map(f64::to_bits) == y.as_f64s().map(f64::to_bits));
        println!("{pair:?}: {us:.1} us per point, side by side {lanes:.1} (same bits: {same})");
        reasons.push(r);
    }
    // Each pair against the first.
    for (k, other) in reasons.iter().enumerate().skip(1) {
        let pairs = || reasons[0].iter().zip(other);
        let same = pairs().filter(|(a, b)| a.reason == b.reason).count();
        let jarm = pairs().filter(|(a, b)| a.is_jarm == b.is_jarm).count();
        let dtheta = pairs()
            .filter(|(a, b)| a.reason == b.reason && a.theta_event.is_finite())
            .map(|(a, b)| ((a.theta_event - b.theta_event) / a.theta_event.abs().max(1.0)).abs())
            .fold(0.0, f64::max);
        println!(
            "pair {k} against pair 0: same reason {same}/{}, same is_jarm {jarm}, largest relative \
             theta_event difference {dtheta:.1e}",
            points.len()
        );
    }
}

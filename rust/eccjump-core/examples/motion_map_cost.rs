//! Profiling aid: where a motion map spends its time, by the status of the points, one point
//! at a time, then the same grid by `motion_map` on one thread (its first rolling segments
//! side by side) (`cargo run --release -p eccjump-core --features profiling --example motion_map_cost [rk45|dop853]`).
use eccjump_core::maps::motion::{
    motion_map, motion_point, MotionAxes, MotionMapOptions, MotionSummary,
};
use eccjump_core::mechanics::Rule;
use eccjump_core::modes::contact::ContactLaw;
use eccjump_core::motion::SimOptions;
use eccjump_core::ode::{Integrator, SolverOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;
fn main() {
    let method = match std::env::args().nth(1).as_deref() {
        Some("dop853") => Integrator::Dop853,
        _ => Integrator::Rk45,
    };
    let solver = SolverOptions {
        method,
        ..SolverOptions::default()
    };
    let n = 24;
    let mut by_status = [(0usize, 0f64, 0usize); 8];
    let mut each = Vec::with_capacity(n * n * n);
    let lin = |i: usize, lo: f64, hi: f64| lo + (hi - lo) * i as f64 / (n - 1) as f64;
    for ia in (0..n).filter(|_| std::env::var_os("GRID_ONLY").is_none()) {
        for ic in 0..n {
            for ik in 0..n {
                let (a, c, f) = (
                    lin(ia, 1.0, 89.0).to_radians(),
                    lin(ic, 0.02, 0.98),
                    lin(ik, 0.02, 0.98),
                );
                let r = Ramp::new(Cylinder::new(c, f * (1.0 - c)).unwrap(), a).unwrap();
                let o = SimOptions {
                    law: ContactLaw {
                        mu_s: 1.0,
                        mu_k: 1.0,
                        rule: Rule::Paper,
                    },
                    max_transitions: 50,
                    stop_at_landing: true,
                    record_points: false,
                    solver,
                    ..SimOptions::default()
                };
                let t0 = Instant::now();
                let s: MotionSummary = motion_point(&r, &o);
                let dt = t0.elapsed().as_secs_f64();
                each.push(s);
                let k = (s.status as usize).min(7);
                by_status[k].0 += 1;
                by_status[k].1 += dt;
                by_status[k].2 += s.n_modes as usize;
            }
        }
    }
    let total: f64 = by_status.iter().map(|b| b.1).sum();
    for (k, (cnt, t, modes)) in by_status.iter().enumerate().filter(|b| b.1 .0 > 0) {
        println!(
            "status {k}: {cnt} points, {:.1} us/pt, {:.0}% of the time, {:.1} modes/pt",
            t / *cnt as f64 * 1e6,
            t / total * 100.0,
            *modes as f64 / *cnt as f64
        );
    }
    println!("mean {:.1} us/pt", total / (n * n * n) as f64 * 1e6);
    let axis = |lo: f64, hi: f64| (0..n).map(|i| lin(i, lo, hi)).collect::<Vec<_>>();
    let alpha: Vec<f64> = axis(1.0, 89.0).iter().map(|a| a.to_radians()).collect();
    let (chi, frac) = (axis(0.02, 0.98), axis(0.02, 0.98));
    let axes = MotionAxes {
        alpha: &alpha,
        chi: &chi,
        frac: &frac,
        mu_s: &[1.0],
        mu_k: &[],
        restitution: &[0.0],
        theta0: &[0.0],
        omega0: &[0.0],
    };
    let opts = MotionMapOptions {
        rule: Rule::Paper,
        t_max: 100.0,
        max_transitions: 50,
        solver,
    };
    let mut out = vec![MotionSummary::invalid(); n * n * n];
    let t0 = Instant::now();
    motion_map(&axes, &opts, 1, &mut out, &|| false).unwrap();
    let dt = t0.elapsed().as_secs_f64();
    let same = out
        .iter()
        .zip(&each)
        .filter(|(a, b)| format!("{a:?}") == format!("{b:?}"))
        .count();
    println!(
        "motion_map over a grid, one thread: {:.1} us/pt ({same} of {} summaries the same as point by point)",
        dt / (n * n * n) as f64 * 1e6,
        each.len()
    );
}

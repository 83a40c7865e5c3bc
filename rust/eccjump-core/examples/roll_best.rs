//! Profiling aid: the best time per `roll` run from rest to the paper's lift-off (α = 40°,
//! χ = 0.15, k_m = 0.02), per Runge–Kutta pair
//! (`cargo run --release -p eccjump-core --example roll_best [rk45|dop853]`).
use eccjump_core::modes::rolling::run::{roll, RollOptions};
use eccjump_core::ode::{Method, SolverOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;
fn main() {
    let pairs = match std::env::args().nth(1).as_deref() {
        Some("rk45") => vec![Method::Rk45],
        Some("dop853") => vec![Method::Dop853],
        _ => vec![Method::Rk45, Method::Dop853],
    };
    let r = Ramp::new(Cylinder::new(0.15, 0.02).unwrap(), 40f64.to_radians()).unwrap();
    for method in pairs {
        let o = RollOptions {
            solver: SolverOptions {
                method,
                ..SolverOptions::default()
            },
            ..RollOptions::default()
        };
        let run = roll(&r, &o).unwrap();
        let mut best = f64::INFINITY;
        for _ in 0..30 {
            let t0 = Instant::now();
            for _ in 0..1000 {
                std::hint::black_box(roll(&r, &o).unwrap());
            }
            best = best.min(t0.elapsed().as_secs_f64() / 1000.0 * 1e6);
        }
        println!(
            "{method:?}: best {best:.2} us per run, theta_J {:.15} ({} steps, {} evaluations)",
            run.theta.last().unwrap(),
            run.t.len() - 1,
            run.nfev
        );
    }
}

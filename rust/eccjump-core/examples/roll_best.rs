//! Profiling aid: the best time per `roll` run from rest to the paper's lift-off, for the
//! four cases of `benches/bench_peers.py` (α = 40°, 70°, 30°, 10°), per Runge–Kutta pair
//! (`cargo run --release -p eccjump-core --features profiling --example roll_best [rk45|dop853|vern9] [rtol]`, atol =
//! rtol/100; default the core's tolerances).
use eccjump_core::modes::rolling::run::{roll, RollOptions};
use eccjump_core::ode::{Integrator, SolverOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;
fn main() {
    let pairs = match std::env::args().nth(1).as_deref() {
        Some("rk45") => vec![Integrator::Rk45],
        Some("dop853") => vec![Integrator::Dop853],
        Some("vern9") => vec![Integrator::Vern9],
        _ => Integrator::ALL.to_vec(),
    };
    let rtol: Option<f64> = std::env::args().nth(2).map(|r| r.parse().expect("rtol"));
    let cases = [
        (40.0, 0.15, 0.02),
        (70.0, 0.1, 0.27),
        (30.0, 0.1, 0.09),
        (10.0, 0.1, 0.54),
    ];
    for (method, &(alpha, chi, km)) in pairs
        .into_iter()
        .flat_map(|m| cases.iter().map(move |c| (m, c)))
    {
        let r = Ramp::new(Cylinder::new(chi, km).unwrap(), f64::to_radians(alpha)).unwrap();
        let o = RollOptions {
            solver: SolverOptions {
                method,
                rtol: rtol.unwrap_or(SolverOptions::default().rtol),
                atol: rtol.map_or(SolverOptions::default().atol, |r| r / 100.0),
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
            "{method:?} alpha {alpha}: best {best:.2} us per run, theta_J {:.15} ({} steps, {} evaluations)",
            run.theta.last().unwrap(),
            run.t.len() - 1,
            run.nfev
        );
    }
}

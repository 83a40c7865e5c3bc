//! Profiling aid: the best time per `simulate` run of one slip-then-jump case, 5 transitions
//! (`cargo run --release -p eccjump-core --features profiling --example simulate_best [rk45|dop853] [flight]`; with `perf record`
//! for a profile). `flight`: a bouncing case instead (flights and impacts only).
use eccjump_core::mechanics::Rule;
use eccjump_core::modes::contact::ContactLaw;
use eccjump_core::motion::{simulate, SimOptions};
use eccjump_core::ode::{Integrator, SolverOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;
fn main() {
    let method = match std::env::args().nth(1).as_deref() {
        Some("dop853") => Integrator::Dop853,
        _ => Integrator::Rk45,
    };
    // The bouncing case of benches/scipy_motion_cases.py (flies at once, e = 0.5).
    let flight = std::env::args().nth(2).as_deref() == Some("flight");
    let (km, alpha, omega0, e) = if flight {
        (0.2, 20.0, 2.0, 0.5)
    } else {
        (0.4, 30.0, 0.0, 0.0)
    };
    let r = Ramp::new(Cylinder::new(0.5, km).unwrap(), f64::to_radians(alpha)).unwrap();
    let o = SimOptions {
        omega0,
        restitution: e,
        solver: SolverOptions {
            method,
            ..SimOptions::default().solver
        },
        law: ContactLaw {
            mu_s: 1.0,
            mu_k: 1.0,
            rule: Rule::Paper,
        },
        max_transitions: 5,
        ..SimOptions::default()
    };
    let mut best = f64::INFINITY;
    let mut s = 0.0;
    for _ in 0..30 {
        let t0 = Instant::now();
        for _ in 0..1000 {
            s += simulate(&r, &o).unwrap().points.len() as f64;
        }
        best = best.min(t0.elapsed().as_secs_f64() / 1000.0 * 1e6);
    }
    println!("{method:?}: best {best:.2} us per run ({s})");
}

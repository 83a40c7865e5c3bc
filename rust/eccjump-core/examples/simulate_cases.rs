//! Profiling aid: the best time per `simulate` run of each of the 20 cases of
//! `benches/scipy_motion_cases.py`, cut to 5 transitions as `benches/bench_simulate.py` runs
//! them (`cargo run --release -p eccjump-core --features profiling --example simulate_cases [rk45|dop853]
//! [rounds]`; with `perf record` for a profile of the whole set).
use eccjump_core::mechanics::Rule;
use eccjump_core::modes::contact::ContactLaw;
use eccjump_core::motion::{simulate, SimOptions};
use eccjump_core::ode::{Integrator, SolverOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;

/// (name, χ, k_m, α°, μ_s, μ_k (NaN: μ_s), e, rule, θ0°, θ̇0, slip0).
type Case = (
    &'static str,
    f64,
    f64,
    f64,
    f64,
    f64,
    f64,
    Rule,
    f64,
    f64,
    f64,
);

const N: f64 = f64::NAN;
const P: Rule = Rule::Paper;
const F: Rule = Rule::NormalForce;

#[rustfmt::skip]
const CASES: [Case; 20] = [
    ("jarm_paper", 0.15, 0.02, 40.0, 1.0, N, 0.0, P, 0.0, 0.0, 0.0),
    ("jarm_normal_force", 0.15, 0.02, 40.0, 1.0, N, 0.0, F, 0.0, 0.0, 0.0),
    ("jarm_e05", 0.15, 0.02, 40.0, 1.0, N, 0.5, P, 0.0, 0.0, 0.0),
    ("jarm_muk05", 0.15, 0.02, 40.0, 1.0, 0.5, 0.0, P, 0.0, 0.0, 0.0),
    ("slipjump_paper", 0.5, 0.4, 30.0, 1.0, N, 0.0, P, 0.0, 0.0, 0.0),
    ("slipjump_normal_force", 0.5, 0.4, 30.0, 1.0, N, 0.0, F, 0.0, 0.0, 0.0),
    ("slipjump_e05", 0.5, 0.4, 30.0, 1.0, N, 0.5, P, 0.0, 0.0, 0.0),
    ("slipjump_e1", 0.5, 0.4, 30.0, 1.0, N, 1.0, P, 0.0, 0.0, 0.0),
    ("slipjump_muk06", 0.5, 0.4, 30.0, 1.0, 0.6, 0.0, P, 0.0, 0.0, 0.0),
    ("low_friction_mu02", 0.5, 0.4, 30.0, 0.2, N, 0.0, P, 0.0, 0.0, 0.0),
    ("slip_at_start_mu01", 0.3, 0.3, 60.0, 0.1, N, 0.0, P, 0.0, 0.0, 0.0),
    ("alpha0_omega15", 0.3, 0.3, 0.0, 1.0, N, 0.0, P, 0.0, 1.5, 0.0),
    ("alpha0_omega15_mu01", 0.3, 0.3, 0.0, 0.1, N, 0.0, P, 0.0, 1.5, 0.0),
    ("flies_at_once", 0.5, 0.2, 20.0, 1.0, N, 0.0, P, 0.0, 2.0, 0.0),
    ("flies_at_once_e05", 0.5, 0.2, 20.0, 1.0, N, 0.5, P, 0.0, 2.0, 0.0),
    ("slip0_forward", 0.3, 0.3, 30.0, 0.5, N, 0.0, P, 0.0, 0.0, 1.0),
    ("slip0_backspin", 0.3, 0.3, 30.0, 0.5, N, 0.0, P, 0.0, 0.0, -2.0),
    ("theta0_90", 0.6, 0.1, 20.0, 1.0, N, 0.0, P, 90.0, 0.0, 0.0),
    ("steep_heavy_point", 0.9, 0.05, 85.0, 1.0, N, 0.0, P, 0.0, 0.0, 0.0),
    ("centred_low_mu", 0.0, 0.5, 30.0, 0.1, N, 0.0, P, 0.0, 0.0, 0.0),
];

fn main() {
    let method = match std::env::args().nth(1).as_deref() {
        Some("dop853") => Integrator::Dop853,
        _ => Integrator::Rk45,
    };
    let rounds: usize = std::env::args()
        .nth(2)
        .map_or(20, |s| s.parse().expect("rounds: a count"));
    let mut total = 0.0;
    for (name, chi, km, alpha, mu_s, mu_k, e, rule, theta0, omega0, slip0) in CASES {
        let r = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha.to_radians()).unwrap();
        let o = SimOptions {
            law: ContactLaw {
                mu_s,
                mu_k: if mu_k.is_nan() { mu_s } else { mu_k },
                rule,
            },
            restitution: e,
            theta0: theta0.to_radians(),
            omega0,
            slip0,
            t_max: 20.0,
            max_transitions: 5,
            solver: SolverOptions {
                method,
                ..SimOptions::default().solver
            },
            ..SimOptions::default()
        };
        let run = simulate(&r, &o).unwrap();
        let mut best = f64::INFINITY;
        for _ in 0..rounds {
            let t0 = Instant::now();
            for _ in 0..200 {
                std::hint::black_box(simulate(&r, &o).unwrap());
            }
            best = best.min(t0.elapsed().as_secs_f64() / 200.0 * 1e6);
        }
        total += best;
        println!(
            "{name:24} {best:7.2} us  ({} points, {} transitions, {} evaluations)",
            run.points.len(),
            run.transitions.len(),
            run.nfev
        );
    }
    println!(
        "{method:?}: mean {:.2} us per run",
        total / CASES.len() as f64
    );
}

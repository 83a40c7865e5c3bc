//! The ODE route on the n³ benchmark-style grid (α = iπ/(2n), i = 1..n; χ = (j+½)/n;
//! frac = l/n), μ_s = 1, automatic n: prints CPU µs per point (one thread) and, with a
//! file name, writes one line per point (reason, n, θ_J, θ_event) for comparisons.
//! `cargo run --release -p eccjump-core --example ode_grid -- 30 out.txt`
//! Optional 3rd and 4th arguments na, den: only α = iπ/den, i = 1..na (e.g. the small
//! angles of the 100³ grid: `-- 10 - 5 200`; "-" writes no file).
use eccjump_core::jarm::{JarmOptions, JarmResult, Reason};
use eccjump_core::region::{classify_grid, Method};
use std::io::Write;

fn cpu_seconds() -> f64 {
    let Ok(stat) = std::fs::read_to_string("/proc/self/stat") else {
        return f64::NAN;
    };
    let rest = stat.rsplit(')').next().unwrap_or("");
    let f: Vec<f64> = rest
        .split_whitespace()
        .skip(11)
        .take(2)
        .map(|x| x.parse().unwrap_or(f64::NAN))
        .collect();
    (f[0] + f[1]) / 100.0
}

fn main() {
    let args: Vec<String> = std::env::args().collect();
    let n: usize = args.get(1).and_then(|s| s.parse().ok()).unwrap_or(20);
    let na: usize = args.get(3).and_then(|s| s.parse().ok()).unwrap_or(n);
    let den: f64 = args
        .get(4)
        .and_then(|s| s.parse().ok())
        .unwrap_or(2.0 * n as f64);
    let a: Vec<f64> = (1..=na)
        .map(|i| std::f64::consts::PI * i as f64 / den)
        .collect();
    let c: Vec<f64> = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
    let f: Vec<f64> = (0..n).map(|i| i as f64 / n as f64).collect();
    let m = Method::Ode {
        rtol: 1e-10,
        atol: 1e-12,
    };
    let o = JarmOptions::default();
    let mut out = vec![JarmResult::new(Reason::NoRoot); na * n * n];
    let cpu = cpu_seconds();
    classify_grid(&a, &c, &f, 1.0, m, &o, 1, &mut out).unwrap();
    let dcpu = cpu_seconds() - cpu;
    let jarm = out.iter().filter(|r| r.is_jarm).count();
    println!(
        "{na}x{n}^2: CPU {:.2} us/point ({jarm} JARM)",
        dcpu / out.len() as f64 * 1e6
    );
    if let Some(path) = args.get(2).filter(|p| *p != "-") {
        let mut w = std::io::BufWriter::new(std::fs::File::create(path).unwrap());
        for r in &out {
            writeln!(
                w,
                "{} {} {:e} {:e}",
                r.reason as u8, r.n, r.theta_j, r.theta_event
            )
            .unwrap();
        }
    }
}

//! Profiling aid for the closed-form JARM route (`cargo run --release -p eccjump-core --features profiling --example closed_cost
//! [points] [grid]`): single-thread cost per point by reason on random points (the
//! distribution of `benches/bench_peers.py`: α ~ U(0, π/2), χ ~ U(10⁻³, 1), k_m = u(1 − χ),
//! μ_s = 1, refined extrema) and on every 5th point of the 100³ grid of `bench_region.py`
//! (extrema not refined), with a digest of every field of every result: an optimisation that
//! changes any bit of any result changes the digest. With `CLOSED_COST_DUMP=prefix`, every
//! field of every result is also written to `prefix.random.f64` and `prefix.grid.f64` (11
//! little-endian f64 per point, in the order of `JarmResult::as_f64s`), to compare two
//! builds point by point.
use eccjump_core::jarm::{classify, JarmOptions, JarmResult};
use std::f64::consts::FRAC_PI_2;
use std::time::Instant;

/// FNV-1a over the bits of every field of a result.
fn mix(h: &mut u64, r: &JarmResult) {
    for w in r.as_f64s().map(f64::to_bits) {
        for b in w.to_le_bytes() {
            *h = (*h ^ b as u64).wrapping_mul(0x100_0000_01b3);
        }
    }
}

/// xorshift64*: a uniform in [0, 1).
fn uniform(s: &mut u64) -> f64 {
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    (s.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
}

fn report(what: &str, pts: &[(f64, f64, f64)], o: &JarmOptions) {
    let mut by_reason = [(0usize, 0f64); 10];
    let mut h = 0xcbf2_9ce4_8422_2325u64;
    let mut dump = vec![];
    let t_all = Instant::now();
    for &(a, c, k) in pts {
        let t0 = Instant::now();
        let r = classify(a, c, k, 1.0, o);
        let dt = t0.elapsed().as_secs_f64();
        by_reason[r.reason as usize].0 += 1;
        by_reason[r.reason as usize].1 += dt;
        mix(&mut h, &r);
        dump.push(r);
    }
    let total = t_all.elapsed().as_secs_f64();
    if let Ok(prefix) = std::env::var("CLOSED_COST_DUMP") {
        let bytes: Vec<u8> = dump
            .iter()
            .flat_map(JarmResult::as_f64s)
            .flat_map(f64::to_le_bytes)
            .collect();
        std::fs::write(format!("{prefix}.{what}.f64"), bytes).unwrap();
    }
    println!(
        "{what}: {} points, {:.3} us/point (1 thread), digest {h:016x}",
        pts.len(),
        total * 1e6 / pts.len() as f64
    );
    for (code, &(n, t)) in by_reason.iter().enumerate() {
        if n > 0 {
            println!(
                "  reason {code}: {n:7} points, {:8.2} us/point, {:5.1} % of the time",
                t * 1e6 / n as f64,
                100.0 * t / total
            );
        }
    }
}

fn main() {
    let args: Vec<usize> = std::env::args()
        .skip(1)
        .map(|a| a.parse().unwrap())
        .collect();
    let n_random = args.first().copied().unwrap_or(100_000);
    let grid_step = args.get(1).copied().unwrap_or(5);
    let mut s = 20_261_123u64;
    let random: Vec<_> = (0..n_random)
        .map(|_| {
            let a = FRAC_PI_2 * uniform(&mut s);
            let c = 1e-3 + (1.0 - 1e-3) * uniform(&mut s);
            (a, c, uniform(&mut s) * (1.0 - c))
        })
        .collect();
    report("random", &random, &JarmOptions::default());
    let n = 100;
    let mut grid = vec![];
    for i in (2..n).step_by(grid_step) {
        for j in (2..n).step_by(grid_step) {
            for l in (2..n).step_by(grid_step) {
                let c = (j as f64 + 0.5) / n as f64;
                let a = FRAC_PI_2 * (i + 1) as f64 / n as f64;
                grid.push((a, c, l as f64 / n as f64 * (1.0 - c)));
            }
        }
    }
    let o = JarmOptions {
        refine_extrema: false,
        ..JarmOptions::default()
    };
    report("grid", &grid, &o);
}

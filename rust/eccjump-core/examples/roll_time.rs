use eccjump_core::roll::{roll, RollOptions};
use eccjump_core::{Cylinder, Rolling};
use std::time::Instant;
fn main() {
    let r = Rolling::new(Cylinder::new(0.15, 0.02).unwrap(), 40f64.to_radians()).unwrap();
    let o = RollOptions::default();
    let n = 20000;
    let t0 = Instant::now();
    let mut s = 0.0;
    for _ in 0..n {
        s += roll(&r, &o).unwrap().theta.last().unwrap();
    }
    println!(
        "{:.2} us per run ({s})",
        t0.elapsed().as_secs_f64() / n as f64 * 1e6
    );
    let mut o2 = o;
    o2.solver.event_samples = 0;
    let t0 = Instant::now();
    for _ in 0..n {
        s += roll(&r, &o2).unwrap().theta.last().unwrap();
    }
    println!(
        "{:.2} us per run without interior samples",
        t0.elapsed().as_secs_f64() / n as f64 * 1e6
    );
}

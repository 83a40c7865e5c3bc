use eccjump_core::modes::rolling::run::{roll, RollOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;
fn main() {
    let r = Ramp::new(Cylinder::new(0.15, 0.02).unwrap(), 40f64.to_radians()).unwrap();
    let o = RollOptions::default();
    let mut best = f64::INFINITY;
    let mut s = 0.0;
    for _ in 0..30 {
        let t0 = Instant::now();
        for _ in 0..1000 {
            s += roll(&r, &o).unwrap().theta.last().unwrap();
        }
        best = best.min(t0.elapsed().as_secs_f64() / 1000.0 * 1e6);
    }
    println!("best {best:.2} us per run ({s})");
}

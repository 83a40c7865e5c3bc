//! Measurement aid for issue 10 (not part of the library): how fast would a Taylor-series
//! integrator of order 16 take pure rolling from rest to the paper's lift-off, against
//! `roll` with Vern7, at equal accuracy? `cargo run --release -p eccjump-core --example
//! taylor_probe [level]` (default level 1e-8 rad): for each case of `benches/bench_peers.py`
//! and each route, the loosest tolerance of the rtol ladder 1e-6 … 1e-12 (half decades) from
//! which on |θ_J − exact| ≤ level, and the best time per run there.
//!
//! The probe's Taylor route is the bare minimum (no record, no event scan but the lift-off
//! at each step's end, no rejected steps): what it measures is the floor of that lever.
//! Its coefficients come from the recurrences of roll-eq, θ̈ (Ĩ_C + 1 + 2χ cos θ) =
//! χθ̇² sin θ + χ sin(α + θ) + sin α, for the Taylor coefficients x_k of θ(t + τ), v_k of
//! θ̇: s, c (sin θ, cos θ) by s_k = (1/k) Σ j x_j c_{k−j}, c_k = −(1/k) Σ j x_j s_{k−j};
//! p = θ̇², q = p s, d = Ĩ_C + 1 + 2χc, a = θ̈ = n/d with n = χq + χ(sin α c + cos α s) + sin α;
//! v_{k+1} = a_k/(k + 1), x_{k+1} = v_k/(k + 1). Before the timed runs, one run per case
//! (tolerance 1e-10) checks a_0 against the core's θ̈ (`Ramp::omega_dot`) at every step;
//! θ_J is checked against the closed form's on every rung (the rule above).
use eccjump_core::modes::rolling::run::{roll, RollOptions};
use eccjump_core::ode::{Method, SolverOptions};
use eccjump_core::{Cylinder, Ramp};
use std::time::Instant;

/// The order: the polynomials have K + 1 coefficients.
const K: usize = 16;

/// log2 |x| within 0.008 (exponent and a quadratic in the mantissa): step sizes only.
fn lg2(x: f64) -> f64 {
    let b = x.to_bits() & 0x7fff_ffff_ffff_ffff;
    let e = ((b >> 52) as i64 - 1023) as f64;
    let m = f64::from_bits((b & 0x000f_ffff_ffff_ffff) | 0x3ff0_0000_0000_0000) - 1.0;
    e + m * (1.3466 - 0.3466 * m)
}

/// 2^y within 0.4 %.
fn ex2(y: f64) -> f64 {
    let n = y.floor();
    let f = y - n;
    f64::from_bits(((n as i64 + 1023) as u64) << 52) * (1.0 + f * (0.6565 + 0.3435 * f))
}

/// The Taylor coefficients of θ and θ̇ at (θ, θ̇), each order's sums with the newest
/// term last so that it alone waits for the previous order (the stages' chain).
struct Series {
    x: [f64; K + 1],
    v: [f64; K + 1],
    s: [f64; K + 1],
    c: [f64; K + 1],
    p: [f64; K + 1],
    a: [f64; K + 1],
    d: [f64; K + 1],
}

impl Series {
    /// Order k of the recurrences: s_k, c_k, d_k, p_k, q_k and a_k, then v_{k+1}, x_{k+1}.
    /// Inlined at each literal k of [`Series::at`], so every loop has a known length.
    #[inline(always)]
    fn order(&mut self, r: &Ramp, id0: f64, k: usize) {
        let chi = r.body.chi;
        if k > 0 {
            let (mut ss, mut cc) = (0.0, 0.0);
            for j in 1..=k {
                // j x_j = v_{j−1}
                ss += self.v[j - 1] * self.c[k - j];
                cc += self.v[j - 1] * self.s[k - j];
            }
            self.s[k] = ss * (1.0 / k as f64);
            self.c[k] = -cc * (1.0 / k as f64);
            self.d[k] = 2.0 * chi * self.c[k];
        }
        let mut pk = 0.0;
        for j in 1..k {
            pk += self.v[j] * self.v[k - j];
        }
        pk = if k == 0 {
            self.v[0] * self.v[0]
        } else {
            pk + 2.0 * self.v[0] * self.v[k]
        };
        self.p[k] = pk;
        let mut q = 0.0;
        for j in 0..k {
            q += self.p[j] * self.s[k - j];
        }
        q += pk * self.s[0];
        let mut da = 0.0;
        for j in 1..=k {
            da += self.d[j] * self.a[k - j];
        }
        let mut n = chi * (r.sin_a * self.c[k] + r.cos_a * self.s[k]) - da;
        if k == 0 {
            n += r.sin_a;
        }
        self.a[k] = (chi * q + n) * id0;
        self.v[k + 1] = self.a[k] * (1.0 / (k + 1) as f64);
        self.x[k + 1] = self.v[k] * (1.0 / (k + 1) as f64);
    }
}

macro_rules! orders {
    ($z:ident, $r:ident, $id0:ident, $($k:literal)*) => {$($z.order($r, $id0, $k);)*};
}

impl Series {
    #[inline(always)]
    fn at(r: &Ramp, theta: f64, omega: f64) -> Series {
        let mut z = Series {
            x: [0.0; K + 1],
            v: [0.0; K + 1],
            s: [0.0; K + 1],
            c: [0.0; K + 1],
            p: [0.0; K + 1],
            a: [0.0; K + 1],
            d: [0.0; K + 1],
        };
        let (s0, c0) = libm::sincos(theta);
        (z.x[0], z.v[0], z.s[0], z.c[0]) = (theta, omega, s0, c0);
        z.d[0] = r.contact_inertia(c0);
        let id0 = 1.0 / z.d[0];
        orders!(z, r, id0, 0 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
        z
    }
}

fn horner(cf: &[f64; K + 1], tau: f64) -> f64 {
    cf.iter().rev().fold(0.0, |acc, &ck| acc * tau + ck)
}

/// θ_J by the Taylor route at tolerance `tol` (Jorba–Zou step size from the last two
/// coefficients), and the number of steps.
fn taylor_run(r: &Ramp, tol: f64, check: bool) -> (f64, usize) {
    let (mut theta, mut omega) = (0.0f64, 0.0f64);
    for steps in 1..100_000 {
        let z = Series::at(r, theta, omega);
        if check {
            let want = r.omega_dot(theta, omega);
            assert!(
                (z.a[0] - want).abs() <= 1e-14 * want.abs().max(1.0),
                "{} {want}",
                z.a[0]
            );
        }
        let ls = lg2(tol * (1.0 + theta.abs().max(omega.abs())));
        let e = ((ls - lg2(z.x[K - 1].abs().max(z.v[K - 1].abs()))) / (K - 1) as f64)
            .min((ls - lg2(z.x[K].abs().max(z.v[K].abs()))) / K as f64);
        let h = 0.9 * ex2(e.min(10.0));
        let lift = |tau: f64| {
            let w = horner(&z.v, tau);
            r.body.chi * w * w * libm::cos(horner(&z.x, tau)) - r.cos_a
        };
        if lift(h) > 0.0 {
            // Illinois on the step's polynomial.
            let (mut lo, mut hi) = (0.0, h);
            let (mut flo, mut fhi) = (lift(lo), lift(hi));
            for _ in 0..100 {
                let m = hi - fhi * (hi - lo) / (fhi - flo);
                let fm = lift(m);
                if fm > 0.0 {
                    (hi, fhi, flo) = (m, fm, 0.5 * flo);
                } else {
                    (lo, flo, fhi) = (m, fm, 0.5 * fhi);
                }
                if hi - lo < 1e-15 || fm == 0.0 {
                    break;
                }
            }
            return (horner(&z.x, hi), steps);
        }
        (theta, omega) = (horner(&z.x, h), horner(&z.v, h));
    }
    (f64::NAN, 100_000)
}

fn best_us(f: impl Fn() -> f64) -> f64 {
    (0..20)
        .map(|_| {
            let t0 = Instant::now();
            for _ in 0..500 {
                std::hint::black_box(f());
            }
            t0.elapsed().as_secs_f64() / 500.0 * 1e6
        })
        .fold(f64::INFINITY, f64::min)
}

fn main() {
    let level: f64 = std::env::args()
        .nth(1)
        .map_or(1e-8, |s| s.parse().expect("level"));
    let ladder: Vec<f64> = (12..25).map(|k| 10f64.powf(-f64::from(k) / 2.0)).collect();
    // (α [deg], χ, k_m, θ_J by the closed form, `eccjump.jarm(α, χ, k_m, 1e9).theta_J`)
    let cases = [
        (40.0, 0.15, 0.02, 5.835400804966944),
        (70.0, 0.1, 0.27, 5.221936155907998),
        (30.0, 0.1, 0.09, 12.155952837538923),
        (10.0, 0.1, 0.54, 50.169283779103274),
    ];
    for (alpha, chi, km, exact) in cases {
        let r = Ramp::new(Cylinder::new(chi, km).unwrap(), f64::to_radians(alpha)).unwrap();
        let vern7 = |rtol: f64| {
            let o = RollOptions {
                solver: SolverOptions {
                    method: Method::Vern7,
                    rtol,
                    atol: rtol / 100.0,
                    ..SolverOptions::default()
                },
                ..RollOptions::default()
            };
            *roll(&r, &o).unwrap().theta.last().unwrap()
        };
        let taylor = |tol: f64| taylor_run(&r, tol, false).0;
        taylor_run(&r, 1e-10, true);
        let mut line = format!("alpha {alpha:>4}:");
        for (name, route) in [
            ("Vern7", &vern7 as &dyn Fn(f64) -> f64),
            ("Taylor16", &taylor),
        ] {
            // the loosest rung from which on every tighter one is within the level
            let k = (0..ladder.len())
                .rev()
                .take_while(|&k| (route(ladder[k]) - exact).abs() <= level)
                .last();
            line += &match k {
                Some(k) => {
                    let us = best_us(|| route(ladder[k]));
                    format!("  {name} {us:6.2} us @{:.1e}", ladder[k])
                }
                None => format!("  {name} not reached"),
            };
            if name == "Taylor16" {
                if let Some(k) = k {
                    line += &format!(" ({} steps)", taylor_run(&r, ladder[k], false).1);
                }
            }
        }
        println!("{line}");
    }
}

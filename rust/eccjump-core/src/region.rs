//! Vectorised, parallel JARM maps: a list of points or a rectangular grid
//! (α, χ, k_m-fraction with k_m = frac·(1 − χ), so the grid is rectangular), written in place
//! into a caller-provided slice of results.
//!
//! Each point is computed independently (no per-point heap allocation, no reduction whose
//! order depends on scheduling), so results are bit-identical for any thread count.

use crate::error::Result;
use crate::jarm::{classify, JarmOptions, JarmResult};
use crate::jarm_ode::classify_ode;
use crate::parallel::{check_len, par_fill};

/// Which route classifies a point.
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub enum Method {
    /// The paper's closed forms with a rigorous path scan (`jarm::classify`).
    #[default]
    ClosedForm,
    /// Integration of the rolling equation with events (`jarm_ode::classify_ode`).
    Ode { rtol: f64, atol: f64 },
}

/// Classifies one point by the chosen route.
#[inline]
pub fn classify_with(
    method: Method,
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    opts: &JarmOptions,
) -> JarmResult {
    match method {
        Method::ClosedForm => classify(alpha, chi, km, mu_s, opts),
        Method::Ode { rtol, atol } => classify_ode(alpha, chi, km, mu_s, opts, rtol, atol),
    }
}

/// Classifies a list of points (α_i, χ_i, k_m,i, μ_s,i); all inputs have the length of
/// `out` (μ_s may also have length 1: one value for all).
#[allow(clippy::too_many_arguments)] // the four coordinates, the route, options, threads, out
pub fn classify_points(
    alpha: &[f64],
    chi: &[f64],
    km: &[f64],
    mu_s: &[f64],
    method: Method,
    opts: &JarmOptions,
    n_threads: usize,
    out: &mut [JarmResult],
) -> Result<()> {
    let total = out.len();
    check_len("alpha", alpha.len(), total)?;
    check_len("chi", chi.len(), total)?;
    check_len("km", km.len(), total)?;
    if mu_s.len() != 1 {
        check_len("mu_s", mu_s.len(), total)?;
    }
    par_fill(out, n_threads, |g| {
        let m = if mu_s.len() == 1 { mu_s[0] } else { mu_s[g] };
        classify_with(method, alpha[g], chi[g], km[g], m, opts)
    })
}

/// Classifies the grid alpha × chi × frac (C order: α slowest, frac fastest), with
/// k_m = frac·(1 − χ); `out` has length alpha.len()·chi.len()·frac.len().
#[allow(clippy::too_many_arguments)] // the three axes, μ_s, the route, options, threads, out
pub fn classify_grid(
    alpha: &[f64],
    chi: &[f64],
    frac: &[f64],
    mu_s: f64,
    method: Method,
    opts: &JarmOptions,
    n_threads: usize,
    out: &mut [JarmResult],
) -> Result<()> {
    let (nc, nf) = (chi.len(), frac.len());
    check_len("out", out.len(), alpha.len() * nc * nf)?;
    par_fill(out, n_threads, |g| {
        let (ia, rest) = (g / (nc * nf), g % (nc * nf));
        let (ic, jf) = (rest / nf, rest % nf);
        let x = chi[ic];
        classify_with(method, alpha[ia], x, frac[jf] * (1.0 - x), mu_s, opts)
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::jarm::Reason;
    use std::f64::consts::FRAC_PI_2;

    fn grid(n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let a = (1..=n).map(|i| FRAC_PI_2 * i as f64 / n as f64).collect();
        let c = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
        let f = (0..n).map(|i| i as f64 / n as f64).collect();
        (a, c, f)
    }

    fn run(n_threads: usize, a: &[f64], c: &[f64], f: &[f64]) -> Vec<JarmResult> {
        let mut out = vec![JarmResult::new(Reason::NoRoot); a.len() * c.len() * f.len()];
        let o = JarmOptions::default();
        classify_grid(a, c, f, 1.0, Method::ClosedForm, &o, n_threads, &mut out).unwrap();
        out
    }

    fn bits(v: &[JarmResult]) -> Vec<(u8, u64, u64, u64)> {
        v.iter()
            .map(|r| {
                let b = (
                    r.theta_j.to_bits(),
                    r.max_ratio.to_bits(),
                    r.min_fy.to_bits(),
                );
                (r.reason as u8, b.0, b.1, b.2)
            })
            .collect()
    }

    #[test]
    fn bit_identical_for_any_thread_count_and_matches_single_points() {
        let (a, c, f) = grid(14);
        let r1 = run(1, &a, &c, &f);
        for nt in [2, 3, 0] {
            assert_eq!(bits(&run(nt, &a, &c, &f)), bits(&r1));
        }
        // Same as classify on each point, and as classify_points.
        let o = JarmOptions::default();
        let (mut pa, mut pc, mut pk) = (vec![], vec![], vec![]);
        for &x in &a {
            for &y in &c {
                for &z in &f {
                    pa.push(x);
                    pc.push(y);
                    pk.push(z * (1.0 - y));
                }
            }
        }
        for (k, r) in r1.iter().enumerate() {
            assert_eq!(classify(pa[k], pc[k], pk[k], 1.0, &o).reason, r.reason);
        }
        let mut out = vec![JarmResult::new(Reason::NoRoot); pa.len()];
        classify_points(&pa, &pc, &pk, &[1.0], Method::ClosedForm, &o, 2, &mut out).unwrap();
        assert_eq!(bits(&out), bits(&r1));
        // Wrong lengths are errors.
        let mut short = vec![JarmResult::new(Reason::NoRoot); 3];
        let m = Method::ClosedForm;
        assert!(classify_grid(&a, &c, &f, 1.0, m, &o, 1, &mut short).is_err());
        assert!(classify_points(&pa, &pc, &pk[1..], &[1.0], m, &o, 1, &mut out).is_err());
    }

    /// The performance target: run with
    /// `cargo test --release -p eccjump-core region::tests::timing -- --ignored --nocapture`.
    #[test]
    #[ignore]
    fn timing() {
        let (a, c, f) = grid(100);
        let o = JarmOptions {
            refine_extrema: false,
            ..Default::default()
        };
        let mut out = vec![JarmResult::new(Reason::NoRoot); 1_000_000];
        for nt in [1, 2] {
            let t = std::time::Instant::now();
            classify_grid(&a, &c, &f, 1.0, Method::ClosedForm, &o, nt, &mut out).unwrap();
            let dt = t.elapsed().as_secs_f64();
            let jarm = out.iter().filter(|r| r.is_jarm).count();
            println!(
                "{nt} thread(s): {dt:.3} s for 1e6 points ({:.2} us/point/core), {jarm} JARM",
                dt * nt as f64
            );
        }
    }
}

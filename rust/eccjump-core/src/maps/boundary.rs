//! Boundaries of the JARM region: for fixed (χ, k_m, μ_s, n) the α-intervals where the point
//! is a JARM (coarse scan in α, then bisection of each transition on the classification to
//! 1e-12), and for fixed (α, χ, k_m) the smallest μ_s that gives a JARM. Parallel over many
//! (χ, k_m) with a local rayon pool; each entry is computed independently (bit-identical for
//! any thread count).

use crate::error::{check_count, check_range, try_filled, Error, Result};
use crate::jarm::decision::point_ramp;
use crate::jarm::{classify, JarmOptions, Rule};
use crate::maps::parallel::{check_len, par_fill_until};
use std::f64::consts::FRAC_PI_2;

/// Bisection tolerance on α and (relative) on μ_s.
pub const TOL: f64 = 1e-12;

/// The largest scan of [`alpha_intervals`] (each sample is a classification).
pub const MAX_SCAN: usize = 100_000;

/// The whole-call checks of the α-interval searches: each body valid (an error names the
/// index), μ_s ≥ 0 finite, the options valid.
fn check_bodies(chi: &[f64], km: &[f64], mu_s: f64, o: &JarmOptions) -> Result<()> {
    check_len("km", km.len(), chi.len())?;
    check_range("mu_s", mu_s, 0.0, f64::MAX)?;
    o.validate()?;
    for (i, (&c, &k)) in chi.iter().zip(km).enumerate() {
        crate::mechanics::Cylinder::new(c, k).map_err(|e| Error::AtIndex {
            index: i,
            source: Box::new(e),
        })?;
    }
    Ok(())
}

/// The classification options of the boundary searches: from rest, the given rule and turn
/// (0: the first jump), the default turn cap, no refinement of the extrema and no
/// continuation past a slip (`is_jarm`, all a boundary needs, depends on neither).
pub fn boundary_options(rule: Rule, n: u32) -> JarmOptions {
    JarmOptions {
        rule,
        n,
        refine_extrema: false,
        stop_at_slip: true,
        ..JarmOptions::default()
    }
}

fn is_jarm(alpha: f64, chi: f64, km: f64, mu_s: f64, o: &JarmOptions) -> bool {
    classify(alpha, chi, km, mu_s, o).is_jarm
}

/// Bisects a transition of `f` between a (value fa) and b (value !fa) until |b − a| ≤
/// `tol(b)`.
fn bisect_bool(
    f: impl Fn(f64) -> bool,
    mut a: f64,
    mut b: f64,
    fa: bool,
    tol: impl Fn(f64) -> f64,
) -> (f64, f64) {
    while (b - a).abs() > tol(b) {
        let m = 0.5 * (a + b);
        if m == a || m == b {
            break;
        }
        if f(m) == fa {
            a = m;
        } else {
            b = m;
        }
    }
    (a, b)
}

/// The α-intervals [α_min, α_max] ⊂ (0, π/2] where (χ, k_m, μ_s) is a JARM under `o` (set
/// `o.n` for a given turn). `n_scan` coarse samples (≥ 2); intervals narrower than the scan
/// step can be missed. Each end is the JARM side of a bisection to 1e-12.
pub fn alpha_intervals(
    chi: f64,
    km: f64,
    mu_s: f64,
    o: &JarmOptions,
    n_scan: usize,
) -> Vec<(f64, f64)> {
    let n = n_scan.max(2);
    let f = |a: f64| is_jarm(a, chi, km, mu_s, o);
    let mut out = Vec::new();
    let mut prev_a = FRAC_PI_2 / n as f64;
    let mut prev = f(prev_a);
    let mut lo = if prev { Some(prev_a) } else { None };
    for i in 2..=n {
        let a = FRAC_PI_2 * i as f64 / n as f64;
        let cur = f(a);
        if cur != prev {
            let (x, y) = bisect_bool(f, prev_a, a, prev, |_| TOL);
            if cur {
                lo = Some(y);
            } else if let Some(l) = lo.take() {
                out.push((l, x));
            }
        }
        prev = cur;
        prev_a = a;
    }
    if let Some(l) = lo {
        out.push((l, FRAC_PI_2));
    }
    out
}

/// The ends of the JARM α-interval that holds `seed` (a JARM angle) for the body (χ, k_m):
/// step outwards from `seed` by `step`, doubling it, to a non-JARM angle (an end of
/// [0, π/2] that is still a JARM is the interval's end), then bisect each transition to
/// [`TOL`]. (NaN, NaN) if `seed` is not a JARM, or an end is not found in 60 doublings.
/// Finds the thin parts of a region that a coarse scan in α misses.
pub fn alpha_interval_around(
    chi: f64,
    km: f64,
    mu_s: f64,
    o: &JarmOptions,
    seed: f64,
    step: f64,
) -> (f64, f64) {
    let f = |a: f64| is_jarm(a, chi, km, mu_s, o);
    if !(seed.is_finite() && step > 0.0 && f(seed)) {
        return (f64::NAN, f64::NAN);
    }
    let end = |dir: f64, edge: f64| {
        let (mut inner, mut d) = (seed, step);
        for _ in 0..60 {
            let trial = (inner + dir * d).clamp(0.0, FRAC_PI_2);
            if !f(trial) {
                // The JARM side of the transition.
                return bisect_bool(f, inner, trial, true, |_| TOL).0;
            }
            if trial == edge {
                return edge;
            }
            inner = trial;
            d *= 2.0;
        }
        f64::NAN
    };
    (end(-1.0, 0.0), end(1.0, FRAC_PI_2))
}

/// The smallest μ_s that gives a JARM at (α, χ, k_m) (bisection on μ_s, relative 1e-12):
/// +∞ if none up to 1e6. By monotonicity in μ_s (tested in `jarm`), every larger μ_s is one.
pub fn mu_s_min_path(alpha: f64, chi: f64, km: f64, o: &JarmOptions) -> f64 {
    // An invalid point has no μ_s,min: NaN, not "never a JARM" (+∞).
    if point_ramp(alpha, chi, km, 0.0, o).is_none() {
        return f64::NAN;
    }
    let f = |m: f64| is_jarm(alpha, chi, km, m, o);
    if f(0.0) {
        return 0.0;
    }
    let mut hi = 1.0;
    while !f(hi) {
        hi *= 2.0;
        if hi > 1e6 {
            return f64::INFINITY;
        }
    }
    let lo = if hi > 1.0 { 0.5 * hi } else { 0.0 };
    bisect_bool(f, lo, hi, false, |hi| TOL * hi).1
}

/// For many (χ_i, k_m,i): all α-intervals of JARM, each end to 1e-12 (in parallel,
/// bit-identical for any thread count).
pub fn alpha_intervals_many(
    chi: &[f64],
    km: &[f64],
    mu_s: f64,
    o: &JarmOptions,
    n_scan: usize,
    n_threads: usize,
    stop: &dyn Fn() -> bool,
) -> Result<Vec<Vec<(f64, f64)>>> {
    check_bodies(chi, km, mu_s, o)?;
    check_count("n_scan", n_scan, 2, MAX_SCAN)?;
    let mut out = try_filled("the intervals", chi.len(), Vec::new())?;
    par_fill_until(
        &mut out,
        n_threads,
        |i| alpha_intervals(chi[i], km[i], mu_s, o, n_scan),
        stop,
    )?;
    Ok(out)
}

/// For many (seed_i, χ_i, k_m,i): [`alpha_interval_around`] into `out` (in parallel).
#[allow(clippy::too_many_arguments)] // three coordinates, μ_s, options, step, threads, out
pub fn alpha_interval_around_many(
    seed: &[f64],
    chi: &[f64],
    km: &[f64],
    mu_s: f64,
    o: &JarmOptions,
    step: f64,
    n_threads: usize,
    out: &mut [(f64, f64)],
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    let n = out.len();
    check_len("seed", seed.len(), n)?;
    check_len("chi", chi.len(), n)?;
    check_bodies(chi, km, mu_s, o)?;
    check_range("step", step, f64::MIN_POSITIVE, std::f64::consts::FRAC_PI_2)?;
    par_fill_until(
        out,
        n_threads,
        |i| alpha_interval_around(chi[i], km[i], mu_s, o, seed[i], step),
        stop,
    )
}

/// For many (α_i, χ_i, k_m,i): μ_s,min along the path into `out` (NaN for an invalid point).
pub fn mu_s_min_path_many(
    alpha: &[f64],
    chi: &[f64],
    km: &[f64],
    o: &JarmOptions,
    n_threads: usize,
    out: &mut [f64],
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    let n = out.len();
    check_len("alpha", alpha.len(), n)?;
    check_len("chi", chi.len(), n)?;
    check_len("km", km.len(), n)?;
    o.validate()?;
    par_fill_until(
        out,
        n_threads,
        |i| mu_s_min_path(alpha[i], chi[i], km[i], o),
        stop,
    )
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn interval_around_a_seed_is_the_scanned_interval() {
        let o = boundary_options(Rule::Paper, 0);
        let (chi, km, mu_s) = (0.15, 0.02, 1.0);
        let scanned = alpha_intervals(chi, km, mu_s, &o, 180);
        assert!(!scanned.is_empty());
        for &(lo, hi) in &scanned {
            let (a, b) = alpha_interval_around(chi, km, mu_s, &o, 0.5 * (lo + hi), 1e-3);
            assert!(
                (a - lo).abs() < 1e-11 && (b - hi).abs() < 1e-11,
                "{a} {lo} {b} {hi}"
            );
        }
        let (a, b) = alpha_interval_around(chi, km, mu_s, &o, 0.01, 1e-3);
        assert!(a.is_nan() && b.is_nan());
    }

    #[test]
    fn alpha_interval_agrees_with_dense_scan() {
        let o = JarmOptions {
            n: 1,
            refine_extrema: false,
            ..Default::default()
        };
        let (chi, km, mu) = (0.15, 0.02, 1.0);
        let v = alpha_intervals(chi, km, mu, &o, 90);
        assert!(!v.is_empty());
        // 40° is inside.
        assert!(
            v.iter()
                .any(|&(a, b)| a < 40f64.to_radians() && 40f64.to_radians() < b),
            "{v:?}"
        );
        for &(a, b) in &v {
            assert!(is_jarm(a, chi, km, mu, &o) && is_jarm(b, chi, km, mu, &o));
            if a > FRAC_PI_2 / 90.0 {
                assert!(!is_jarm(a - 2e-12, chi, km, mu, &o));
            }
            if b < FRAC_PI_2 {
                assert!(!is_jarm(b + 2e-12, chi, km, mu, &o));
            }
        }
        // Dense scan: every JARM sample lies in an interval, every other one outside.
        for i in 1..=3000 {
            let a = FRAC_PI_2 * i as f64 / 3000.0;
            let inside = v.iter().any(|&(l, h)| l <= a && a <= h);
            assert_eq!(inside, is_jarm(a, chi, km, mu, &o), "{a}");
        }
        // Parallel, bit-identical.
        let chis = [0.15, 0.1, 0.2, 0.05];
        let kms = [0.02, 0.1, 0.0, 0.3];
        let v1 = alpha_intervals_many(&chis, &kms, mu, &o, 90, 1, &|| false).unwrap();
        let v2 = alpha_intervals_many(&chis, &kms, mu, &o, 90, 2, &|| false).unwrap();
        let bits = |v: &Vec<Vec<(f64, f64)>>| -> Vec<(u64, u64)> {
            v.iter()
                .flatten()
                .map(|&(a, b)| (a.to_bits(), b.to_bits()))
                .collect()
        };
        assert_eq!(bits(&v1), bits(&v2));
        assert_eq!(v1[0][0].0.to_bits(), v[0].0.to_bits());
    }

    #[test]
    fn mu_s_min_along_the_path() {
        let o = JarmOptions::default();
        let (a, chi, km) = (40f64.to_radians(), 0.15, 0.02);
        let m = mu_s_min_path(a, chi, km, &o);
        assert!(m < 1.0);
        assert!(is_jarm(a, chi, km, m, &o));
        assert!(!is_jarm(a, chi, km, m * (1.0 - 1e-9), &o));
        // Paper rule: it is the largest friction ratio on the path up to θ_J (incl. μ(θ_J)).
        let r = classify(a, chi, km, 10.0, &o);
        assert!((r.max_ratio - m).abs() < 1e-9 * m, "{} {m}", r.max_ratio);
        let mut out = [0.0];
        mu_s_min_path_many(&[a], &[chi], &[km], &o, 2, &mut out, &|| false).unwrap();
        assert_eq!(out[0].to_bits(), m.to_bits());
    }
}

#[cfg(test)]
mod validation_tests {
    use super::*;

    #[test]
    fn invalid_input_is_an_error_or_nan_never_an_answer() {
        let o = boundary_options(Rule::Paper, 0);
        // A body out of range is an error naming it and its index (was: "never a JARM").
        let e = alpha_intervals_many(&[0.1, 2.0], &[0.02, 0.02], 1.0, &o, 180, 1, &|| false);
        let msg = e.unwrap_err().to_string();
        assert!(
            msg.starts_with("chi = 2 ") && msg.ends_with("(at index 1)"),
            "{msg}"
        );
        assert!(alpha_intervals_many(&[0.1], &[0.02], f64::NAN, &o, 180, 1, &|| false).is_err());
        assert!(
            alpha_intervals_many(&[0.1], &[0.02], 1.0, &o, MAX_SCAN + 1, 1, &|| false).is_err()
        );
        // μ_s,min of an invalid point is NaN (was +∞).
        assert!(mu_s_min_path(f64::NAN, 0.15, 0.02, &o).is_nan());
        assert!(mu_s_min_path(0.7, 0.15, 0.02, &o).is_finite());
    }
}

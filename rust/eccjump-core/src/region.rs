//! Vectorised, parallel JARM maps: a list of points (structure of arrays) or a rectangular
//! grid (α, χ, k_m-fraction with k_m = frac·(1 − χ)), written in place into caller-provided
//! output slices. Each point is computed independently with no heap allocation, so the
//! results are bit-identical for any thread count.

use crate::error::{Error, Result};
use crate::jarm::{classify, JarmOptions, JarmResult};
use rayon::prelude::*;

/// Output slices, one entry per point; every field is optional (None = not wanted).
#[derive(Debug, Default)]
pub struct RegionOut<'a> {
    pub is_jarm: Option<&'a mut [bool]>,
    pub reason: Option<&'a mut [u8]>,
    pub n: Option<&'a mut [u32]>,
    pub theta_j: Option<&'a mut [f64]>,
    pub theta_event: Option<&'a mut [f64]>,
    pub max_ratio: Option<&'a mut [f64]>,
    pub min_fy: Option<&'a mut [f64]>,
}

const CHUNK: usize = 256;

/// One chunk of the outputs.
#[derive(Default)]
struct Chunk<'a> {
    start: usize,
    len: usize,
    is_jarm: Option<&'a mut [bool]>,
    reason: Option<&'a mut [u8]>,
    n: Option<&'a mut [u32]>,
    theta_j: Option<&'a mut [f64]>,
    theta_event: Option<&'a mut [f64]>,
    max_ratio: Option<&'a mut [f64]>,
    min_fy: Option<&'a mut [f64]>,
}

impl Chunk<'_> {
    #[inline]
    fn put(&mut self, i: usize, r: &JarmResult) {
        if let Some(s) = self.is_jarm.as_deref_mut() {
            s[i] = r.is_jarm;
        }
        if let Some(s) = self.reason.as_deref_mut() {
            s[i] = r.reason as u8;
        }
        if let Some(s) = self.n.as_deref_mut() {
            s[i] = r.n;
        }
        if let Some(s) = self.theta_j.as_deref_mut() {
            s[i] = r.theta_j;
        }
        if let Some(s) = self.theta_event.as_deref_mut() {
            s[i] = r.theta_event;
        }
        if let Some(s) = self.max_ratio.as_deref_mut() {
            s[i] = r.max_ratio;
        }
        if let Some(s) = self.min_fy.as_deref_mut() {
            s[i] = r.min_fy;
        }
    }
}

fn check_len(name: &'static str, got: usize, want: usize) -> Result<()> {
    if got == want {
        Ok(())
    } else {
        Err(Error::InvalidParameter {
            name,
            value: got as f64,
            allowed: format!("length {want}"),
        })
    }
}

fn split<T>(s: Option<&mut [T]>, total: usize) -> Vec<Option<&mut [T]>> {
    let nch = total.div_ceil(CHUNK);
    match s {
        Some(s) => s.chunks_mut(CHUNK).map(Some).collect(),
        None => (0..nch).map(|_| None).collect(),
    }
}

/// Splits the outputs into chunks (one allocation per call, none per point).
fn chunks<'a>(out: RegionOut<'a>, total: usize) -> Result<Vec<Chunk<'a>>> {
    macro_rules! len {
        ($f:ident) => {
            if let Some(s) = out.$f.as_deref() {
                check_len(stringify!($f), s.len(), total)?;
            }
        };
    }
    len!(is_jarm);
    len!(reason);
    len!(n);
    len!(theta_j);
    len!(theta_event);
    len!(max_ratio);
    len!(min_fy);
    let nch = total.div_ceil(CHUNK);
    let mut a = split(out.is_jarm, total).into_iter();
    let mut b = split(out.reason, total).into_iter();
    let mut c = split(out.n, total).into_iter();
    let mut d = split(out.theta_j, total).into_iter();
    let mut e = split(out.theta_event, total).into_iter();
    let mut f = split(out.max_ratio, total).into_iter();
    let mut g = split(out.min_fy, total).into_iter();
    let mut v = Vec::with_capacity(nch);
    for k in 0..nch {
        let start = k * CHUNK;
        v.push(Chunk {
            start,
            len: CHUNK.min(total - start),
            is_jarm: a.next().flatten(),
            reason: b.next().flatten(),
            n: c.next().flatten(),
            theta_j: d.next().flatten(),
            theta_event: e.next().flatten(),
            max_ratio: f.next().flatten(),
            min_fy: g.next().flatten(),
        });
    }
    Ok(v)
}

/// Runs `f` in a local pool of `n_threads` threads (0 = all cores).
fn in_pool<F: FnOnce() + Send>(n_threads: usize, f: F) -> Result<()> {
    let pool = rayon::ThreadPoolBuilder::new()
        .num_threads(n_threads)
        .build()
        .map_err(|_| Error::InvalidParameter {
            name: "n_threads",
            value: n_threads as f64,
            allowed: "a thread count the system can start".to_string(),
        })?;
    pool.install(f);
    Ok(())
}

/// Classifies a list of points (α_i, χ_i, k_m,i, μ_s,i); all input slices have the same
/// length (μ_s may also have length 1: one value for all).
pub fn classify_points(
    alpha: &[f64],
    chi: &[f64],
    km: &[f64],
    mu_s: &[f64],
    opts: &JarmOptions,
    n_threads: usize,
    out: RegionOut<'_>,
) -> Result<()> {
    let total = alpha.len();
    check_len("chi", chi.len(), total)?;
    check_len("km", km.len(), total)?;
    if mu_s.len() != 1 {
        check_len("mu_s", mu_s.len(), total)?;
    }
    let cs = chunks(out, total)?;
    let o = *opts;
    in_pool(n_threads, move || {
        cs.into_par_iter().for_each(|mut ch| {
            for i in 0..ch.len {
                let g = ch.start + i;
                let m = if mu_s.len() == 1 { mu_s[0] } else { mu_s[g] };
                let r = classify(alpha[g], chi[g], km[g], m, &o);
                ch.put(i, &r);
            }
        });
    })
}

/// Classifies the grid alpha × chi × frac (C order: α slowest, frac fastest), with
/// k_m = frac·(1 − χ). Output slices have length alpha.len()·chi.len()·frac.len().
pub fn classify_grid(
    alpha: &[f64],
    chi: &[f64],
    frac: &[f64],
    mu_s: f64,
    opts: &JarmOptions,
    n_threads: usize,
    out: RegionOut<'_>,
) -> Result<()> {
    let (nc, nf) = (chi.len(), frac.len());
    let total = alpha.len() * nc * nf;
    let cs = chunks(out, total)?;
    let o = *opts;
    in_pool(n_threads, move || {
        cs.into_par_iter().for_each(|mut ch| {
            for i in 0..ch.len {
                let g = ch.start + i;
                let (ia, rest) = (g / (nc * nf), g % (nc * nf));
                let (ic, jf) = (rest / nf, rest % nf);
                let x = chi[ic];
                let r = classify(alpha[ia], x, frac[jf] * (1.0 - x), mu_s, &o);
                ch.put(i, &r);
            }
        });
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::FRAC_PI_2;

    fn grid(n: usize) -> (Vec<f64>, Vec<f64>, Vec<f64>) {
        let a = (1..=n).map(|i| FRAC_PI_2 * i as f64 / n as f64).collect();
        let c = (0..n).map(|i| (i as f64 + 0.5) / n as f64).collect();
        let f = (0..n).map(|i| i as f64 / n as f64).collect();
        (a, c, f)
    }

    fn run(n_threads: usize, a: &[f64], c: &[f64], f: &[f64]) -> (Vec<u8>, Vec<f64>, Vec<f64>) {
        let total = a.len() * c.len() * f.len();
        let (mut reason, mut th, mut mr) = (vec![0u8; total], vec![0.0; total], vec![0.0; total]);
        let out = RegionOut {
            reason: Some(&mut reason),
            theta_j: Some(&mut th),
            max_ratio: Some(&mut mr),
            ..Default::default()
        };
        classify_grid(a, c, f, 1.0, &JarmOptions::default(), n_threads, out).unwrap();
        (reason, th, mr)
    }

    #[test]
    fn bit_identical_for_any_thread_count_and_matches_single_points() {
        let (a, c, f) = grid(14);
        let r1 = run(1, &a, &c, &f);
        for nt in [2, 3, 0] {
            let r = run(nt, &a, &c, &f);
            assert_eq!(r.0, r1.0);
            let bits = |v: &Vec<f64>| v.iter().map(|x| x.to_bits()).collect::<Vec<_>>();
            assert_eq!(bits(&r.1), bits(&r1.1));
            assert_eq!(bits(&r.2), bits(&r1.2));
        }
        // Same as classify on each point, and as classify_points.
        let o = JarmOptions::default();
        let mut k = 0;
        let (mut pa, mut pc, mut pk) = (vec![], vec![], vec![]);
        for &x in &a {
            for &y in &c {
                for &z in &f {
                    let r = classify(x, y, z * (1.0 - y), 1.0, &o);
                    assert_eq!(r.reason as u8, r1.0[k]);
                    k += 1;
                    pa.push(x);
                    pc.push(y);
                    pk.push(z * (1.0 - y));
                }
            }
        }
        let mut reason = vec![0u8; k];
        let out = RegionOut {
            reason: Some(&mut reason),
            ..Default::default()
        };
        classify_points(&pa, &pc, &pk, &[1.0], &o, 2, out).unwrap();
        assert_eq!(reason, r1.0);
        // Wrong lengths are errors.
        let mut short = vec![0u8; 3];
        let out = RegionOut {
            reason: Some(&mut short),
            ..Default::default()
        };
        assert!(classify_grid(&a, &c, &f, 1.0, &o, 1, out).is_err());
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
        for nt in [1, 2] {
            let total = 1_000_000;
            let mut reason = vec![0u8; total];
            let t = std::time::Instant::now();
            let out = RegionOut {
                reason: Some(&mut reason),
                ..Default::default()
            };
            classify_grid(&a, &c, &f, 1.0, &o, nt, out).unwrap();
            let dt = t.elapsed().as_secs_f64();
            let jarm = reason.iter().filter(|&&r| r == 0).count();
            println!(
                "{nt} thread(s): {dt:.3} s for 1e6 points ({:.2} us/point/core), {jarm} JARM",
                dt * nt as f64
            );
        }
    }
}

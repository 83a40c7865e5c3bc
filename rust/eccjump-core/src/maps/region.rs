//! Vectorised, parallel JARM maps: a list of points or a rectangular grid
//! (α, χ, k_m-fraction with k_m = frac·(1 − χ), so the grid is rectangular), written in place
//! into caller-provided result columns ([`JarmColumns`]).
//!
//! Each point is computed independently (no per-point heap allocation, no reduction whose
//! order depends on scheduling), so results are bit-identical for any thread count.

use crate::error::Result;
use crate::jarm::{classify_many, JarmOptions, JarmResult, Method, Reason};
use crate::maps::columns::JarmColumns;
use crate::maps::parallel::{check_len, par_pieces_until, MAX_PIECE, PIECE};

/// Classifies a list of points (α_i, χ_i, k_m,i, μ_s,i, n_i); all inputs have the length of
/// `out` (μ_s and n may also have length 1: one value for all; n = 0 is the first jump,
/// whatever its turn, and overrides `opts.n`). Whole-call options are checked first.
/// Interrupted (`stop`), the points not reached keep what `out` held.
#[allow(clippy::too_many_arguments)] // the five coordinates, the route, options, threads, out
pub fn classify_points(
    alpha: &[f64],
    chi: &[f64],
    km: &[f64],
    mu_s: &[f64],
    n: &[u32],
    method: Method,
    opts: &JarmOptions,
    n_threads: usize,
    out: &mut JarmColumns,
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    let total = out.len();
    check_len("alpha", alpha.len(), total)?;
    check_len("chi", chi.len(), total)?;
    check_len("km", km.len(), total)?;
    if mu_s.len() != 1 {
        check_len("mu_s", mu_s.len(), total)?;
    }
    if n.len() != 1 {
        check_len("n", n.len(), total)?;
    }
    opts.validate()?;
    method.validate()?;
    let point = |g: usize| {
        let m = if mu_s.len() == 1 { mu_s[0] } else { mu_s[g] };
        let o = JarmOptions {
            n: if n.len() == 1 { n[0] } else { n[g] },
            ..*opts
        };
        (alpha[g], chi[g], km[g], m, o)
    };
    fill(method, out, n_threads, point, stop)
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
    out: &mut JarmColumns,
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    let (nc, nf) = (chi.len(), frac.len());
    check_len("out", out.len(), grid_size(alpha.len(), nc, nf)?)?;
    // μ_s is one value for the whole grid: an invalid one is an error, not a map of
    // INVALID_PARAMS points.
    crate::error::check_range("mu_s", mu_s, 0.0, f64::MAX)?;
    opts.validate()?;
    method.validate()?;
    let point = |g: usize| {
        let (ia, rest) = (g / (nc * nf), g % (nc * nf));
        let (ic, jf) = (rest / nf, rest % nf);
        let x = chi[ic];
        (alpha[ia], x, frac[jf] * (1.0 - x), mu_s, *opts)
    };
    fill(method, out, n_threads, point, stop)
}

/// Point g of `out` = the classification of `point(g)`, in parallel by pieces: small ones
/// for the closed form (its points take microseconds; small pieces keep the threads
/// balanced), pieces integrated side by side for the ODE route ([`classify_many`]); the same
/// bits either way.
fn fill(
    method: Method,
    out: &mut JarmColumns,
    n_threads: usize,
    point: impl Fn(usize) -> (f64, f64, f64, f64, JarmOptions) + Sync,
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    match method {
        Method::ClosedForm => fill_by::<MAX_PIECE>(method, out, n_threads, point, stop),
        Method::Ode { .. } => fill_by::<PIECE>(method, out, n_threads, point, stop),
    }
}

/// [`fill`] by pieces of N points, each classified into a buffer of N rows on the thread's
/// stack and then written into the columns.
fn fill_by<const N: usize>(
    method: Method,
    out: &mut JarmColumns,
    n_threads: usize,
    point: impl Fn(usize) -> (f64, f64, f64, f64, JarmOptions) + Sync,
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    par_pieces_until(
        out.pieces_mut(N),
        n_threads,
        |c, mut piece, cancelled| {
            let mut rows = [JarmResult::new(Reason::InvalidParams); N];
            let rows = &mut rows[..piece.len()];
            classify_many(method, |i| point(c * N + i), rows, cancelled);
            piece.put(rows);
        },
        stop,
    )
}

/// The number of points of an `na × nc × nf` grid, or `OutOfMemory` if it overflows.
pub fn grid_size(na: usize, nc: usize, nf: usize) -> Result<usize> {
    na.checked_mul(nc)
        .and_then(|x| x.checked_mul(nf))
        .ok_or(crate::error::Error::OutOfMemory {
            what: "the grid",
            bytes: u64::MAX,
        })
}

//! Parallel maps over independent points, on a local rayon pool, in chunks between which the
//! caller may stop the work (Ctrl-C).
//!
//! Every output element is computed from its index alone and written in place, so results
//! are bit-identical for any thread count and any chunking; the only allocation is the pool.

use crate::error::{check_count, Error, Result};
use rayon::prelude::*;
use std::time::{Duration, Instant};

/// Points handed to one task: small enough to balance uneven per-point costs, large enough
/// to keep scheduling overhead negligible.
const TASK: usize = 256;

/// The largest thread count a map accepts: far above any machine this runs on, and small
/// enough that starting the pool stays cheap (3000 threads took 13 s for one point).
pub const MAX_THREADS: usize = 256;

/// Wall time aimed at between two looks at the stop flag: a Ctrl-C is honoured well within
/// a second unless a single point takes longer.
const SLICE: Duration = Duration::from_millis(100);

/// A pool of `n_threads` threads (0 = one per core), `n_threads` ≤ [`MAX_THREADS`].
pub fn pool(n_threads: usize) -> Result<rayon::ThreadPool> {
    check_count("n_threads", n_threads, 0, MAX_THREADS)?;
    rayon::ThreadPoolBuilder::new()
        .num_threads(n_threads)
        .build()
        .map_err(|_| Error::InvalidParameter {
            name: "n_threads",
            value: n_threads as f64,
            allowed: "a thread count the system can start".to_string(),
        })
}

/// Fills `out[i] = point(i)` in parallel on `n_threads` threads (0 = one per core).
pub fn par_fill<T, F>(out: &mut [T], n_threads: usize, point: F) -> Result<()>
where
    T: Send,
    F: Fn(usize) -> T + Sync,
{
    par_fill_until(out, n_threads, point, &|| false)
}

/// [`par_fill`] in chunks of about [`SLICE`] of wall time each (the chunk size adapts to the
/// cost per point); between chunks `stop()` is asked, on the calling thread, and a `true`
/// ends the work with `Error::Interrupted` (the part of `out` not yet reached is left as it
/// was).
pub fn par_fill_until<T, F>(
    out: &mut [T],
    n_threads: usize,
    point: F,
    stop: &dyn Fn() -> bool,
) -> Result<()>
where
    T: Send,
    F: Fn(usize) -> T + Sync,
{
    let pool = pool(n_threads)?;
    let mut start = 0;
    let mut chunk = TASK;
    while start < out.len() {
        if stop() {
            return Err(Error::Interrupted);
        }
        let end = out.len().min(start + chunk);
        let t = Instant::now();
        pool.install(|| {
            out[start..end]
                .par_chunks_mut(TASK)
                .enumerate()
                .for_each(|(k, ch)| {
                    for (i, o) in ch.iter_mut().enumerate() {
                        *o = point(start + k * TASK + i);
                    }
                })
        });
        start = end;
        // Aim the next chunk at SLICE: double while far below it, halve above.
        let took = t.elapsed();
        if took < SLICE / 4 {
            chunk = chunk.saturating_mul(2);
        } else if took > SLICE && chunk > TASK {
            chunk /= 2;
        }
    }
    if stop() {
        return Err(Error::Interrupted);
    }
    Ok(())
}

/// Never stop: the `stop` of a map that is not to be interrupted.
pub fn never() -> bool {
    false
}

/// Checks that an input or output has the expected length, naming it otherwise.
pub fn check_len(name: &'static str, got: usize, want: usize) -> Result<()> {
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

#[cfg(test)]
mod tests {
    use super::*;
    use std::cell::Cell;

    #[test]
    fn chunked_fill_is_the_plain_fill_and_stops_when_asked() {
        let f = |i: usize| (i as f64).sqrt().sin();
        let mut a = vec![0.0; 100_000];
        let mut b = vec![0.0; 100_000];
        par_fill(&mut a, 1, f).unwrap();
        par_fill_until(&mut b, 2, f, &|| false).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
        let asked = Cell::new(0);
        let stop = || {
            asked.set(asked.get() + 1);
            asked.get() > 1
        };
        let mut c = vec![-1.0; 100_000];
        assert_eq!(par_fill_until(&mut c, 2, f, &stop), Err(Error::Interrupted));
        assert!(
            c[..TASK] == a[..TASK] && c[99_999] == -1.0,
            "the first chunk only"
        );
    }

    #[test]
    fn thread_count_is_bounded() {
        assert!(pool(MAX_THREADS + 1).is_err());
        assert!(pool(2).is_ok());
    }
}

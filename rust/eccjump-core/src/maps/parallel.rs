//! Parallel maps over independent points, on a local rayon pool.
//!
//! Every output element is computed from its index alone and written in place, so results
//! are bit-identical for any thread count; the only allocation is the pool itself.

use crate::error::{Error, Result};
use rayon::prelude::*;

/// Points handed to one task: small enough to balance uneven per-point costs, large enough
/// to keep scheduling overhead negligible.
const CHUNK: usize = 256;

/// A pool of `n_threads` threads (0 = one per core).
pub fn pool(n_threads: usize) -> Result<rayon::ThreadPool> {
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
    pool(n_threads)?.install(|| {
        out.par_chunks_mut(CHUNK).enumerate().for_each(|(k, ch)| {
            for (i, o) in ch.iter_mut().enumerate() {
                *o = point(k * CHUNK + i);
            }
        })
    });
    Ok(())
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

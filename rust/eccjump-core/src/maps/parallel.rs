//! Parallel maps over independent points, on a local rayon pool; the caller may stop the work
//! (Ctrl-C) while it runs.
//!
//! Every output element is computed from its index alone and written in place, so results
//! are bit-identical for any thread count; the only allocation is the pool.

use crate::error::{check_count, try_empty, Error, Result};
use rayon::prelude::*;
pub use rayon::ThreadPool;
use std::sync::atomic::{AtomicBool, Ordering};
use std::sync::mpsc::{self, RecvTimeoutError};
use std::time::Duration;

/// The most points in one piece of work. Rayon splits a range only while its split budget
/// lasts (about one split per thread) or when a piece is stolen; a thread that runs
/// through a long, cheap piece then finds nothing left to steal while another works through
/// an expensive one alone. With chunks of 256 points the ODE maps, whose points at small α
/// cost milliseconds and sit together at the start of a grid, ran only 1.25× faster on two
/// threads. Pieces of at most 64 points (≈ 0.1 ms of closed form, ms of ODE) balance both.
pub const MAX_PIECE: usize = 64;

/// Points per piece of [`par_fill_pieces_until`]: enough that the lanes of a piece stay
/// full most of the time (they empty at its end), few enough to balance the threads.
pub const PIECE: usize = 256;

/// The largest thread count a map accepts: far above any machine this runs on, and small
/// enough that starting the pool stays cheap (3000 threads took 13 s for one point).
pub const MAX_THREADS: usize = 256;

/// How often the calling thread asks whether to stop: a Ctrl-C is honoured well within a
/// second unless a single point takes longer.
const POLL: Duration = Duration::from_millis(20);

/// A pool of `n_threads` threads (0 = one per core), `n_threads` ≤ [`MAX_THREADS`].
pub fn pool(n_threads: usize) -> Result<ThreadPool> {
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

/// Fills `out[i] = point(i)` in parallel on `n_threads` threads (0 = one per core), and its
/// caller may stop it: while the pool works (driven from a scoped
/// thread), the calling thread asks `stop()` every [`POLL`]; a `true` makes the workers skip
/// the points not yet started and ends the work with `Error::Interrupted` (the part of `out`
/// not reached is left as it was). No barrier between parts of the work: the threads stay
/// busy to the end, whatever the spread of cost per point.
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
    run_until(n_threads, stop, |cancel| {
        out.par_iter_mut()
            .enumerate()
            .with_max_len(MAX_PIECE)
            .for_each(|(i, o)| {
                if !cancel.load(Ordering::Relaxed) {
                    *o = point(i);
                }
            })
    })
}

/// [`par_fill_until`] by pieces: `piece(start, out[start..start + len], cancelled)` fills
/// pieces of at most 256 points at once (the ODE route integrates a piece's points
/// side by side), asking `cancelled()` (the caller's stop, seen by the workers) as often as
/// it likes; a piece not started when the caller stops is skipped.
pub fn par_fill_pieces_until<T, F>(
    out: &mut [T],
    n_threads: usize,
    piece: F,
    stop: &dyn Fn() -> bool,
) -> Result<()>
where
    T: Send,
    F: Fn(usize, &mut [T], &dyn Fn() -> bool) + Sync,
{
    par_pieces_until(
        out.par_chunks_mut(PIECE),
        n_threads,
        |c, part, cancelled| piece(c * PIECE, part, cancelled),
        stop,
    )
}

/// `work(c, piece, cancelled)` for every piece of an output already cut into pieces (the
/// c-th of `pieces`, e.g. the columns of a struct of arrays), in parallel, one piece per
/// job, with the caller's stop as in [`par_fill_pieces_until`].
pub fn par_pieces_until<I, F>(
    pieces: I,
    n_threads: usize,
    work: F,
    stop: &dyn Fn() -> bool,
) -> Result<()>
where
    I: IndexedParallelIterator + Send,
    F: Fn(usize, I::Item, &dyn Fn() -> bool) + Sync,
{
    run_until(n_threads, stop, |cancel| {
        let cancelled = || cancel.load(Ordering::Relaxed);
        // One piece per job (rayon would otherwise split only a few times: see MAX_PIECE).
        pieces.enumerate().with_max_len(1).for_each(|(c, piece)| {
            if !cancelled() {
                work(c, piece, &cancelled);
            }
        })
    })
}

/// Runs `work(cancel)` on a pool of `n_threads` (driven from a scoped thread) while the
/// calling thread asks `stop()` every [`POLL`] and, on a `true`, sets `cancel` for the
/// workers; `Error::Interrupted` if it did.
fn run_until<W>(n_threads: usize, stop: &dyn Fn() -> bool, work: W) -> Result<()>
where
    W: FnOnce(&AtomicBool) + Send,
{
    let pool = pool(n_threads)?;
    if stop() {
        return Err(Error::Interrupted);
    }
    let cancel = AtomicBool::new(false);
    let stopped = std::thread::scope(|s| {
        // The driver says when it is done, so the caller wakes at once (not at the next poll).
        let (done_tx, done_rx) = mpsc::channel::<()>();
        let cancel = &cancel;
        let pool = &pool;
        let h = s.spawn(move || {
            pool.install(|| work(cancel));
            let _ = done_tx.send(());
        });
        let mut stopped = false;
        while let Err(RecvTimeoutError::Timeout) = done_rx.recv_timeout(POLL) {
            if !stopped && stop() {
                stopped = true;
                cancel.store(true, Ordering::Relaxed);
            }
        }
        // A panic in a point is a bug: passed on as it is, not hidden.
        if let Err(p) = h.join() {
            std::panic::resume_unwind(p);
        }
        stopped
    });
    if stopped {
        Err(Error::Interrupted)
    } else {
        Ok(())
    }
}

/// `count` copies of `value`, allocated fallibly (`OutOfMemory` naming `what`) and written
/// on `pool`: a large output's pages are first touched by the threads, not by one.
pub fn filled_on<T: Clone + Send + Sync>(
    pool: &ThreadPool,
    what: &'static str,
    count: usize,
    value: T,
) -> Result<Vec<T>> {
    let mut v = try_empty(what, count)?;
    pool.install(|| {
        (0..count)
            .into_par_iter()
            .map(|_| value.clone())
            .collect_into_vec(&mut v)
    });
    Ok(v)
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
    fn stoppable_fill_is_the_plain_fill_and_stops_when_asked() {
        let f = |i: usize| (i as f64).sqrt().sin();
        let a: Vec<f64> = (0..100_000).map(f).collect();
        let mut b = vec![0.0; 100_000];
        par_fill_until(&mut b, 2, f, &|| false).unwrap();
        assert!(a.iter().zip(&b).all(|(x, y)| x.to_bits() == y.to_bits()));
        // Slow points (1 ms each: 50 s in all) and a stop at the first poll after the start.
        let slow = |i: usize| {
            std::thread::sleep(Duration::from_millis(1));
            f(i)
        };
        let asked = Cell::new(0);
        let stop = || {
            asked.set(asked.get() + 1);
            asked.get() > 1
        };
        let mut c = vec![-1.0; 100_000];
        let t = std::time::Instant::now();
        assert_eq!(
            par_fill_until(&mut c, 2, slow, &stop),
            Err(Error::Interrupted)
        );
        assert!(t.elapsed() < Duration::from_secs(2), "{:?}", t.elapsed());
        // Few points are done by the stop, and none on a loaded machine where both polls
        // come before the first point's millisecond is over.
        let done = c.iter().filter(|&&x| x != -1.0).count();
        assert!(done < 10_000, "{done}");
        assert!(c
            .iter()
            .zip(&a)
            .all(|(x, y)| *x == -1.0 || x.to_bits() == y.to_bits()));
    }

    #[test]
    fn parallel_fill_is_the_serial_one() {
        for threads in [1, 2, 3] {
            let p = pool(threads).unwrap();
            assert_eq!(filled_on(&p, "x", 1001, 7u8).unwrap(), vec![7u8; 1001]);
            assert!(filled_on(&p, "x", 0, 1.0).unwrap().is_empty());
        }
        // Too large a request is an error naming it, not an abort.
        let p = pool(1).unwrap();
        let e = filled_on(&p, "the result", usize::MAX / 2, 0u64).unwrap_err();
        assert!(
            matches!(
                e,
                Error::OutOfMemory {
                    what: "the result",
                    ..
                }
            ),
            "{e:?}"
        );
    }

    #[test]
    fn thread_count_is_bounded() {
        assert!(pool(MAX_THREADS + 1).is_err());
        assert!(pool(2).is_ok());
    }
}

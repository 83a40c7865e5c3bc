//! A JARM map's results as one column per field (struct of arrays), the form the bridge
//! hands to numpy without a copy.
//!
//! The map's threads write each piece of points straight into the columns: no array of
//! per-point results is built and then split. For 10⁶ points that array was 88 MB more
//! memory to touch and a pass over it per field, about 40 ms of a 0.7 s map on two threads.

use std::mem::size_of;

use crate::error::{check_room, Result};
use crate::jarm::{JarmResult, Reason};
use crate::maps::parallel::{filled_on, ThreadPool};
use rayon::prelude::*;

/// The results of a map, one vector per field of [`JarmResult`] (same names and order).
#[derive(Debug, Clone, PartialEq)]
pub struct JarmColumns {
    /// [`JarmResult::is_jarm`] of every point.
    pub is_jarm: Vec<bool>,
    /// [`JarmResult::reason`] of every point, as its code.
    pub reason: Vec<u8>,
    /// [`JarmResult::n`] of every point.
    pub n: Vec<u32>,
    /// [`JarmResult::theta_j`] of every point.
    pub theta_j: Vec<f64>,
    /// [`JarmResult::theta_event`] of every point.
    pub theta_event: Vec<f64>,
    /// [`JarmResult::fx_j`] of every point.
    pub fx_j: Vec<f64>,
    /// [`JarmResult::fy_j`] of every point.
    pub fy_j: Vec<f64>,
    /// [`JarmResult::max_ratio`] of every point.
    pub max_ratio: Vec<f64>,
    /// [`JarmResult::theta_max_ratio`] of every point.
    pub theta_max_ratio: Vec<f64>,
    /// [`JarmResult::min_fy`] of every point.
    pub min_fy: Vec<f64>,
    /// [`JarmResult::theta_min_fy`] of every point.
    pub theta_min_fy: Vec<f64>,
}

impl JarmColumns {
    /// `len` points, each `InvalidParams` until the map writes it, allocated fallibly
    /// (`OutOfMemory` naming "the result") and first written by `pool`'s threads.
    pub fn new(pool: &ThreadPool, len: usize) -> Result<Self> {
        let blank = JarmResult::new(Reason::InvalidParams);
        // All columns at once, so that a map too large is refused at once, naming its size.
        let row = size_of::<bool>() + size_of::<u8>() + size_of::<u32>() + 8 * size_of::<f64>();
        check_room("the result", len.saturating_mul(row) as u64)?;
        let real = |value: f64| filled_on(pool, "the result", len, value);
        Ok(Self {
            is_jarm: filled_on(pool, "the result", len, blank.is_jarm)?,
            reason: filled_on(pool, "the result", len, blank.reason.code())?,
            n: filled_on(pool, "the result", len, blank.n)?,
            theta_j: real(blank.theta_j)?,
            theta_event: real(blank.theta_event)?,
            fx_j: real(blank.fx_j)?,
            fy_j: real(blank.fy_j)?,
            max_ratio: real(blank.max_ratio)?,
            theta_max_ratio: real(blank.theta_max_ratio)?,
            min_fy: real(blank.min_fy)?,
            theta_min_fy: real(blank.theta_min_fy)?,
        })
    }

    /// The number of points.
    pub fn len(&self) -> usize {
        self.reason.len()
    }

    /// True if there are no points.
    pub fn is_empty(&self) -> bool {
        self.reason.is_empty()
    }

    /// The result of point `i` (a code that names no reason reads as `InvalidParams`).
    pub fn row(&self, i: usize) -> JarmResult {
        JarmResult {
            is_jarm: self.is_jarm[i],
            reason: Reason::from_code(self.reason[i]).unwrap_or(Reason::InvalidParams),
            n: self.n[i],
            theta_j: self.theta_j[i],
            theta_event: self.theta_event[i],
            fx_j: self.fx_j[i],
            fy_j: self.fy_j[i],
            max_ratio: self.max_ratio[i],
            theta_max_ratio: self.theta_max_ratio[i],
            min_fy: self.min_fy[i],
            theta_min_fy: self.theta_min_fy[i],
        }
    }

    /// Every point's result, in order.
    pub fn rows(&self) -> Vec<JarmResult> {
        (0..self.len()).map(|i| self.row(i)).collect()
    }

    /// The consecutive pieces of at most `size` points (the last may be shorter), for the
    /// map's threads to write in parallel.
    pub fn pieces_mut(&mut self, size: usize) -> impl IndexedParallelIterator<Item = Piece<'_>> {
        (
            self.is_jarm.par_chunks_mut(size),
            self.reason.par_chunks_mut(size),
            self.n.par_chunks_mut(size),
            self.theta_j.par_chunks_mut(size),
            self.theta_event.par_chunks_mut(size),
            self.fx_j.par_chunks_mut(size),
            self.fy_j.par_chunks_mut(size),
            self.max_ratio.par_chunks_mut(size),
            self.theta_max_ratio.par_chunks_mut(size),
            self.min_fy.par_chunks_mut(size),
            self.theta_min_fy.par_chunks_mut(size),
        )
            .into_par_iter()
            .map(
                |(is_jarm, reason, n, theta_j, theta_event, fx_j, fy_j, mr, tmr, mf, tmf)| Piece {
                    is_jarm,
                    reason,
                    n,
                    theta_j,
                    theta_event,
                    fx_j,
                    fy_j,
                    max_ratio: mr,
                    theta_max_ratio: tmr,
                    min_fy: mf,
                    theta_min_fy: tmf,
                },
            )
    }
}

/// Consecutive points of [`JarmColumns`], written by one thread.
pub struct Piece<'a> {
    is_jarm: &'a mut [bool],
    reason: &'a mut [u8],
    n: &'a mut [u32],
    theta_j: &'a mut [f64],
    theta_event: &'a mut [f64],
    fx_j: &'a mut [f64],
    fy_j: &'a mut [f64],
    max_ratio: &'a mut [f64],
    theta_max_ratio: &'a mut [f64],
    min_fy: &'a mut [f64],
    theta_min_fy: &'a mut [f64],
}

impl Piece<'_> {
    /// The number of points.
    pub fn len(&self) -> usize {
        self.reason.len()
    }

    /// True if there are no points.
    pub fn is_empty(&self) -> bool {
        self.reason.is_empty()
    }

    /// Writes `rows` (one per point of the piece, in order).
    pub fn put(&mut self, rows: &[JarmResult]) {
        for (i, r) in rows.iter().enumerate().take(self.len()) {
            self.is_jarm[i] = r.is_jarm;
            self.reason[i] = r.reason.code();
            self.n[i] = r.n;
            self.theta_j[i] = r.theta_j;
            self.theta_event[i] = r.theta_event;
            self.fx_j[i] = r.fx_j;
            self.fy_j[i] = r.fy_j;
            self.max_ratio[i] = r.max_ratio;
            self.theta_max_ratio[i] = r.theta_max_ratio;
            self.min_fy[i] = r.min_fy;
            self.theta_min_fy[i] = r.theta_min_fy;
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::maps::parallel::pool;

    /// A result whose every field tells its point apart.
    fn row(i: usize) -> JarmResult {
        let x = i as f64;
        JarmResult {
            is_jarm: i % 3 == 0,
            reason: Reason::ALL[i % Reason::ALL.len()],
            n: i as u32,
            theta_j: x + 0.1,
            theta_event: x + 0.2,
            fx_j: x + 0.3,
            fy_j: x + 0.4,
            max_ratio: x + 0.5,
            theta_max_ratio: x + 0.6,
            min_fy: x + 0.7,
            theta_min_fy: x + 0.8,
        }
    }

    #[test]
    fn pieces_write_every_field_of_every_point_in_place() {
        let p = pool(2).unwrap();
        for (len, size) in [(0, 4), (1, 4), (1000, 64), (1001, 64), (257, 256)] {
            let mut c = JarmColumns::new(&p, len).unwrap();
            assert_eq!(c.len(), len);
            assert!((0..len).all(|i| c.row(i).as_f64s().map(f64::to_bits)
                == JarmResult::new(Reason::InvalidParams)
                    .as_f64s()
                    .map(f64::to_bits)));
            let count = c.pieces_mut(size).len();
            assert_eq!(count, len.div_ceil(size));
            c.pieces_mut(size).enumerate().for_each(|(k, mut piece)| {
                let rows: Vec<_> = (0..piece.len()).map(|i| row(k * size + i)).collect();
                assert!(piece.len() == size || (k + 1) * size >= len);
                piece.put(&rows);
            });
            for i in 0..len {
                let (got, want) = (c.row(i), row(i));
                assert_eq!(
                    got.as_f64s().map(f64::to_bits),
                    want.as_f64s().map(f64::to_bits)
                );
                assert_eq!(got.is_jarm, want.is_jarm);
            }
        }
    }

    #[test]
    fn a_result_too_large_is_out_of_memory() {
        let p = pool(1).unwrap();
        let e = JarmColumns::new(&p, usize::MAX / 2).unwrap_err();
        assert!(matches!(e, crate::Error::OutOfMemory { .. }), "{e:?}");
    }
}

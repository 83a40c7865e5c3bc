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

/// [`JarmColumns`] and its [`Piece`] from one list of the fields of [`JarmResult`] (same
/// names and order), each with its column's type, how a result `$r`'s field goes into the
/// column and how a column's value `$x` comes back.
macro_rules! jarm_columns {
    (|$r:ident, $x:ident| $($f:ident: $t:ty = $put:expr, $get:expr;)*) => {
        /// The results of a map, one vector per field of [`JarmResult`] (same names and order;
        /// the reason as its code).
        #[derive(Debug, Clone, PartialEq)]
        pub struct JarmColumns {
            $(
                #[doc = concat!("[`JarmResult::", stringify!($f), "`] of every point.")]
                pub $f: Vec<$t>,
            )*
        }

        /// Consecutive points of [`JarmColumns`], written by one thread.
        pub(crate) struct Piece<'a> {
            $($f: &'a mut [$t],)*
        }

        impl JarmColumns {
            /// `len` points, each `InvalidParams` until the map writes it, allocated fallibly
            /// (`OutOfMemory` naming "the result") and first written by `pool`'s threads.
            pub fn new(pool: &ThreadPool, len: usize) -> Result<Self> {
                let $r = JarmResult::new(Reason::InvalidParams);
                // All columns at once, so that a map too large is refused at once, naming
                // its size.
                let row = 0 $(+ size_of::<$t>())*;
                check_room("the result", len.saturating_mul(row) as u64)?;
                Ok(Self {
                    $($f: filled_on(pool, "the result", len, $put)?,)*
                })
            }

            /// The result of point `i` (a code that names no reason reads as `InvalidParams`).
            pub fn row(&self, i: usize) -> JarmResult {
                JarmResult {
                    $($f: {
                        let $x = self.$f[i];
                        $get
                    },)*
                }
            }

            /// The consecutive pieces of at most `size` points (the last may be shorter), for
            /// the map's threads to write in parallel.
            pub(crate) fn pieces_mut(
                &mut self,
                size: usize,
            ) -> impl IndexedParallelIterator<Item = Piece<'_>> {
                ($(self.$f.par_chunks_mut(size),)*)
                    .into_par_iter()
                    .map(|($($f,)*)| Piece { $($f,)* })
            }
        }

        impl Piece<'_> {
            /// Writes `rows` (one per point of the piece, in order).
            pub(crate) fn put(&mut self, rows: &[JarmResult]) {
                for (i, $r) in rows.iter().enumerate().take(self.len()) {
                    $(self.$f[i] = $put;)*
                }
            }
        }
    };
}

jarm_columns! { |r, x|
    is_jarm: bool = r.is_jarm, x;
    reason: u8 = r.reason.code(), Reason::from_code(x).unwrap_or(Reason::InvalidParams);
    n: u32 = r.n, x;
    theta_j: f64 = r.theta_j, x;
    theta_event: f64 = r.theta_event, x;
    fx_j: f64 = r.fx_j, x;
    fy_j: f64 = r.fy_j, x;
    max_ratio: f64 = r.max_ratio, x;
    theta_max_ratio: f64 = r.theta_max_ratio, x;
    min_fy: f64 = r.min_fy, x;
    theta_min_fy: f64 = r.theta_min_fy, x;
}

impl JarmColumns {
    /// The number of points.
    pub fn len(&self) -> usize {
        self.reason.len()
    }

    /// True if there are no points.
    pub fn is_empty(&self) -> bool {
        self.reason.is_empty()
    }

    /// Every point's result, in order.
    pub fn rows(&self) -> Vec<JarmResult> {
        (0..self.len()).map(|i| self.row(i)).collect()
    }
}

impl Piece<'_> {
    /// The number of points.
    pub(crate) fn len(&self) -> usize {
        self.reason.len()
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

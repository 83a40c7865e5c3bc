//! The one error type of the core. The Python bridge maps every variant to a Python
//! exception (`InvalidParameter` → `ValueError`), so no failure ever surfaces as a panic.

use thiserror::Error;

/// Everything that can go wrong in the core.
#[derive(Debug, Clone, PartialEq, Error)]
pub enum Error {
    /// A parameter is NaN, infinite or outside its allowed range.
    #[error("{name} = {} is outside the allowed range {allowed}", short(*value))]
    InvalidParameter {
        /// The parameter's name as the Python API spells it.
        name: &'static str,
        /// The value given.
        value: f64,
        /// The allowed range, e.g. "[0, 1]".
        allowed: String,
    },
    /// A root finder was handed an interval whose ends do not bracket a root.
    #[error("no sign change on [{a}, {b}]: f(a) = {fa}, f(b) = {fb}")]
    NoBracket {
        /// Left end.
        a: f64,
        /// Right end.
        b: f64,
        /// f(a).
        fa: f64,
        /// f(b).
        fb: f64,
    },
    /// An output (or work buffer) would not fit in memory: `bytes` were asked for (saturated
    /// at u64::MAX when the size itself overflows).
    #[error("{what} needs {} of memory, more than can be allocated", bytes_text(*bytes))]
    OutOfMemory {
        /// What was to be allocated.
        what: &'static str,
        /// The size asked for, in bytes.
        bytes: u64,
    },
    /// The caller asked to stop (e.g. Ctrl-C) between two chunks of work.
    #[error("interrupted")]
    Interrupted,
    /// An error about the entry at `index` of an array argument.
    #[error("{source} (at index {index})")]
    AtIndex {
        /// The index of the offending entry.
        index: usize,
        /// What is wrong with it.
        source: Box<Error>,
    },
    /// An iteration limit was reached before convergence.
    #[error("{what} did not converge within {iterations} iterations")]
    NoConvergence {
        /// What did not converge.
        what: &'static str,
        /// The iteration limit.
        iterations: usize,
    },
}

/// Shorthand used throughout the core.
pub type Result<T> = std::result::Result<T, Error>;

impl Error {
    /// `InvalidParameter`: `name` = `value` is outside `allowed`.
    pub fn invalid(name: &'static str, value: f64, allowed: impl Into<String>) -> Self {
        let allowed = allowed.into();
        Error::InvalidParameter {
            name,
            value,
            allowed,
        }
    }
}

fn bytes_text(bytes: u64) -> String {
    if bytes == u64::MAX {
        "more than 2^64 bytes".to_string()
    } else {
        format!("{:.3} GiB", bytes as f64 / (1u64 << 30) as f64)
    }
}

/// A vector of `count` copies of `value`, allocated fallibly: `OutOfMemory` naming `what`
/// instead of an abort when the allocator refuses (or the size overflows).
pub fn try_filled<T: Clone>(what: &'static str, count: usize, value: T) -> Result<Vec<T>> {
    let mut v = try_empty(what, count)?;
    v.resize(count, value);
    Ok(v)
}

/// An empty vector with room for exactly `count` items, allocated fallibly: `OutOfMemory`
/// naming `what` instead of an abort when the allocator refuses (or the size overflows).
pub fn try_empty<T>(what: &'static str, count: usize) -> Result<Vec<T>> {
    // A size beyond isize::MAX bytes is refused by the allocator too; it is named as saturated.
    let bytes = count
        .checked_mul(std::mem::size_of::<T>())
        .filter(|&b| b <= isize::MAX as usize)
        .map_or(u64::MAX, |b| b as u64);
    let mut v = Vec::new();
    v.try_reserve_exact(count)
        .map_err(|_| Error::OutOfMemory { what, bytes })?;
    Ok(v)
}

/// Checks that `bytes` could be allocated in one piece, before a result made of several
/// buffers is: without it, where the system lends memory it may not have (overcommit), the
/// first buffers are allocated and filled before a later one fails, which takes seconds and
/// names only that buffer's size. The probe is never written and is released at once.
pub fn check_room(what: &'static str, bytes: u64) -> Result<()> {
    let too_large = Error::OutOfMemory { what, bytes };
    let count = usize::try_from(bytes).map_err(|_| too_large.clone())?;
    let mut probe = Vec::<u8>::new();
    probe.try_reserve_exact(count).map_err(|_| too_large)?;
    // An allocation that is never used may be optimised away, and would then always succeed.
    std::hint::black_box(&probe);
    Ok(())
}

/// Reserves room for one more element, fallibly (amortised doubling, like `push`).
pub fn try_grow<T>(what: &'static str, v: &mut Vec<T>) -> Result<()> {
    if v.len() < v.capacity() {
        return Ok(());
    }
    let extra = v.len().max(16);
    v.try_reserve(extra).map_err(|_| Error::OutOfMemory {
        what,
        bytes: ((v.len() + extra) * std::mem::size_of::<T>()) as u64,
    })
}

/// Checks that an integer work parameter lies in `[lo, hi]`.
pub fn check_count(name: &'static str, value: usize, lo: usize, hi: usize) -> Result<usize> {
    if (lo..=hi).contains(&value) {
        Ok(value)
    } else {
        Err(Error::invalid(name, value as f64, format!("[{lo}, {hi}]")))
    }
}

/// A number as it appears in a message: short (at most 17 significant digits, exponent
/// form for very large or small magnitudes), ±f64::MAX as ±inf (an open end).
pub fn short(x: f64) -> String {
    if x >= f64::MAX {
        "inf".to_string()
    } else if x <= -f64::MAX {
        "-inf".to_string()
    } else if x != 0.0 && (x.abs() >= 1e9 || x.abs() < 1e-5) {
        format!("{x:e}")
    } else {
        format!("{x}")
    }
}

/// Checks that `value` is finite and lies in `[lo, hi]`, naming the parameter otherwise
/// (hi = f64::MAX reads as an open end, "inf)").
pub fn check_range(name: &'static str, value: f64, lo: f64, hi: f64) -> Result<f64> {
    if value.is_finite() && value >= lo && value <= hi {
        Ok(value)
    } else {
        let close = if hi >= f64::MAX { ")" } else { "]" };
        let allowed = format!("[{}, {}{close}", short(lo), short(hi));
        Err(Error::invalid(name, value, allowed))
    }
}

/// Checks that `value` is finite and strictly positive.
pub fn check_positive(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() && value > 0.0 {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "(0, inf)"))
    }
}

/// Checks that `value` is finite (neither NaN nor infinite).
pub fn check_finite(name: &'static str, value: f64) -> Result<f64> {
    if value.is_finite() {
        Ok(value)
    } else {
        Err(Error::invalid(name, value, "(-inf, inf)"))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn room_is_probed_without_being_used_and_a_refusal_names_the_whole_size() {
        assert_eq!(check_room("x", 1 << 20), Ok(()));
        // Far beyond any machine's memory and swap: refused at once, naming all of it.
        let e = check_room("the result", 1 << 50).unwrap_err();
        assert_eq!(
            e,
            Error::OutOfMemory {
                what: "the result",
                bytes: 1 << 50
            }
        );
        assert!(e.to_string().contains("1048576.000 GiB"), "{e}");
        assert!(check_room("x", u64::MAX).is_err());
    }
}

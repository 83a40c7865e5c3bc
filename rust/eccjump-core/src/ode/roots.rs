//! Bracketing root finders for scalar functions: Brent's method (a translation of
//! scipy's `brentq.c`) and plain bisection to the last representable bit.
//!
//! Both take an interval whose ends have opposite signs and never leave it, so a root they
//! return is always bracketed; both stop at an iteration limit with an error, never hang.

use crate::error::{Error, Result};

/// Where a root finder stopped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Root {
    /// The root estimate.
    pub x: f64,
    /// Lower end of a bracket [lo, hi] that still contains the sign change, lo ≤ x ≤ hi.
    pub lo: f64,
    /// Upper end of that bracket.
    pub hi: f64,
    /// Function evaluations used.
    pub evaluations: usize,
}

fn bracket_error(a: f64, b: f64, fa: f64, fb: f64) -> Error {
    Error::NoBracket { a, b, fa, fb }
}

/// Brent's method on [a, b] given f(a) = fa and f(b) = fb of opposite signs (or one zero).
/// Converges when the bracket is below `xtol + rtol |x|`; `rtol` ≥ 4 ε is sensible.
#[allow(clippy::too_many_arguments)] // f, the bracket with its values, and three limits
pub fn brent<F: FnMut(f64) -> f64>(
    mut f: F,
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
    xtol: f64,
    rtol: f64,
    max_iter: usize,
) -> Result<Root> {
    let (mut xpre, mut xcur) = (a, b);
    let (mut fpre, mut fcur) = (fa, fb);
    let (mut xblk, mut fblk) = (0.0f64, 0.0f64);
    let (mut spre, mut scur) = (0.0f64, 0.0f64);
    if fpre == 0.0 {
        return Ok(Root {
            x: xpre,
            lo: xpre,
            hi: xpre,
            evaluations: 0,
        });
    }
    if fcur == 0.0 {
        return Ok(Root {
            x: xcur,
            lo: xcur,
            hi: xcur,
            evaluations: 0,
        });
    }
    if fpre.is_nan() || fcur.is_nan() || fpre.signum() == fcur.signum() {
        return Err(bracket_error(a, b, fa, fb));
    }
    for iter in 0..max_iter {
        if fpre != 0.0 && fcur != 0.0 && fpre.signum() != fcur.signum() {
            xblk = xpre;
            fblk = fpre;
            spre = xcur - xpre;
            scur = spre;
        }
        if fblk.abs() < fcur.abs() {
            xpre = xcur;
            xcur = xblk;
            xblk = xpre;
            fpre = fcur;
            fcur = fblk;
            fblk = fpre;
        }
        let delta = 0.5 * (xtol + rtol * xcur.abs());
        let sbis = 0.5 * (xblk - xcur);
        if fcur == 0.0 {
            // An exact zero: the bracket collapses onto it (the other end may be stale).
            return Ok(Root {
                x: xcur,
                lo: xcur,
                hi: xcur,
                evaluations: iter,
            });
        }
        if sbis.abs() < delta {
            let (lo, hi) = if xcur < xblk {
                (xcur, xblk)
            } else {
                (xblk, xcur)
            };
            return Ok(Root {
                x: xcur,
                lo,
                hi,
                evaluations: iter,
            });
        }
        if spre.abs() > delta && fcur.abs() < fpre.abs() {
            let stry = if xpre == xblk {
                // Secant step.
                -fcur * (xcur - xpre) / (fcur - fpre)
            } else {
                // Inverse quadratic interpolation.
                let dpre = (fpre - fcur) / (xpre - xcur);
                let dblk = (fblk - fcur) / (xblk - xcur);
                -fcur * (fblk * dblk - fpre * dpre) / (dblk * dpre * (fblk - fpre))
            };
            if 2.0 * stry.abs() < spre.abs().min(3.0 * sbis.abs() - delta) {
                spre = scur;
                scur = stry;
            } else {
                spre = sbis;
                scur = sbis;
            }
        } else {
            spre = sbis;
            scur = sbis;
        }
        xpre = xcur;
        fpre = fcur;
        if scur.abs() > delta {
            xcur += scur;
        } else {
            xcur += if sbis > 0.0 { delta } else { -delta };
        }
        fcur = f(xcur);
        if fcur.is_nan() {
            return Err(Error::NoConvergence {
                what: "brent (f returned NaN)",
                iterations: iter,
            });
        }
    }
    Err(Error::NoConvergence {
        what: "brent",
        iterations: max_iter,
    })
}

/// Bisection on [a, b] (fa, fb of opposite signs) until the midpoint is no longer strictly
/// inside the bracket: the result is the root to the last bit the arithmetic can resolve.
/// Deterministic and robust for functions with nearby extrema, where Brent may stall.
pub fn bisect<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, fa: f64, fb: f64) -> Result<Root> {
    if fa == 0.0 {
        return Ok(Root {
            x: a,
            lo: a,
            hi: a,
            evaluations: 0,
        });
    }
    if fb == 0.0 {
        return Ok(Root {
            x: b,
            lo: b,
            hi: b,
            evaluations: 0,
        });
    }
    if fa.is_nan() || fb.is_nan() || fa.signum() == fb.signum() {
        return Err(bracket_error(a, b, fa, fb));
    }
    let (mut lo, mut hi, mut flo) = (a, b, fa);
    // 2100 halvings exhaust any f64 interval; the limit only guards against NaN loops.
    for iter in 0..2100 {
        let mid = 0.5 * (lo + hi);
        if mid <= lo.min(hi) || mid >= lo.max(hi) {
            let x = if flo.abs() <= f(hi).abs() { lo } else { hi };
            let (l, h) = if lo < hi { (lo, hi) } else { (hi, lo) };
            return Ok(Root {
                x,
                lo: l,
                hi: h,
                evaluations: iter + 1,
            });
        }
        let fm = f(mid);
        if fm == 0.0 {
            return Ok(Root {
                x: mid,
                lo: mid,
                hi: mid,
                evaluations: iter + 1,
            });
        }
        if fm.signum() == flo.signum() {
            lo = mid;
            flo = fm;
        } else {
            hi = mid;
        }
    }
    Err(Error::NoConvergence {
        what: "bisection",
        iterations: 2100,
    })
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn brent_finds_cube_root_of_two() {
        let f = |x: f64| x * x * x - 2.0;
        let r = brent(f, 0.0, 2.0, f(0.0), f(2.0), 0.0, 4.0 * f64::EPSILON, 100).unwrap();
        assert!((r.x - 2f64.cbrt()).abs() < 1e-15);
        assert!(r.lo <= r.x && r.x <= r.hi);
    }

    #[test]
    fn an_exact_zero_collapses_the_bracket() {
        // The secant step from (0, -1), (4, 3) lands exactly on the root 1 of this piecewise f.
        let f = |x: f64| if x <= 1.0 { x - 1.0 } else { 0.75 * (x - 1.0) };
        let r = brent(f, 0.0, 4.0, f(0.0), f(4.0), 0.0, 4.0 * f64::EPSILON, 100).unwrap();
        assert_eq!((r.x, r.lo, r.hi), (1.0, 1.0, 1.0));
    }

    #[test]
    fn bisection_is_exact_to_the_last_bit() {
        let f = |x: f64| x.cos() - x;
        let r = bisect(f, 0.0, 1.0, f(0.0), f(1.0)).unwrap();
        assert!(r.hi - r.lo <= 2.0 * f64::EPSILON);
        assert!((r.x - 0.739_085_133_215_160_6).abs() < 2e-16);
    }

    #[test]
    fn no_bracket_is_an_error() {
        let f = |x: f64| x * x + 1.0;
        assert!(brent(f, -1.0, 1.0, 2.0, 2.0, 0.0, 1e-15, 100).is_err());
        assert!(bisect(f, -1.0, 1.0, 2.0, 2.0).is_err());
    }
}

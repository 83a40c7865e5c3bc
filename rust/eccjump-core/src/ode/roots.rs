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

impl Root {
    /// The root x itself, found after `evaluations`.
    fn exact(x: f64, evaluations: usize) -> Self {
        Root {
            x,
            lo: x,
            hi: x,
            evaluations,
        }
    }
}

/// What every bracketing method checks first: an end of [a, b] that is a root, or a
/// bracket without a sign change (or with a NaN), which is an error.
fn settled_at_start(a: f64, b: f64, fa: f64, fb: f64) -> Option<Result<Root>> {
    if fa == 0.0 {
        Some(Ok(Root::exact(a, 0)))
    } else if fb == 0.0 {
        Some(Ok(Root::exact(b, 0)))
    } else if fa.is_nan() || fb.is_nan() || fa.signum() == fb.signum() {
        Some(Err(Error::NoBracket { a, b, fa, fb }))
    } else {
        None
    }
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
    if let Some(settled) = settled_at_start(a, b, fa, fb) {
        return settled;
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

/// Newton's method kept inside a bracket (Numerical Recipes' `rtsafe`, with a first guess):
/// on [a, b] with f(a) = fa and f(b) = fb of opposite signs (or one zero), `f` returning the
/// value and the derivative. A Newton step that would leave the bracket, or that shrinks the
/// last step by less than half, is replaced by a bisection, so the bracket always holds the
/// sign change and the method never does worse than bisection. Converges when a step is below
/// `rtol |x|` (the last Newton step is taken, not evaluated: its error is of the order of the
/// step squared) or the bracket cannot shrink; `x0` is the first point evaluated (the middle
/// if it is not strictly inside). A simple root costs about three evaluations from a good
/// `x0`, against Brent's seven or eight from the bracket alone. The slope must be f' (its sign
/// and size are trusted for the stopping test; a wrong sign, zero or NaN only costs bisections).
#[allow(clippy::too_many_arguments)] // f, the bracket with its values, the guess, two limits
pub fn newton_bracketed<F: FnMut(f64) -> (f64, f64)>(
    mut f: F,
    a: f64,
    b: f64,
    fa: f64,
    fb: f64,
    x0: f64,
    rtol: f64,
    max_iter: usize,
) -> Result<Root> {
    if let Some(settled) = settled_at_start(a, b, fa, fb) {
        return settled;
    }
    // `neg` is the end where f < 0, `pos` the end where f > 0.
    let (mut neg, mut pos) = if fa < 0.0 { (a, b) } else { (b, a) };
    let (lo, hi) = (a.min(b), a.max(b));
    let mut x = if x0 > lo && x0 < hi {
        x0
    } else {
        0.5 * (a + b)
    };
    let mut step_old = hi - lo;
    let mut step = step_old;
    let (mut fx, mut dfx) = f(x);
    // The previous point and slope, for the curvature that predicts the last step's error.
    let (mut x_prev, mut dfx_prev) = (f64::NAN, f64::NAN);
    for iter in 1..=max_iter {
        if fx == 0.0 {
            return Ok(Root::exact(x, iter));
        }
        if fx.is_nan() {
            return Err(Error::NoConvergence {
                what: "newton (f returned NaN)",
                iterations: iter,
            });
        }
        if fx < 0.0 {
            neg = x;
        } else {
            pos = x;
        }
        let newton = x - fx / dfx;
        let (lo, hi) = (neg.min(pos), neg.max(pos));
        // After a Newton step s the error is ≈ |f''/(2f')| s²; with f'' from the last two
        // slopes, a step whose predicted error is 16 times below the tolerance is taken
        // without evaluating its end (the evaluation that would only confirm it).
        let curvature = (dfx - dfx_prev) / (x - x_prev);
        let predicted = (curvature / (2.0 * dfx)).abs() * (x - newton) * (x - newton);
        if (x - newton).abs() <= rtol * x.abs()
            || (newton > lo && newton < hi && 16.0 * predicted <= rtol * newton.abs())
        {
            // Converged: the step rounds to within the tolerance (possibly to x itself).
            return Ok(Root {
                x: newton.clamp(lo, hi),
                lo,
                hi,
                evaluations: iter,
            });
        }
        (x_prev, dfx_prev) = (x, dfx);
        let inside = newton > lo && newton < hi;
        if inside && (2.0 * fx).abs() <= (step_old * dfx).abs() {
            step_old = step;
            step = x - newton;
            x = newton;
        } else {
            step_old = step;
            step = 0.5 * (pos - neg);
            let mid = neg + step;
            if mid <= neg.min(pos) || mid >= neg.max(pos) {
                break; // the bracket is two adjacent floats
            }
            x = mid;
        }
        if step.abs() <= rtol * x.abs() {
            return Ok(Root {
                x,
                lo: neg.min(pos),
                hi: neg.max(pos),
                evaluations: iter,
            });
        }
        (fx, dfx) = f(x);
    }
    if (neg - pos).abs() <= rtol * x.abs() || {
        let m = 0.5 * (neg + pos);
        m <= neg.min(pos) || m >= neg.max(pos)
    } {
        return Ok(Root {
            x,
            lo: neg.min(pos),
            hi: neg.max(pos),
            evaluations: max_iter,
        });
    }
    Err(Error::NoConvergence {
        what: "newton",
        iterations: max_iter,
    })
}

/// Bisection on [a, b] (fa, fb of opposite signs) until the midpoint is no longer strictly
/// inside the bracket: the result is the root to the last bit the arithmetic can resolve.
/// Deterministic and robust for functions with nearby extrema, where Brent may stall.
pub fn bisect<F: FnMut(f64) -> f64>(mut f: F, a: f64, b: f64, fa: f64, fb: f64) -> Result<Root> {
    if let Some(settled) = settled_at_start(a, b, fa, fb) {
        return settled;
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
    fn newton_reaches_the_last_bits_in_few_evaluations() {
        // cos x − x has a simple root; from a guess 1e-5 off, two or three evaluations.
        let f = |x: f64| (x.cos() - x, -x.sin() - 1.0);
        let root = 0.739_085_133_215_160_6;
        for x0 in [root + 1e-5, root - 1e-6, 0.2, 0.999] {
            let mut n = 0;
            let r = newton_bracketed(
                |x| {
                    n += 1;
                    f(x)
                },
                0.0,
                1.0,
                1.0,
                1f64.cos() - 1.0,
                x0,
                4.0 * f64::EPSILON,
                100,
            )
            .unwrap();
            assert!((r.x - root).abs() <= 2.0 * f64::EPSILON, "{x0}: {}", r.x);
            assert!(r.lo <= r.x && r.x <= r.hi && r.lo <= root && root <= r.hi);
            assert_eq!(r.evaluations, n);
            if (x0 - root).abs() < 1e-4 {
                assert!(n <= 3, "{x0}: {n} evaluations");
            }
        }
    }

    #[test]
    fn newton_with_a_wrong_slope_still_converges_by_bisection() {
        // A slope of the wrong sign (or zero, or NaN) sends the Newton steps out of the
        // bracket: the safeguard bisects, to the last bit, and never leaves [a, b]. (A slope
        // of the right sign but a wrong size is not detected: `f` must return f'.)
        for slope in [-1.0, 0.0, f64::NAN] {
            let f = |x: f64| (x * x * x - 2.0, slope);
            let r = newton_bracketed(f, 0.0, 2.0, -2.0, 6.0, 1.9, 4.0 * f64::EPSILON, 200).unwrap();
            assert!((r.x - 2f64.cbrt()).abs() < 1e-14, "{slope}: {}", r.x);
            assert!((0.0..=2.0).contains(&r.x));
        }
        // A double root at an end, a root at an end, no bracket, NaN inside.
        let r = newton_bracketed(|x| (x, 1.0), 0.0, 1.0, 0.0, 1.0, 0.5, 1e-15, 50).unwrap();
        assert_eq!(r.x, 0.0);
        assert!(newton_bracketed(|x| (x, 1.0), 1.0, 2.0, 1.0, 2.0, 1.5, 1e-15, 50).is_err());
        let nan = |_: f64| (f64::NAN, 1.0);
        assert!(newton_bracketed(nan, -1.0, 1.0, -1.0, 1.0, 0.5, 1e-15, 50).is_err());
        // The iteration limit is an error or a converged bracket, never a hang.
        let slow = |x: f64| ((x - 0.3).powi(3), 3.0 * (x - 0.3).powi(2));
        let r = newton_bracketed(slow, 0.0, 1.0, -0.027, 0.343, 0.9, 4.0 * f64::EPSILON, 400);
        assert!(r.map_or(true, |r| (r.x - 0.3).abs() < 1e-4));
    }

    #[test]
    fn no_bracket_is_an_error() {
        let f = |x: f64| x * x + 1.0;
        assert!(brent(f, -1.0, 1.0, 2.0, 2.0, 0.0, 1e-15, 100).is_err());
        assert!(bisect(f, -1.0, 1.0, 2.0, 2.0).is_err());
    }
}

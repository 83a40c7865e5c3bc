//! Estimates from a cell's cubic Hermite interpolant (values g0, g1 and scaled slopes
//! m = h g' at its ends, on t ∈ [0, 1]): where its minimum is and how deep, and where its
//! root is. Cheap screens and first guesses for the exact searches of the path scan and the
//! event scan, never results by themselves.

/// The minimum on t ∈ [0, 1] of the cubic Hermite interpolant with values g0, g1 and scaled
/// slopes m0 = h g0' < 0 < m1 = h g1'.
#[inline]
pub fn hermite_min(g0: f64, m0: f64, g1: f64, m1: f64) -> (f64, f64) {
    let b = 3.0 * (g1 - g0) - 2.0 * m0 - m1;
    let c = 2.0 * (g0 - g1) + m0 + m1;
    let disc = (b * b - 3.0 * c * m0).max(0.0);
    let den = b + disc.sqrt();
    let t = if den > 0.0 {
        (-m0 / den).clamp(0.0, 1.0)
    } else {
        0.5
    };
    (t, g0 + t * (m0 + t * (b + t * c)))
}

/// A root in (0, 1) of the cubic Hermite interpolant with values g0, g1 of opposite signs and
/// scaled slopes m0, m1: two Newton steps on the cubic from the secant root, kept in [0, 1]
/// (the secant root if they fail). Only a first guess for the root finder, which checks it.
#[inline]
pub fn hermite_root(g0: f64, m0: f64, g1: f64, m1: f64) -> f64 {
    let b = 3.0 * (g1 - g0) - 2.0 * m0 - m1;
    let c = 2.0 * (g0 - g1) + m0 + m1;
    let secant = g0 / (g0 - g1);
    let mut t = secant;
    for _ in 0..2 {
        let p = g0 + t * (m0 + t * (b + t * c));
        let dp = m0 + t * (2.0 * b + 3.0 * t * c);
        t = (t - p / dp).clamp(0.0, 1.0);
    }
    if t.is_finite() {
        t
    } else {
        secant
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn estimates_are_exact_for_a_cubic() {
        // g(t) = (t − 0.4)²(t + 1) + 0.05 on [0, 1], minimum 0.05 at 0.4: a cubic is its
        // own interpolant.
        let g = |t: f64| (t - 0.4) * (t - 0.4) * (t + 1.0) + 0.05;
        let dg = |t: f64| (t - 0.4) * (3.0 * t + 1.6);
        let (t, m) = hermite_min(g(0.0), dg(0.0), g(1.0), dg(1.0));
        assert!(
            (t - 0.4).abs() < 1e-14 && (m - 0.05).abs() < 1e-14,
            "{t} {m}"
        );
        // A root of a monotone cubic (the crossings it serves): two Newton steps from the
        // secant.
        let f = |t: f64| t * t * t + t - 0.5;
        let df = |t: f64| 3.0 * t * t + 1.0;
        let r = hermite_root(f(0.0), df(0.0), f(1.0), df(1.0));
        assert!(f(r).abs() < 1e-3, "{r} {}", f(r));
        // Outside its premises the estimates stay in [0, 1] and finite.
        let (t, m) = hermite_min(1.0, 0.0, 1.0, 0.0);
        assert!((0.0..=1.0).contains(&t) && m.is_finite());
        assert!((0.0..=1.0).contains(&hermite_root(1.0, 0.0, -1.0, 0.0)));
    }
}

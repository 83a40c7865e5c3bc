//! Verner's most efficient 9(8) pair: 16 stages (15 evaluations of f, plus f at the step end,
//! which the next step begins with), scipy's error norm of the 8th-order estimate, and the
//! 8th-degree interpolant from four extra stages: the fastest pair at the default
//! tolerances (`docs/performance.md`). Its step control is scipy's but for the safety factor
//! and the first step (`verner_pair!` in `pair/verner.rs`).

super::verner::verner_pair!(
    /// The stages of one Verner 9(8) step: 16 stages, the FSAL derivative at the step end
    /// (`k[16]`) and, once the interpolant is built, its four extra stages; err^(−1/9) by
    /// [`crate::trig::inv_ninth_root`].
    Vern9,
    vern9,
    crate::trig::inv_ninth_root,
    [1 2 3 4 5 6 7 8 9 10 11 12 13 14 15],
    [0 1 2 3]
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::pair::RkPair;
    use crate::ode::{OdeSystem, State};

    #[test]
    fn one_step_of_a_quadrature_is_9th_order_and_dense_8th() {
        let [(e0, d0, nfev, degree), (e1, d1, ..)] =
            [1.6, 0.8].map(super::super::testing::quadrature_step::<Vern9<1>>);
        assert_eq!((nfev, degree), ([16, 20], 8));
        // Local error O(h^10) for the step, O(h^9) for the interpolant: halving h divides
        // them by 2^10 = 1024 and 2^9 = 512 (loosely: by more than 600 and 300).
        assert!(e0 < 1e-8 && e0 / e1.max(1e-300) > 600.0, "{e0} {e1}");
        assert!(d0 < 1e-7 && d0 / d1 > 300.0, "{d0} {d1}");
    }

    /// y' = y², y(0) = 1/2 (y = 1/(2 − t)): every elementary differential is there; the step
    /// is 9th order (local error O(h^10)) and the error estimate 8th order (O(h^9)).
    #[test]
    fn one_step_of_a_nonlinear_equation_is_9th_order_with_an_8th_order_estimate() {
        struct Square;
        impl OdeSystem<1> for Square {
            fn rhs(&self, _t: f64, y: &State<1>) -> State<1> {
                State::<1>::new(y[0] * y[0])
            }
        }
        let (mut errs, mut estimates) = (Vec::new(), Vec::new());
        for h in [0.6, 0.3] {
            let mut nfev = 0;
            let mut pair = Vern9::<1>::empty();
            let y = State::<1>::new(0.5);
            let y_new = pair
                .attempt(&Square, 0.0, &y, &State::<1>::new(0.25), h, &mut nfev)
                .unwrap()
                .0;
            errs.push((y_new[0] - 1.0 / (2.0 - h)).abs());
            // With rtol = 1 and atol = 0 the norm is |error estimate| / |y_new|.
            estimates.push(pair.error_norm(h, &y, &y_new, 1.0, 0.0) * y_new[0]);
        }
        let ratio = |v: &[f64]| v[0] / v[1].max(1e-300);
        // At least 2^10 = 1024 and 2^9 = 512 (loosely): here both fall faster still, their
        // leading coefficients being small for this equation (measured 1.6e4 and 1.8e4),
        // which the order conditions (`ode::tableau`) pin down exactly. The estimate bounds
        // the error from above, as an error estimate of lower order should.
        assert!(ratio(&errs) > 600.0 && errs[0] < 1e-9, "{errs:?}");
        assert!(ratio(&estimates) > 300.0, "{estimates:?}");
        assert!(
            estimates[0] > errs[0] && estimates[1] > errs[1],
            "{errs:?} {estimates:?}"
        );
    }
}

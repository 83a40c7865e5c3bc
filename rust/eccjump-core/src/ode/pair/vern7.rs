//! Verner's most efficient 7(6) pair: 10 stages (9 evaluations of f, plus f at the step end,
//! which the next step begins with), scipy's error norm of the 6th-order estimate, and the
//! 7th-degree interpolant from five extra stages. At tolerances of 1e-8 … 1e-11 it reaches a
//! given accuracy with fewer evaluations than DOP853 (12 per step) on smooth problems. Its
//! step control is scipy's but for the safety factor and the first step
//! (`verner_pair!` in `pair/verner.rs`).

super::verner::verner_pair!(
    /// The stages of one Verner 7(6) step: 10 stages, the FSAL derivative at the step end
    /// (`k[10]`) and, once the interpolant is built, its five extra stages; err^(−1/7) by
    /// [`crate::trig::inv_seventh_root`].
    Vern7,
    vern7,
    crate::trig::inv_seventh_root,
    [1 2 3 4 5 6 7 8 9],
    [0 1 2 3 4]
);

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::pair::RkPair;
    use crate::ode::{OdeSystem, State};

    #[test]
    fn one_step_of_a_quadrature_is_7th_order_and_dense_7th() {
        let [(e0, d0, nfev, degree), (e1, d1, ..)] =
            [0.8, 0.4].map(super::super::testing::quadrature_step::<Vern7<1>>);
        assert_eq!((nfev, degree), ([10, 15], 7));
        // Local error O(h^8) for the step and the interpolant: halving h divides them by
        // 2^8 = 256 (loosely: by more than 150; smaller steps reach rounding).
        assert!(e0 < 1e-9 && e0 / e1.max(1e-300) > 150.0, "{e0} {e1}");
        assert!(d0 < 1e-9 && d0 / d1 > 150.0, "{d0} {d1}");
    }

    /// y' = y², y(0) = 1 (y = 1/(1 − t)): a nonlinear equation, so every tree's elementary
    /// differential is there, not only the quadrature's; the step is 7th order (local
    /// error O(h^8)) and the error estimate 6th order (O(h^7)).
    #[test]
    fn one_step_of_a_nonlinear_equation_is_7th_order_with_a_6th_order_estimate() {
        struct Square;
        impl OdeSystem<1> for Square {
            fn rhs(&self, _t: f64, y: &State<1>) -> State<1> {
                State::<1>::new(y[0] * y[0])
            }
        }
        let (mut errs, mut estimates, mut dense_errs) = (Vec::new(), Vec::new(), Vec::new());
        for h in [0.1, 0.05] {
            let mut nfev = 0;
            let mut pair = Vern7::<1>::empty();
            let y = State::<1>::new(1.0);
            let y_new = pair
                .attempt(&Square, 0.0, &y, &State::<1>::new(1.0), h, &mut nfev)
                .unwrap();
            errs.push((y_new[0] - 1.0 / (1.0 - h)).abs());
            // With rtol = 1 and atol = 0 the norm is |error estimate| / |y_new|.
            estimates.push(pair.error_norm(h, &y, &y_new, 1.0, 0.0) * y_new[0]);
            let d = pair.dense(&Square, 0.0, h, &y, &y_new, &mut nfev).unwrap();
            dense_errs.push(
                (1..20)
                    .map(|i| {
                        let t = h * i as f64 / 20.0;
                        (d.eval(t)[0] - 1.0 / (1.0 - t)).abs()
                    })
                    .fold(0.0, f64::max),
            );
        }
        let ratio = |v: &[f64]| v[0] / v[1].max(1e-300);
        // 2^8 = 256 and 2^7 = 128, loosely (the step's error falls faster still: its
        // leading coefficient is small here and changes sign near h = 0.02).
        assert!(ratio(&errs) > 180.0 && errs[0] < 1e-11, "{errs:?}");
        assert!((90.0..200.0).contains(&ratio(&estimates)), "{estimates:?}");
        assert!(ratio(&dense_errs) > 150.0, "{dense_errs:?}");
        // The estimate is of the 6th-order solution's error: it exceeds the 7th's.
        assert!(estimates[0] > errs[0], "{estimates:?} {errs:?}");
    }
}

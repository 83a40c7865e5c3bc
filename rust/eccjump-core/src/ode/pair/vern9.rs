//! Verner's most efficient 9(8) pair: 16 stages (15 evaluations of f, plus f at the step end,
//! which the next step begins with), scipy's error norm of the 8th-order estimate, and the
//! 8th-degree interpolant from four extra stages (built only where a step's ends cannot
//! clear it of events): the fastest pair at the default tolerances (`docs/performance.md`).
//!
//! Its step control is scipy's but for two constants (no scipy steps to keep, unlike RK45
//! and DOP853):
//! - safety 0.75, not scipy's 0.9: with 0.9 a quarter to a third of the steps of a rolling
//!   run are rejected (the error constant changes quickly along a turn); 0.75 reaches the
//!   same accuracy with 10–25 % fewer evaluations (Python models of the pairs over rolling
//!   runs, rtol 3e-7 … 3e-13);
//! - a first step probed up to three times: from rest scipy's first step is 1e-4, and four
//!   steps pass before the step reaches its size.

use super::{all_finite, unrolled_stages, weighted_sum};
use super::{RkPair, Summand};
use crate::ode::dense::MAX_DEGREE;
use crate::ode::tableau::vern9::{A_EXTRA, C_EXTRA, E, N_STAGES, N_STAGES_EXTENDED, R};
use crate::ode::{DenseStep, OdeSystem, State};

/// The stages of one Verner 9(8) step: 16 stages, the FSAL derivative at the step end
/// (`k[16]`) and, once the interpolant is built, its four extra stages.
#[derive(Debug, Clone, Copy)]
pub struct Vern9<const N: usize> {
    /// The stages: the step's, f at its end (`k[N_STAGES]`) and, once the interpolant is
    /// built, its extra ones.
    pub k: [State<N>; N_STAGES_EXTENDED],
}

impl<const N: usize> RkPair<N> for Vern9<N> {
    super::tableau_members!(vern9; 1 2 3 4 5 6 7 8 9 10 11 12 13 14 15);
    const SAFETY: f64 = 0.75;
    const FIRST_STEP_PROBES: usize = 3;

    /// err^(−1/9) without `pow`, to the relative error of a quartic fit (below 1e-5:
    /// [`crate::trig::inv_ninth_root`]), enough for a step-size factor.
    #[inline]
    fn error_power(err: f64) -> f64 {
        crate::trig::inv_ninth_root(err)
    }

    /// (d/0.01)^ERROR_EXPONENT by `error_power`: the probes' three `pow` calls were 4 % of
    /// a short run.
    #[inline]
    fn first_step_power(d: f64) -> f64 {
        Self::error_power(d / 0.01)
    }

    /// The error estimate Σ (b_j − b̂_j) K_j (the second sum is not used).
    #[inline(always)]
    fn error_sums<V: Summand>(k: &[V]) -> [V; 2] {
        [weighted_sum(&k[..=N_STAGES], &E), V::zero()]
    }

    /// The extra stages, then `dense_from_stages`.
    fn dense<S: OdeSystem<N>>(
        &mut self,
        sys: &S,
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        y_new: &State<N>,
        nfev: &mut usize,
    ) -> Option<DenseStep<N>> {
        let at = (t_old, y_old, h);
        let k = &mut self.k;
        unrolled_stages!(sys, at, k, nfev, N_STAGES + 1, (A_EXTRA, C_EXTRA); 0 1 2 3);
        self.dense_from_stages(t_old, h, y_old, y_new)
    }

    /// The coefficients Σ_i R_ji K_i of σ^(j+1), one per row of R (before the factor h);
    /// zero above the pair's degree.
    #[inline(always)]
    fn dense_sums<V: Summand>(k: &[V]) -> [V; MAX_DEGREE] {
        std::array::from_fn(|j| R.get(j).map_or(V::zero(), |r| weighted_sum(k, r)))
    }

    /// The interpolant is already in powers of σ: y(σ) = y_old + h Σ_j Q_j σ^(j+1).
    #[inline]
    fn dense_from_sums(
        q: &[State<N>; MAX_DEGREE],
        _ends: (&State<N>, &State<N>),
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        _y_new: &State<N>,
    ) -> Option<DenseStep<N>> {
        let dense = DenseStep::from_powers(t_old, h, *y_old, &q[..R.len()]);
        dense.q.iter().all(all_finite).then_some(dense)
    }
}

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

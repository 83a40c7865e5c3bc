//! Verner's most efficient 7(6) pair: 10 stages (9 evaluations of f, plus f at the step end,
//! which the next step begins with), scipy's error norm of the 6th-order estimate, and the
//! 7th-degree interpolant from five extra stages. At tolerances of 1e-8 … 1e-11 it reaches a
//! given accuracy with fewer evaluations than DOP853 (12 per step) on smooth problems. Its
//! step control is scipy's but for the safety factor and the first step (below): no scipy
//! steps to keep, unlike RK45 and DOP853.

use super::{scaled_error_norm, solution, unrolled_stages, weighted_sum, RkPair, Summand};
use crate::ode::dense::MAX_DEGREE;
use crate::ode::tableau::vern7::{
    A, A_EXTRA, B, C, C_EXTRA, E, ERROR_EXPONENT, N_STAGES, N_STAGES_EXTENDED, R,
};
use crate::ode::{DenseStep, OdeSystem, State};

/// The stages of one Verner 7(6) step: 10 stages, the FSAL derivative at the step end
/// (`k[10]`) and, once the interpolant is built, its five extra stages.
#[derive(Debug, Clone, Copy)]
pub struct Vern7<const N: usize> {
    /// Stages 0..=15.
    pub k: [State<N>; N_STAGES_EXTENDED],
}

impl<const N: usize> RkPair<N> for Vern7<N> {
    const ERROR_EXPONENT: f64 = ERROR_EXPONENT;

    /// Not scipy's 0.9: with 0.9 a quarter to a third of the steps of a rolling run are
    /// rejected (the error constant changes quickly along a turn); 0.75 reaches the same
    /// accuracy with 5–10 % fewer evaluations (39 rolling runs, rtol 3e-7 … 3e-12).
    const SAFETY: f64 = 0.75;

    /// From rest scipy's first step is 1e-4, and four steps pass before the step reaches
    /// its size; two more probes of the first-step estimate save most of them.
    const FIRST_STEP_PROBES: usize = 3;

    /// err^(−1/7) without `pow` ([`crate::trig::inv_seventh_root`], within 4 ulp of it).
    #[inline]
    fn error_power(err: f64) -> f64 {
        crate::trig::inv_seventh_root(err)
    }

    /// (d/0.01)^(−1/7) by [`Self::error_power`]: the probes' three `pow` calls were 4 % of
    /// a short run.
    #[inline]
    fn first_step_power(d: f64) -> f64 {
        Self::error_power(d / 0.01)
    }

    #[inline]
    fn empty() -> Self {
        Self {
            k: [State::<N>::zeros(); N_STAGES_EXTENDED],
        }
    }

    /// 10 evaluations of f when it succeeds (stages 1 … 9 and f at y_new).
    #[inline]
    fn attempt<S: OdeSystem<N>>(
        &mut self,
        sys: &S,
        t: f64,
        y: &State<N>,
        f: &State<N>,
        h: f64,
        nfev: &mut usize,
    ) -> Option<State<N>> {
        let k = &mut self.k;
        k[0] = *f;
        let at = (t, y, h);
        unrolled_stages!(sys, at, k, nfev, 0, (A, C); 1 2 3 4 5 6 7 8 9);
        solution(sys, at, k, &B, nfev)
    }

    /// The error estimate Σ (b_j − b̂_j) K_j (the second sum is not used).
    #[inline(always)]
    fn error_sums<V: Summand>(k: &[V]) -> [V; 2] {
        [weighted_sum(&k[..=N_STAGES], &E), V::zero()]
    }

    #[inline]
    fn error_from_sums(
        [sum, _]: &[State<N>; 2],
        h: f64,
        y: &State<N>,
        y_new: &State<N>,
        rtol: f64,
        atol: f64,
    ) -> f64 {
        scaled_error_norm(sum, h, y, y_new, rtol, atol)
    }

    #[inline]
    fn f_new(&self) -> State<N> {
        self.k[N_STAGES]
    }

    /// Five more stages, then [`Self::dense_from_stages`].
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
        unrolled_stages!(sys, at, k, nfev, N_STAGES + 1, (A_EXTRA, C_EXTRA); 0 1 2 3 4);
        self.dense_from_stages(t_old, h, y_old, y_new)
    }

    const STAGES: usize = N_STAGES;
    const EXTRA: usize = N_STAGES_EXTENDED - N_STAGES - 1;

    #[inline(always)]
    fn a(s: usize) -> &'static [f64] {
        &A[s]
    }

    #[inline(always)]
    fn b() -> &'static [f64] {
        &B
    }

    #[inline(always)]
    fn a_extra(i: usize) -> &'static [f64] {
        &A_EXTRA[i]
    }

    #[inline(always)]
    fn stages(&self) -> &[State<N>] {
        &self.k
    }

    /// The coefficients Σ_i R_ji K_i of σ^(j+1), j = 0 … 6 (before the factor h).
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
        dense.q.iter().all(super::all_finite).then_some(dense)
    }
}

#[cfg(test)]
mod tests {
    use super::*;

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

//! Dormand–Prince 5(4) (scipy's `RK45`): `rk_step`, the error norm and `RkDenseOutput`,
//! operation by operation as scipy, so that accepted steps agree with scipy's to rounding.

use super::{weighted_sum, RkPair, Summand};
use crate::ode::dense::MAX_DEGREE;
use crate::ode::tableau::dp5::{E, N_STAGES, P};
use crate::ode::{DenseStep, OdeSystem, State};

/// The stages of one Dormand–Prince 5(4) step; `k[6]` is the FSAL derivative at its end.
#[derive(Debug, Clone, Copy)]
pub struct Dp5<const N: usize> {
    /// The 6 stages and f(t + h, y_new).
    pub k: [State<N>; N_STAGES + 1],
}

impl<const N: usize> RkPair<N> for Dp5<N> {
    super::tableau_members!(dp5; 1 2 3 4 5);

    /// err^(−1/5) without `pow` ([`crate::trig::inv_fifth_root`], within 4 ulp of it).
    #[inline]
    fn error_power(err: f64) -> f64 {
        crate::trig::inv_fifth_root(err)
    }

    /// The error estimate Σ E_j K_j (the second sum is not used).
    #[inline(always)]
    fn error_sums<V: Summand>(k: &[V]) -> [V; 2] {
        [weighted_sum(&k[..=N_STAGES], &E), V::zero()]
    }

    /// scipy's `RkDenseOutput`: Q = Kᵀ P, no evaluation of f.
    #[inline]
    fn dense<S: OdeSystem<N>>(
        &mut self,
        _sys: &S,
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        y_new: &State<N>,
        _nfev: &mut usize,
    ) -> Option<DenseStep<N>> {
        self.dense_from_stages(t_old, h, y_old, y_new)
    }

    /// scipy's `RkDenseOutput`: Q = Kᵀ P, summed stage after stage.
    #[inline(always)]
    fn dense_sums<V: Summand>(k: &[V]) -> [V; MAX_DEGREE] {
        // Each sum in the same order as one at a time, all four in one pass over the
        // stages (a closure per sum was not inlined for lanes of five components).
        let mut q = [V::zero(); MAX_DEGREE];
        for (ki, pi) in k[..=N_STAGES].iter().zip(P.iter()) {
            for (qj, pij) in q.iter_mut().zip(pi) {
                *qj = *qj + *ki * *pij;
            }
        }
        q
    }

    #[inline]
    fn dense_from_sums(
        q: &[State<N>; MAX_DEGREE],
        _ends: (&State<N>, &State<N>),
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        _y_new: &State<N>,
    ) -> Option<DenseStep<N>> {
        Some(DenseStep::from_powers(t_old, h, *y_old, &q[..P[0].len()]))
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_step_of_linear_growth_is_exact() {
        // y' = 1 is integrated exactly by any consistent method (up to the rounding of
        // Σ b_i), with an error estimate at rounding level.
        struct One;
        impl OdeSystem<1> for One {
            fn rhs(&self, _t: f64, _y: &State<1>) -> State<1> {
                State::<1>::new(1.0)
            }
        }
        let mut nfev = 0;
        let mut pair = Dp5::<1>::empty();
        let y = State::<1>::new(2.0);
        let y_new = pair.attempt(&One, 0.0, &y, &State::<1>::new(1.0), 0.5, &mut nfev);
        let (y_new, _) = y_new.unwrap();
        assert!((y_new[0] - 2.5).abs() < 1e-15);
        assert_eq!(nfev, 6);
        assert!(pair.error_norm(0.5, &y, &y_new, 1e-6, 1e-9) < 1e-8);
    }
}

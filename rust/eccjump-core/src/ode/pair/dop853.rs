//! Dormand–Prince 8(5,3) (scipy's `DOP853`): 12 stages, the combined 5th/3rd-order error
//! norm of Hairer's code, and the 7th-degree dense output from three extra stages.

use super::{all_finite, error_scale, unrolled_stages, weighted_sum, RkPair, Summand};
use crate::ode::dense::MAX_DEGREE;
use crate::ode::tableau::dop853::{A_EXTRA, C_EXTRA, D, E3, E5, N_STAGES, N_STAGES_EXTENDED};
use crate::ode::{DenseStep, OdeSystem, State};

/// The stages of one DOP853 step: 12 stages, the FSAL derivative at the step end
/// (`k[12]`) and, once the dense output is built, its three extra stages.
#[derive(Debug, Clone, Copy)]
pub struct Dop853<const N: usize> {
    /// Stages 0..=15.
    pub k: [State<N>; N_STAGES_EXTENDED],
}

impl<const N: usize> RkPair<N> for Dop853<N> {
    super::tableau_members!(dop853; 1 2 3 4 5 6 7 8 9 10 11);

    /// err^(−1/8) by three square roots (each correctly rounded, so portable to the last
    /// bit) instead of `pow`, which costs as much as a few stages.
    #[inline]
    fn error_power(err: f64) -> f64 {
        1.0 / err.sqrt().sqrt().sqrt()
    }

    /// The 5th- and 3rd-order error estimates Σ E5_j K_j and Σ E3_j K_j.
    #[inline(always)]
    fn error_sums<V: Summand>(k: &[V]) -> [V; 2] {
        let k = &k[..=N_STAGES];
        [weighted_sum(k, &E5), weighted_sum(k, &E3)]
    }

    /// scipy's `DOP853._estimate_error_norm`: the 5th-order estimate, damped by the
    /// 3rd-order one, |h| ‖e5‖² / √((‖e5‖² + 0.01 ‖e3‖²) N) (Hairer's `err`).
    #[inline]
    fn error_from_sums(
        [e5, e3]: &[State<N>; 2],
        h: f64,
        y: &State<N>,
        y_new: &State<N>,
        rtol: f64,
        atol: f64,
    ) -> f64 {
        let scale = error_scale(y, y_new, rtol, atol);
        let err5 = e5.component_div(&scale);
        let err3 = e3.component_div(&scale);
        let e5 = err5.dot(&err5);
        let e3 = err3.dot(&err3);
        if e5 == 0.0 && e3 == 0.0 {
            return 0.0;
        }
        let denom = e5 + 0.01 * e3;
        h.abs() * e5 / (denom * N as f64).sqrt()
    }

    /// scipy's `_dense_output_impl` and `Dop853DenseOutput`: three more stages, then
    /// [`Self::dense_from_stages`].
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
        unrolled_stages!(sys, at, k, nfev, N_STAGES + 1, (A_EXTRA, C_EXTRA); 0 1 2);
        self.dense_from_stages(t_old, h, y_old, y_new)
    }

    /// The sums Σ D_ij K_j of the dense output's F3 … F6 (before the factor h).
    #[inline(always)]
    fn dense_sums<V: Summand>(k: &[V]) -> [V; MAX_DEGREE] {
        let mut sums = [V::zero(); MAX_DEGREE];
        for (s, d) in sums.iter_mut().zip(&D) {
            *s = weighted_sum(k, d);
        }
        sums
    }

    /// y(σ) = y_old + σ(F0 + (1−σ)(F1 + σ(F2 + (1−σ)(F3 + σ(F4 + (1−σ)(F5 + σF6)))))),
    /// expanded into powers of σ (the form every dense step shares).
    #[inline]
    fn dense_from_sums(
        sums: &[State<N>; MAX_DEGREE],
        (f_old, f_new): (&State<N>, &State<N>),
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        y_new: &State<N>,
    ) -> Option<DenseStep<N>> {
        let delta = y_new - y_old;
        let mut f = [State::<N>::zeros(); DEGREE];
        f[0] = delta;
        f[1] = f_old * h - delta;
        f[2] = delta * 2.0 - (f_new + f_old) * h;
        for (fi, si) in f[3..].iter_mut().zip(sums) {
            *fi = si * h;
        }
        let q: [State<N>; DEGREE] = powers(&f).map(|pj| pj / h);
        let dense = DenseStep::from_powers(t_old, h, *y_old, &q);
        dense.q.iter().all(all_finite).then_some(dense)
    }
}

/// Degree of DOP853's dense output.
const DEGREE: usize = 7;

/// scipy's nested form σ(F0 + (1−σ)(F1 + σ(F2 + (1−σ)(F3 + σ(F4 + (1−σ)(F5 + σF6))))))
/// as the coefficients p_1 … p_7 of σ^1 … σ^7:
/// p1 = F0 + F1, p2 = −F1 + F2 + F3, p3 = −F2 − 2F3 + F4 + F5, p4 = F3 − 2F4 − 3F5 + F6,
/// p5 = F4 + 3F5 − 3F6, p6 = −F5 + 3F6, p7 = −F6 (expanded once per step, so the scan's
/// samples cost a Horner sum each).
#[inline]
fn powers<const N: usize>(f: &[State<N>; DEGREE]) -> [State<N>; DEGREE] {
    let [f0, f1, f2, f3, f4, f5, f6] = *f;
    [
        f0 + f1,
        f2 - f1 + f3,
        (f4 - f2) + (f5 - f3 * 2.0),
        (f3 + f6) - (f4 * 2.0 + f5 * 3.0),
        f4 + (f5 - f6) * 3.0,
        f6 * 3.0 - f5,
        -f6,
    ]
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn one_step_of_a_quadrature_is_8th_order_and_dense_7th() {
        let [(e0, d0, nfev, degree), (e1, d1, ..)] =
            [0.4, 0.2].map(super::super::testing::quadrature_step::<Dop853<1>>);
        assert_eq!((nfev, degree), ([12, 15], 7));
        // Local error O(h^9) for the step, O(h^8) for the interpolant: halving h divides
        // them by 2^9 = 512 and 2^8 = 256 (loosely: by more than 200 and 100).
        assert!(e0 < 1e-11 && e0 / e1.max(1e-300) > 200.0, "{e0} {e1}");
        assert!(d0 < 1e-9 && d0 / d1 > 100.0, "{d0} {d1}");
    }

    #[test]
    fn powers_are_the_nested_form() {
        let mut x = 0.3f64;
        let mut next = || {
            x = (x * 7.31 + 0.17).fract();
            2.0 * x - 1.0
        };
        for _ in 0..200 {
            let f: [State<1>; DEGREE] = std::array::from_fn(|_| State::<1>::new(next()));
            let p = powers(&f);
            for i in 0..=10 {
                let s = i as f64 / 10.0;
                let v = 1.0 - s;
                let g = |i: usize| f[i][0];
                let nested = s
                    * (g(0)
                        + v * (g(1)
                            + s * (g(2) + v * (g(3) + s * (g(4) + v * (g(5) + s * g(6)))))));
                let sum: f64 = (0..DEGREE).map(|j| p[j][0] * s.powi(j as i32 + 1)).sum();
                assert!((nested - sum).abs() < 1e-14, "{nested} {sum}");
            }
        }
    }

    #[test]
    fn error_norm_is_zero_for_a_constant_and_small_for_a_line() {
        struct Line;
        impl OdeSystem<1> for Line {
            fn rhs(&self, _t: f64, _y: &State<1>) -> State<1> {
                State::<1>::new(2.0)
            }
        }
        let mut nfev = 0;
        let mut pair = Dop853::<1>::empty();
        let y = State::<1>::new(1.0);
        let y_new = pair
            .attempt(&Line, 0.0, &y, &State::<1>::new(2.0), 0.5, &mut nfev)
            .unwrap()
            .0;
        assert!((y_new[0] - 2.0).abs() < 1e-15);
        assert!(pair.error_norm(0.5, &y, &y_new, 1e-6, 1e-9) < 1e-6);
    }
}

//! A Verner pair (today Vern9 alone; Vern7 was removed, `docs/performance.md`): the stages
//! of a step with f at its end (which the next step begins with), scipy's error norm of the
//! one embedded estimate, the interpolant from extra stages (built only where a step's ends
//! cannot clear it of events), and its own step control, as [`verner_pair!`] over its
//! tableau module.

/// The Verner pair `$name` over the tableau module `$tab` (`crate::ode::tableau::$tab`: A,
/// B, C, E, R, A_EXTRA, C_EXTRA and the sizes), with err^ERROR_EXPONENT by `$root` and the
/// literal indices of its stages after the first (`[1 2 …]`) and of its extra stages
/// (`[0 1 …]`), so that each stage's weighted sum is unrolled.
///
/// Their step control is scipy's but for two constants (no scipy steps to keep, unlike
/// RK45 and DOP853):
/// - safety 0.75, not scipy's 0.9: with 0.9 a quarter to a third of the steps of a rolling
///   run are rejected (the error constant changes quickly along a turn); 0.75 reaches the
///   same accuracy with 10–25 % fewer evaluations (Python models
///   of the pairs over rolling runs, rtol 3e-7 … 3e-13);
/// - a first step probed up to three times: from rest scipy's first step is 1e-4, and four
///   steps pass before the step reaches its size.
macro_rules! verner_pair {
    ($(#[$doc:meta])* $name:ident, $tab:ident, $root:path,
     [$($s:literal)*], [$($x:literal)*]) => {
        $(#[$doc])*
        #[derive(Debug, Clone, Copy)]
        pub struct $name<const N: usize> {
            /// The stages: the step's, f at its end (`k[N_STAGES]`) and, once the
            /// interpolant is built, its extra ones.
            pub k: [$crate::ode::State<N>; $crate::ode::tableau::$tab::N_STAGES_EXTENDED],
        }

        impl<const N: usize> $crate::ode::pair::RkPair<N> for $name<N> {
            const ERROR_EXPONENT: f64 = $crate::ode::tableau::$tab::ERROR_EXPONENT;
            const SAFETY: f64 = 0.75;
            const FIRST_STEP_PROBES: usize = 3;

            /// err^ERROR_EXPONENT without `pow`, to the relative error of a quartic fit (below
            /// 1e-5: `crate::trig::inv_ninth_root`), enough for a step-size factor.
            #[inline]
            fn error_power(err: f64) -> f64 {
                $root(err)
            }

            /// (d/0.01)^ERROR_EXPONENT by `error_power`: the probes' three `pow`
            /// calls were 4 % of a short run.
            #[inline]
            fn first_step_power(d: f64) -> f64 {
                Self::error_power(d / 0.01)
            }

            #[inline]
            fn empty() -> Self {
                Self {
                    k: [$crate::ode::State::<N>::zeros();
                        $crate::ode::tableau::$tab::N_STAGES_EXTENDED],
                }
            }

            /// N_STAGES evaluations of f when it succeeds (stages 1 … N_STAGES − 1 and f at
            /// y_new).
            #[inline]
            fn attempt<S: $crate::ode::OdeSystem<N>>(
                &mut self,
                sys: &S,
                t: f64,
                y: &$crate::ode::State<N>,
                f: &$crate::ode::State<N>,
                h: f64,
                nfev: &mut usize,
            ) -> Option<($crate::ode::State<N>, Option<$crate::ode::SinCos>)> {
                use $crate::ode::tableau::$tab::{A, B, C};
                let k = &mut self.k;
                k[0] = *f;
                let at = (t, y, h);
                $crate::ode::pair::unrolled_stages!(sys, at, k, nfev, 0, (A, C); $($s)*);
                $crate::ode::pair::solution(sys, at, k, &B, nfev)
            }

            /// The error estimate Σ (b_j − b̂_j) K_j (the second sum is not used).
            #[inline(always)]
            fn error_sums<V: $crate::ode::pair::Summand>(k: &[V]) -> [V; 2] {
                use $crate::ode::tableau::$tab::{E, N_STAGES};
                [$crate::ode::pair::weighted_sum(&k[..=N_STAGES], &E), V::zero()]
            }

            #[inline]
            fn error_from_sums(
                [sum, _]: &[$crate::ode::State<N>; 2],
                h: f64,
                y: &$crate::ode::State<N>,
                y_new: &$crate::ode::State<N>,
                rtol: f64,
                atol: f64,
            ) -> f64 {
                $crate::ode::pair::scaled_error_norm(sum, h, y, y_new, rtol, atol)
            }

            #[inline]
            fn f_new(&self) -> $crate::ode::State<N> {
                self.k[$crate::ode::tableau::$tab::N_STAGES]
            }

            /// The extra stages, then `dense_from_stages`.
            fn dense<S: $crate::ode::OdeSystem<N>>(
                &mut self,
                sys: &S,
                t_old: f64,
                h: f64,
                y_old: &$crate::ode::State<N>,
                y_new: &$crate::ode::State<N>,
                nfev: &mut usize,
            ) -> Option<$crate::ode::DenseStep<N>> {
                use $crate::ode::tableau::$tab::{A_EXTRA, C_EXTRA, N_STAGES};
                let at = (t_old, y_old, h);
                let k = &mut self.k;
                $crate::ode::pair::unrolled_stages!(
                    sys, at, k, nfev, N_STAGES + 1, (A_EXTRA, C_EXTRA); $($x)*
                );
                self.dense_from_stages(t_old, h, y_old, y_new)
            }

            const STAGES: usize = $crate::ode::tableau::$tab::N_STAGES;
            const EXTRA: usize = $crate::ode::tableau::$tab::N_STAGES_EXTENDED
                - $crate::ode::tableau::$tab::N_STAGES
                - 1;

            #[inline(always)]
            fn a(s: usize) -> &'static [f64] {
                &$crate::ode::tableau::$tab::A[s]
            }

            #[inline(always)]
            fn b() -> &'static [f64] {
                &$crate::ode::tableau::$tab::B
            }

            #[inline(always)]
            fn a_extra(i: usize) -> &'static [f64] {
                &$crate::ode::tableau::$tab::A_EXTRA[i]
            }

            #[inline(always)]
            fn stages(&self) -> &[$crate::ode::State<N>] {
                &self.k
            }

            /// The coefficients Σ_i R_ji K_i of σ^(j+1), one per row of R (before the
            /// factor h); zero above the pair's degree.
            #[inline(always)]
            fn dense_sums<V: $crate::ode::pair::Summand>(
                k: &[V],
            ) -> [V; $crate::ode::dense::MAX_DEGREE] {
                use $crate::ode::tableau::$tab::R;
                std::array::from_fn(|j| {
                    R.get(j)
                        .map_or(V::zero(), |r| $crate::ode::pair::weighted_sum(k, r))
                })
            }

            /// The interpolant is already in powers of σ: y(σ) = y_old + h Σ_j Q_j σ^(j+1).
            #[inline]
            fn dense_from_sums(
                q: &[$crate::ode::State<N>; $crate::ode::dense::MAX_DEGREE],
                _ends: (&$crate::ode::State<N>, &$crate::ode::State<N>),
                t_old: f64,
                h: f64,
                y_old: &$crate::ode::State<N>,
                _y_new: &$crate::ode::State<N>,
            ) -> Option<$crate::ode::DenseStep<N>> {
                let degree = $crate::ode::tableau::$tab::R.len();
                let dense = $crate::ode::DenseStep::from_powers(t_old, h, *y_old, &q[..degree]);
                dense
                    .q
                    .iter()
                    .all($crate::ode::pair::all_finite)
                    .then_some(dense)
            }
        }
    };
}
pub(crate) use verner_pair;

//! Embedded Runge–Kutta pairs: the stages of one step, its error norm and its dense output.
//! The step-size control ([`crate::ode::stepper`]) and the driver ([`crate::ode::solver`])
//! are the same for every pair; they see a pair only through [`RkPair`].

pub mod dop853;
pub mod dp5;
pub mod vern9;

pub use dop853::Dop853;
pub use dp5::Dp5;
pub use vern9::Vern9;

use super::dense::MAX_DEGREE;

/// The most stages any pair keeps: its own, f at the step end and the dense output's extra
/// ones (Vern9's 21; DOP853 keeps 16, RK45 7).
pub const MAX_STAGES: usize = {
    use super::tableau::{dop853, vern9};
    let (a, b) = (dop853::N_STAGES_EXTENDED, vern9::N_STAGES_EXTENDED);
    if a > b {
        a
    } else {
        b
    }
};
use super::{DenseStep, OdeSystem, SinCos, State};

named_enum! {
    /// Which pair an integration uses; its name is scipy's "RK45" or "DOP853", or Verner's
    /// "Vern9".
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Default)]
    pub enum Integrator {
        /// Dormand–Prince 5(4) with its 4th-degree dense output (scipy's `RK45`): the default,
        /// step for step as scipy.
        #[default]
        Rk45 = 0 => "RK45",
        /// Dormand–Prince 8(5,3) with its 7th-degree dense output (scipy's `DOP853`): fewer
        /// steps at tight tolerances.
        Dop853 = 1 => "DOP853",
        /// Verner's most efficient 9(8) pair with its 8th-degree interpolant (`Vern9` as in
        /// DifferentialEquations.jl): the fastest pair at the default tolerances
        /// (`docs/performance.md`).
        Vern9 = 2 => "Vern9",
    }
}

impl Integrator {
    /// The pair named `name` (see [`Integrator::name`]).
    pub fn from_name(name: &str) -> Option<Integrator> {
        Integrator::ALL.into_iter().find(|m| m.name() == name)
    }
}

/// One embedded pair with room for its stages (kept between the attempt of a step, its
/// error norm and its dense output, so nothing is recomputed or allocated).
pub trait RkPair<const N: usize>: Copy {
    /// The step-size exponent −1/(q + 1), q the order of the error estimator.
    const ERROR_EXPONENT: f64;

    /// The margin by which the step-size factor multiplies err^ERROR_EXPONENT (scipy's
    /// `SAFETY`, 0.9, unless the pair has its own). Here, not in [`super::stepper`], which
    /// reads it from the pair, so that the pairs do not depend on the step-size control.
    const SAFETY: f64 = 0.9;

    /// Evaluations of f the first-step selection may make (scipy's: 1; see
    /// [`super::stepper::select_initial_step`]).
    const FIRST_STEP_PROBES: usize = 1;

    /// err^ERROR_EXPONENT, the heart of the step-size factor (each pair computes it without
    /// `pow`, whose latency is that of several stages).
    fn error_power(err: f64) -> f64;

    /// (0.01/d)^(−ERROR_EXPONENT), the first-step estimate from d = max(d1, d2)
    /// ([`super::stepper::select_initial_step`]): by `pow`, as scipy's `**`, so that RK45
    /// and DOP853 take scipy's first step to the last bit, unless the pair has its own.
    #[inline]
    fn first_step_power(d: f64) -> f64 {
        crate::trig::pow(0.01 / d, -Self::ERROR_EXPONENT)
    }

    /// A pair with zeroed stages.
    fn empty() -> Self;

    /// One step of size h from (t, y) with f = f(t, y): returns y_new with the sine and
    /// cosine of y_new[0] if the FSAL evaluation computed them
    /// ([`OdeSystem::rhs_with_trig`]), and keeps the stages, including the FSAL derivative
    /// f(t + h, y_new); `None` as soon as a stage or y_new is not finite. `nfev` counts the
    /// evaluations of f made.
    fn attempt<S: OdeSystem<N>>(
        &mut self,
        sys: &S,
        t: f64,
        y: &State<N>,
        f: &State<N>,
        h: f64,
        nfev: &mut usize,
    ) -> Option<(State<N>, Option<SinCos>)>;

    /// The scaled error norm of the last attempt (scipy's `_estimate_error_norm`, with
    /// the scale atol + rtol max(|y|, |y_new|) per component).
    #[inline]
    fn error_norm(&self, h: f64, y: &State<N>, y_new: &State<N>, rtol: f64, atol: f64) -> f64 {
        let sums = Self::error_sums(self.stages());
        Self::error_from_sums(&sums, h, y, y_new, rtol, atol)
    }

    /// The weighted sums of the stages K_0 … K_STAGES that the error norm is made of (for
    /// one state, or for lanes).
    fn error_sums<V: Summand>(k: &[V]) -> [V; 2];

    /// The error norm from [`Self::error_sums`]: scipy's norm of the one estimate (DOP853
    /// combines its two).
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

    /// f(t + h, y_new) of the last attempt.
    fn f_new(&self) -> State<N>;

    /// The dense output of the last attempt, once accepted, from (t_old, y_old) over h to
    /// y_new. DOP853 evaluates f three more times here; `None` if those are not finite.
    fn dense<S: OdeSystem<N>>(
        &mut self,
        sys: &S,
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        y_new: &State<N>,
        nfev: &mut usize,
    ) -> Option<DenseStep<N>>;

    // The tableau as the integrator of many trajectories side by side
    // ([`crate::ode::lanes`]) applies it: it computes the stages of all its lanes at once,
    // then hands each lane's stages to the pair for the error norm and the dense output.

    /// The stages s of a step before its FSAL evaluation (stage s is f at y_new).
    const STAGES: usize;
    /// The extra stages of the dense output (they follow the FSAL stage).
    const EXTRA: usize;
    /// Row s of the tableau's A, s = 1 … STAGES − 1 (its first s entries are used).
    fn a(s: usize) -> &'static [f64];
    /// The weights b of y_new.
    fn b() -> &'static [f64];
    /// Row i of A for extra stage i (its first STAGES + 1 + i entries are used).
    fn a_extra(i: usize) -> &'static [f64];
    /// The stages: STAGES, the FSAL one, then the extra ones.
    fn stages(&self) -> &[State<N>];
    /// The dense output from the stages held, the extra ones included (what [`Self::dense`]
    /// does after evaluating them).
    #[inline(always)]
    fn dense_from_stages(
        &self,
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        y_new: &State<N>,
    ) -> Option<DenseStep<N>> {
        let k = self.stages();
        let ends = (&k[0], &k[Self::STAGES]);
        Self::dense_from_sums(&Self::dense_sums(k), ends, t_old, h, y_old, y_new)
    }

    /// The weighted sums of all stages (extra ones included) that the dense output is made
    /// of (for one state, or for lanes).
    fn dense_sums<V: Summand>(k: &[V]) -> [V; MAX_DEGREE];

    /// The dense output from [`Self::dense_sums`] and the derivatives (f_old, f_new) at
    /// the step's ends; `None` if not finite.
    fn dense_from_sums(
        sums: &[State<N>; MAX_DEGREE],
        ends: (&State<N>, &State<N>),
        t_old: f64,
        h: f64,
        y_old: &State<N>,
        y_new: &State<N>,
    ) -> Option<DenseStep<N>>;
}

/// All components finite? Every new vector is checked, so NaN/inf never propagates.
#[inline]
pub fn all_finite<const N: usize>(v: &State<N>) -> bool {
    v.iter().all(|x| x.is_finite())
}

/// scipy's error scale atol + max(|y|, |y_new|) rtol, component by component: what each
/// pair divides its error estimate by.
#[inline]
pub fn error_scale<const N: usize>(
    y: &State<N>,
    y_new: &State<N>,
    rtol: f64,
    atol: f64,
) -> State<N> {
    State::<N>::from_fn(|i, _| atol + y[i].abs().max(y_new[i].abs()) * rtol)
}

/// scipy's `RungeKutta._estimate_error_norm` from the error sum Σ E_j K_j: the RMS norm of
/// h Σ E_j K_j over the error scale (the pairs with one error estimate: RK45, Vern9).
#[inline]
pub fn scaled_error_norm<const N: usize>(
    sum: &State<N>,
    h: f64,
    y: &State<N>,
    y_new: &State<N>,
    rtol: f64,
    atol: f64,
) -> f64 {
    let err = sum * h;
    rms_norm(&err.component_div(&error_scale(y, y_new, rtol, atol)))
}

/// The RMS norm of scipy's `common.norm`: ‖v‖₂ / √N.
#[inline]
pub fn rms_norm<const N: usize>(v: &State<N>) -> f64 {
    v.dot(v).sqrt() / (N as f64).sqrt()
}

/// Σ_j w_j K_j, summed in the order numpy's `np.dot(K.T, w)` uses here (OpenBLAS
/// `dgemv_t`: four running sums over whole blocks of four terms, combined pairwise, then
/// the remaining terms in sequence; no fused multiply-add). Any order would do for
/// accuracy; this one reproduces scipy's error norms to the last bit, and since the norm
/// is a difference of nearly equal quantities, other orders shift scipy's step sizes by
/// ~1e-12 relative.
#[inline(always)]
pub fn weighted_sum<V: Summand>(k: &[V], w: &[f64]) -> V {
    let len = k.len().min(w.len());
    let blocked = len / 4 * 4;
    let mut acc = [V::zero(); 4];
    // A zero weight adds an exact zero: skipping it changes no bit (the weights are
    // constants, so in an unrolled loop the test costs nothing; DOP853's tableau is
    // one-third zeros).
    for j in 0..blocked {
        if w[j] != 0.0 {
            acc[j % 4] = acc[j % 4] + k[j] * w[j];
        }
    }
    let mut sum = (acc[0] + acc[1]) + (acc[2] + acc[3]);
    for j in blocked..len {
        if w[j] != 0.0 {
            sum = sum + k[j] * w[j];
        }
    }
    sum
}

/// What [`weighted_sum`] adds up: a state, or the states of many lanes.
pub trait Summand: Copy + std::ops::Add<Output = Self> + std::ops::Mul<f64, Output = Self> {
    /// All components 0.
    fn zero() -> Self;
}

impl<const N: usize> Summand for State<N> {
    #[inline(always)]
    fn zero() -> Self {
        State::<N>::zeros()
    }
}

/// The end of an explicit step after its stages k[..b.len()]: y_new = y + (Σ_j b_j K_j) h
/// and, FSAL, k[b.len()] = f(t + h, y_new), with the trigonometry of y_new[0] that f
/// computed; `None` if either is not finite.
#[inline(always)]
pub(crate) fn solution<S: OdeSystem<N>, const N: usize>(
    sys: &S,
    (t, y, h): (f64, &State<N>, f64),
    k: &mut [State<N>],
    b: &[f64],
    nfev: &mut usize,
) -> Option<(State<N>, Option<SinCos>)> {
    let s = b.len();
    let y_new = y + weighted_sum(&k[..s], b) * h;
    if !all_finite(&y_new) {
        return None;
    }
    let trig;
    (k[s], trig) = sys.rhs_with_trig(t + h, &y_new);
    *nfev += 1;
    all_finite(&k[s]).then_some((y_new, trig))
}

/// Stages `$first + i` for the literal indices i, from row i of `$a` and node i of `$c`
/// ([`stage`]), returning `None` from the calling function at the first one not finite.
/// Each index is a constant, so that each weighted sum is unrolled and its zero
/// coefficients drop out (DOP853's tableau is one-third zeros).
macro_rules! unrolled_stages {
    ($sys:expr, $at:expr, $k:expr, $nfev:expr, $first:expr, ($a:expr, $c:expr); $($i:literal)*) => {
        $(if !$crate::ode::pair::stage($sys, $at, $k, $first + $i, (&$a[$i], $c[$i]), $nfev) {
            return None;
        })*
    };
}
pub(crate) use unrolled_stages;

/// The members of [`RkPair`] that only name the pair's tableau (the module
/// `crate::ode::tableau::$tab`), the same in every pair: its exponent, the zeroed pair, scipy's
/// `rk_step` with its stages after the first (`$s`: literal indices, so that each stage is
/// unrolled), f at y_new, and the tableau as the lanes apply it.
macro_rules! tableau_members {
    ($tab:ident; $($s:literal)*) => {
        const ERROR_EXPONENT: f64 = $crate::ode::tableau::$tab::ERROR_EXPONENT;

        #[inline]
        fn empty() -> Self {
            use $crate::ode::tableau::$tab::N_STAGES_EXTENDED;
            Self {
                k: [$crate::ode::State::<N>::zeros(); N_STAGES_EXTENDED],
            }
        }

        /// scipy's `rk_step`: one evaluation of f per stage after the first, and one at y_new,
        /// when it succeeds.
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

        #[inline]
        fn f_new(&self) -> $crate::ode::State<N> {
            self.k[$crate::ode::tableau::$tab::N_STAGES]
        }

        const STAGES: usize = $crate::ode::tableau::$tab::N_STAGES;
        const EXTRA: usize = $crate::ode::tableau::$tab::N_STAGES_EXTENDED - Self::STAGES - 1;

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
    };
}
pub(crate) use tableau_members;

/// Stage s of an explicit pair: k[s] = f(t + c h, y + (Σ_{j<s} K_j a_j) h), in scipy's
/// order of operations; false if it is not finite.
#[inline(always)]
pub(crate) fn stage<S: OdeSystem<N>, const N: usize>(
    sys: &S,
    (t, y, h): (f64, &State<N>, f64),
    k: &mut [State<N>],
    s: usize,
    (a, c): (&[f64], f64),
    nfev: &mut usize,
) -> bool {
    let ys = y + weighted_sum(&k[..s], &a[..s]) * h;
    k[s] = sys.rhs(t + c * h, &ys);
    *nfev += 1;
    all_finite(&k[s])
}

/// What the pairs' tests share.
#[cfg(test)]
pub(crate) mod testing {
    use super::RkPair;
    use crate::ode::{OdeSystem, State};

    /// y' = cos t: every stage is known exactly, so one step checks the order of a pair's
    /// solution and of its dense output against sin.
    struct Cos;
    impl OdeSystem<1> for Cos {
        fn rhs(&self, t: f64, _y: &State<1>) -> State<1> {
            State::<1>::new(t.cos())
        }
    }

    /// One step of P over h of y' = cos t from 0 and its dense output: the step's error,
    /// the dense output's largest error at 21 points, the evaluations of f (step, then
    /// with the dense output) and the dense output's degree.
    pub(crate) fn quadrature_step<P: RkPair<1>>(h: f64) -> (f64, f64, [usize; 2], usize) {
        let mut nfev = 0;
        let mut pair = P::empty();
        let y = State::<1>::new(0.0);
        let y_new = pair
            .attempt(&Cos, 0.0, &y, &State::<1>::new(1.0), h, &mut nfev)
            .unwrap()
            .0;
        let step_nfev = nfev;
        let d = pair.dense(&Cos, 0.0, h, &y, &y_new, &mut nfev).unwrap();
        let worst = (0..=20)
            .map(|i| {
                let t = h * i as f64 / 20.0;
                (d.eval(t)[0] - t.sin()).abs()
            })
            .fold(0.0, f64::max);
        (
            (y_new[0] - h.sin()).abs(),
            worst,
            [step_nfev, nfev],
            d.degree,
        )
    }
}

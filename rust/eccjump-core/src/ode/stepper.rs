//! One adaptive step of any embedded pair: step-size control as scipy's
//! `RungeKutta._step_impl`, plus scipy's `select_initial_step`. The pair itself (stages,
//! error norm, dense output) is a [`RkPair`].
//!
//! The arithmetic follows scipy operation by operation (same order of the scalar factors)
//! so that accepted step sizes agree with scipy's to rounding.

use super::dense::DenseStep;
use super::pair::{all_finite, rms_norm, RkPair};
use super::{OdeSystem, SinCos, State};

// scipy's third constant, `SAFETY`, is the pair's ([`RkPair::SAFETY`]): Vern9 has its own.

/// Smallest factor by which a rejected step shrinks (scipy `MIN_FACTOR`).
pub const MIN_FACTOR: f64 = 0.2;
/// Largest factor by which an accepted step grows (scipy `MAX_FACTOR`).
pub const MAX_FACTOR: f64 = 10.0;

/// The next representable number after t in the direction of `direction` (C `nextafter`;
/// `f64::next_up` needs a newer Rust than our minimum).
#[inline]
pub fn next_after(t: f64, direction: f64) -> f64 {
    if t.is_nan() || t.is_infinite() {
        return t;
    }
    if t == 0.0 {
        let tiny = f64::from_bits(1);
        return if direction < 0.0 { -tiny } else { tiny };
    }
    let bits = t.to_bits();
    // Moving away from zero increments the magnitude bits, towards zero decrements them.
    let away = (t > 0.0) == (direction > 0.0);
    f64::from_bits(if away { bits + 1 } else { bits - 1 })
}

/// The smallest admissible step at t: ten floating-point spacings (scipy's `min_step`).
#[inline]
pub fn min_step(t: f64, direction: f64) -> f64 {
    10.0 * (next_after(t, direction) - t).abs()
}

/// A point of the solution with the derivative there: where an integration starts, (t0,
/// y0) and f0 = f(t0, y0).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point<const N: usize> {
    /// t.
    pub t: f64,
    /// y(t).
    pub y: State<N>,
    /// f(t, y).
    pub f: State<N>,
}

/// +1 or −1: the direction of integration from t0 to t_bound (+1 if they are equal).
#[inline]
fn direction_to(t0: f64, t_bound: f64) -> f64 {
    if t_bound >= t0 {
        1.0
    } else {
        -1.0
    }
}

/// scipy 1.17 `select_initial_step` (Hairer–Nørsett–Wanner II.4 with scipy's bounds by
/// the interval length and max_step), from `start` towards `t_bound` with the tolerances
/// (rtol, atol). Makes one evaluation of f; `None` if it is not finite.
/// `power(d)` is the pair's (0.01/d)^(1/(q + 1)) ([`RkPair::first_step_power`]).
///
/// With `probes` > 1, where scipy's answer is its cap of 100 times the probe step (always
/// from y0 = 0, whose probe step is 1e-6), the estimate is made again from a probe of the
/// step found, up to `probes` evaluations in all: one evaluation instead of the whole steps
/// that would grow the step tenfold at a time (three or four of them from rest).
pub fn select_initial_step<S: OdeSystem<N>, const N: usize>(
    (power, probes): (fn(f64) -> f64, usize),
    sys: &S,
    start: &Point<N>,
    t_bound: f64,
    max_step: f64,
    (rtol, atol): (f64, f64),
    nfev: &mut usize,
) -> Option<f64> {
    let Point {
        t: t0,
        y: y0,
        f: f0,
    } = start;
    let (t0, direction) = (*t0, direction_to(*t0, t_bound));
    if N == 0 {
        return Some(f64::INFINITY);
    }
    let interval_length = (t_bound - t0).abs();
    if interval_length == 0.0 {
        return Some(0.0);
    }
    let scale = y0.map(|v| atol + v.abs() * rtol);
    let d0 = rms_norm(&y0.component_div(&scale));
    let d1 = rms_norm(&f0.component_div(&scale));
    let h0 = if d0 < 1e-5 || d1 < 1e-5 {
        1e-6
    } else {
        0.01 * d0 / d1
    };
    // Do not probe beyond t_bound.
    let mut h0 = h0.min(interval_length);
    let mut h = 0.0;
    for probe in 0..probes.max(1) {
        let y1 = y0 + f0 * (h0 * direction);
        let f1 = sys.rhs(t0 + h0 * direction, &y1);
        *nfev += 1;
        if !all_finite(&f1) {
            // A later probe reaches farther than scipy's: where f is not finite there, the
            // step found so far stands.
            return (probe > 0).then_some(h);
        }
        let d2 = rms_norm(&(f1 - f0).component_div(&scale)) / h0;
        let h1 = if d1 <= 1e-15 && d2 <= 1e-15 {
            (h0 * 1e-3).max(1e-6)
        } else {
            power(d1.max(d2))
        };
        h = (100.0 * h0).min(h1).min(interval_length).min(max_step);
        // Probe again only where the cap by the probe step set h.
        if probe + 1 == probes || h < 100.0 * h0 {
            break;
        }
        h0 = h;
    }
    Some(h)
}

/// Why a step attempt ended.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum StepStatus {
    /// A step was accepted; the stepper now stands at its end.
    Accepted,
    /// The step fell below [`min_step`] (scipy's "step size too small").
    TooSmall,
    /// A stage, the new state or the error norm was not finite.
    NonFinite,
}

/// A step being tried: its size and whether an attempt was already rejected.
#[derive(Debug, Clone, Copy)]
pub struct Trial {
    /// |h| of the next attempt.
    pub h_abs: f64,
    /// An attempt of this step was rejected: the step size may not grow.
    pub rejected: bool,
}

/// The verdict on one attempt.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Judgement {
    /// Accepted: the stepper stands at the attempt's end.
    Accepted,
    /// Rejected: try again with the smaller trial size.
    Retry,
    /// The error norm is not finite.
    NonFinite,
}

/// The integrator's state between steps: scipy's `RungeKutta` attributes.
#[derive(Debug, Clone, Copy)]
pub struct Stepper<P, const N: usize> {
    /// Current time.
    pub t: f64,
    /// Current state.
    pub y: State<N>,
    /// f(t, y), reused as the first stage of the next step (FSAL).
    pub f: State<N>,
    /// sin and cos of y[0], if the right-hand side computed them with f
    /// ([`OdeSystem::rhs_with_trig`]): for the events and the observer at (t, y).
    pub trig: Option<SinCos>,
    /// The step size to try next.
    pub h_abs: f64,
    /// Start of the last accepted step.
    pub t_old: f64,
    /// State at `t_old`.
    pub y_old: State<N>,
    /// The pair with the stages of the last attempted step; after acceptance they define
    /// its dense output.
    pub pair: P,
    /// +1 or −1: the sign of t_bound − t0.
    pub direction: f64,
    /// End of the integration interval; steps are clipped to land on it.
    pub t_bound: f64,
    /// Largest allowed |h|.
    pub max_step: f64,
    /// Largest change of the first component per step: a trial is clipped to it by the
    /// component's rate at the step's start, and an attempt that changes it more is retried
    /// shorter ([`crate::ode::SolverOptions::max_first_change`]).
    pub max_first_change: f64,
    /// Relative tolerance of the error norm.
    pub rtol: f64,
    /// Absolute tolerance of the error norm.
    pub atol: f64,
}

impl<P: RkPair<N>, const N: usize> Stepper<P, N> {
    /// A stepper at `start`, first trial step `h_abs`, towards `t_bound` with steps of at
    /// most `max_step` and the tolerances (rtol, atol).
    pub fn new(
        start: Point<N>,
        h_abs: f64,
        t_bound: f64,
        max_step: f64,
        (rtol, atol): (f64, f64),
    ) -> Self {
        Self {
            t: start.t,
            y: start.y,
            f: start.f,
            trig: None,
            h_abs,
            t_old: start.t,
            y_old: start.y,
            pair: P::empty(),
            direction: direction_to(start.t, t_bound),
            t_bound,
            max_step,
            max_first_change: f64::INFINITY,
            rtol,
            atol,
        }
    }

    /// Attempts steps until one is accepted (scipy `_step_impl`): clips to t_bound,
    /// shrinks by max(0.2, 0.9 err^e) on rejection, grows by min(10, 0.9 err^e)
    /// on acceptance (e = −1/(q + 1) of the pair) but never grows right after a rejection
    /// in the same call. The integrator of many trajectories side by side
    /// ([`crate::ode::lanes`]) takes the same steps through the same three parts:
    /// [`Self::first_trial`], [`Self::trial`] and [`Self::judge`].
    #[inline]
    pub fn step<S: OdeSystem<N>>(
        &mut self,
        sys: &S,
        nfev: &mut usize,
        n_rejected: &mut usize,
    ) -> StepStatus {
        self.step_from(self.first_trial(), sys, nfev, n_rejected)
    }

    /// [`Self::step`] from the trial `trial` of the current step (one that the integrator
    /// of many trajectories began).
    #[inline]
    pub fn step_from<S: OdeSystem<N>>(
        &mut self,
        mut trial: Trial,
        sys: &S,
        nfev: &mut usize,
        n_rejected: &mut usize,
    ) -> StepStatus {
        loop {
            let Some((t_new, h)) = self.trial(trial.h_abs) else {
                return StepStatus::TooSmall;
            };
            let t = self.t;
            let Some((y_new, trig)) = self.pair.attempt(sys, t, &self.y, &self.f, h, nfev) else {
                return StepStatus::NonFinite;
            };
            let err = self
                .pair
                .error_norm(h, &self.y, &y_new, self.rtol, self.atol);
            let f_new = self.pair.f_new();
            match self.judge(&mut trial, t_new, h, err, &y_new, &f_new) {
                Judgement::Accepted => {
                    self.trig = trig;
                    return StepStatus::Accepted;
                }
                Judgement::NonFinite => return StepStatus::NonFinite,
                Judgement::Retry => *n_rejected += 1,
            }
        }
    }

    /// The first trial of a step: the next step size, clipped to [min_step, max_step] and
    /// to `max_first_change` / |f₀| (∞ / 0 is ∞; a NaN rate leaves `max_step`).
    #[inline]
    pub fn first_trial(&self) -> Trial {
        let min_step = min_step(self.t, self.direction);
        let max_step = self.max_step.min(self.max_first_change / self.f[0].abs());
        let h_abs = if self.h_abs > max_step {
            max_step
        } else if self.h_abs < min_step {
            min_step
        } else {
            self.h_abs
        };
        Trial {
            h_abs,
            rejected: false,
        }
    }

    /// (t_new, h) of a trial of size `h_abs`, landing exactly on t_bound rather than past
    /// it; `None` if the step is too small (a NaN step, from a NaN first_step or max_step,
    /// ends here too, not in a loop).
    #[inline]
    pub fn trial(&self, h_abs: f64) -> Option<(f64, f64)> {
        let t = self.t;
        if h_abs.is_nan() || h_abs < min_step(t, self.direction) {
            return None;
        }
        let mut t_new = t + h_abs * self.direction;
        if self.direction * (t_new - self.t_bound) > 0.0 {
            t_new = self.t_bound;
        }
        Some((t_new, t_new - t))
    }

    /// Accepts the attempt of size h (its error norm `err`, end state `y_new` and
    /// f there) and sets the next step size, or shrinks `trial` for another attempt.
    #[inline]
    pub fn judge(
        &mut self,
        trial: &mut Trial,
        t_new: f64,
        h: f64,
        err: f64,
        y_new: &State<N>,
        f_new: &State<N>,
    ) -> Judgement {
        let power = P::error_power(err);
        self.judge_powered(trial, t_new, h, (err, power), y_new, f_new)
    }

    /// [`Self::judge`] with err^e (`P::error_power(err)`) already computed, as the
    /// integrator of many trajectories does for all its lanes at once.
    #[inline]
    pub fn judge_powered(
        &mut self,
        trial: &mut Trial,
        t_new: f64,
        h: f64,
        (err, power): (f64, f64),
        y_new: &State<N>,
        f_new: &State<N>,
    ) -> Judgement {
        let h_abs = h.abs();
        if err.is_nan() {
            return Judgement::NonFinite;
        }
        let change = (y_new[0] - self.y[0]).abs();
        if err < 1.0 && change > self.max_first_change {
            // Accurate but too long a step (from a rate near 0, which `first_trial` could
            // not clip): retried at the length that makes the change about 0.9 of the cap.
            trial.h_abs = h_abs * (0.9 * self.max_first_change / change);
            trial.rejected = true;
            return Judgement::Retry;
        }
        if err < 1.0 {
            let mut factor = if err == 0.0 {
                MAX_FACTOR
            } else {
                MAX_FACTOR.min(P::SAFETY * power)
            };
            if trial.rejected {
                factor = factor.min(1.0);
            }
            self.t_old = self.t;
            self.y_old = self.y;
            self.t = t_new;
            self.y = *y_new;
            self.f = *f_new;
            // Unknown here: the caller sets the trigonometry of y_new if f came with it.
            self.trig = None;
            self.h_abs = h_abs * factor;
            return Judgement::Accepted;
        }
        trial.h_abs = h_abs * MIN_FACTOR.max(P::SAFETY * power);
        trial.rejected = true;
        Judgement::Retry
    }

    /// The dense output of the last accepted step (`None` if a stage it needs is not
    /// finite).
    #[inline]
    pub fn dense<S: OdeSystem<N>>(&mut self, sys: &S, nfev: &mut usize) -> Option<DenseStep<N>> {
        let (t_old, h, y_old, y) = (self.t_old, self.t - self.t_old, self.y_old, self.y);
        self.pair.dense(sys, t_old, h, &y_old, &y, nfev)
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::pair::vern9::Vern9;

    #[test]
    fn next_after_moves_one_ulp() {
        assert_eq!(next_after(1.0, 1.0), 1.0 + f64::EPSILON);
        assert_eq!(next_after(1.0, -1.0), 1.0 - f64::EPSILON / 2.0);
        assert_eq!(next_after(-1.0, -1.0), -1.0 - f64::EPSILON);
        assert_eq!(next_after(0.0, 1.0), f64::from_bits(1));
        assert_eq!(next_after(0.0, -1.0), -f64::from_bits(1));
        assert_eq!(min_step(1.0, 1.0), 10.0 * f64::EPSILON);
    }

    /// y'' = −sin(y + 0.5) from rest, off its equilibrium (y' = 0, y'' ≠ 0): scipy's
    /// estimate from y = (0, 0) is capped at 100 × its 1e-6 probe; more probes lift the cap,
    /// each one evaluation, and change nothing where the cap does not bind.
    #[test]
    fn more_probes_lift_the_cap_of_the_first_step_from_rest() {
        struct Pendulum;
        impl OdeSystem<2> for Pendulum {
            fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
                State::<2>::new(y[1], -libm::sin(y[0] + 0.5))
            }
        }
        /// y'' = 1 while y' ≤ 1e-3, not finite beyond.
        struct Wall;
        impl OdeSystem<2> for Wall {
            fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
                let a = if y[1] > 1e-3 { f64::NAN } else { 1.0 };
                State::<2>::new(y[1], a)
            }
        }
        /// The first step from y0 with `probes` and the evaluations it made.
        fn first<S: OdeSystem<2>>(sys: &S, y0: State<2>, probes: usize) -> (Option<f64>, usize) {
            let f0 = sys.rhs(0.0, &y0);
            let mut nfev = 0;
            let start = Point {
                t: 0.0,
                y: y0,
                f: f0,
            };
            let h = select_initial_step(
                (Vern9::<2>::first_step_power, probes),
                sys,
                &start,
                100.0,
                f64::INFINITY,
                (1e-8, 1e-10),
                &mut nfev,
            );
            (h, nfev)
        }
        let rest = State::<2>::zeros();
        let (h1, n1) = first(&Pendulum, rest, 1);
        assert_eq!((h1, n1), (Some(100.0 * 1e-6), 1), "scipy's cap");
        let (h2, n2) = first(&Pendulum, rest, 2);
        let (h3, n3) = first(&Pendulum, rest, 3);
        assert_eq!((n2, n3), (2, 3));
        assert_eq!(
            h2,
            h1.map(|h| 100.0 * h),
            "the second probe is capped at 100 × the first"
        );
        // The third is not capped: the estimate itself, 0.01^(1/9) / max(d1, d2)^(1/9).
        let h3 = h3.unwrap();
        assert!(h3 > 1e-2 && h3 < 1.0, "{h3}");
        // A later probe where f is not finite keeps the step found before it: probes at
        // 1e-6 and 1e-4 see a finite f; the third, at 1e-2, does not.
        let two = first(&Wall, rest, 2).0;
        assert_eq!(two, first(&Wall, rest, 1).0.map(|h| 100.0 * h));
        assert_eq!(first(&Wall, rest, 3).0, two);
        // Moving: the estimate binds at once, the other probes are not made.
        let moving = State::<2>::new(0.3, 0.2);
        assert_eq!(first(&Pendulum, moving, 3), first(&Pendulum, moving, 1));
        assert_eq!(first(&Pendulum, moving, 3).1, 1);
    }
}

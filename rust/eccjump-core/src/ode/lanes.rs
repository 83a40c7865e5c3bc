//! Many independent trajectories side by side, [`LANES`] at a time: the same steps, events
//! and outcomes as [`crate::ode::solve`] gives each of them, bit for bit, in less time.
//!
//! One trajectory's step is a chain of dependent operations (stage after stage, each with a
//! `sin_cos`), so one trajectory keeps only a sliver of a core busy. Here the stages of
//! [`LANES`] trajectories are computed together, component by component across the lanes
//! ([`Lanes`]), which the compiler turns into vector instructions, and the right-hand sides
//! of all lanes are evaluated at once ([`LaneRhs`], with [`crate::trig::lanes`]).
//! Everything that decides, per trajectory, stays the scalar code of [`crate::ode`], so
//! it exists once: the step-size control ([`Stepper::first_trial`], [`Stepper::trial`],
//! [`Stepper::judge`]), each pair's error norm and dense output (from the lane's stages,
//! [`RkPair::dense_from_stages`]) and the event scan ([`scan_step`]). A lane whose
//! trajectory ends takes the next one at once.
//!
//! The right-hand side of a lane batch is autonomous (t does not enter it): the systems
//! integrated this way (rolling) are.

// Lane loops index several arrays in step: the form that the compiler vectorizes.
#![allow(clippy::needless_range_loop)]

use super::pair::{all_finite, weighted_sum, RkPair, Summand};
use super::solver::{Observation, Outcome, Run, SolverOptions, Status};
use super::stepper::{Judgement, StepStatus, Trial};
use super::{DenseStep, EventFunctions, OdeSystem, State};
pub use crate::trig::lanes::{Lane, LANES};

/// N components of [`LANES`] states: component i of lane l is `self.0[i][l]`.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Lanes<const N: usize>(pub [Lane; N]);

impl<const N: usize> Lanes<N> {
    /// Lane l as a state.
    #[inline(always)]
    pub fn lane(&self, l: usize) -> State<N> {
        State::<N>::from_fn(|i, _| self.0[i][l])
    }

    /// Sets lane l to `v`.
    #[inline(always)]
    pub fn set_lane(&mut self, l: usize, v: &State<N>) {
        for i in 0..N {
            self.0[i][l] = v[i];
        }
    }

    /// self + d·h, lane by lane (each lane's own h), in the order of `y + d * h` on states.
    #[inline(always)]
    fn plus_times(&self, d: &Self, h: &Lane) -> Self {
        let mut out = *self;
        for i in 0..N {
            for l in 0..LANES {
                out.0[i][l] = self.0[i][l] + d.0[i][l] * h[l];
            }
        }
        out
    }
}

impl<const N: usize> std::ops::Add for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn add(mut self, rhs: Self) -> Self {
        for i in 0..N {
            for l in 0..LANES {
                self.0[i][l] += rhs.0[i][l];
            }
        }
        self
    }
}

impl<const N: usize> std::ops::Mul<f64> for Lanes<N> {
    type Output = Self;
    #[inline(always)]
    fn mul(mut self, w: f64) -> Self {
        for row in self.0.iter_mut() {
            for x in row.iter_mut() {
                *x *= w;
            }
        }
        self
    }
}

impl<const N: usize> Summand for Lanes<N> {
    #[inline(always)]
    fn zero() -> Self {
        Self([[0.0; LANES]; N])
    }
}

/// A system whose right-hand side can be evaluated for [`LANES`] states at once.
pub trait LaneRhs<const N: usize>: OdeSystem<N> {
    /// f at lane l's state by `systems[l]`, for every lane; bit for bit
    /// [`OdeSystem::rhs`] (at any t: the system is autonomous).
    fn rhs_lanes(systems: &[&Self; LANES], y: &Lanes<N>) -> Lanes<N>;
}

/// One trajectory of a batch: its system, its events and what it does with what the
/// integration reports (as the observer of [`crate::ode::solve`]).
pub trait Track<const N: usize> {
    /// The system.
    type Sys: LaneRhs<N>;
    /// The events.
    type Events: EventFunctions<N>;
    /// The system.
    fn sys(&self) -> &Self::Sys;
    /// The events.
    fn events(&self) -> &Self::Events;
    /// An accepted step or an event, in the order [`crate::ode::solve`] reports them (by
    /// shared reference: the events, also borrowed from the track, are scanned meanwhile;
    /// a track keeps what it learns in cells).
    fn observe(&self, obs: Observation<'_, N>);
}

/// A trajectory to integrate: the track, its start (t0, y0), its end t_end and options (all
/// tracks of a batch share the pair P).
pub struct Start<T, const N: usize> {
    /// The trajectory.
    pub track: T,
    /// Initial time.
    pub t0: f64,
    /// Initial state.
    pub y0: State<N>,
    /// Final time.
    pub t_end: f64,
    /// Tolerances, limits, event samples.
    pub opts: SolverOptions,
}

/// A lane's trajectory between rounds: its integration and the step it is trying.
struct Slot<P, T, const N: usize> {
    track: T,
    run: Run<P, N>,
    trial: Trial,
}

/// Fewest busy lanes worth a round once no trajectory is waiting: with fewer, each goes on
/// alone by the scalar loop (a round computes all lanes, and costs about three scalar
/// steps with AVX2, more without).
const MIN_BUSY: usize = 4;

/// Integrates every trajectory that `next` gives, [`LANES`] at a time with the pair P, each
/// exactly as [`crate::ode::solve_until`] would (the same steps, observations and outcome,
/// bit for bit), and hands each to `done` with its outcome as soon as it ends. `stop` is
/// asked as `solve_until` asks it, per trajectory. Uses AVX2 where the CPU has it (the
/// same operations, so the same bits; no fused multiply-add).
pub fn solve_lanes<P, T, const N: usize>(
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    #[cfg(target_arch = "x86_64")]
    {
        if std::arch::is_x86_feature_detected!("avx2") {
            // SAFETY: the CPU has AVX2, the only feature the function is compiled for.
            unsafe { lanes_avx2::<P, T, N>(next, done, stop) };
            return;
        }
    }
    lanes::<P, T, N>(next, done, stop);
}

/// [`lanes`] compiled for AVX2 (two 4-wide registers per lane group instead of four SSE2
/// ones).
#[cfg(target_arch = "x86_64")]
#[target_feature(enable = "avx2")]
unsafe fn lanes_avx2<P, T, const N: usize>(
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    lanes::<P, T, N>(next, done, stop);
}

/// The rounds of [`solve_lanes`].
#[inline(always)]
fn lanes<P, T, const N: usize>(
    mut next: impl FnMut() -> Option<Start<T, N>>,
    mut done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    let mut slots: [Option<Slot<P, T, N>>; LANES] = std::array::from_fn(|_| None);
    let mut exhausted = false;
    // Stages: STAGES, the FSAL one, the extra ones of the dense output (at most 16).
    let mut k = [Lanes::<N>::zero(); 16];
    let n_k = P::STAGES + 1 + P::EXTRA;
    debug_assert!(n_k <= k.len());
    loop {
        // Fill the free lanes; a trajectory that ends before its first step is done at once.
        for slot in slots.iter_mut().filter(|s| s.is_none()) {
            while !exhausted {
                let Some(Start {
                    track,
                    t0,
                    y0,
                    t_end,
                    opts,
                }) = next()
                else {
                    exhausted = true;
                    break;
                };
                match Run::<P, N>::begin(track.sys(), t0, y0, t_end, &opts) {
                    Ok(mut run) => {
                        if run.ends_here(stop) {
                            done(track, run.out);
                        } else {
                            let trial = run.st.first_trial();
                            *slot = Some(Slot { track, run, trial });
                            break;
                        }
                    }
                    Err(out) => done(track, out),
                }
            }
        }
        // Too few left for a round: each goes on alone (the scalar step is the same step).
        let busy = slots.iter().filter(|s| s.is_some()).count();
        if exhausted && busy < MIN_BUSY {
            for slot in slots.iter_mut() {
                if let Some(Slot {
                    track,
                    mut run,
                    trial,
                }) = slot.take()
                {
                    let (sys, out) = (track.sys(), &mut run.out);
                    let status = run
                        .st
                        .step_from(trial, sys, &mut out.nfev, &mut out.n_rejected);
                    let out = match status {
                        StepStatus::TooSmall | StepStatus::NonFinite => {
                            run.out.status = if status == StepStatus::TooSmall {
                                Status::StepTooSmall
                            } else {
                                Status::NonFinite
                            };
                            run.out
                        }
                        StepStatus::Accepted => {
                            let dense = run.st.dense(sys, &mut run.out.nfev);
                            let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
                            if run.after_step(track.events(), dense, observer) {
                                run.out
                            } else {
                                run.to_end(sys, track.events(), observer, stop)
                            }
                        }
                    };
                    done(track, out);
                }
            }
            return;
        }
        // Each lane's trial step; a step too small ends its trajectory.
        let mut h = [0.0; LANES];
        let mut t_new = [0.0; LANES];
        for (l, slot) in slots.iter_mut().enumerate() {
            let Some(s) = slot else { continue };
            match s.run.st.trial(s.trial.h_abs) {
                Some((tn, hl)) => (t_new[l], h[l]) = (tn, hl),
                None => {
                    s.run.out.status = Status::StepTooSmall;
                    let s = slot.take().expect("a lane in use");
                    done(s.track, s.run.out);
                }
            }
        }
        let Some(first) = slots.iter().position(Option::is_some) else {
            continue;
        };
        // Free lanes repeat the first busy one (the same inputs, the same finite values),
        // so every lane's arithmetic is that of a real trajectory.
        let busy = |l: usize| if slots[l].is_some() { l } else { first };
        let systems: [&T::Sys; LANES] =
            std::array::from_fn(|l| slots[busy(l)].as_ref().expect("busy").track.sys());
        let mut y = Lanes::<N>::zero();
        let mut f = Lanes::<N>::zero();
        for l in 0..LANES {
            let st = &slots[busy(l)].as_ref().expect("busy").run.st;
            y.set_lane(l, &st.y);
            f.set_lane(l, &st.f);
            h[l] = h[busy(l)];
        }
        // The stages of every lane, then the end state y + (Σ b_j K_j) h and f there (FSAL).
        k[0] = f;
        for s in 1..P::STAGES {
            let d = weighted_sum(&k[..s], &P::a(s)[..s]);
            k[s] = T::Sys::rhs_lanes(&systems, &y.plus_times(&d, &h));
        }
        let y_new = y.plus_times(&weighted_sum(&k[..P::STAGES], P::b()), &h);
        k[P::STAGES] = T::Sys::rhs_lanes(&systems, &y_new);
        // The extra stages of the dense output, from the step's start (y, h): needed by the
        // lanes whose step is accepted (almost all of them), computed for all.
        for i in 0..P::EXTRA {
            let j = P::STAGES + 1 + i;
            let d = weighted_sum(&k[..j], &P::a_extra(i)[..j]);
            k[j] = T::Sys::rhs_lanes(&systems, &y.plus_times(&d, &h));
        }
        // Each lane's verdict and, for an accepted step, its dense output and events: the
        // scalar code, from the lane's stages.
        for l in 0..LANES {
            let Some(s) = slots[l].as_mut() else { continue };
            let ended = match judge_lane(s, &k[..n_k], l, (t_new[l], h[l]), &y_new) {
                Judgement::Retry => {
                    s.run.out.n_rejected += 1;
                    false
                }
                Judgement::NonFinite => {
                    s.run.out.status = Status::NonFinite;
                    true
                }
                Judgement::Accepted => {
                    let dense = dense_of_lane(s, &k[..n_k], l);
                    let track = &s.track;
                    let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
                    if s.run.after_step(track.events(), dense, observer) || s.run.ends_here(stop) {
                        true
                    } else {
                        s.trial = s.run.st.first_trial();
                        false
                    }
                }
            };
            if ended {
                let s = slots[l].take().expect("a lane in use");
                done(s.track, s.run.out);
            }
        }
    }
}

/// Lane l's attempt judged by the scalar step control, from its stages `k` (and counted
/// as the scalar attempt counts its evaluations, up to a non-finite one).
#[inline(always)]
fn judge_lane<P: RkPair<N>, T, const N: usize>(
    s: &mut Slot<P, T, N>,
    k: &[Lanes<N>],
    l: usize,
    (t_new, h): (f64, f64),
    y_new: &Lanes<N>,
) -> Judgement {
    let run = &mut s.run;
    let stages = run.st.pair.stages_mut();
    for (j, kj) in k[..=P::STAGES].iter().enumerate() {
        stages[j] = kj.lane(l);
    }
    let yl = y_new.lane(l);
    let bad =
        (1..=P::STAGES).find(|&j| !all_finite(&stages[j]) || (j == P::STAGES && !all_finite(&yl)));
    if let Some(j) = bad {
        // The scalar attempt stops at the first non-finite stage (before f(y_new) if y_new
        // itself is not finite).
        run.out.nfev += if all_finite(&yl) || j < P::STAGES {
            j
        } else {
            j - 1
        };
        return Judgement::NonFinite;
    }
    run.out.nfev += P::STAGES;
    let st = &mut run.st;
    let err = st.pair.error_norm(h, &st.y, &yl, st.rtol, st.atol);
    let fl = k[P::STAGES].lane(l);
    st.judge(&mut s.trial, t_new, h, err, &yl, &fl)
}

/// The dense output of lane l's accepted step from its extra stages, as
/// [`Stepper::dense`] makes it (`None` if one of them is not finite).
#[inline(always)]
fn dense_of_lane<P: RkPair<N>, T, const N: usize>(
    s: &mut Slot<P, T, N>,
    k: &[Lanes<N>],
    l: usize,
) -> Option<DenseStep<N>> {
    let run = &mut s.run;
    let stages = run.st.pair.stages_mut();
    for j in P::STAGES + 1..P::STAGES + 1 + P::EXTRA {
        stages[j] = k[j].lane(l);
        run.out.nfev += 1;
        if !all_finite(&stages[j]) {
            return None;
        }
    }
    let st = &run.st;
    st.pair
        .dense_from_stages(st.t_old, st.t - st.t_old, &st.y_old, &st.y)
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::ode::events::{Direction, EventSpec};
    use crate::ode::pair::{Dop853, Dp5};
    use crate::ode::{solve_until, Method};
    use crate::trig::lanes::sin_cos_lanes;
    use std::cell::RefCell;

    /// A damped pendulum θ'' = −g sin θ − c θ' (autonomous), per lane (g, c).
    struct Pendulum {
        g: f64,
        c: f64,
    }

    impl OdeSystem<2> for Pendulum {
        fn rhs(&self, _t: f64, y: &State<2>) -> State<2> {
            let (s, _) = crate::trig::sin_cos(y[0]);
            State::<2>::new(y[1], -self.g * s - self.c * y[1])
        }
    }

    impl LaneRhs<2> for Pendulum {
        fn rhs_lanes(systems: &[&Self; LANES], y: &Lanes<2>) -> Lanes<2> {
            let (s, _) = sin_cos_lanes(&y.0[0]);
            let mut acc = [0.0; LANES];
            for l in 0..LANES {
                acc[l] = -systems[l].g * s[l] - systems[l].c * y.0[1][l];
            }
            Lanes([y.0[1], acc])
        }
    }

    /// Events: θ' falling through 0 (terminal), θ rising through 1 (not terminal); the
    /// observations in a log.
    struct Swings {
        sys: Pendulum,
        log: RefCell<Vec<(u8, u64, u64, u64)>>,
    }

    impl EventFunctions<2> for Swings {
        fn count(&self) -> usize {
            2
        }
        fn spec(&self, k: usize) -> EventSpec {
            EventSpec {
                direction: if k == 0 {
                    Direction::Falling
                } else {
                    Direction::Rising
                },
                terminal: k == 0,
            }
        }
        fn value(&self, k: usize, _t: f64, y: &State<2>) -> f64 {
            if k == 0 {
                y[1]
            } else {
                y[0] - 1.0
            }
        }
    }

    impl Track<2> for Swings {
        type Sys = Pendulum;
        type Events = Self;
        fn sys(&self) -> &Pendulum {
            &self.sys
        }
        fn events(&self) -> &Self {
            self
        }
        fn observe(&self, obs: Observation<'_, 2>) {
            let entry = match obs {
                Observation::Step { t, y, .. } => (0, t.to_bits(), y[0].to_bits(), y[1].to_bits()),
                Observation::Event { index, t, y } => {
                    (1 + index as u8, t.to_bits(), y[0].to_bits(), y[1].to_bits())
                }
            };
            self.log.borrow_mut().push(entry);
        }
    }

    fn outcome_bits(o: &Outcome<2>) -> (Status, u64, u64, u64, usize, usize, usize) {
        let y = (o.y[0].to_bits(), o.y[1].to_bits());
        (
            o.status,
            o.t.to_bits(),
            y.0,
            y.1,
            o.nfev,
            o.n_accepted,
            o.n_rejected,
        )
    }

    /// Every trajectory of a batch (some ending at their event, some at t_end, some at the
    /// step limit, some not starting at all) as `solve_until` integrates it alone, for both
    /// pairs, by the plain and (where the CPU has it) the AVX2 build of the rounds.
    #[test]
    fn a_batch_is_each_trajectory_bit_for_bit() {
        let starts = |i: usize| {
            let x = i as f64;
            let sys = Pendulum {
                g: 1.0 + (x * 0.37).fract() * 9.0,
                c: (x * 0.61).fract() * 0.3,
            };
            let y0 = State::<2>::new(0.2 + (x * 0.13).fract() * 2.5, (x * 0.71).fract() - 0.5);
            let y0 = if i % 41 == 40 {
                State::<2>::new(f64::NAN, 0.0)
            } else {
                y0
            };
            let opts = SolverOptions {
                rtol: [1e-6, 1e-9, 1e-11][i % 3],
                atol: 1e-12,
                max_steps: if i % 17 == 5 { 7 } else { 100_000 },
                ..SolverOptions::default()
            };
            let t_end = if i % 13 == 2 { 0.3 } else { 50.0 };
            (sys, y0, t_end, opts)
        };
        let n = 150;
        for method in Method::ALL {
            let alone: Vec<_> = (0..n)
                .map(|i| {
                    let (sys, y0, t_end, opts) = starts(i);
                    let opts = SolverOptions { method, ..opts };
                    let ev = Swings {
                        sys,
                        log: RefCell::new(Vec::new()),
                    };
                    let mut obs = |o: Observation<'_, 2>| ev.observe(o);
                    let out = solve_until(&ev.sys, &ev, 0.0, y0, t_end, &opts, &mut obs, &|| false);
                    (outcome_bits(&out), ev.log.into_inner())
                })
                .collect();
            for avx2 in [false, true] {
                let mut i = 0;
                let got = RefCell::new(vec![None; n]);
                let next = || {
                    (i < n).then(|| {
                        let (sys, y0, t_end, opts) = starts(i);
                        i += 1;
                        let track = Swings {
                            sys,
                            log: RefCell::new(Vec::new()),
                        };
                        Start {
                            track: (i - 1, track),
                            t0: 0.0,
                            y0,
                            t_end,
                            opts: SolverOptions { method, ..opts },
                        }
                    })
                };
                let done = |(j, t): (usize, Swings), out: Outcome<2>| {
                    got.borrow_mut()[j] = Some((outcome_bits(&out), t.log.into_inner()));
                };
                run_batch(method, avx2, next, done);
                for (j, g) in got.into_inner().into_iter().enumerate() {
                    assert_eq!(
                        g.as_ref(),
                        Some(&alone[j]),
                        "{method:?} avx2 {avx2} trajectory {j}"
                    );
                }
            }
            // The batch met every kind of end.
            let ends: std::collections::BTreeSet<_> =
                alone.iter().map(|a| format!("{:?}", a.0 .0)).collect();
            assert!(ends.len() >= 4, "{ends:?}");
        }
    }

    impl Track<2> for (usize, Swings) {
        type Sys = Pendulum;
        type Events = Swings;
        fn sys(&self) -> &Pendulum {
            &self.1.sys
        }
        fn events(&self) -> &Swings {
            &self.1
        }
        fn observe(&self, obs: Observation<'_, 2>) {
            self.1.observe(obs)
        }
    }

    fn run_batch(
        method: Method,
        avx2: bool,
        next: impl FnMut() -> Option<Start<(usize, Swings), 2>>,
        done: impl FnMut((usize, Swings), Outcome<2>),
    ) {
        let never = || false;
        match (method, avx2) {
            (Method::Rk45, false) => lanes::<Dp5<2>, _, 2>(next, done, &never),
            (Method::Dop853, false) => lanes::<Dop853<2>, _, 2>(next, done, &never),
            (Method::Rk45, true) => solve_lanes::<Dp5<2>, _, 2>(next, done, &never),
            (Method::Dop853, true) => solve_lanes::<Dop853<2>, _, 2>(next, done, &never),
        }
    }
}

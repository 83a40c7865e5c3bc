//! Many independent trajectories side by side, [`LANES`] at a time: the same steps, events
//! and outcomes as [`crate::ode::solve`] gives each of them, bit for bit, in less time.
//!
//! One trajectory's step is a chain of dependent operations (stage after stage, each with a
//! `sin_cos`), so one trajectory keeps only a sliver of a core busy. Here the stages of
//! [`LANES`] trajectories are computed together, component by component across the lanes
//! ([`Lanes`]), which the compiler turns into vector instructions: the right-hand sides of
//! all lanes at once ([`LaneRhs`], with [`crate::trig::lanes`]), and each pair's weighted
//! sums of the stages for its error norm and dense output ([`RkPair::error_sums`],
//! [`RkPair::dense_sums`], generic over a state or lanes: one formula). Everything that
//! decides, per trajectory, stays the scalar code of [`crate::ode`], so it exists once: the
//! step-size control (`Stepper::first_trial`, `trial`, `judge_powered`), the error norm
//! and dense output from the sums ([`RkPair::error_from_sums`],
//! [`RkPair::dense_from_sums`]), the event scan and the observations (`solver::Run`). A
//! lane whose trajectory ends takes the next one at once; the last few finish alone.
//!
//! The right-hand side of a lane batch is autonomous (t does not enter it): the systems
//! integrated this way (rolling) are.

// Lane loops index several arrays in step: the form that the compiler vectorizes.
#![allow(clippy::needless_range_loop)]

use super::dense::MAX_DEGREE;
use super::pair::{
    all_finite, weighted_sum, Dop853, Dp5, Method, RkPair, Summand, Vern7, Vern9, MAX_STAGES,
};
use super::solver::{Observation, Outcome, Run, SolverOptions, Status};
use super::stepper::{Judgement, Trial};
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

    /// Called once the stages of a round are done: lane l's system may prepare what the
    /// event scan of its step will ask at the step's end `y_new` (a memo of its
    /// trigonometry, say). Nothing by default.
    #[inline(always)]
    fn step_end_lanes(systems: &[&Self; LANES], y_new: &Lanes<N>) {
        let _ = (systems, y_new);
    }
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
/// bit for bit), and hands each to `done` with its outcome as soon as it ends. `next` is
/// asked whenever a lane is free, so a `None` need not be its last word: `done` may give it
/// more (the continuation of a trajectory); the work ends when no lane is busy and `next`
/// has nothing. `stop` is asked as `solve_until` asks it, per trajectory. Uses AVX2 where
/// the CPU has it (the same operations, so the same bits; no fused multiply-add).
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
    // Stages: STAGES, the FSAL one, the extra ones of the dense output.
    let mut k = [Lanes::<N>::zero(); MAX_STAGES];
    let n_k = P::STAGES + 1 + P::EXTRA;
    debug_assert!(n_k <= k.len());
    loop {
        // Fill the free lanes; a trajectory that ends before its first step is done at once.
        // `next` may have nothing now and more later (a trajectory that `done` starts).
        let mut exhausted = false;
        for slot in slots.iter_mut().filter(|s| s.is_none()) {
            while slot.is_none() {
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
                        }
                    }
                    Err(out) => done(track, out),
                }
            }
            if exhausted {
                break;
            }
        }
        let busy = slots.iter().filter(|s| s.is_some()).count();
        if busy == 0 {
            if exhausted {
                return;
            }
            continue;
        }
        // Too few left for a round: each goes on alone (the scalar step is the same step),
        // then `next` is asked again.
        if exhausted && busy < MIN_BUSY {
            for slot in slots.iter_mut() {
                if let Some(Slot { track, run, trial }) = slot.take() {
                    let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
                    let (sys, events) = (track.sys(), track.events());
                    let out = run.to_end(Some(trial), sys, events, observer, stop);
                    done(track, out);
                }
            }
            continue;
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
        T::Sys::step_end_lanes(&systems, &y_new);
        // Each lane's verdict by the scalar step control, from its error sums.
        let err_sums = P::error_sums(&k[..=P::STAGES]);
        let finite = finite_lanes(&k[1..=P::STAGES], &y_new);
        let mut err = [0.0; LANES];
        for l in 0..LANES {
            if let Some(s) = slots[l].as_ref().filter(|_| finite[l]) {
                let (st, sums) = (&s.run.st, err_sums.map(|e| e.lane(l)));
                err[l] = P::error_from_sums(&sums, h[l], &st.y, &y_new.lane(l), st.rtol, st.atol);
            }
        }
        // err^e of every lane at once (its square roots in vector registers).
        let mut power = [0.0; LANES];
        for l in 0..LANES {
            power[l] = P::error_power(err[l]);
        }
        let mut accepted = [false; LANES];
        for l in 0..LANES {
            let Some(s) = slots[l].as_mut() else { continue };
            let step = (t_new[l], h[l]);
            let error = (err[l], power[l]);
            match judge_lane(s, &k[..=P::STAGES], (l, finite[l]), error, step, &y_new) {
                Judgement::Accepted => accepted[l] = true,
                Judgement::Retry => s.run.out.n_rejected += 1,
                Judgement::NonFinite => {
                    let mut s = slots[l].take().expect("a lane in use");
                    s.run.out.status = Status::NonFinite;
                    done(s.track, s.run.out);
                }
            }
        }
        // The accepted steps that their ends alone clear of events: observed
        // without dense output (the scalar code).
        let mut ended = [false; LANES];
        let mut dense_for = [false; LANES];
        for l in (0..LANES).filter(|&l| accepted[l]) {
            let s = slots[l].as_mut().expect("an accepted lane");
            let track = &s.track;
            let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
            if s.run.after_quiet_step(track.events(), &f.lane(l), observer) {
                ended[l] = s.run.ends_here(stop);
            } else {
                dense_for[l] = true;
            }
        }
        if dense_for.contains(&true) {
            // The extra stages of the dense output, from the step's start (y, h), computed
            // for all lanes, used by those that need them.
            // (A lane whose trajectory ended meanwhile repeats one in use, as free lanes do.)
            let any = slots.iter().flatten().next().expect("a lane in use");
            let systems: [&T::Sys; LANES] =
                std::array::from_fn(|l| slots[l].as_ref().unwrap_or(any).track.sys());
            for i in 0..P::EXTRA {
                let j = P::STAGES + 1 + i;
                let d = weighted_sum(&k[..j], &P::a_extra(i)[..j]);
                k[j] = T::Sys::rhs_lanes(&systems, &y.plus_times(&d, &h));
            }
            // The other accepted steps' dense output, events and observations: the scalar
            // code.
            let dense_sums = P::dense_sums(&k[..n_k]);
            for l in (0..LANES).filter(|&l| dense_for[l]) {
                let s = slots[l].as_mut().expect("an accepted lane");
                let dense = dense_of_lane(s, &k[..n_k], &dense_sums, l);
                let track = &s.track;
                let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
                ended[l] = s.run.after_step(track.events(), dense.as_ref(), observer)
                    || s.run.ends_here(stop);
            }
        }
        for l in (0..LANES).filter(|&l| accepted[l]) {
            if ended[l] {
                let s = slots[l].take().expect("a lane in use");
                done(s.track, s.run.out);
            } else {
                let s = slots[l].as_mut().expect("an accepted lane");
                s.trial = s.run.st.first_trial();
            }
        }
    }
}

/// Lane l's attempt judged by the scalar step control, from its error norm and err^e
/// (and counted as the scalar attempt counts its evaluations, up to a non-finite one).
#[inline(always)]
fn judge_lane<P: RkPair<N>, T, const N: usize>(
    s: &mut Slot<P, T, N>,
    k: &[Lanes<N>],
    (l, finite): (usize, bool),
    error: (f64, f64),
    (t_new, h): (f64, f64),
    y_new: &Lanes<N>,
) -> Judgement {
    let run = &mut s.run;
    let yl = y_new.lane(l);
    let bad = (!finite)
        .then(|| {
            (1..=P::STAGES)
                .find(|&j| !all_finite(&k[j].lane(l)) || (j == P::STAGES && !all_finite(&yl)))
        })
        .flatten();
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
    let fl = k[P::STAGES].lane(l);
    run.st
        .judge_powered(&mut s.trial, t_new, h, error, &yl, &fl)
}

/// Whether all of each lane's stages `k` and its y_new are finite (the common case, tested
/// for all lanes at once; a lane that fails is then searched stage by stage).
#[inline(always)]
fn finite_lanes<const N: usize>(k: &[Lanes<N>], y_new: &Lanes<N>) -> [bool; LANES] {
    let mut finite = [true; LANES];
    for v in k.iter().chain(std::iter::once(y_new)) {
        for row in &v.0 {
            for l in 0..LANES {
                finite[l] &= row[l].is_finite();
            }
        }
    }
    finite
}

/// The dense output of lane l's accepted step, as [`Stepper::dense`] makes it, from the
/// lanes' dense sums (`None` if an extra stage or the output is not finite).
#[inline(always)]
fn dense_of_lane<P: RkPair<N>, T, const N: usize>(
    s: &mut Slot<P, T, N>,
    k: &[Lanes<N>],
    sums: &[Lanes<N>; MAX_DEGREE],
    l: usize,
) -> Option<DenseStep<N>> {
    let run = &mut s.run;
    for kj in &k[P::STAGES + 1..P::STAGES + 1 + P::EXTRA] {
        run.out.nfev += 1;
        if !all_finite(&kj.lane(l)) {
            return None;
        }
    }
    let st = &run.st;
    let ends = (&k[0].lane(l), &k[P::STAGES].lane(l));
    let (t_old, h) = (st.t_old, st.t - st.t_old);
    P::dense_from_sums(&sums.map(|q| q.lane(l)), ends, t_old, h, &st.y_old, &st.y)
}

/// A track with its caller's key, so that `done` knows whose outcome it gets.
pub struct Keyed<K, T> {
    /// The caller's key.
    pub key: K,
    /// The track.
    pub track: T,
}

impl<K, T: Track<N>, const N: usize> Track<N> for Keyed<K, T> {
    type Sys = T::Sys;
    type Events = T::Events;
    #[inline]
    fn sys(&self) -> &T::Sys {
        self.track.sys()
    }
    #[inline]
    fn events(&self) -> &T::Events {
        self.track.events()
    }
    #[inline]
    fn observe(&self, obs: Observation<'_, N>) {
        self.track.observe(obs)
    }
}

/// [`solve_lanes`] with the pair `method`.
pub fn solve_lanes_with<T: Track<N>, const N: usize>(
    method: Method,
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) {
    match method {
        Method::Rk45 => solve_lanes::<Dp5<N>, T, N>(next, done, stop),
        Method::Dop853 => solve_lanes::<Dop853<N>, T, N>(next, done, stop),
        Method::Vern7 => solve_lanes::<Vern7<N>, T, N>(next, done, stop),
        Method::Vern9 => solve_lanes::<Vern9<N>, T, N>(next, done, stop),
    }
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

    impl Swings {
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

    /// A trajectory of the batch: its number, its events, and how many times it is to be
    /// continued from where it ends (by `done`, through `next`).
    struct Numbered(usize, Swings, usize);

    impl Track<2> for Numbered {
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

    type Bits = (Status, u64, u64, u64, usize, usize, usize);
    /// One integration: its outcome and its observations, as bits.
    type Record = (Bits, Vec<(u8, u64, u64, u64)>);

    fn outcome_bits(o: &Outcome<2>) -> Bits {
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

    /// Trajectory i: its pendulum, start, end and options (some end at their event, some
    /// at t_end, some at the step limit, some do not start at all).
    fn problem(i: usize, method: Method) -> (Pendulum, State<2>, f64, SolverOptions) {
        let x = i as f64;
        let sys = Pendulum {
            g: 1.0 + (x * 0.37).fract() * 9.0,
            c: (x * 0.61).fract() * 0.3,
        };
        let y0 = if i % 41 == 40 {
            State::<2>::new(f64::NAN, 0.0)
        } else {
            State::<2>::new(0.2 + (x * 0.13).fract() * 2.5, (x * 0.71).fract() - 0.5)
        };
        let opts = SolverOptions {
            rtol: [1e-6, 1e-9, 1e-11][i % 3],
            atol: 1e-12,
            max_steps: if i % 17 == 5 { 7 } else { 100_000 },
            method,
            ..SolverOptions::default()
        };
        let t_end = if i % 13 == 2 { 0.3 } else { 50.0 };
        (sys, y0, t_end, opts)
    }

    /// Trajectory i and its continuations (each from where the one before ended, with a
    /// kick), each by `solve_until` alone.
    fn alone(i: usize, method: Method) -> Vec<Record> {
        let (_, mut y0, t_end, opts) = problem(i, method);
        let mut t0 = 0.0;
        let mut runs = Vec::new();
        for _ in 0..=i % 3 {
            let ev = Swings {
                sys: problem(i, method).0,
                log: RefCell::new(Vec::new()),
            };
            let mut obs = |o: Observation<'_, 2>| ev.observe(o);
            let out = solve_until(&ev.sys, &ev, t0, y0, t_end, &opts, &mut obs, &|| false);
            runs.push((outcome_bits(&out), ev.log.into_inner()));
            (t0, y0) = (out.t, State::<2>::new(out.y[0], out.y[1] + 1.0));
        }
        runs
    }

    /// Every trajectory of a batch as `solve_until` integrates it alone, for every pair, by
    /// the plain and (where the CPU has it) the AVX2 build of the rounds; some trajectories
    /// are continued by `done` after the last one has started.
    #[test]
    fn a_batch_is_each_trajectory_bit_for_bit() {
        let n = 150;
        for method in Method::ALL {
            let want: Vec<_> = (0..n).map(|i| alone(i, method)).collect();
            for avx2 in [false, true] {
                let got = RefCell::new(vec![Vec::new(); n]);
                let queue = RefCell::new(Vec::new());
                let mut i = 0;
                let next = || {
                    if let Some(start) = queue.borrow_mut().pop() {
                        return Some(start);
                    }
                    (i < n).then(|| {
                        let (sys, y0, t_end, opts) = problem(i, method);
                        i += 1;
                        let log = RefCell::new(Vec::new());
                        let track = Numbered(i - 1, Swings { sys, log }, (i - 1) % 3);
                        Start {
                            track,
                            t0: 0.0,
                            y0,
                            t_end,
                            opts,
                        }
                    })
                };
                let done = |Numbered(j, s, more): Numbered, out: Outcome<2>| {
                    got.borrow_mut()[j].push((outcome_bits(&out), s.log.into_inner()));
                    if more > 0 {
                        let (sys, _, t_end, opts) = problem(j, method);
                        let log = RefCell::new(Vec::new());
                        queue.borrow_mut().push(Start {
                            track: Numbered(j, Swings { sys, log }, more - 1),
                            t0: out.t,
                            y0: State::<2>::new(out.y[0], out.y[1] + 1.0),
                            t_end,
                            opts,
                        });
                    }
                };
                let never = || false;
                match (method, avx2) {
                    (Method::Rk45, false) => lanes::<Dp5<2>, _, 2>(next, done, &never),
                    (Method::Dop853, false) => lanes::<Dop853<2>, _, 2>(next, done, &never),
                    (Method::Rk45, true) => solve_lanes::<Dp5<2>, _, 2>(next, done, &never),
                    (Method::Dop853, true) => solve_lanes::<Dop853<2>, _, 2>(next, done, &never),
                    (Method::Vern7, false) => lanes::<Vern7<2>, _, 2>(next, done, &never),
                    (Method::Vern7, true) => solve_lanes::<Vern7<2>, _, 2>(next, done, &never),
                    (Method::Vern9, false) => lanes::<Vern9<2>, _, 2>(next, done, &never),
                    (Method::Vern9, true) => solve_lanes::<Vern9<2>, _, 2>(next, done, &never),
                }
                for (j, g) in got.into_inner().iter().enumerate() {
                    assert_eq!(g, &want[j], "{method:?} avx2 {avx2} trajectory {j}");
                }
            }
            // The batch met every kind of end.
            let ends: std::collections::BTreeSet<_> = want
                .iter()
                .flatten()
                .map(|a| format!("{:?}", a.0 .0))
                .collect();
            assert!(ends.len() >= 4, "{ends:?}");
        }
    }
}

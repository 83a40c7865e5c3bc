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
    all_finite, weighted_sum, Dop853, Dp5, Integrator, RkPair, Summand, Vern9, MAX_STAGES,
};
use super::solver::{Observation, Outcome, Run, SolverOptions, Status};
use super::stepper::{Judgement, Trial};
use super::{DenseStep, EventFunctions, OdeSystem, SinCos, State};
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

    /// [`Self::rhs_lanes`] with the sines and cosines of y[0] it computed on the way, if
    /// any, lane by lane ([`OdeSystem::rhs_with_trig`]): asked at the steps' ends (FSAL),
    /// for their event scans and observers. None by default.
    #[inline(always)]
    fn rhs_lanes_with_trig(
        systems: &[&Self; LANES],
        y: &Lanes<N>,
    ) -> (Lanes<N>, Option<[Lane; 2]>) {
        (Self::rhs_lanes(systems, y), None)
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

/// A lane per trajectory under way, `None` where free.
type Slots<P, T, const N: usize> = [Option<Slot<P, T, N>>; LANES];

/// The rounds of [`solve_lanes`]: each fills the free lanes, tries a step of every busy
/// one (its stages computed for all lanes at once), judges each lane's attempt, and
/// scans and observes each accepted step, with or without its dense output.
#[inline(always)]
fn lanes<P, T, const N: usize>(
    mut next: impl FnMut() -> Option<Start<T, N>>,
    mut done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    let mut slots: Slots<P, T, N> = std::array::from_fn(|_| None);
    // Stages: STAGES, the FSAL one, the extra ones of the dense output.
    let mut k = [Lanes::<N>::zero(); MAX_STAGES];
    debug_assert!(P::STAGES + 1 + P::EXTRA <= k.len());
    loop {
        let exhausted = fill(&mut slots, &mut next, &mut done, stop);
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
            finish_alone(&mut slots, &mut done, stop);
            continue;
        }
        let Some(mut round) = trials(&mut slots, &mut done) else {
            continue;
        };
        let y_new = stages::<P, T, N>(&slots, &mut round, &mut k);
        let accepted = verdicts(&mut slots, &round, &k, y_new, &mut done);
        let (mut ended, dense_for) = quiet_steps(&mut slots, &round, accepted, stop);
        if dense_for.contains(&true) {
            dense_steps(&mut slots, &round, &mut k, dense_for, &mut ended, stop);
        }
        after_round(&mut slots, accepted, ended, &mut done);
    }
}

/// Fills the free lanes from `next`; a trajectory that ends before its first step is done
/// at once. True if `next` has nothing now (it may have more later: a trajectory that
/// `done` starts).
#[inline(always)]
fn fill<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    next: &mut impl FnMut() -> Option<Start<T, N>>,
    done: &mut impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) -> bool
where
    P: RkPair<N>,
    T: Track<N>,
{
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
                return true;
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
    }
    false
}

/// Every busy lane's trajectory to its end alone, by the scalar loop.
#[inline(always)]
fn finish_alone<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    done: &mut impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    for slot in slots.iter_mut() {
        if let Some(Slot { track, run, trial }) = slot.take() {
            let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
            let (sys, events) = (track.sys(), track.events());
            let out = run.to_end(Some(trial), sys, events, observer, stop);
            done(track, out);
        }
    }
}

/// One round's steps, lane by lane: each one's start (y, f), size h and end time t_new.
/// Free lanes repeat the first busy one (the same inputs, the same finite values), so
/// every lane's arithmetic is that of a real trajectory.
struct Round<const N: usize> {
    y: Lanes<N>,
    f: Lanes<N>,
    h: Lane,
    t_new: Lane,
}

/// Each busy lane's trial step (a step too small ends its trajectory): the round, or
/// `None` if no lane is left busy.
#[inline(always)]
fn trials<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    done: &mut impl FnMut(T, Outcome<N>),
) -> Option<Round<N>>
where
    P: RkPair<N>,
{
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
    let first = slots.iter().position(Option::is_some)?;
    let busy = |l: usize| if slots[l].is_some() { l } else { first };
    let mut y = Lanes::<N>::zero();
    let mut f = Lanes::<N>::zero();
    for l in 0..LANES {
        let st = &slots[busy(l)].as_ref().expect("busy").run.st;
        y.set_lane(l, &st.y);
        f.set_lane(l, &st.f);
        h[l] = h[busy(l)];
    }
    Some(Round { y, f, h, t_new })
}

/// Lane l's system, or that of a busy lane where l is free.
#[inline(always)]
fn systems<P, T: Track<N>, const N: usize>(slots: &Slots<P, T, N>) -> [&T::Sys; LANES] {
    let any = slots.iter().flatten().next().expect("a lane in use");
    std::array::from_fn(|l| slots[l].as_ref().unwrap_or(any).track.sys())
}

/// The stages of every lane into `k`, then the end state y + (Σ b_j K_j) h and f there
/// (FSAL): returns the end state with the sine and cosine of its y[0] by lane, if f
/// came with them.
#[inline(always)]
fn stages<P, T, const N: usize>(
    slots: &Slots<P, T, N>,
    round: &mut Round<N>,
    k: &mut [Lanes<N>; MAX_STAGES],
) -> (Lanes<N>, Option<[Lane; 2]>)
where
    P: RkPair<N>,
    T: Track<N>,
{
    let systems = systems(slots);
    let (y, h) = (&round.y, &round.h);
    k[0] = round.f;
    for s in 1..P::STAGES {
        let d = weighted_sum(&k[..s], &P::a(s)[..s]);
        k[s] = T::Sys::rhs_lanes(&systems, &y.plus_times(&d, h));
    }
    let y_new = y.plus_times(&weighted_sum(&k[..P::STAGES], P::b()), h);
    let trig;
    (k[P::STAGES], trig) = T::Sys::rhs_lanes_with_trig(&systems, &y_new);
    (y_new, trig)
}

/// Each lane's verdict by the scalar step control, from its error sums (err^e of every
/// lane at once, its square roots in vector registers): which lanes' steps were accepted.
/// A lane whose attempt is not finite is done.
#[inline(always)]
fn verdicts<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    round: &Round<N>,
    k: &[Lanes<N>; MAX_STAGES],
    (y_new, trig): (Lanes<N>, Option<[Lane; 2]>),
    done: &mut impl FnMut(T, Outcome<N>),
) -> [bool; LANES]
where
    P: RkPair<N>,
{
    let y_new = &y_new;
    let err_sums = P::error_sums(&k[..=P::STAGES]);
    let finite = finite_lanes(&k[1..=P::STAGES], y_new);
    let mut err = [0.0; LANES];
    for l in 0..LANES {
        if let Some(s) = slots[l].as_ref().filter(|_| finite[l]) {
            let (st, sums) = (&s.run.st, err_sums.map(|e| e.lane(l)));
            let h = round.h[l];
            err[l] = P::error_from_sums(&sums, h, &st.y, &y_new.lane(l), st.rtol, st.atol);
        }
    }
    let mut power = [0.0; LANES];
    for l in 0..LANES {
        power[l] = P::error_power(err[l]);
    }
    let mut accepted = [false; LANES];
    for l in 0..LANES {
        let Some(s) = slots[l].as_mut() else { continue };
        let step = (round.t_new[l], round.h[l]);
        let error = (err[l], power[l]);
        match judge_lane(s, &k[..=P::STAGES], (l, finite[l]), error, step, y_new) {
            Judgement::Accepted => {
                accepted[l] = true;
                s.run.st.trig = trig.map(|[sin, cos]| SinCos {
                    theta: y_new.0[0][l],
                    sin: sin[l],
                    cos: cos[l],
                });
            }
            Judgement::Retry => s.run.out.n_rejected += 1,
            Judgement::NonFinite => {
                let mut s = slots[l].take().expect("a lane in use");
                s.run.out.status = Status::NonFinite;
                done(s.track, s.run.out);
            }
        }
    }
    accepted
}

/// The accepted steps that their ends alone clear of events, observed without dense output
/// (the scalar code): which lanes' trajectories ended there, and which steps need their
/// dense output.
#[inline(always)]
fn quiet_steps<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    round: &Round<N>,
    accepted: [bool; LANES],
    stop: &dyn Fn() -> bool,
) -> ([bool; LANES], [bool; LANES])
where
    P: RkPair<N>,
    T: Track<N>,
{
    let mut ended = [false; LANES];
    let mut dense_for = [false; LANES];
    for l in (0..LANES).filter(|&l| accepted[l]) {
        let s = slots[l].as_mut().expect("an accepted lane");
        let track = &s.track;
        let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
        if s.run
            .after_quiet_step(track.events(), &round.f.lane(l), observer)
        {
            ended[l] = s.run.ends_here(stop);
        } else {
            dense_for[l] = true;
        }
    }
    (ended, dense_for)
}

/// The extra stages of the dense output, from the step's start (y, h), computed for all
/// lanes, used by those in `dense_for`, whose accepted steps' dense output, events and
/// observations are then the scalar code's. Which trajectories ended goes to `ended`.
#[inline(always)]
fn dense_steps<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    round: &Round<N>,
    k: &mut [Lanes<N>; MAX_STAGES],
    dense_for: [bool; LANES],
    ended: &mut [bool; LANES],
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    // (A lane whose trajectory ended meanwhile repeats one in use, as free lanes do.)
    let systems = systems(slots);
    for i in 0..P::EXTRA {
        let j = P::STAGES + 1 + i;
        let d = weighted_sum(&k[..j], &P::a_extra(i)[..j]);
        k[j] = T::Sys::rhs_lanes(&systems, &round.y.plus_times(&d, &round.h));
    }
    let n_k = P::STAGES + 1 + P::EXTRA;
    let dense_sums = P::dense_sums(&k[..n_k]);
    for l in (0..LANES).filter(|&l| dense_for[l]) {
        let s = slots[l].as_mut().expect("an accepted lane");
        let dense = dense_of_lane(s, &k[..n_k], &dense_sums, l);
        let track = &s.track;
        let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
        ended[l] =
            s.run.after_step(track.events(), dense.as_ref(), observer) || s.run.ends_here(stop);
    }
}

/// After the round: each accepted lane whose trajectory ended is done, the others begin
/// their next step.
#[inline(always)]
fn after_round<P, T, const N: usize>(
    slots: &mut Slots<P, T, N>,
    accepted: [bool; LANES],
    ended: [bool; LANES],
    done: &mut impl FnMut(T, Outcome<N>),
) where
    P: RkPair<N>,
{
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
    method: Integrator,
    next: impl FnMut() -> Option<Start<T, N>>,
    done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) {
    match method {
        Integrator::Rk45 => solve_lanes::<Dp5<N>, T, N>(next, done, stop),
        Integrator::Dop853 => solve_lanes::<Dop853<N>, T, N>(next, done, stop),
        Integrator::Vern9 => solve_lanes::<Vern9<N>, T, N>(next, done, stop),
    }
}

#[cfg(test)]
mod tests;

//! The rounds of a batch: [`LANES`] trajectories take one step each, their stages computed
//! together, everything that decides per trajectory by the scalar code (`solver::Run`,
//! the stepper). Every helper is `#[inline(always)]`: the rounds are compiled once more for
//! AVX2 ([`super::solve_lanes`]), and a helper left out of line would not be.

// Lane loops index several arrays in step: the form that the compiler vectorizes.
#![allow(clippy::needless_range_loop)]

use super::{LaneRhs, Lanes, Start, Track};
use crate::ode::dense::MAX_DEGREE;
use crate::ode::pair::{all_finite, weighted_sum, RkPair, Summand, MAX_STAGES};
use crate::ode::solver::{Observation, Outcome, Run, Status};
use crate::ode::stepper::{Judgement, Trial};
use crate::ode::{DenseStep, Ivp};
use crate::trig::lanes::{Lane, LANES};

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

/// The lanes of a batch, and room for the stages of a round: P's, the FSAL one and the
/// dense output's extra ones.
struct Batch<P, T, const N: usize> {
    slots: [Option<Slot<P, T, N>>; LANES],
    k: [Lanes<N>; MAX_STAGES],
}

/// Where the lanes of a round start: each one's state, f there, its step h and the time
/// t_new it steps to.
struct RoundStart<const N: usize> {
    y: Lanes<N>,
    f: Lanes<N>,
    h: Lane,
    t_new: Lane,
}

/// The rounds of [`super::solve_lanes`]: fill the free lanes, then a round of steps, until
/// no lane is busy and `next` has nothing; too few busy lanes for a round go on alone.
#[inline(always)]
pub(super) fn rounds<P, T, const N: usize>(
    mut next: impl FnMut() -> Option<Start<T, N>>,
    mut done: impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) where
    P: RkPair<N>,
    T: Track<N>,
{
    debug_assert!(P::STAGES + 1 + P::EXTRA <= MAX_STAGES);
    let mut batch = Batch::<P, T, N> {
        slots: std::array::from_fn(|_| None),
        k: [Lanes::<N>::zero(); MAX_STAGES],
    };
    loop {
        let exhausted = batch.fill(&mut next, &mut done, stop);
        let busy = batch.slots.iter().filter(|s| s.is_some()).count();
        if busy == 0 {
            if exhausted {
                return;
            }
        } else if exhausted && busy < MIN_BUSY {
            // Then `next` is asked again.
            batch.finish_alone(&mut done, stop);
        } else {
            batch.round(&mut done, stop);
        }
    }
}

impl<P: RkPair<N>, T: Track<N>, const N: usize> Batch<P, T, N> {
    /// Gives each free lane the next trajectory (one that ends before its first step is
    /// done at once). True if `next` has nothing now; it may have more later (a trajectory
    /// that `done` starts).
    #[inline(always)]
    fn fill(
        &mut self,
        next: &mut impl FnMut() -> Option<Start<T, N>>,
        done: &mut impl FnMut(T, Outcome<N>),
        stop: &dyn Fn() -> bool,
    ) -> bool {
        for slot in self.slots.iter_mut().filter(|s| s.is_none()) {
            while slot.is_none() {
                let Some(start) = next() else {
                    return true;
                };
                *slot = begin(start, done, stop);
            }
        }
        false
    }

    /// Each busy lane goes on alone to its end (the scalar step is the same step).
    #[inline(always)]
    fn finish_alone(&mut self, done: &mut impl FnMut(T, Outcome<N>), stop: &dyn Fn() -> bool) {
        for slot in self.slots.iter_mut() {
            if let Some(Slot { track, run, trial }) = slot.take() {
                let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
                let (sys, events) = (track.sys(), track.events());
                let out = run.to_end(Some(trial), sys, events, observer, stop);
                done(track, out);
            }
        }
    }

    /// One step of every busy lane: its trial, the stages of all lanes at once, the verdicts,
    /// then the accepted steps' events and observations.
    #[inline(always)]
    fn round(&mut self, done: &mut impl FnMut(T, Outcome<N>), stop: &dyn Fn() -> bool) {
        let Some(start) = self.start(done) else {
            return;
        };
        let y_new = stages::<P, T::Sys, N>(&systems(&self.slots), &mut self.k, &start);
        let accepted = self.judge(&start, &y_new, done);
        let (mut ended, dense_for) = self.quiet_steps(&accepted, &start.f, stop);
        if dense_for.contains(&true) {
            self.dense_steps(&start, &dense_for, &mut ended, stop);
        }
        self.after_round(&accepted, &ended, done);
    }

    /// Each busy lane's trial step (a step too small ends its trajectory) and where the
    /// round starts; None if no lane is left. Free lanes repeat the first busy one (the
    /// same inputs, the same finite values), so every lane's arithmetic is that of a real
    /// trajectory.
    #[inline(always)]
    fn start(&mut self, done: &mut impl FnMut(T, Outcome<N>)) -> Option<RoundStart<N>> {
        let mut h = [0.0; LANES];
        let mut t_new = [0.0; LANES];
        for (l, slot) in self.slots.iter_mut().enumerate() {
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
        let first = self.slots.iter().position(Option::is_some)?;
        let busy = |l: usize| if self.slots[l].is_some() { l } else { first };
        let mut y = Lanes::<N>::zero();
        let mut f = Lanes::<N>::zero();
        for l in 0..LANES {
            let st = &self.slots[busy(l)].as_ref().expect("busy").run.st;
            y.set_lane(l, &st.y);
            f.set_lane(l, &st.f);
            h[l] = h[busy(l)];
        }
        Some(RoundStart { y, f, h, t_new })
    }

    /// Each busy lane's verdict by the scalar step control, from its error sums: which are
    /// accepted; a rejected one counts its retry, a non-finite one is done.
    #[inline(always)]
    fn judge(
        &mut self,
        start: &RoundStart<N>,
        y_new: &Lanes<N>,
        done: &mut impl FnMut(T, Outcome<N>),
    ) -> [bool; LANES] {
        let (slots, k) = (&mut self.slots, &self.k[..=P::STAGES]);
        let h = &start.h;
        let err_sums = P::error_sums(k);
        let finite = finite_lanes(&k[1..], y_new);
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
            let step = (start.t_new[l], h[l]);
            let error = (err[l], power[l]);
            match judge_lane(s, k, (l, finite[l]), error, step, y_new) {
                Judgement::Accepted => accepted[l] = true,
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

    /// The accepted steps that their ends alone clear of events, observed without dense
    /// output (the scalar code): which of them end their trajectory, and which accepted
    /// steps need their dense output.
    #[inline(always)]
    fn quiet_steps(
        &mut self,
        accepted: &[bool; LANES],
        f: &Lanes<N>,
        stop: &dyn Fn() -> bool,
    ) -> ([bool; LANES], [bool; LANES]) {
        let mut ended = [false; LANES];
        let mut dense_for = [false; LANES];
        for l in (0..LANES).filter(|&l| accepted[l]) {
            let s = self.slots[l].as_mut().expect("an accepted lane");
            let track = &s.track;
            let observer = &mut |obs: Observation<'_, N>| track.observe(obs);
            if s.run.after_quiet_step(track.events(), &f.lane(l), observer) {
                ended[l] = s.run.ends_here(stop);
            } else {
                dense_for[l] = true;
            }
        }
        (ended, dense_for)
    }

    /// The dense output of the steps `dense_for` (its extra stages computed for all lanes
    /// from the round's start, used by those that need them; a lane whose trajectory ended
    /// meanwhile repeats one in use, as free lanes do), then their events and observations
    /// by the scalar code; which end their trajectory, into `ended`.
    #[inline(always)]
    fn dense_steps(
        &mut self,
        start: &RoundStart<N>,
        dense_for: &[bool; LANES],
        ended: &mut [bool; LANES],
        stop: &dyn Fn() -> bool,
    ) {
        let n_k = P::STAGES + 1 + P::EXTRA;
        let (slots, k) = (&mut self.slots, &mut self.k);
        let systems = systems(slots);
        for i in 0..P::EXTRA {
            let j = P::STAGES + 1 + i;
            let d = weighted_sum(&k[..j], &P::a_extra(i)[..j]);
            k[j] = T::Sys::rhs_lanes(&systems, &start.y.plus_times(&d, &start.h));
        }
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

    /// The accepted lanes after their step: a trajectory that ended is done, the others
    /// try their next step.
    #[inline(always)]
    fn after_round(
        &mut self,
        accepted: &[bool; LANES],
        ended: &[bool; LANES],
        done: &mut impl FnMut(T, Outcome<N>),
    ) {
        for l in (0..LANES).filter(|&l| accepted[l]) {
            if ended[l] {
                let s = self.slots[l].take().expect("a lane in use");
                done(s.track, s.run.out);
            } else {
                let s = self.slots[l].as_mut().expect("an accepted lane");
                s.trial = s.run.st.first_trial();
            }
        }
    }
}

/// The integration of `start` in a lane, or None if it ends before its first step (then
/// `done` has it).
#[inline(always)]
fn begin<P: RkPair<N>, T: Track<N>, const N: usize>(
    start: Start<T, N>,
    done: &mut impl FnMut(T, Outcome<N>),
    stop: &dyn Fn() -> bool,
) -> Option<Slot<P, T, N>> {
    let Start {
        track,
        t0,
        y0,
        t_end,
        opts,
    } = start;
    let ivp = Ivp {
        sys: track.sys(),
        events: track.events(),
        t0,
        y0,
        t_end,
        opts: &opts,
    };
    match Run::<P, N>::begin(&ivp) {
        Ok(mut run) => {
            if run.ends_here(stop) {
                done(track, run.out);
                None
            } else {
                let trial = run.st.first_trial();
                Some(Slot { track, run, trial })
            }
        }
        Err(out) => {
            done(track, out);
            None
        }
    }
}

/// Each lane's system; a free lane takes the first busy lane's (at least one is busy).
#[inline(always)]
fn systems<P, T: Track<N>, const N: usize>(
    slots: &[Option<Slot<P, T, N>>; LANES],
) -> [&T::Sys; LANES] {
    let any = slots.iter().flatten().next().expect("a lane in use");
    std::array::from_fn(|l| slots[l].as_ref().unwrap_or(any).track.sys())
}

/// The stages of every lane from the round's start, then the end state y + (Σ b_j K_j) h
/// and f there (FSAL), into `k`; returns the end state.
#[inline(always)]
fn stages<P: RkPair<N>, S: LaneRhs<N>, const N: usize>(
    systems: &[&S; LANES],
    k: &mut [Lanes<N>; MAX_STAGES],
    start: &RoundStart<N>,
) -> Lanes<N> {
    let (y, h) = (&start.y, &start.h);
    k[0] = start.f;
    for s in 1..P::STAGES {
        let d = weighted_sum(&k[..s], &P::a(s)[..s]);
        k[s] = S::rhs_lanes(systems, &y.plus_times(&d, h));
    }
    let y_new = y.plus_times(&weighted_sum(&k[..P::STAGES], P::b()), h);
    k[P::STAGES] = S::rhs_lanes(systems, &y_new);
    S::step_end_lanes(systems, &y_new);
    y_new
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

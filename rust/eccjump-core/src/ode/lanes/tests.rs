//! The unit tests of `lanes.rs` (a child module, `#[cfg(test)] mod tests;` there, for the
//! private items they use).

use super::*;
use crate::ode::events::{Direction, EventSpec};
use crate::ode::pair::{Dop853, Dp5};
use crate::ode::{solve_until, Integrator};
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
    fn values(&self, first: usize, _t: f64, y: &State<2>, out: &mut [f64]) {
        for (k, o) in (first..).zip(out.iter_mut()) {
            *o = if k == 0 { y[1] } else { y[0] - 1.0 };
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
fn problem(i: usize, method: Integrator) -> (Pendulum, State<2>, f64, SolverOptions) {
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
fn alone(i: usize, method: Integrator) -> Vec<Record> {
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
    for method in Integrator::ALL {
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
                (Integrator::Rk45, false) => lanes::<Dp5<2>, _, 2>(next, done, &never),
                (Integrator::Dop853, false) => lanes::<Dop853<2>, _, 2>(next, done, &never),
                (Integrator::Rk45, true) => solve_lanes::<Dp5<2>, _, 2>(next, done, &never),
                (Integrator::Dop853, true) => solve_lanes::<Dop853<2>, _, 2>(next, done, &never),
                (Integrator::Vern9, false) => lanes::<Vern9<2>, _, 2>(next, done, &never),
                (Integrator::Vern9, true) => solve_lanes::<Vern9<2>, _, 2>(next, done, &never),
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

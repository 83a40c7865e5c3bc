//! The unit tests of `events.rs` (a child module, `#[cfg(test)] mod tests;` there, for the
//! private items they use).

use super::*;
use crate::ode::{solve, OdeSystem, SolverOptions, Status};

/// y' = 1 (so y = t): the steps are long and the dense output exact.
struct Clock;
impl OdeSystem<1> for Clock {
    fn rhs(&self, _t: f64, _y: &State<1>) -> State<1> {
        State::<1>::new(1.0)
    }
}

/// g(y) = (y − c)² − depth, a dip of width 2√depth around c when depth > 0; with or
/// without its slope, falling or rising (then −g).
struct Dip {
    c: f64,
    depth: f64,
    slopes: bool,
    direction: Direction,
}
/// Without `slopes` its slopes are NaN: no dip test.
impl EventFunctions<1> for Dip {
    const HAS_SLOPES: bool = true;
    fn count(&self) -> usize {
        1
    }
    fn spec(&self, _k: usize) -> EventSpec {
        EventSpec {
            direction: self.direction,
            terminal: true,
        }
    }
    fn values(&self, _first: usize, _t: f64, y: &State<1>, out: &mut [f64]) {
        let g = (y[0] - self.c) * (y[0] - self.c) - self.depth;
        out[0] = if self.direction == Direction::Rising {
            -g
        } else {
            g
        };
    }
    fn slopes(&self, _first: usize, _t: f64, y: &State<1>, out: &mut [f64]) {
        let s = 2.0 * (y[0] - self.c);
        out[0] = if !self.slopes {
            f64::NAN
        } else if self.direction == Direction::Rising {
            -s
        } else {
            s
        };
    }
}

fn first_event(dip: &Dip) -> Option<f64> {
    let so = SolverOptions::default();
    let out = solve(
        &Clock,
        dip,
        0.0,
        State::<1>::zeros(),
        10.0,
        &so,
        &mut |_| {},
    );
    (out.status == Status::Event(0)).then_some(out.t)
}

#[test]
fn a_dip_between_two_samples_is_a_crossing() {
    for direction in [Direction::Falling, Direction::Rising, Direction::Any] {
        // A window 2e-3 wide at 3.3, between the samples of a step of ~10.
        let dip = |slopes| Dip {
            c: 3.3,
            depth: 1e-6,
            slopes,
            direction,
        };
        assert_eq!(first_event(&dip(false)), None, "sign sampling misses it");
        let t = first_event(&dip(true)).expect("the dip test finds it");
        assert!((t - (3.3 - 1e-3)).abs() < 1e-12, "{t}");
        // A dip that stays on its side is no event, grazing or not.
        for depth in [-1e-6, -1e-14, -1.0] {
            let d = Dip { depth, ..dip(true) };
            assert_eq!(first_event(&d), None, "{depth}");
        }
    }
    // A falling event whose function rises above 0 and back between two samples: its
    // crossing is the fall back, after the extremum.
    let bump = Dip {
        c: 3.3,
        depth: 1e-6,
        slopes: true,
        direction: Direction::Rising,
    };
    struct Flip(Dip);
    impl EventFunctions<1> for Flip {
        const HAS_SLOPES: bool = true;
        fn count(&self) -> usize {
            1
        }
        fn spec(&self, _k: usize) -> EventSpec {
            EventSpec {
                direction: Direction::Falling,
                terminal: true,
            }
        }
        fn values(&self, first: usize, t: f64, y: &State<1>, out: &mut [f64]) {
            self.0.values(first, t, y, out)
        }
        fn slopes(&self, first: usize, t: f64, y: &State<1>, out: &mut [f64]) {
            self.0.slopes(first, t, y, out)
        }
    }
    let so = SolverOptions::default();
    let out = solve(
        &Clock,
        &Flip(bump),
        0.0,
        State::<1>::zeros(),
        10.0,
        &so,
        &mut |_| {},
    );
    assert_eq!(out.status, Status::Event(0));
    assert!((out.t - (3.3 + 1e-3)).abs() < 1e-12, "{}", out.t);
}

#[test]
fn a_start_at_zero_that_returns_within_the_first_cell_is_a_crossing() {
    // g = ±y(c − y) along y = t: exactly 0 at the start, out to one side and back
    // across 0 at t = c, inside the first cell of a first step of 1 (a slip that
    // starts at v = 0 and returns to it: issue 35). The sign test cannot see it
    // (its left value is 0); the dip test, from the slope at the start, does.
    struct Return {
        c: f64,
        sign: f64,
        slopes: bool,
    }
    impl EventFunctions<1> for Return {
        const HAS_SLOPES: bool = true;
        fn count(&self) -> usize {
            1
        }
        fn spec(&self, _k: usize) -> EventSpec {
            EventSpec {
                direction: Direction::Any,
                terminal: true,
            }
        }
        fn values(&self, _first: usize, _t: f64, y: &State<1>, out: &mut [f64]) {
            out[0] = self.sign * y[0] * (self.c - y[0]);
        }
        fn slopes(&self, _first: usize, _t: f64, y: &State<1>, out: &mut [f64]) {
            let s = self.sign * (self.c - 2.0 * y[0]);
            out[0] = if self.slopes { s } else { f64::NAN };
        }
    }
    let so = SolverOptions {
        first_step: Some(1.0),
        ..SolverOptions::default()
    };
    for sign in [1.0, -1.0] {
        let at = |slopes| {
            let ev = Return {
                c: 0.05,
                sign,
                slopes,
            };
            let out = solve(
                &Clock,
                &ev,
                0.0,
                State::<1>::zeros(),
                10.0,
                &so,
                &mut |_| {},
            );
            (out.status == Status::Event(0)).then_some(out.t)
        };
        assert_eq!(at(false), None, "sign sampling misses it");
        let t = at(true).expect("the dip test finds it");
        assert!((t - 0.05).abs() < 1e-14, "{t}");
    }
}

#[test]
fn crossings_need_a_nonzero_left_value() {
    use Direction::*;
    assert!(crosses(Rising, -1.0, 1.0) && crosses(Rising, -1.0, 0.0));
    assert!(!crosses(Rising, 0.0, 1.0) && !crosses(Rising, 1.0, -1.0));
    assert!(crosses(Falling, 1.0, -1.0) && crosses(Falling, 1.0, 0.0));
    assert!(!crosses(Falling, 0.0, -1.0) && !crosses(Falling, -1.0, 1.0));
    assert!(crosses(Any, 1.0, -1.0) && crosses(Any, -1.0, 1.0));
    assert!(!crosses(Any, 0.0, 0.0) && !crosses(Any, 1.0, 2.0));
}

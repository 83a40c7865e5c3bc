//! The dense output of a rolling run: the state (and the kinematics) at any time of the run,
//! from the 4th-order interpolant of every accepted step, ending exactly where the run ends
//! (at its terminal event, not at the end of the step that contains it).

use crate::mechanics::Ramp;
use crate::modes::rolling::Kinematics;
use crate::ode::{DenseStep, State};

/// `sol(t)` of a run over [t_start, t_end].
#[derive(Debug, Clone, PartialEq)]
pub struct RollSolution {
    /// The body on its ramp (for the kinematics).
    pub ramp: Ramp,
    /// The interpolant of every accepted step, in time order.
    pub steps: Vec<DenseStep<2>>,
    /// Where the run ended: the terminal event, t_max, or the last good state.
    pub t_end: f64,
}

impl RollSolution {
    /// The first time covered.
    pub fn t_start(&self) -> f64 {
        self.steps.first().map_or(self.t_end, |s| s.t_old)
    }

    /// The state (θ, θ̇) at time t, or None outside [t_start, t_end] (or for NaN).
    pub fn state(&self, t: f64) -> Option<State<2>> {
        if !(t >= self.t_start() && t <= self.t_end) || self.steps.is_empty() {
            return None;
        }
        // The last step that starts at or before t.
        let k = self.steps.partition_point(|s| s.t_old <= t).max(1) - 1;
        Some(self.steps[k].eval(t))
    }

    /// θ, θ̇, θ̈ and the contact forces at time t (pure rolling), or None outside the run.
    pub fn kinematics(&self, t: f64) -> Option<Kinematics> {
        self.state(t).map(|y| self.ramp.kinematics(y[0], y[1]))
    }
}

#[cfg(test)]
mod tests {
    use crate::mechanics::{Cylinder, Ramp};
    use crate::modes::rolling::run::{roll, RollOptions, RollStatus};

    #[test]
    fn ends_at_the_terminal_event() {
        // The README case: lift-off at t = 4.18302 inside a step that ends later.
        let r = Ramp::new(Cylinder::new(0.15, 0.02).unwrap(), 40f64.to_radians()).unwrap();
        let o = RollOptions {
            mu_s: Some(1.0),
            dense_output: true,
            ..RollOptions::default()
        };
        let run = roll(&r, &o).unwrap();
        assert!(matches!(run.status, RollStatus::Event(_)));
        let sol = run.dense.as_ref().unwrap();
        let t_event = run.events.last().unwrap().t;
        assert_eq!(sol.t_end, t_event);
        let last = sol.steps.last().unwrap();
        assert!(
            last.t_old + last.h > t_event,
            "the step containing the event ends later"
        );
        let y = sol.state(t_event).unwrap();
        assert!((y[0] - run.theta.last().unwrap()).abs() < 1e-12);
        assert!(sol.state(t_event * (1.0 + 1e-12)).is_none());
        assert!(sol.state(f64::NAN).is_none() && sol.state(-1e-3).is_none());
        // The kinematics agree with the recorded ones at the end.
        let k = sol.kinematics(t_event).unwrap();
        assert!((k.fy - run.fy.last().unwrap()).abs() < 1e-10);
    }
}

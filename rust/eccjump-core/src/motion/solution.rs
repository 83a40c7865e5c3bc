//! The dense output of a full-motion run, `sol(t)` across segments: the interpolant of every
//! accepted step in rolling and slipping, the exact motion in flight. At the boundary of two
//! segments (an impact changes the velocities at once) it gives the later segment's start.

use crate::mechanics::BodyState;
use crate::modes::flight::Flight;
use crate::ode::roots::brent;
use crate::ode::{DenseStep, State};

/// The dense output of one segment.
#[derive(Debug, Clone, PartialEq)]
pub enum Piece {
    /// Rolling: steps in time since the segment's start, state (θ, θ̇); l = θ + `l_shift`.
    Roll {
        /// The interpolants.
        steps: Vec<DenseStep<2>>,
        /// l − θ along the segment.
        l_shift: f64,
    },
    /// Slipping: steps in the run's time, state (θ, θ̇, l, l̇, q).
    Slip {
        /// The interpolants.
        steps: Vec<DenseStep<5>>,
    },
    /// Slipping near the Painlevé singularity: steps in the normal impulse since the
    /// segment's start, state (t, θ, θ̇, l, l̇, q) (t increases with the impulse).
    Impulse {
        /// The interpolants.
        steps: Vec<DenseStep<6>>,
    },
    /// Flight: exact.
    Flight(Flight),
    /// A single state: a run that ended where it started (a jam at the start).
    Still(BodyState),
}

/// `sol(t)` of a run over [0, t_end].
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MotionSolution {
    /// (start time, piece) of every segment, in time order.
    pub pieces: Vec<(f64, Piece)>,
    /// Where the run ended.
    pub t_end: f64,
}

/// The step of `steps` that covers time t (the last one starting at or before it).
fn step_at<const N: usize>(steps: &[DenseStep<N>], t: f64) -> Option<&DenseStep<N>> {
    let k = steps.partition_point(|s| s.t_old <= t);
    steps.get(k.max(1) - 1)
}

/// The state of `steps` (in the normal impulse, time its first component, increasing) at
/// time t: the step that covers t, then the impulse there by Brent's method.
fn at_time(steps: &[DenseStep<6>], t: f64) -> Option<State<6>> {
    let k = steps.partition_point(|s| s.y_old[0] <= t);
    let step = steps.get(k.max(1) - 1)?;
    let p_end = step.t_old + step.h;
    let g = |p: f64| step.eval(p)[0] - t;
    let (g0, g1) = (step.y_old[0] - t, g(p_end));
    if g1 <= 0.0 {
        // t past the last step's end (the run's end, up to rounding): its end state.
        return Some(step.eval(p_end));
    }
    let root = brent(g, step.t_old, p_end, g0, g1, 0.0, 4.0 * f64::EPSILON, 200).ok()?;
    Some(step.eval(root.x))
}

impl MotionSolution {
    /// The state at time t, or None outside [0, t_end] (or for NaN).
    pub fn state(&self, t: f64) -> Option<BodyState> {
        if !(t >= 0.0 && t <= self.t_end) {
            return None;
        }
        let k = self.pieces.partition_point(|(t0, _)| *t0 <= t);
        let (t0, piece) = self.pieces.get(k.max(1) - 1)?;
        match piece {
            Piece::Roll { steps, l_shift } => {
                let y = step_at(steps, t - t0)?.eval(t - t0);
                Some(BodyState::rolling(y[0], y[1], y[0] + l_shift))
            }
            Piece::Slip { steps } => {
                let y = step_at(steps, t)?.eval(t);
                Some(BodyState::in_contact(y[0], y[1], y[2], y[3]))
            }
            Piece::Impulse { steps } => {
                let y = at_time(steps, t)?;
                Some(BodyState::in_contact(y[1], y[2], y[3], y[4]))
            }
            Piece::Flight(f) => Some(f.state(t - t0)),
            Piece::Still(s) => Some(*s),
        }
    }
}

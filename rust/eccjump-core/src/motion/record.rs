//! What a full-motion run records: the time series of every mode (one row per accepted
//! step or flight sample, the boundary of two segments recorded on both sides), the
//! transitions, the flights, the impacts, the segments and the energy ledger.

use crate::error::{try_grow, Result};
use crate::mechanics::BodyState;
use crate::modes::contact::{Mode, TransitionReason};
use crate::motion::solution::MotionSolution;

/// One recorded point of the run.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Point {
    /// Time.
    pub t: f64,
    /// The state.
    pub state: BodyState,
    /// Contact force along the ramp [M g] (0 in flight).
    pub fx: f64,
    /// Normal contact force [M g] (0 in flight).
    pub fy: f64,
    /// Mechanical energy (kinetic + potential) [M g R].
    pub energy: f64,
    /// Energy dissipated so far (slip and impacts) [M g R].
    pub dissipated: f64,
    /// The mode.
    pub mode: Mode,
}

/// A change of mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Transition {
    /// Time.
    pub t: f64,
    /// The mode before (None for the start).
    pub from: Option<Mode>,
    /// The mode after.
    pub to: Mode,
    /// Why.
    pub reason: TransitionReason,
    /// The state after the transition (after the impact, for a landing).
    pub state: BodyState,
}

/// One flight.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct FlightRecord {
    /// Lift-off time.
    pub t_liftoff: f64,
    /// Landing time (NaN if the run ended in flight).
    pub t_landing: f64,
    /// θ at lift-off.
    pub theta_liftoff: f64,
    /// θ at landing (or at the end of the run).
    pub theta_landing: f64,
    /// The largest gap b − 1 during the flight.
    pub apex: f64,
    /// l at landing (or at the end) − l at lift-off.
    pub distance: f64,
}

/// One impact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactRecord {
    /// Time.
    pub t: f64,
    /// Normal speed of the contact point before the impact (−u_n ≥ 0).
    pub normal_speed: f64,
    /// Slip velocity of the contact point before the impact.
    pub slip_before: f64,
    /// Tangential impulse [M √(gR)].
    pub pt: f64,
    /// Normal impulse.
    pub pn: f64,
    /// Kinetic energy lost in it (including a separation speed the Zeno rule discarded).
    pub energy_lost: f64,
    /// The contact point stuck at the end of the impact (else it was sliding).
    pub sticking: bool,
    /// The mode after it.
    pub outcome: Mode,
}

/// One segment of constant mode.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Segment {
    /// The mode.
    pub mode: Mode,
    /// Why it began.
    pub reason: TransitionReason,
    /// Start time.
    pub t_start: f64,
    /// End time.
    pub t_end: f64,
    /// Right-hand-side evaluations spent in it (0 in flight: it is exact).
    pub nfev: usize,
    /// The friction direction σ of a slip (0 in the other modes).
    pub sigma: f64,
    /// The event that ended it (None: a limit, or the end of the run).
    pub crossing: Option<Crossing>,
}

/// The event that ended a segment: where a function of the state crossed 0, located in
/// time (the sensitivities carry each through its time correction).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Crossing {
    /// Rolling: the paper's lift-off function L rose through 0.
    Liftoff,
    /// Rolling or sliding: the normal force fell through 0.
    NormalForce,
    /// Rolling: the friction margin μ_s F_y − |F_x| fell through 0.
    FrictionCone,
    /// Sliding: the slip velocity reached 0.
    SlipStops,
    /// Sliding: part of the segment went on in the normal impulse (near D = 0).
    Impulse,
    /// Flight: b fell to 1, a landing.
    Landing,
}

named_enum! {
    /// How a run ended.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum MotionStatus {
        /// t reached t_max.
        TimeLimit = 0 => "t_max",
        /// l reached l_max.
        DistanceLimit = 1 => "l_max",
        /// The transition budget was used up.
        MaxTransitions = 2 => "max_transitions",
        /// D fell to its threshold during a slip (Painlevé).
        Painleve = 3 => "painleve",
        /// No consistent contact mode and flight impossible.
        Jam = 4 => "jam",
        /// The integrator or the landing search failed.
        Failed = 5 => "failed",
        /// Ended, as asked, at the first landing (once the mode after it was chosen).
        Landed = 6 => "landed",
    }
}

/// A whole run.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct MotionRun {
    /// Every recorded point, in time order.
    pub points: Vec<Point>,
    /// Every transition, the start first.
    pub transitions: Vec<Transition>,
    /// Every flight.
    pub flights: Vec<FlightRecord>,
    /// Every impact.
    pub impacts: Vec<ImpactRecord>,
    /// Every segment.
    pub segments: Vec<Segment>,
    /// The mechanical energy at the start [M g R].
    pub energy0: f64,
    /// Energy dissipated by sliding friction.
    pub dissipated_slip: f64,
    /// Energy dissipated by impacts.
    pub dissipated_impacts: f64,
    /// How the run ended (None only while it runs).
    pub status: Option<MotionStatus>,
    /// What happened, in words.
    pub message: String,
    /// Right-hand-side evaluations of the integrator.
    pub nfev: usize,
    /// The dense output, when asked for.
    pub dense: Option<MotionSolution>,
}

impl MotionRun {
    /// Records a point (fallibly: `OutOfMemory` instead of an abort).
    #[inline]
    pub(crate) fn push(&mut self, p: Point) -> Result<()> {
        if self.points.len() == self.points.capacity() {
            try_grow("the record of the run", &mut self.points)?;
        }
        self.points.push(p);
        Ok(())
    }

    /// Energy dissipated so far.
    pub fn dissipated(&self) -> f64 {
        self.dissipated_slip + self.dissipated_impacts
    }
}

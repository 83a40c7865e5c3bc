//! A sliding segment under way: its system and events, its start and what it records. `simulate` integrates it alone; a motion
//! map integrates the sliding segments of many runs side by side ([`crate::ode::lanes`]),
//! each the same as alone, bit for bit.

use std::cell::RefCell;

use crate::error::{try_grow, Error, Result};
use crate::mechanics::{BodyState, Ramp};
use crate::modes::contact::Mode;
use crate::modes::slipping::{SlipEvents, Slipping};
use crate::motion::options::SimOptions;
use crate::motion::record::Point;
use crate::ode::lanes::Track;
use crate::ode::{DenseStep, Observation, SinCos, SolverOptions, State};

/// The contact state of a sliding segment's y = (θ, θ̇, l, l̇, q).
#[inline]
pub(crate) fn slip_state(y: &State<5>) -> BodyState {
    BodyState::in_contact(y[0], y[1], y[2], y[3])
}

/// What a sliding segment has recorded so far.
struct Record {
    points: Vec<Point>,
    /// The dense output of every step, when asked for.
    steps: Vec<DenseStep<5>>,
    /// The first failed allocation, if any: after it nothing more is recorded.
    memory: Option<Error>,
}

/// A sliding segment between its start and its end.
pub(crate) struct SlipTrack {
    events: SlipEvents,
    /// Start time.
    pub t0: f64,
    /// Start state (θ, θ̇, l, l̇, q = 0).
    pub y0: State<5>,
    /// The end of the integration (the run's t_max).
    pub t_end: f64,
    /// The integrator's options (the run's, with the step budget left).
    pub solver: SolverOptions,
    /// Energy dissipated before the segment by sliding, and by impacts (which stays so
    /// during it): a point's `dissipated` is (slid + q) + impacts.
    slid: f64,
    impacts: f64,
    record_points: bool,
    dense_output: bool,
    record: RefCell<Record>,
}

impl SlipTrack {
    /// The segment from `s` with friction direction `sigma`, at t0 with `solver`, after
    /// (by sliding, by impacts) dissipated so far; its start point recorded.
    pub(crate) fn begin(
        ramp: &Ramp,
        opts: &SimOptions,
        (s, sigma): (BodyState, f64),
        (t0, solver): (f64, SolverOptions),
        (slid, impacts): (f64, f64),
    ) -> Result<Self> {
        let track = Self {
            events: SlipEvents {
                slipping: Slipping::new(*ramp, sigma, opts.law.mu_k),
                l_max: opts.l_max,
            },
            t0,
            y0: State::<5>::new(s.theta, s.omega, s.l, s.ldot, 0.0),
            t_end: opts.t_max,
            solver: SolverOptions {
                dense_every_step: solver.dense_every_step || opts.dense_output,
                ..solver
            },
            slid,
            impacts,
            record_points: opts.record_points,
            dense_output: opts.dense_output,
            record: RefCell::new(Record {
                points: Vec::new(),
                steps: Vec::new(),
                memory: None,
            }),
        };
        track.record_point(&mut track.record.borrow_mut().points, t0, &track.y0, None)?;
        Ok(track)
    }

    /// The friction direction σ of the slip.
    pub(crate) fn sigma(&self) -> f64 {
        self.events.slipping.sigma
    }

    /// The points and dense-output steps recorded (an error if recording ran out of
    /// memory).
    pub(crate) fn finish(self) -> Result<(Vec<Point>, Vec<DenseStep<5>>)> {
        let rec = self.record.into_inner();
        match rec.memory {
            Some(e) => Err(e),
            None => Ok((rec.points, rec.steps)),
        }
    }

    /// Records the point (t, y), if points are recorded (with the trigonometry of θ from
    /// `trig` when it is there).
    fn record_point(
        &self,
        points: &mut Vec<Point>,
        t: f64,
        y: &State<5>,
        trig: Option<SinCos>,
    ) -> Result<()> {
        if !self.record_points {
            return Ok(());
        }
        let trig = SinCos::reuse(y[0], trig);
        let slipping = &self.events.slipping;
        let k = slipping.kinematics_sc(y[1], trig.sin, trig.cos);
        let state = slip_state(y);
        if points.len() == points.capacity() {
            try_grow("the record of the run", points)?;
        }
        points.push(Point {
            t,
            state,
            fx: k.fx,
            fy: k.fy,
            energy: slipping.ramp.energy_of_trig(&state, (trig.sin, trig.cos)),
            dissipated: self.slid + y[4] + self.impacts,
            mode: Mode::Slip,
        });
        Ok(())
    }
}

impl Track<5> for SlipTrack {
    type Sys = Slipping;
    type Events = SlipEvents;
    #[inline]
    fn sys(&self) -> &Slipping {
        &self.events.slipping
    }
    #[inline]
    fn events(&self) -> &SlipEvents {
        &self.events
    }
    #[inline]
    fn observe(&self, obs: Observation<'_, 5>) {
        let Observation::Step { dense, t, y, trig } = obs else {
            return;
        };
        let rec = &mut *self.record.borrow_mut();
        // After a failed allocation the rest is not recorded; the run reports it.
        if rec.memory.is_some() {
            return;
        }
        if let Err(e) = self.record_point(&mut rec.points, t, y, trig) {
            rec.memory = Some(e);
        } else if let (true, Some(dense)) = (self.dense_output, dense) {
            // (always there: the solver makes every step's when it is recorded)
            match try_grow("the dense output", &mut rec.steps) {
                Ok(()) => rec.steps.push(*dense),
                Err(e) => rec.memory = Some(e),
            }
        }
    }
}

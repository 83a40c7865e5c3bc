//! Maps of the full motion: what the body does at every point of a grid over
//! (α, χ, k_m fraction, μ_s, μ_k, e, θ0, θ̇0) ([`MotionAxes`]) or of a list of points
//! ([`MotionColumns`](crate::maps::motion_points::MotionColumns)), each point run by
//! [`simulate`] to its first landing and kept as a fixed-size [`MotionSummary`]. Both are
//! [`MotionPoints`] sources of one driver, [`motion_map`].
//!
//! Each point is computed from its index alone and written in place (the parallel driver of
//! [`crate::maps::parallel`]), so maps are bit-identical for any thread count, and a point's
//! summary is exactly [`MotionSummary::of`] the run `simulate` gives at that point.

use crate::error::{Error, Result};
use crate::maps::parallel::par_fill_pieces_until;
use crate::mechanics::{Cylinder, Ramp, Rule};
use crate::modes::contact::{ContactLaw, Mode, TransitionReason};
use crate::modes::rolling::run::RollOptions;
use crate::modes::rolling::track::roll_batch;
use crate::motion::simulate::{Need, Sim};
use crate::motion::sliding::SlipTrack;
use crate::motion::{simulate, MotionRun, MotionStatus, SimOptions};
use crate::ode::lanes::{solve_lanes_with, Keyed, Start};
use crate::ode::{Integrator, SolverOptions};
use std::cell::{Cell, RefCell};

/// Modes of the sequence kept per point (the start's mode first): with 2 bits per mode the
/// code fits a `u16`.
pub const SEQUENCE_LEN: usize = 8;

/// `status` of a point whose parameters are invalid (μ_k > μ_s, a value out of range).
pub const INVALID: u8 = 255;

/// `liftoff_reason` of a point that never flies.
pub const NO_REASON: u8 = 255;

named_enum! {
    /// How the first landing ended.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum LandingOutcome {
        /// No landing (no flight, or the run ended in the air).
        None = 0 => "none",
        /// The body leaves the impact rolling.
        Sticks = 1 => "sticks",
        /// It leaves the impact sliding.
        Slides = 2 => "slides",
        /// It bounces (flies again).
        Bounces = 3 => "bounces",
        /// No contact mode is consistent after the impact: the run ends there (a jam).
        Ends = 4 => "ends",
    }
}

/// What one point of a motion map did, up to its first landing.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionSummary {
    /// [`MotionStatus`] code of the run, or [`INVALID`].
    pub status: u8,
    /// The first [`SEQUENCE_LEN`] modes, Σ (mode_i + 1)·4^i (0: no mode; see [`sequence_code`]).
    pub sequence: u16,
    /// Modes in the run (the start's included); more than [`SEQUENCE_LEN`] means the code is
    /// cut.
    pub n_modes: u16,
    /// Lift-off straight out of pure rolling: the run starts rolling and its second mode is a
    /// flight by the lift-off rule (a JARM).
    pub jarm: bool,
    /// A slip came before the first flight (or in a run that never flies).
    pub slipped_first: bool,
    /// Time and angle of the first slip onset (NaN if none).
    pub slip_t: f64,
    /// See `slip_t`.
    pub slip_theta: f64,
    /// [`TransitionReason`] code of the first transition into flight, or [`NO_REASON`].
    pub liftoff_reason: u8,
    /// Time and angle of the first lift-off (NaN if none).
    pub liftoff_t: f64,
    /// See `liftoff_t`.
    pub liftoff_theta: f64,
    /// Duration of the first flight (NaN if it did not land).
    pub flight_time: f64,
    /// Largest height of the first flight above contact, b − 1 (NaN if no flight).
    pub apex: f64,
    /// Distance along the ramp covered by the first flight (NaN if no flight).
    pub distance: f64,
    /// [`LandingOutcome`] code of the first landing.
    pub landing: u8,
    /// Energy dissipated over the run (by sliding and by the impacts) [M g R].
    pub energy_lost: f64,
}

impl MotionSummary {
    /// The summary of a point that was not run (invalid parameters).
    pub const fn invalid() -> Self {
        Self {
            status: INVALID,
            sequence: 0,
            n_modes: 0,
            jarm: false,
            slipped_first: false,
            slip_t: f64::NAN,
            slip_theta: f64::NAN,
            liftoff_reason: NO_REASON,
            liftoff_t: f64::NAN,
            liftoff_theta: f64::NAN,
            flight_time: f64::NAN,
            apex: f64::NAN,
            distance: f64::NAN,
            landing: LandingOutcome::None as u8,
            energy_lost: f64::NAN,
        }
    }

    /// The summary of a run made under the lift-off `rule`.
    pub fn of(run: &MotionRun, rule: Rule) -> Self {
        let tr = &run.transitions;
        let first_flight = tr.iter().position(|t| t.to == Mode::Flight);
        let before_flight = &tr[..first_flight.unwrap_or(tr.len())];
        let slip = before_flight.iter().find(|t| t.to == Mode::Slip);
        let mut s = Self {
            status: run.status.map_or(MotionStatus::Failed, |s| s) as u8,
            sequence: sequence_code(tr.iter().map(|t| t.to)),
            n_modes: tr.len().min(u16::MAX as usize) as u16,
            jarm: first_flight == Some(1)
                && tr[0].to == Mode::Roll
                && leaves_by_the_rule(rule, tr[1].reason),
            slipped_first: slip.is_some(),
            slip_t: slip.map_or(f64::NAN, |t| t.t),
            slip_theta: slip.map_or(f64::NAN, |t| t.state.theta),
            energy_lost: run.dissipated(),
            ..Self::invalid()
        };
        if let Some(k) = first_flight {
            s.liftoff_reason = tr[k].reason as u8;
            s.liftoff_t = tr[k].t;
            s.liftoff_theta = tr[k].state.theta;
        }
        if let Some(f) = run.flights.first() {
            s.flight_time = f.t_landing - f.t_liftoff;
            s.apex = f.apex;
            s.distance = f.distance;
        }
        if !run.impacts.is_empty() {
            // The transition out of the first landing, if the run went on.
            let after = first_flight.and_then(|k| tr[k + 1..].first());
            s.landing = match after.map(|t| t.to) {
                Some(Mode::Roll) => LandingOutcome::Sticks,
                Some(Mode::Slip) => LandingOutcome::Slides,
                Some(Mode::Flight) => LandingOutcome::Bounces,
                None => LandingOutcome::Ends,
            } as u8;
        }
        s
    }
}

/// Whether a flight straight out of rolling for `reason` is the lift-off `rule` firing (a
/// JARM): under "paper" its condition χθ̇² cos θ = cos α; under "normal_force" F_y reaching 0,
/// which the friction ratio |F_x|/F_y → ∞ turns into a slip onset found inconsistent just
/// before it (`docs/motion.md`), both as the JARM classification counts them.
pub fn leaves_by_the_rule(rule: Rule, reason: TransitionReason) -> bool {
    match rule {
        Rule::Paper => reason == TransitionReason::Liftoff,
        Rule::NormalForce => matches!(
            reason,
            TransitionReason::NormalForce | TransitionReason::SlipInconsistent
        ),
    }
}

/// Σ (mode_i + 1)·4^i over the first [`SEQUENCE_LEN`] modes: 0 digits mark the end, so
/// every sequence has its own code (ROLL→FLIGHT = 1 + 3·4 = 13).
pub fn sequence_code(modes: impl Iterator<Item = Mode>) -> u16 {
    modes
        .take(SEQUENCE_LEN)
        .enumerate()
        .map(|(i, m)| (m as u16 + 1) << (2 * i))
        .sum()
}

/// Where the points of a motion map come from: a grid ([`MotionAxes`]) or columns of points
/// ([`MotionColumns`](crate::maps::motion_points::MotionColumns)). [`motion_map`] runs
/// either, so the two differ only in how point g's values are found.
pub trait MotionPoints: Sync {
    /// The number of points, or an error naming the first bad axis or column.
    fn count(&self) -> Result<usize>;

    /// The values of point `g` (< [`count`](Self::count)) in the order of
    /// [`PARAMETERS`](crate::motion::options::PARAMETERS) (α, χ, k_m, μ_s, μ_k, e, θ0, θ̇0),
    /// μ_k = μ_s where it is not given.
    fn values(&self, g: usize) -> [f64; 8];
}

/// The axes of a motion map (each non-empty; `mu_k` empty means μ_k = μ_s at every point).
/// The grid is their product in C order (α slowest, θ̇0 fastest), with k_m = frac·(1 − χ).
#[derive(Debug, Clone, Copy)]
pub struct MotionAxes<'a> {
    /// Ramp angles α (rad).
    pub alpha: &'a [f64],
    /// χ = d/R.
    pub chi: &'a [f64],
    /// k_m/(1 − χ) ∈ [0, 1].
    pub frac: &'a [f64],
    /// Static friction coefficients.
    pub mu_s: &'a [f64],
    /// Kinetic friction coefficients (empty: μ_k = μ_s).
    pub mu_k: &'a [f64],
    /// Stronge's coefficients of restitution.
    pub restitution: &'a [f64],
    /// Initial angles θ0.
    pub theta0: &'a [f64],
    /// Initial angular velocities θ̇0.
    pub omega0: &'a [f64],
}

impl MotionAxes<'_> {
    /// Lengths of the eight axes (μ_k counted as 1 when empty).
    pub fn shape(&self) -> [usize; 8] {
        [
            self.alpha.len(),
            self.chi.len(),
            self.frac.len(),
            self.mu_s.len(),
            self.mu_k.len().max(1),
            self.restitution.len(),
            self.theta0.len(),
            self.omega0.len(),
        ]
    }
}

impl MotionPoints for MotionAxes<'_> {
    /// The number of grid points (an error if it overflows, or an axis other than μ_k is
    /// empty).
    fn count(&self) -> Result<usize> {
        let names = crate::motion::options::PARAMETERS;
        let shape = self.shape();
        if let Some(k) = shape.iter().position(|&n| n == 0) {
            return Err(Error::InvalidParameter {
                name: names[k],
                value: 0.0,
                allowed: "an axis of at least one value".to_string(),
            });
        }
        shape
            .iter()
            .try_fold(1usize, |a, &n| a.checked_mul(n))
            .ok_or(Error::OutOfMemory {
                what: "the grid",
                bytes: u64::MAX,
            })
    }

    /// Grid point `g`: its index on each axis, C order.
    fn values(&self, g: usize) -> [f64; 8] {
        let shape = self.shape();
        let mut idx = [0usize; 8];
        let mut rest = g;
        for k in (0..8).rev() {
            idx[k] = rest % shape[k];
            rest /= shape[k];
        }
        let chi = self.chi[idx[1]];
        let mu_s = self.mu_s[idx[3]];
        [
            self.alpha[idx[0]],
            chi,
            self.frac[idx[2]] * (1.0 - chi),
            mu_s,
            self.mu_k.get(idx[4]).copied().unwrap_or(mu_s),
            self.restitution[idx[5]],
            self.theta0[idx[6]],
            self.omega0[idx[7]],
        ]
    }
}

/// The ramp and options of one point from its values, in the order of
/// [`PARAMETERS`](crate::motion::options::PARAMETERS) (α, χ, k_m, μ_s, μ_k, e, θ0, θ̇0), the
/// rest from `base`; None where a value is invalid (k_m > 1 − χ, μ_k > μ_s, out of range).
pub(crate) fn point_from(values: [f64; 8], base: &SimOptions) -> Option<(Ramp, SimOptions)> {
    let [alpha, chi, km, mu_s, mu_k, restitution, theta0, omega0] = values;
    let ramp = Ramp::new(Cylinder::new(chi, km).ok()?, alpha).ok()?;
    let rule = base.law.rule;
    let opts = SimOptions {
        law: ContactLaw { mu_s, mu_k, rule },
        restitution,
        theta0,
        omega0,
        ..*base
    };
    opts.validate().ok()?;
    Some((ramp, opts))
}

/// The options every point of a map shares.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct MotionMapOptions {
    /// The lift-off rule.
    pub rule: Rule,
    /// End time of each run (it ends earlier at its first landing).
    pub t_max: f64,
    /// Transitions a run may make before its first landing.
    pub max_transitions: usize,
    /// Tolerances and the step budget of each run.
    pub solver: SolverOptions,
}

impl MotionMapOptions {
    /// The simulator's options for a point, before the point's own values are filled in.
    pub(crate) fn base(&self) -> SimOptions {
        SimOptions {
            law: ContactLaw {
                mu_s: 1.0,
                mu_k: 1.0,
                rule: self.rule,
            },
            t_max: self.t_max,
            max_transitions: self.max_transitions,
            solver: self.solver,
            stop_at_landing: true,
            record_points: false,
            dense_output: false,
            ..SimOptions::default()
        }
    }

    /// Checks the shared options, naming the first bad one.
    pub fn validate(&self) -> Result<()> {
        self.base().validate()
    }
}

/// The summary of one point, as [`motion_map`] computes it: invalid parameters (k_m = 0
/// included) give [`MotionSummary::invalid`], a run that fails its status.
pub fn motion_point(ramp: &Ramp, opts: &SimOptions) -> MotionSummary {
    summary(simulate(ramp, opts), opts.law.rule)
}

/// The summary of a run's result.
fn summary(result: Result<MotionRun>, rule: Rule) -> MotionSummary {
    match result {
        Ok(run) => MotionSummary::of(&run, rule),
        Err(Error::InvalidParameter { .. }) => MotionSummary::invalid(),
        Err(_) => MotionSummary {
            status: MotionStatus::Failed as u8,
            ..MotionSummary::invalid()
        },
    }
}

/// Fills `out` (one summary per point of `points`) in parallel on `n_threads` threads, each
/// exactly [`motion_point`] at its point (an invalid point: [`MotionSummary::invalid`]), the
/// same bits for any thread count; `stop()` may end the work (`Error::Interrupted`). The
/// count of `points` is checked first, then the options.
pub fn motion_map(
    points: &impl MotionPoints,
    opts: &MotionMapOptions,
    n_threads: usize,
    out: &mut [MotionSummary],
    stop: &dyn Fn() -> bool,
) -> Result<()> {
    crate::maps::parallel::check_len("out", out.len(), points.count()?)?;
    opts.validate()?;
    let base = opts.base();
    let (rule, method) = (base.law.rule, base.solver.method);
    par_fill_pieces_until(
        out,
        n_threads,
        |start, piece, cancelled| {
            let point = |g| point_from(points.values(g), &base);
            motion_piece(&point, rule, method, start, piece, cancelled)
        },
        stop,
    )
}

/// The summaries of the points start, start + 1, … (`point(g)`: the ramp and options of
/// point g, None where invalid) into `out`, each exactly [`motion_point`] there. The points'
/// runs go on together, in waves: every rolling segment that some run needs is integrated
/// side by side with the others ([`roll_batch`]), then every sliding segment
/// ([`solve_lanes_with`]), each run going on (flights, impacts, decisions) as soon as its
/// segment ends, until every run is over.
fn motion_piece(
    point: &dyn Fn(usize) -> Option<(Ramp, SimOptions)>,
    rule: Rule,
    method: Integrator,
    start: usize,
    out: &mut [MotionSummary],
    cancelled: &dyn Fn() -> bool,
) {
    // The points' parameters first: the runs borrow them.
    let params: Vec<Option<(Ramp, SimOptions)>> =
        (0..out.len()).map(|k| point(start + k)).collect();
    // As `motion_point`: a run is not stopped between its segments (a map stops between
    // the segments' steps, and discards what it has).
    let never = || false;
    let waves = Waves {
        runs: RefCell::new((0..out.len()).map(|_| None).collect()),
        rolls: RefCell::new(Vec::new()),
        slips: RefCell::new(Vec::new()),
        out: Cell::from_mut(out).as_slice_of_cells(),
        rule,
    };
    for (k, p) in params.iter().enumerate() {
        match p {
            None => waves.out[k].set(MotionSummary::invalid()),
            Some((ramp, o)) => match Sim::begin(ramp, o, &never) {
                Err(e) => waves.out[k].set(summary(Err(e), waves.rule)),
                Ok(mut run) => {
                    let need = run.advance();
                    waves.route(k, run, need);
                }
            },
        }
    }
    while !cancelled() && !waves.idle() {
        roll_batch(
            method,
            || {
                let (k, o) = waves.rolls.borrow_mut().pop()?;
                params[k].as_ref().map(|(ramp, _)| (k, *ramp, o))
            },
            |k, rr| waves.resume(k, |run| run.rolled(rr)),
            cancelled,
        );
        solve_lanes_with(
            method,
            || {
                if cancelled() {
                    return None;
                }
                let (key, track) = waves.slips.borrow_mut().pop()?;
                let track: SlipTrack = *track;
                let (t0, y0, t_end, opts) = (track.t0, track.y0, track.t_end, track.solver);
                Some(Start {
                    track: Keyed { key, track },
                    t0,
                    y0,
                    t_end,
                    opts,
                })
            },
            |k: Keyed<usize, SlipTrack>, outcome| {
                waves.resume(k.key, |run| run.slid(k.track, &outcome))
            },
            cancelled,
        );
    }
}

/// The runs of a piece of a motion map between their segments ([`motion_piece`]).
struct Waves<'p> {
    /// Each point's run while it waits for a segment.
    runs: RefCell<Vec<Option<Sim<'p>>>>,
    /// The rolling segments waiting: (point, options).
    rolls: RefCell<Vec<(usize, RollOptions)>>,
    /// The sliding segments waiting: (point, track).
    slips: RefCell<Vec<(usize, Box<SlipTrack>)>>,
    out: &'p [Cell<MotionSummary>],
    rule: Rule,
}

impl<'p> Waves<'p> {
    /// No segment waits.
    fn idle(&self) -> bool {
        self.rolls.borrow().is_empty() && self.slips.borrow().is_empty()
    }

    /// Point k's run after `advance`: its summary, or the segment it waits for.
    fn route(&self, k: usize, run: Sim<'p>, need: Result<Need>) {
        match need {
            Err(e) => self.out[k].set(summary(Err(e), self.rule)),
            Ok(Need::Done) => self.out[k].set(summary(run.finish(), self.rule)),
            Ok(Need::Roll(o)) => {
                self.runs.borrow_mut()[k] = Some(run);
                self.rolls.borrow_mut().push((k, o));
            }
            Ok(Need::Slip(track)) => {
                self.runs.borrow_mut()[k] = Some(run);
                self.slips.borrow_mut().push((k, track));
            }
        }
    }

    /// Point k's run, its segment integrated (`go_on` hands it over), on to what it needs
    /// next.
    fn resume(&self, k: usize, go_on: impl FnOnce(&mut Sim<'p>) -> Result<()>) {
        let taken = self.runs.borrow_mut()[k].take();
        let mut run = taken.expect("a run waits for its segment");
        let need = go_on(&mut run).and_then(|()| run.advance());
        self.route(k, run, need);
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    fn opts() -> MotionMapOptions {
        MotionMapOptions {
            rule: Rule::Paper,
            t_max: 100.0,
            max_transitions: 50,
            solver: SolverOptions::default(),
        }
    }

    #[test]
    fn sequence_codes_are_distinct_and_named_by_their_digits() {
        use Mode::*;
        assert_eq!(sequence_code([Roll, Flight].into_iter()), 1 + 3 * 4);
        assert_eq!(
            sequence_code([Roll, Slip, Flight, Roll].into_iter()),
            1 + 2 * 4 + 3 * 16 + 32 * 2
        );
        assert_ne!(
            sequence_code([Roll].into_iter()),
            sequence_code([Roll, Roll].into_iter())
        );
    }

    #[test]
    fn a_grid_point_is_the_summary_of_simulate_there() {
        let alpha = [0.4, 0.7];
        let chi = [0.15, 0.5];
        let frac = [0.02 / 0.85, 0.8];
        let mu = [1.0];
        let e = [0.0, 0.5];
        let zero = [0.0];
        let axes = MotionAxes {
            alpha: &alpha,
            chi: &chi,
            frac: &frac,
            mu_s: &mu,
            mu_k: &[],
            restitution: &e,
            theta0: &zero,
            omega0: &zero,
        };
        let n = axes.count().unwrap();
        let mut out = vec![MotionSummary::invalid(); n];
        motion_map(&axes, &opts(), 1, &mut out, &|| false).unwrap();
        let mut two = out.clone();
        motion_map(&axes, &opts(), 2, &mut two, &|| false).unwrap();
        for (g, (a, b)) in out.iter().zip(&two).enumerate() {
            // Bit-identical for any thread count (NaN fields compared by bits).
            assert_eq!(format!("{a:?}"), format!("{b:?}"), "point {g}");
            let (ramp, o) = point_from(axes.values(g), &opts().base()).unwrap();
            let run = simulate(&ramp, &o).unwrap();
            assert_eq!(
                format!("{a:?}"),
                format!("{:?}", MotionSummary::of(&run, o.law.rule))
            );
            assert_eq!(a.status, MotionStatus::Landed as u8, "point {g}: {a:?}");
        }
        assert!(out.iter().any(|s| s.jarm) && out.iter().any(|s| s.slipped_first));
    }

    #[test]
    fn points_of_every_start_are_the_summary_of_simulate_there() {
        // The first rolling segments of a map run side by side: starts from rest and moving,
        // slipping or flying at once, invalid points (μ_k > μ_s), every pair.
        let (alpha, chi, frac) = ([0.3, 1.2], [0.15, 0.6], [0.1, 0.9]);
        let (mu_s, mu_k) = ([0.2, 1.0], [0.15, 0.5]);
        let (theta0, omega0) = ([0.0, 2.0], [0.0, 1.5]);
        let axes = MotionAxes {
            alpha: &alpha,
            chi: &chi,
            frac: &frac,
            mu_s: &mu_s,
            mu_k: &mu_k,
            restitution: &[0.5],
            theta0: &theta0,
            omega0: &omega0,
        };
        for method in crate::ode::Integrator::ALL {
            let o = MotionMapOptions {
                t_max: 20.0,
                max_transitions: 20,
                solver: SolverOptions {
                    method,
                    ..SolverOptions::default()
                },
                ..opts()
            };
            let mut out = vec![MotionSummary::invalid(); axes.count().unwrap()];
            motion_map(&axes, &o, 2, &mut out, &|| false).unwrap();
            // Points by their first mode (none: invalid).
            let mut first = [0; 4];
            for (g, got) in out.iter().enumerate() {
                let alone = match point_from(axes.values(g), &o.base()) {
                    Some((ramp, p)) => motion_point(&ramp, &p),
                    None => MotionSummary::invalid(),
                };
                first[(alone.sequence & 3) as usize] += 1;
                assert_eq!(format!("{got:?}"), format!("{alone:?}"), "point {g}");
            }
            assert!(first.iter().all(|&n| n > 10), "{first:?}");
            assert!(out.iter().any(|s| s.status == MotionStatus::Landed as u8));
            assert!(out
                .iter()
                .any(|s| s.status == MotionStatus::TimeLimit as u8));
        }
    }

    #[test]
    fn long_stick_slip_chatter_in_a_map_is_simulate_too() {
        // On a ramp of 1° these bodies alternate between rolling and slipping before they
        // ever fly: dozens of segments, waves of both kinds until max_transitions.
        let axes = MotionAxes {
            alpha: &[1f64.to_radians()],
            chi: &[0.7713, 0.813],
            frac: &[0.5209, 0.6043, 0.7296],
            mu_s: &[1.0],
            mu_k: &[],
            restitution: &[0.0],
            theta0: &[0.0],
            omega0: &[0.0],
        };
        for method in crate::ode::Integrator::ALL {
            let o = MotionMapOptions {
                max_transitions: 50,
                solver: SolverOptions {
                    method,
                    ..SolverOptions::default()
                },
                ..opts()
            };
            let mut out = vec![MotionSummary::invalid(); axes.count().unwrap()];
            motion_map(&axes, &o, 1, &mut out, &|| false).unwrap();
            for (g, got) in out.iter().enumerate() {
                let (ramp, p) = point_from(axes.values(g), &o.base()).unwrap();
                let alone = motion_point(&ramp, &p);
                assert_eq!(format!("{got:?}"), format!("{alone:?}"), "point {g}");
            }
            let chattering = out
                .iter()
                .filter(|s| s.status == MotionStatus::MaxTransitions as u8)
                .count();
            assert!(chattering >= 3, "{chattering}");
        }
    }

    #[test]
    fn invalid_points_are_marked_not_errors() {
        let axes = MotionAxes {
            alpha: &[0.5],
            chi: &[0.5],
            frac: &[0.5],
            mu_s: &[0.5],
            mu_k: &[0.4, 0.6],
            restitution: &[0.0],
            theta0: &[0.0],
            omega0: &[0.0],
        };
        let mut out = vec![MotionSummary::invalid(); 2];
        motion_map(&axes, &opts(), 1, &mut out, &|| false).unwrap();
        assert_eq!(out[0].status, MotionStatus::Landed as u8);
        assert_eq!(out[1].status, INVALID);
    }
}

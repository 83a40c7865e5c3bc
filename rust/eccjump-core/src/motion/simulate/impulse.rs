//! The driver's slip in the normal impulse ([`crate::modes::slip_in_impulse`]): where F_y
//! rises to `F_SWITCH` during a slip, or a slip begins above it, the slip goes on against
//! the normal impulse until it stops, lifts off, recovers (time again, no transition) or is
//! an impulsive jam. Rare and short, so it is integrated alone, also inside a motion map:
//! a map's run is the same as `simulate`'s, bit for bit.

use super::{Driver, Next};
use crate::error::{try_grow, Result};
use crate::mechanics::BodyState;
use crate::modes::contact::{Mode, TransitionReason};
use crate::modes::slip_in_impulse::{ImpulseEvent, ImpulseEvents, D_JAM, P_MAX};
use crate::modes::slipping::Slipping;
use crate::motion::record::{Crossing, MotionStatus, Point};
use crate::motion::solution::Piece;
use crate::ode::{self, Observation, Outcome, State, Status};

/// The contact state of y = (t, θ, θ̇, l, l̇, q).
fn state_of(y: &State<6>) -> BodyState {
    BodyState::in_contact(y[1], y[2], y[3], y[4])
}

impl Driver<'_> {
    /// The slip from `s` with friction direction σ, integrated in the normal impulse from
    /// the run's time: what comes next.
    pub(super) fn slip_in_impulse(&mut self, s: BodyState, sigma: f64) -> Result<Next> {
        self.crossing = Some(Crossing::Impulse);
        let opts = self.opts;
        let events = ImpulseEvents {
            slip: Slipping::new(*self.ramp, sigma, opts.law.mu_k),
            t_max: opts.t_max,
            l_max: opts.l_max,
        };
        let solver = ode::SolverOptions {
            max_steps: self.steps_left.max(1),
            dense_every_step: opts.dense_output,
            ..opts.solver
        };
        let y0 = State::<6>::new(self.t, s.theta, s.omega, s.l, s.ldot, 0.0);
        // What the observer keeps: every accepted step's end and dense output, grown
        // fallibly (the first failure ends the recording and is reported).
        let (mut ends, mut steps, mut memory) = (vec![y0], Vec::new(), None);
        let outcome = ode::solve_until(
            &events.slip,
            &events,
            0.0,
            y0,
            P_MAX,
            &solver,
            &mut |obs: Observation<'_, 6>| {
                let Observation::Step { y, dense, .. } = obs else {
                    return;
                };
                if memory.is_some() {
                    return;
                }
                let kept = try_grow("the record of the run", &mut ends).map(|()| ends.push(*y));
                let kept = match (kept, dense.filter(|_| opts.dense_output)) {
                    (Ok(()), Some(d)) => {
                        try_grow("the dense output", &mut steps).map(|()| steps.push(*d))
                    }
                    (kept, _) => kept,
                };
                memory = kept.err();
            },
            self.stop,
        );
        if let Some(e) = memory {
            return Err(e);
        }
        self.impulse_end(&events.slip, &ends, steps, &outcome)
    }

    /// The slip in the impulse has ended with `outcome`, having passed through `ends`: its
    /// points and dense output recorded, the run's clock and ledger moved on.
    fn impulse_end(
        &mut self,
        slip: &Slipping,
        ends: &[State<6>],
        steps: Vec<ode::DenseStep<6>>,
        outcome: &Outcome<6>,
    ) -> Result<Next> {
        if outcome.status == Status::Stopped {
            return Err(crate::error::Error::Interrupted);
        }
        let before = self.run.dissipated();
        for y in ends.iter().filter(|_| self.opts.record_points) {
            let state = state_of(y);
            let k = slip.kinematics(y[1], y[2]);
            self.run.push(Point {
                t: y[0],
                state,
                fx: k.fx,
                fy: k.fy,
                energy: self.ramp.energy_of(&state),
                dissipated: before + y[5],
                mode: Mode::Slip,
            })?;
        }
        if let Some(sol) = self.run.dense.as_mut() {
            sol.pieces.push((self.t, Piece::Impulse { steps }));
        }
        self.steps_left = self.steps_left.saturating_sub(outcome.n_accepted);
        self.run.nfev += outcome.nfev;
        self.run.dissipated_slip += outcome.y[5];
        self.t = outcome.y[0];
        let end = state_of(&outcome.y);
        // The normal force grows without bound while the impulse stays finite (P = outcome.t,
        // the independent variable), except where P itself passed P_MAX.
        let jam = |cause: &str| {
            Next::End(
                MotionStatus::Painleve,
                format!(
                    "Painlevé jam: during the slip at t = {:.6}, θ = {:.4}°, {cause} with the slip \
                     still on (normal impulse {:.4} M√(gR)): the rigid model cannot continue",
                    outcome.y[0],
                    end.theta.to_degrees(),
                    outcome.t,
                ),
            )
        };
        let force = format!("the normal force grows without bound (D fell to {D_JAM:e})");
        Ok(match outcome.status {
            Status::Finished => jam("the normal impulse passed 1e4 (P_MAX)"),
            Status::Event(k) => match ImpulseEvent::ALL[k] {
                ImpulseEvent::NormalForce => {
                    Next::Mode(Mode::Flight, TransitionReason::NormalForce, end, 0.0)
                }
                ImpulseEvent::Stops => self.slip_stopped(end),
                ImpulseEvent::Recovers => Next::Resume(end, slip.sigma),
                ImpulseEvent::Jam => jam(&force),
                ImpulseEvent::TLimit => {
                    self.t = self.opts.t_max;
                    self.end_of_time()
                }
                ImpulseEvent::LLimit => self.end_of_ramp(),
            },
            other => self.failed("slipping (in the normal impulse)", other),
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{Cylinder, Ramp, Rule};
    use crate::modes::contact::ContactLaw;
    use crate::motion::options::SimOptions;
    use crate::motion::simulate;

    /// Issue 38's reproducer: D falls to 2.1e-7 in a slip whose velocity then reaches 0.
    fn reproducer(dense_output: bool) -> (Ramp, crate::motion::record::MotionRun) {
        let body = Cylinder::new(0.677301413067792, 0.17587848529965222).unwrap();
        let ramp = Ramp::new(body, 1.3179033062341512).unwrap();
        let opts = SimOptions {
            law: ContactLaw {
                mu_s: 1.4800299961460412,
                mu_k: 1.0117188986517158,
                rule: Rule::Paper,
            },
            theta0: 3.479669684013747,
            omega0: 0.08695780632623507,
            t_max: 30.0,
            dense_output,
            ..SimOptions::default()
        };
        (ramp, simulate(&ramp, &opts).unwrap())
    }

    #[test]
    fn a_slip_through_a_near_singular_normal_force_goes_on() {
        let (ramp, run) = reproducer(false);
        let seq: Vec<_> = run.transitions.iter().map(|t| (t.to, t.reason)).collect();
        assert_eq!(
            seq[..4],
            [
                (Mode::Slip, TransitionReason::Start),
                (Mode::Slip, TransitionReason::Reverse),
                (Mode::Flight, TransitionReason::NormalForce),
                (Mode::Slip, TransitionReason::Impact),
            ]
        );
        // The figures (integrated tighter and against the normal impulse there).
        let times: Vec<f64> = run.transitions.iter().map(|t| t.t).collect();
        assert!((times[1] - 4.1456228514).abs() < 1e-9, "{}", times[1]);
        assert!((times[2] - 4.1599367580).abs() < 1e-9, "{}", times[2]);
        assert!((times[3] - 14.028).abs() < 1e-3, "{}", times[3]);
        // The peak normal force, near 6e4, and the ledger along the whole run.
        let peak = run.points.iter().map(|p| p.fy).fold(0.0, f64::max);
        assert!((5e4..8e4).contains(&peak), "{peak}");
        for p in &run.points {
            let ledger = p.energy + p.dissipated - run.energy0;
            assert!(ledger.abs() < 1e-8, "{ledger} at t = {}", p.t);
            assert_eq!(p.energy, ramp.energy_of(&p.state));
        }
        assert!(run.points.windows(2).all(|w| w[0].t <= w[1].t));
    }

    #[test]
    fn the_dense_output_follows_the_slip_in_the_impulse() {
        let (_, run) = reproducer(true);
        let sol = run.dense.as_ref().unwrap();
        assert!(sol
            .pieces
            .iter()
            .any(|(_, p)| matches!(p, Piece::Impulse { .. })));
        // Every recorded point, the stretch in the impulse included, is sol(t) there.
        for p in run.points.iter().filter(|p| p.t < 4.16) {
            let s = sol.state(p.t).unwrap();
            let scale = 1.0 + p.state.omega.abs() + p.state.theta.abs();
            assert!(
                (s.theta - p.state.theta).abs() < 1e-9 * scale,
                "t = {}",
                p.t
            );
            assert!(
                (s.omega - p.state.omega).abs() < 1e-6 * scale,
                "t = {}",
                p.t
            );
        }
    }

    /// Issue 46's reproducer: a slip with D near 1e-5 whose normal force falls to 0. In the
    /// impulse form t(P) has a square-root end there, and a step across it recorded time
    /// running backwards; the slip now goes back to time before F_y reaches 0.
    #[test]
    fn a_lift_off_from_a_slip_with_a_small_d_keeps_time_running_forwards() {
        let body = Cylinder::new(0.9758587534345973, 0.02414124656540273).unwrap();
        let ramp = Ramp::new(body, 1.1591320168877168).unwrap();
        let run_at = |rtol: f64, atol: f64| {
            let mut opts = SimOptions {
                law: ContactLaw {
                    mu_s: 0.24285567417068332,
                    mu_k: 0.24285567417068332,
                    rule: Rule::NormalForce,
                },
                t_max: 50.0,
                max_transitions: 400,
                ..SimOptions::default()
            };
            (opts.solver.rtol, opts.solver.atol) = (rtol, atol);
            simulate(&ramp, &opts).unwrap()
        };
        let (run, tight) = (run_at(1e-9, 1e-12), run_at(1e-12, 1e-14));
        assert!(run.points.windows(2).all(|w| w[0].t <= w[1].t));
        // The slip lifted off at F_y = 0 in time (D near 1e-5 with F_y small is no reason for
        // the impulse form).
        let lift = &run.transitions[4];
        assert_eq!(
            (lift.to, lift.reason),
            (Mode::Flight, TransitionReason::NormalForce)
        );
        assert_eq!(run.segments[3].crossing, Some(Crossing::NormalForce));
        assert!(run.points.iter().all(|p| p.fy >= -1e-9));
        // Every transition agrees with a run a thousand times tighter.
        assert_eq!(run.transitions.len(), tight.transitions.len());
        for (a, b) in run.transitions.iter().zip(&tight.transitions) {
            assert_eq!((a.to, a.reason), (b.to, b.reason));
            assert!((a.t - b.t).abs() < 1e-6 * (1.0 + b.t), "{} {}", a.t, b.t);
        }
    }

    #[test]
    fn a_slip_whose_impulse_grows_without_bound_is_a_jam() {
        // Slipping on with the slip velocity near 3 while D decays in the impulse.
        let body = Cylinder::new(0.9955002834343927, 0.0035667539688122203).unwrap();
        let ramp = Ramp::new(body, 0.9773168482142575).unwrap();
        let opts = SimOptions {
            law: ContactLaw {
                mu_s: 1.4839922141387332,
                mu_k: 0.49084438262344054,
                rule: Rule::Paper,
            },
            theta0: 3.848699841633905,
            omega0: -1.7081478105864063,
            slip0: -0.6795759322843109,
            t_max: 20.0,
            ..SimOptions::default()
        };
        let run = simulate(&ramp, &opts).unwrap();
        assert_eq!(run.status, Some(MotionStatus::Painleve));
        assert!(run.message.starts_with("Painlevé jam"), "{}", run.message);
        // The force diverges, not the impulse (issue 46): the message says so and gives P.
        assert!(
            run.message.contains("normal force grows"),
            "{}",
            run.message
        );
        let p: f64 = run.message.split("normal impulse ").nth(1).unwrap()[..5]
            .trim()
            .parse()
            .unwrap();
        assert!(p > 0.0 && p < 1.0, "{}", run.message);
        let last = run.points.last().unwrap();
        assert!(last.state.slip_velocity().abs() > 1.0);
        assert!(last.fy > 1e8, "{}", last.fy);
    }
}

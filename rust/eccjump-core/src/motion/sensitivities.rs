//! The sensitivities of a full motion: the derivatives of each transition's time and angle
//! with respect to the eight parameters p = (α, χ, k_m, μ_s, μ_k, e, θ0, θ̇0), computed
//! after a run along its segments, as `docs/motion.md` ("Sensitivities") derives them: along
//! a segment the variational equations S' = f_x S + f_p in dual numbers ([`crate::dual`]); at
//! an event g(x; p) = 0 the time's dτ/dp = −(g_x S + g_p)/(g_x f_m) and dx⁻ = S + f_m dτ;
//! across a landing x⁺ = R(x⁻; p), R's Jacobian by central differences on its branch; the
//! next mode from S⁺ = dx⁺ − f_m⁺ dτ. Flagged, with every later transition NaN: a grazing
//! event, a tie, a slip in the normal impulse, a landing whose outcome changes within the step.

use crate::dual::{sin_cos, Dual};
use crate::error::{Error, Result};
use crate::mechanics::body::{inertias, Cylinder};
use crate::mechanics::newton_euler::{newton_euler_dual, Constraint, Response, Setting};
use crate::mechanics::{BodyState, Ramp};
use crate::modes::contact::Mode;
use crate::modes::flight::Flight;
use crate::motion::landing::{land, Landed};
use crate::motion::options::{SimOptions, MAX_ANGLE_STEP};
use crate::motion::record::{Crossing, MotionRun, Segment};
use crate::ode::{self, Integrator, NoEvents, OdeSystem, State, Status};

pub use crate::motion::options::PARAMETERS;

/// The number of parameters.
pub const P: usize = PARAMETERS.len();

/// In a `Dual<9>`, the direction of time (after the eight parameters).
const TIME: usize = P;

/// The variational state: x (6) and S (6 × 8, row by row).
const V: usize = 6 + 6 * P;

/// |g_x f| below this times the size of g's partials: a grazing event.
const GRAZING: f64 = 1e-8;

/// Another event function within this (relative) of 0 at an event: a tie.
const TIE: f64 = 1e-9;

/// The relative step of the central differences of the landing map.
const STEP: f64 = 1e-6;

/// The factors of [`STEP`] tried in turn where a step leaves the landing's branch.
const SHRINK: [f64; 3] = [1.0, 1e-2, 1e-4];

/// The derivatives of a run's transitions.
#[derive(Debug, Clone, PartialEq, Default)]
pub struct Sensitivities {
    /// For each transition, d(t, θ)/dp: `[0]` the time, `[1]` the angle, each over
    /// [`PARAMETERS`]. NaN where `singular`.
    pub transitions: Vec<[[f64; P]; 2]>,
    /// The transition is not differentiable, or follows one that is not (module notes).
    pub singular: Vec<bool>,
}

/// The model's parameters as dual numbers, each its own direction (k_m and χ independent).
struct Params<const N: usize> {
    setting: Setting<Dual<N>>,
    mu_s: Dual<N>,
    mu_k: Dual<N>,
}

impl<const N: usize> Params<N> {
    fn of(ramp: &Ramp, opts: &SimOptions) -> Self {
        let (chi, km) = (
            Dual::variable(ramp.body.chi, 1),
            Dual::variable(ramp.body.km, 2),
        );
        let (sin_a, mut cos_a) = sin_cos(Dual::variable(ramp.alpha, 0));
        cos_a.v = ramp.cos_a; // exactly 0 at π/2, as the run's
        let icm = if ramp.body.km < 1.0 {
            inertias(chi, km, 1.0 - km).1
        } else {
            km // k_m = 1 forces χ = 0, where Ĩ_CM = k_m (the body module's limit)
        };
        Self {
            setting: Setting {
                chi,
                icm,
                sin_a,
                cos_a,
            },
            mu_s: Dual::variable(opts.law.mu_s, 3),
            mu_k: Dual::variable(opts.law.mu_k, 4),
        }
    }

    /// Newton–Euler at x under the constraint of `mode` (friction direction σ in a slip).
    fn respond(&self, x: &[Dual<N>; 6], mode: Mode, sigma: f64) -> Option<Response<Dual<N>>> {
        let constraint = match mode {
            Mode::Roll => Constraint::Ramp,
            Mode::Slip => Constraint::Sliding {
                sigma,
                mu_k: self.mu_k,
            },
            Mode::Flight => Constraint::Free,
        };
        newton_euler_dual(&self.setting, x[0], x[1], constraint)
    }

    /// x' = f_m(x).
    fn field(&self, x: &[Dual<N>; 6], mode: Mode, sigma: f64) -> Option<[Dual<N>; 6]> {
        let r = self.respond(x, mode, sigma)?;
        Some([x[1], r.theta_dd, x[3], r.l_dd, x[5], r.b_dd])
    }

    /// The event function of `crossing` at x in a segment of `mode`; None for the slip in
    /// the normal impulse, which has none in time.
    fn crossing(&self, c: Crossing, x: &[Dual<N>; 6], mode: Mode, sigma: f64) -> Option<Dual<N>> {
        Some(match c {
            Crossing::Liftoff => self.respond(x, Mode::Flight, 0.0)?.b_dd,
            Crossing::NormalForce => self.respond(x, mode, sigma)?.fy,
            Crossing::FrictionCone => {
                let r = self.respond(x, Mode::Roll, 0.0)?;
                self.mu_s * r.fy - r.fx.scale(r.fx.v.signum())
            }
            Crossing::SlipStops => x[3] - x[1],
            Crossing::Landing => x[4] + (-1.0),
            Crossing::Impulse => return None,
        })
    }

    /// The event functions of a segment of `mode` besides the one that ended it.
    fn others(&self, c: Crossing, x: &[Dual<N>; 6], seg: &Segment, paper: bool) -> Vec<f64> {
        let candidates: &[Crossing] = match seg.mode {
            Mode::Roll if paper => &[
                Crossing::Liftoff,
                Crossing::NormalForce,
                Crossing::FrictionCone,
            ],
            Mode::Roll => &[Crossing::NormalForce, Crossing::FrictionCone],
            Mode::Slip => &[Crossing::NormalForce, Crossing::SlipStops],
            Mode::Flight => &[],
        };
        candidates
            .iter()
            .filter(|&&o| o != c)
            .filter_map(|&o| self.crossing(o, x, seg.mode, seg.sigma).map(|g| g.v))
            .collect()
    }
}

/// The variational equations of one mode: x' = f_m(x), S' = f_x S + f_p.
struct Variational<'a> {
    params: &'a Params<P>,
    mode: Mode,
    sigma: f64,
}

impl OdeSystem<V> for Variational<'_> {
    fn rhs(&self, _t: f64, y: &State<V>) -> State<V> {
        match self.params.field(&unpack(y), self.mode, self.sigma) {
            Some(f) => pack(&f),
            None => State::<V>::from_element(f64::NAN),
        }
    }
}

/// The state and its sensitivity as dual numbers.
fn unpack(y: &State<V>) -> [Dual<P>; 6] {
    std::array::from_fn(|i| Dual {
        v: y[i],
        d: std::array::from_fn(|k| y[6 + P * i + k]),
    })
}

/// The inverse of [`unpack`].
fn pack(x: &[Dual<P>; 6]) -> State<V> {
    State::<V>::from_fn(|j, _| {
        if j < 6 {
            x[j].v
        } else {
            let (i, k) = ((j - 6) / P, (j - 6) % P);
            x[i].d[k]
        }
    })
}

/// The state `s` with sensitivity `d` (rows θ, θ̇, l, l̇, b, ḃ).
fn with_partials<const N: usize>(s: &BodyState, d: &[[f64; N]; 6]) -> [Dual<N>; 6] {
    let v = s.values();
    std::array::from_fn(|i| Dual { v: v[i], d: d[i] })
}

/// The sensitivities of `run`, a run of `simulate` on `ramp` with `opts`. Each segment's
/// variational equations take about the steps the run took; `stop()` is asked every few
/// thousand steps, and a `true` ends it with `Error::Interrupted`.
pub fn sensitivities(
    ramp: &Ramp,
    opts: &SimOptions,
    run: &MotionRun,
    stop: &dyn Fn() -> bool,
) -> Result<Sensitivities> {
    let n = run.transitions.len();
    let mut out = Sensitivities {
        transitions: vec![[[f64::NAN; P]; 2]; n],
        singular: vec![true; n],
    };
    let Some(first) = run.transitions.first() else {
        return Ok(out);
    };
    // The start: θ = θ0, θ̇ = θ̇0, l̇ = θ̇0 + slip0.
    let unit = |k: usize| std::array::from_fn(|j| if j == k { 1.0 } else { 0.0 });
    let d0 = [unit(6), unit(7), [0.0; P], unit(7), [0.0; P], [0.0; P]];
    out.transitions[0] = [[0.0; P], d0[0]];
    out.singular[0] = false;
    let mut walk = Walk {
        ramp,
        opts,
        stop,
        p8: Params::of(ramp, opts),
        p9: Params::of(ramp, opts),
        steps_left: opts.solver.max_steps,
    };
    let mut x = with_partials(&first.state, &d0);
    for (i, seg) in run.segments.iter().enumerate() {
        let Some(next) = run.transitions.get(i + 1) else {
            break;
        };
        // Segments and transitions pair up until a slip in the normal impulse.
        let start = &run.transitions[i];
        if seg.t_start != start.t || seg.mode != start.to {
            break;
        }
        let Some(end) = walk.integrate(seg, &x)? else {
            break;
        };
        let Some(passage) = walk.event(seg, &end, start.state, next.state, run, i) else {
            break;
        };
        out.transitions[i + 1] = [passage.d_t, passage.d_theta];
        out.singular[i + 1] = false;
        match passage.next {
            Some(xn) => x = xn,
            None => break,
        }
    }
    Ok(out)
}

/// What a segment hands on: the derivatives of the transition after it, and the state with
/// its sensitivity that the next segment starts from (None at the last segment, and after a
/// landing that is not differentiable).
struct Passage {
    d_t: [f64; P],
    d_theta: [f64; P],
    next: Option<[Dual<P>; 6]>,
}

/// What [`sensitivities`] walks a run with.
struct Walk<'a> {
    ramp: &'a Ramp,
    opts: &'a SimOptions,
    stop: &'a dyn Fn() -> bool,
    p8: Params<P>,
    p9: Params<{ P + 1 }>,
    /// Accepted steps left for the variational equations of the remaining segments.
    steps_left: usize,
}

impl Walk<'_> {
    /// The transition `after` segment `seg` (number i of `run`, from `start`), which ended in
    /// `end` (its integrated sensitivity); None where it is not differentiable.
    fn event(
        &self,
        seg: &Segment,
        end: &[Dual<P>; 6],
        start: BodyState,
        after: BodyState,
        run: &MotionRun,
        i: usize,
    ) -> Option<Passage> {
        let c = seg.crossing?;
        // The state at the event as the run had it, with the integrated sensitivity.
        let before = match c {
            Crossing::Landing => BodyState {
                b: 1.0,
                ..Flight::new(*self.ramp, start).state(seg.t_end - seg.t_start)
            },
            _ => after,
        };
        let s_minus: [[f64; P]; 6] = std::array::from_fn(|j| end[j].d);
        let f = self.values(&before, seg.mode, seg.sigma)?;
        let dtau = self.time_shift(c, &before, &s_minus, &f, seg)?;
        let dx: [[f64; P]; 6] =
            std::array::from_fn(|j| std::array::from_fn(|k| s_minus[j][k] + f[j] * dtau[k]));
        // The transition's own (t, θ) is that of the state before it; a landing that is not
        // differentiable leaves them valid and only flags what follows.
        let dx_plus = match c {
            Crossing::Landing => self.landing(&before, &dx),
            _ => Some(dx),
        };
        let next = dx_plus.and_then(|dx_plus| {
            let next_seg = run.segments.get(i + 1)?;
            let f_plus = self.values(&after, next_seg.mode, next_seg.sigma)?;
            let s_plus = std::array::from_fn(|j| {
                std::array::from_fn(|k| dx_plus[j][k] - f_plus[j] * dtau[k])
            });
            Some(with_partials(&after, &s_plus))
        });
        Some(Passage {
            d_t: dtau,
            d_theta: dx[0],
            next,
        })
    }

    /// The variational equations of `seg` integrated from x over the segment (None if
    /// the integrator failed).
    fn integrate(&mut self, seg: &Segment, x: &[Dual<P>; 6]) -> Result<Option<[Dual<P>; 6]>> {
        if seg.t_end <= seg.t_start {
            return Ok(Some(*x));
        }
        let sys = Variational {
            params: &self.p8,
            mode: seg.mode,
            sigma: seg.sigma,
        };
        // DOP853 whatever the run's pair: the variational equations are a separate smooth
        // problem of 54 components, where RK45 at rtol 1e-10 took 13× its time (24 ms
        // against 1.8 ms for the paper's body with 19 transitions). Tolerances no tighter
        // than the defaults: the rounding of Newton–Euler's partials (its LU, conditioned
        // like 1/D in a slip) lies above tighter ones and stalls the step size (a slip after
        // a settle: 9.2 s and the step limit at rtol 1e-13, 3 ms at 1e-10). The steps of
        // all segments together are bounded by the run's `max_steps`.
        let defaults = ode::SolverOptions::default();
        let solver = ode::SolverOptions {
            max_first_change: MAX_ANGLE_STEP,
            method: Integrator::Dop853,
            rtol: self.opts.solver.rtol.max(defaults.rtol),
            atol: self.opts.solver.atol.max(defaults.atol),
            max_steps: self.steps_left.max(1),
            ..self.opts.solver
        };
        let (t0, t1, y0) = (seg.t_start, seg.t_end, pack(x));
        let out = ode::solve_until(&sys, &NoEvents, t0, y0, t1, &solver, &mut |_| {}, self.stop);
        self.steps_left = self.steps_left.saturating_sub(out.n_accepted);
        match out.status {
            Status::Stopped => Err(Error::Interrupted),
            Status::Finished => Ok(Some(unpack(&out.y))),
            _ => Ok(None),
        }
    }

    /// f_m at s, its values.
    fn values(&self, s: &BodyState, mode: Mode, sigma: f64) -> Option<[f64; 6]> {
        let f = self
            .p8
            .field(&with_partials(s, &[[0.0; P]; 6]), mode, sigma)?;
        Some(f.map(|x| x.v))
    }

    /// dτ/dp of the event `c` that ended `seg` at `s` (sensitivity `d`, field `f`); None
    /// where it is not differentiable (grazing, a tie).
    fn time_shift(
        &self,
        c: Crossing,
        s: &BodyState,
        d: &[[f64; P]; 6],
        f: &[f64; 6],
        seg: &Segment,
    ) -> Option<[f64; P]> {
        let d9: [[f64; P + 1]; 6] =
            std::array::from_fn(|j| std::array::from_fn(|k| if k < P { d[j][k] } else { f[j] }));
        let x = with_partials(s, &d9);
        let g = self.p9.crossing(c, &x, seg.mode, seg.sigma)?;
        let rate = g.d[TIME];
        let size = 1.0 + g.d[..P].iter().fold(0.0f64, |m, v| m.max(v.abs()));
        if rate.is_nan() || rate.abs() <= GRAZING * size {
            return None;
        }
        let scale = 1.0 + x.iter().fold(0.0f64, |m, v| m.max(v.v.abs()));
        let paper = self.opts.law.rule == crate::mechanics::Rule::Paper;
        let others = self.p9.others(c, &x, seg, paper);
        if others.iter().any(|g| g.abs() <= TIE * scale) {
            return None;
        }
        Some(std::array::from_fn(|k| -g.d[k] / rate))
    }

    /// dx⁺ = R_x dx⁻ + R_p across the landing at `before` (central differences of the
    /// landing map, both sides on its branch).
    fn landing(&self, before: &BodyState, dx: &[[f64; P]; 6]) -> Option<[[f64; P]; 6]> {
        let base = land(self.ramp, self.opts, before)?;
        let branch = |l: &Landed| (l.sticking, l.flies, l.settled);
        let rates = |l: &Landed| l.state.values();
        // ∂R/∂(one input), by a central difference of `map` at h, or at a smaller step where
        // one side leaves the branch: a slow landing is on a branch only ~|u| wide (its
        // outcome turns with the direction of the contact velocity u), so a step of 1e-6
        // of θ̇ can cross a boundary that a step of 1e-10 does not (rounding then costs
        // ~ε/1e-10 ≈ 2e-6 of relative accuracy). A switch at every step is a switch.
        let diff = |map: &dyn Fn(f64) -> Option<Landed>, h: f64| -> Option<[f64; 6]> {
            SHRINK.iter().find_map(|&f| {
                let h = h * f;
                let (up, down) = (map(h)?, map(-h)?);
                if branch(&up) != branch(&base) || branch(&down) != branch(&base) {
                    return None;
                }
                let (u, w) = (rates(&up), rates(&down));
                Some(std::array::from_fn(|j| (u[j] - w[j]) / (2.0 * h)))
            })
        };
        let mut out = [[0.0; P]; 6];
        // The state: θ, θ̇, l̇, ḃ (l and b pass through unchanged).
        out[2] = dx[2];
        out[4] = dx[4];
        let v = before.values();
        for j in [0, 1, 3, 5] {
            let map = |h: f64| {
                let mut w = v;
                w[j] += h;
                land(self.ramp, self.opts, &BodyState::from_values(w))
            };
            let col = diff(&map, STEP * (1.0 + v[j].abs()))?;
            for (row, c) in out.iter_mut().zip(col) {
                for k in 0..P {
                    row[k] += c * dx[j][k];
                }
            }
        }
        // The parameters the law reads: χ, k_m, μ_s, μ_k, e. It reads e², so at e = 0 the
        // derivative in e is 0; a step there would keep a bounce (e |u_n| above the Zeno
        // threshold) that e = 0 never makes.
        let (body, law) = (&self.ramp.body, &self.opts.law);
        let values = [body.chi, body.km, law.mu_s, law.mu_k, self.opts.restitution];
        let last = if self.opts.restitution == 0.0 { 4 } else { 5 };
        for k in 1..=last {
            let map = |h: f64| self.land_moved(before, k, h);
            let col = diff(&map, STEP * (1.0 + values[k - 1].abs()))?;
            for (row, c) in out.iter_mut().zip(col) {
                row[k] += c;
            }
        }
        Some(out)
    }

    /// The landing at `before` with parameter k (1 χ, 2 k_m, 3 μ_s, 4 μ_k, 5 e) moved by h
    /// (the body built from the module's formulas, unchecked: a step may leave the range).
    fn land_moved(&self, before: &BodyState, k: usize, h: f64) -> Option<Landed> {
        let (mut ramp, mut opts) = (*self.ramp, *self.opts);
        let b = &mut ramp.body;
        match k {
            1 | 2 => {
                let (chi, km) = if k == 1 {
                    (b.chi + h, b.km)
                } else {
                    (b.chi, b.km + h)
                };
                let (ic, icm) = inertias(chi, km, 1.0 - km);
                *b = Cylinder { chi, km, ic, icm };
            }
            3 => opts.law.mu_s += h,
            4 => opts.law.mu_k += h,
            _ => opts.restitution += h,
        }
        land(&ramp, &opts, before)
    }
}

#[cfg(test)]
mod tests;

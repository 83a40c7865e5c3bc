//! A slip near the Painlevé singularity, integrated against the normal impulse P
//! (dP = F_y dt) instead of time: the state y = (t, θ, θ̇, l, l̇, q) and its events. The system
//! is the sliding mode itself, [`Slipping`], as an `OdeSystem<6>` (in time it is one of 5).
//!
//! In time the sliding equations ([`crate::modes::slipping`]) divide by D = Ĩ_CM + χ K sin θ:
//! as D → 0⁺ the normal force F_y = Ĩ_CM B/D and θ̈ = K B/D grow without bound, yet the motion
//! may be regular (physics notes): the slip velocity can reach 0 at a small positive D, and
//! the run goes on. Divided by F_y every rate stays finite at D = 0:
//!
//!   dt/dP = D/(Ĩ_CM B),   dθ̇/dP = K/Ĩ_CM,   dθ/dP = θ̇ dt/dP,   dl/dP = l̇ dt/dP,
//!   dl̇/dP = (sin α + χθ̇² sin θ) dt/dP + σμ_k − χ cos θ K/Ĩ_CM,   dq/dP = −σμ_k v,
//!
//! (l̈ = sin α + F_x − χ(cos θ θ̈ − sin θ θ̇²), F_x = σμ_k F_y, v = l̇ − θ̇). Where D keeps falling
//! with the slip on, dD/dP = (dD/dθ) θ̇ D/(Ĩ_CM B) makes it decay exponentially in P: time
//! stands still while the impulse grows, the rigid model's impulsive jam. It is declared when D
//! falls to [`D_JAM`] (below it float64 no longer resolves the time it takes) or P passes
//! [`P_MAX`]; before that, the slip velocity reaching 0 (stick or reverse), F_y falling back to
//! [`F_BACK`] (time again), B falling to 0 (lift-off), t_max or l_max end the segment.
//!
//! Which variable a slip is integrated in follows the size of F_y, not of D: the time form's
//! rates grow like F_y, the impulse form's dt/dP = 1/F_y. Near a lift-off with D small B falls
//! to 0 too, F_y → 0 and t(P) has a square-root end (B ∝ √(P* − P)): a step across it ran t
//! backwards (issue 46), so such a slip goes back to time before F_y reaches 0.

use crate::mechanics::friction::Sliding;
use crate::mechanics::liftoff::free_normal_acceleration;
use crate::modes::slipping::{normal_force_above, Slipping, F_BACK};
use crate::ode::{Direction, EventFunctions, EventSpec, OdeSystem, State};

/// D at which the slip, still on, is an impulsive jam (status `painleve`): its time to
/// fall further, D/(Ĩ_CM B) per unit impulse, is below what the run's float64 time resolves.
pub const D_JAM: f64 = 1e-12;

/// The impulse after which the slip, still on, is an impulsive jam: velocities change by
/// about P/Ĩ_CM, so this is far beyond any finite motion's.
pub const P_MAX: f64 = 1e4;

/// What the impulse form needs at one state: K, D and B = cos α − χθ̇² cos θ.
struct Coefficients {
    sin_t: f64,
    cos_t: f64,
    k: f64,
    d: f64,
    load: f64,
}

/// The impulse form's coefficients and rates (Ĩ_CM > 0: `simulate` refuses the body without it).
impl Slipping {
    fn coefficients(&self, theta: f64, omega: f64) -> Coefficients {
        let r = &self.ramp;
        let (sin_t, cos_t) = crate::trig::sin_cos(theta);
        let sl = Sliding::new(&r.body, sin_t, cos_t, self.sigma, self.mu_k);
        Coefficients {
            sin_t,
            cos_t,
            k: sl.k,
            d: sl.d,
            // B = −L, the free normal acceleration's formula.
            load: -free_normal_acceleration(r.body.chi * omega * omega, cos_t, r.cos_a),
        }
    }

    /// d/dP of (θ̇, l̇): the velocities' change per unit impulse, and dt/dP.
    fn rates(&self, omega: f64, c: &Coefficients) -> (f64, f64, f64) {
        let r = &self.ramp;
        let chi = r.body.chi;
        let dt = c.d / (r.body.icm * c.load);
        let domega = c.k / r.body.icm;
        let dldot = (r.sin_a + chi * omega * omega * c.sin_t) * dt + self.sigma * self.mu_k
            - chi * c.cos_t * domega;
        (dt, domega, dldot)
    }
}

/// The sliding equations against the normal impulse, in y = (t, θ, θ̇, l, l̇, q).
impl OdeSystem<6> for Slipping {
    fn rhs(&self, _p: f64, y: &State<6>) -> State<6> {
        let c = self.coefficients(y[1], y[2]);
        let (dt, domega, dldot) = self.rates(y[2], &c);
        let v = y[4] - y[2];
        State::<6>::new(
            dt,
            y[2] * dt,
            domega,
            y[4] * dt,
            dldot,
            -self.sigma * self.mu_k * v,
        )
    }
}

named_enum! {
    /// The events that end a slip in the normal impulse, in tie order (the index is the
    /// discriminant), all terminal.
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum ImpulseEvent {
        /// B falls to 0, so F_y does: the body leaves the ramp.
        NormalForce = 0,
        /// The slip velocity returns to 0: stick or reverse.
        Stops = 1,
        /// F_y falls to [`F_BACK`]: the slip goes on in time.
        Recovers = 2,
        /// D falls to [`D_JAM`] with the slip on: the impulsive jam.
        Jam = 3,
        /// t reaches t_max.
        TLimit = 4,
        /// l reaches l_max.
        LLimit = 5,
    }
}

/// The events of a slip in the normal impulse (no change bounds: such slips are rare and
/// short, so the scan samples every step).
#[derive(Debug, Clone, PartialEq)]
pub struct ImpulseEvents {
    /// The slip.
    pub slip: Slipping,
    /// The time that ends the run.
    pub t_max: f64,
    /// The l that ends the run (∞: never).
    pub l_max: f64,
}

impl EventFunctions<6> for ImpulseEvents {
    const HAS_SLOPES: bool = true;
    fn count(&self) -> usize {
        ImpulseEvent::ALL.len()
    }
    fn spec(&self, k: usize) -> EventSpec {
        let direction = match ImpulseEvent::ALL[k] {
            ImpulseEvent::NormalForce | ImpulseEvent::Recovers | ImpulseEvent::Jam => {
                Direction::Falling
            }
            ImpulseEvent::Stops => Direction::Any,
            ImpulseEvent::TLimit | ImpulseEvent::LLimit => Direction::Rising,
        };
        EventSpec {
            direction,
            terminal: true,
        }
    }
    fn values(&self, first: usize, _p: f64, y: &State<6>, out: &mut [f64]) {
        let c = self.slip.coefficients(y[1], y[2]);
        for (i, o) in out.iter_mut().enumerate() {
            *o = match ImpulseEvent::ALL[first + i] {
                ImpulseEvent::NormalForce => c.load,
                ImpulseEvent::Stops => y[4] - y[2],
                ImpulseEvent::Recovers => {
                    normal_force_above(F_BACK, self.slip.ramp.body.icm, c.load, c.d)
                }
                ImpulseEvent::Jam => c.d - D_JAM,
                ImpulseEvent::TLimit => y[0] - self.t_max,
                // A constant, finite g never crosses: l_max = ∞ disables the event.
                ImpulseEvent::LLimit if self.l_max.is_finite() => y[3] - self.l_max,
                ImpulseEvent::LLimit => -1.0,
            };
        }
    }
    /// The slip velocity's slope dv/dP for the dip test (a slip that starts at v = 0 and
    /// returns to it within a cell); the other events have none (NaN).
    fn slopes(&self, first: usize, _p: f64, y: &State<6>, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = match ImpulseEvent::ALL[first + i] {
                ImpulseEvent::Stops => {
                    let c = self.slip.coefficients(y[1], y[2]);
                    let (_, domega, dldot) = self.slip.rates(y[2], &c);
                    dldot - domega
                }
                _ => f64::NAN,
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{Cylinder, Ramp};

    /// The impulse form is the time form divided by F_y, at random states.
    #[test]
    fn rates_are_the_time_derivatives_over_the_normal_force() {
        let mut rng = crate::testing::Lcg(11);
        let mut next = || rng.next();
        let mut checked = 0;
        while checked < 500 {
            let chi = 0.05 + 0.9 * next();
            let km = (0.02 + 0.9 * next()) * (1.0 - chi);
            let ramp = Ramp::new(Cylinder::new(chi, km).unwrap(), 1.5 * next()).unwrap();
            let (theta, omega, ldot) = (12.0 * (next() - 0.5), 3.0 * (next() - 0.5), next());
            let (sigma, mu) = (if next() < 0.5 { -1.0 } else { 1.0 }, 0.05 + next());
            let time = Slipping::new(ramp, sigma, mu);
            let k = time.kinematics(theta, omega);
            if !(k.d > 1e-3 && k.load > 1e-3) {
                continue;
            }
            checked += 1;
            let y = State::<6>::new(0.3, theta, omega, 0.2, ldot, 0.0);
            let dp = time.rhs(0.0, &y);
            let v = ldot - omega;
            let expect = [1.0, omega, k.theta_dd, ldot, k.l_dd, -k.fx * v];
            for (i, e) in expect.iter().enumerate() {
                let got = dp[i] * k.fy;
                assert!((got - e).abs() < 1e-11 * (1.0 + e.abs()), "{i}: {got} {e}");
            }
        }
    }
}

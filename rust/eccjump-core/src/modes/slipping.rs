//! Slipping (contact with sliding: b = 1, F_x = σ μ_k F_y, σ = −sign of the slip velocity
//! v = l̇ − θ̇): the closed forms, the ODE in y = (θ, θ̇, l, l̇, q) and its events.
//!
//! Newton–Euler ([`crate::mechanics::newton_euler`]) with b̈ = 0 and F_x = σ μ_k F_y gives,
//! with B = cos α − χθ̇² cos θ and K, D of [`Sliding`],
//!
//!   θ̈ = K B/D,   F_y = Ĩ_CM B/D,   l̈ = sin α + F_x − χ(cos θ θ̈ − sin θ θ̇²),
//!
//! and friction dissipates q̇ = −F_x v (= μ_k F_y |v| ≥ 0 while the slip is along −σ),
//! integrated as the fifth state so that the energy ledger of a run is an independent check
//! of the equations. The signed work, not μ_k F_y |v|: it is smooth where the step that
//! ends the slip overshoots v = 0, so q at the located event is as accurate as the state
//! (|v| has a kink there, which cost the ledger up to 1e-4).

use crate::mechanics::friction::Sliding;
use crate::mechanics::Ramp;
use crate::ode::lanes::{Lane, LaneRhs, Lanes, LANES};
use crate::ode::{
    Change, DenseStep, Direction, EventBounds, EventFunctions, EventSpec, OdeSystem, SinCos, State,
};
use crate::trig::lanes::sin_cos_lanes;

// The switch between the two forms of a slip (in time, here; in the normal impulse,
// `slip_in_impulse`, which builds on `Slipping`) is kept here, below both, so that neither
// form's module needs the other's.

/// The normal force [M g] above which a slip goes on in the normal impulse (the time form's
/// event [`SlipEvent::Singular`]). Both forms are exact; the switch only chooses the variable
/// in which steps stay well scaled: about 10³ times F_y's usual size, where D is near 10⁻⁴
/// for the usual Ĩ_CM B.
pub const F_SWITCH: f64 = 1e3;

/// The normal force at which a slip in the normal impulse ([`crate::modes::slip_in_impulse`])
/// goes back to time: a tenth of [`F_SWITCH`], so that a slip hovering near the switch does
/// not alternate at every step.
pub const F_BACK: f64 = 1e2;

/// A function of the contact state with the sign of F_y − `level` where D > 0, free of the
/// pole of F_y = Ĩ_CM B/D at D = 0 (an event function's roots are found on it).
#[inline]
pub(crate) fn normal_force_above(level: f64, icm: f64, load: f64, d: f64) -> f64 {
    icm * load - level * d
}

/// Accelerations and contact force of the sliding mode at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct SlipKinematics {
    /// θ̈.
    pub theta_dd: f64,
    /// l̈.
    pub l_dd: f64,
    /// Friction force along the ramp, σ μ_k F_y [M g].
    pub fx: f64,
    /// Normal force [M g].
    pub fy: f64,
    /// D of [`Sliding`]; ≤ 0 is the Painlevé case.
    pub d: f64,
    /// B = cos α − χθ̇² cos θ = −L (the normal force has its sign where D > 0).
    pub load: f64,
}

impl SlipKinematics {
    /// The acceleration of the slip velocity, v̇ = l̈ − θ̈.
    #[inline]
    pub fn slip_acceleration(&self) -> f64 {
        self.l_dd - self.theta_dd
    }
}

/// The sliding mode of a body on its ramp, friction in direction σ = ±1 with μ_k.
#[derive(Debug, Clone, PartialEq)]
pub struct Slipping {
    /// The body on its ramp.
    pub ramp: Ramp,
    /// Direction of the friction force along x (−sign of the slip velocity).
    pub sigma: f64,
    /// Kinetic friction coefficient.
    pub mu_k: f64,
}

impl Slipping {
    /// The sliding mode with friction direction σ and kinetic coefficient μ_k.
    pub fn new(ramp: Ramp, sigma: f64, mu_k: f64) -> Self {
        Self { ramp, sigma, mu_k }
    }

    /// The sliding accelerations and force at (θ, θ̇). Computed for any D ≠ 0 (callers test
    /// `d`: the mode is consistent only where D > 0 and B > 0).
    #[inline]
    pub fn kinematics(&self, theta: f64, omega: f64) -> SlipKinematics {
        let (s, c) = crate::trig::sin_cos(theta);
        self.kinematics_sc(omega, s, c)
    }

    /// [`Self::kinematics`] given s = sin θ and c = cos θ.
    #[inline(always)]
    pub(crate) fn kinematics_sc(&self, omega: f64, s: f64, c: f64) -> SlipKinematics {
        let r = &self.ramp;
        let chi = r.body.chi;
        let chi_w2 = chi * omega * omega;
        let load = r.cos_a - chi_w2 * c;
        let sl = Sliding::new(&r.body, s, c, self.sigma, self.mu_k);
        let theta_dd = sl.k * load / sl.d;
        let fy = r.body.icm * load / sl.d;
        let fx = self.sigma * self.mu_k * fy;
        SlipKinematics {
            theta_dd,
            l_dd: r.sin_a + fx - chi * c * theta_dd + chi_w2 * s,
            fx,
            fy,
            d: sl.d,
            load,
        }
    }
}

/// The sliding equations in y = (θ, θ̇, l, l̇, q), q the energy dissipated by friction.
impl OdeSystem<5> for Slipping {
    #[inline]
    fn rhs(&self, t: f64, y: &State<5>) -> State<5> {
        self.rhs_with_trig(t, y).0
    }

    /// f and (sin θ, cos θ).
    #[inline]
    fn rhs_with_trig(&self, _t: f64, y: &State<5>) -> (State<5>, Option<SinCos>) {
        let trig = SinCos::of(y[0]);
        (self.derivative(y[1], y[3], trig.sin, trig.cos), Some(trig))
    }
}

impl Slipping {
    /// The derivative of (θ, θ̇, l, l̇, q) at θ̇ = `omega`, l̇ = `ldot`, given s = sin θ and
    /// c = cos θ (θ, l and q do not enter it).
    #[inline(always)]
    fn derivative(&self, omega: f64, ldot: f64, s: f64, c: f64) -> State<5> {
        let k = self.kinematics_sc(omega, s, c);
        let v = ldot - omega;
        State::<5>::new(omega, k.theta_dd, ldot, k.l_dd, -k.fx * v)
    }
}

impl LaneRhs<5> for Slipping {
    /// [`OdeSystem::rhs`] of each lane's system, bit for bit (the same `sin_cos` by
    /// [`sin_cos_lanes`], the same arithmetic per lane).
    #[inline(always)]
    fn rhs_lanes(systems: &[&Self; LANES], y: &Lanes<5>) -> Lanes<5> {
        Self::rhs_lanes_with_trig(systems, y).0
    }

    #[inline(always)]
    fn rhs_lanes_with_trig(
        systems: &[&Self; LANES],
        y: &Lanes<5>,
    ) -> (Lanes<5>, Option<[Lane; 2]>) {
        let (s, c) = sin_cos_lanes(&y.0[0]);
        let mut out = Lanes([[0.0; LANES]; 5]);
        for l in 0..LANES {
            let d = systems[l].derivative(y.0[1][l], y.0[3][l], s[l], c[l]);
            out.set_lane(l, &d);
        }
        (out, Some([s, c]))
    }
}

named_enum! {
    /// The events that end a slip, in tie order (the index is the discriminant).
    #[derive(Debug, Clone, Copy, PartialEq, Eq)]
    pub enum SlipEvent {
        /// B falls to 0, so F_y does: the body leaves the ramp (both rules coincide here).
        NormalForce = 0,
        /// The slip velocity returns to 0: stick or reverse.
        Stops = 1,
        /// F_y rises to [`F_SWITCH`] (D falls towards the Painlevé singularity): the slip goes
        /// on in the normal impulse ([`crate::modes::slip_in_impulse`]).
        Singular = 2,
        /// l reaches l_max.
        LLimit = 3,
    }
}

/// The events of a slip, all terminal.
#[derive(Debug, Clone, PartialEq)]
pub struct SlipEvents {
    /// The sliding mode.
    pub slipping: Slipping,
    /// The l that ends the run (∞: never).
    pub l_max: f64,
}

impl EventFunctions<5> for SlipEvents {
    const HAS_SLOPES: bool = true;
    fn count(&self) -> usize {
        SlipEvent::ALL.len()
    }
    fn spec(&self, k: usize) -> EventSpec {
        let direction = match SlipEvent::ALL[k] {
            SlipEvent::NormalForce => Direction::Falling,
            SlipEvent::Stops => Direction::Any,
            SlipEvent::Singular | SlipEvent::LLimit => Direction::Rising,
        };
        EventSpec {
            direction,
            terminal: true,
        }
    }
    #[inline]
    fn values(&self, first: usize, t: f64, y: &State<5>, out: &mut [f64]) {
        self.values_at(first, t, y, None, out);
    }
    /// All events from one `sin_cos` (or none, with `trig`).
    #[inline]
    fn values_at(&self, first: usize, _: f64, y: &State<5>, trig: Option<SinCos>, out: &mut [f64]) {
        let r = &self.slipping.ramp;
        let (s, c) = SinCos::at(y[0], trig);
        let sl = Sliding::new(&r.body, s, c, self.slipping.sigma, self.slipping.mu_k);
        let load = r.cos_a - r.body.chi * y[1] * y[1] * c;
        for (i, o) in out.iter_mut().enumerate() {
            *o = match SlipEvent::ALL[first + i] {
                SlipEvent::NormalForce => load,
                SlipEvent::Stops => y[3] - y[1],
                SlipEvent::Singular => normal_force_above(F_SWITCH, r.body.icm, load, sl.d),
                // A constant, finite g never crosses: l_max = ∞ disables the event.
                SlipEvent::LLimit if self.l_max.is_finite() => y[2] - self.l_max,
                SlipEvent::LLimit => -1.0,
            };
        }
    }

    /// The slip velocity's slope, v̇ = l̈ − θ̈, for the dip test: a slip that starts at
    /// v = 0 (onset, reversal) and returns to 0 within the scan's first cell is found (its
    /// sign test cannot see it); the other events have none (NaN).
    #[inline]
    fn slopes(&self, first: usize, _t: f64, y: &State<5>, out: &mut [f64]) {
        for (i, o) in out.iter_mut().enumerate() {
            *o = match SlipEvent::ALL[first + i] {
                SlipEvent::Stops => self.slipping.kinematics(y[0], y[1]).slip_acceleration(),
                _ => f64::NAN,
            };
        }
    }
    #[inline]
    fn bounds(&self) -> Option<&impl EventBounds<5>> {
        Some(self)
    }
}

impl EventBounds<5> for SlipEvents {
    /// Bounds on how much each event can change within the step `dense` (in the sense of
    /// [`EventBounds::change_bounds`]), so that the scan skips the interior samples (a
    /// `sin_cos` each) wherever they provably cannot show a crossing. With Θ, W, Λ, V the
    /// interpolant's bounds on |θ|, |θ̇|, |l|, |l̇| over the step and R_θ, R_ω, R_l, R_v on
    /// their rates, each g changes by at most L|h|, L = Σ G_i R_i with G_i ≥ |∂g/∂y_i|:
    /// - B = cos α − χθ̇² cos θ: G_θ = χW², G_ω = 2χW;
    /// - the slip velocity l̇ − θ̇: G_v = G_ω = 1;
    /// - Ĩ_CM B − F D (F_y − F where D > 0), D = Ĩ_CM + χ² sin²θ − σμ_kχ sin θ(1 + χ cos θ),
    ///   dD/dθ = χ² sin 2θ − σμ_kχ(cos θ + χ cos 2θ): G_θ = Ĩ_CM χW² + F(χ² + μ_kχ(1 + χ)),
    ///   G_ω = 2Ĩ_CM χW;
    /// - l − l_max: G_l = 1 (a disabled l_max is a constant: 0).
    ///
    /// Plus 4δ, δ = 2⁻⁴⁰(M + Σ G_i |y_i|max) with M the sum of the magnitudes of g's terms:
    /// as in the rolling bounds, hundreds of times the rounding of g, of sin_cos and of the
    /// interpolant (`modes::rolling::bounds`).
    ///
    /// Each g is smooth, and bends by at most M|h|²/8 from its chord, M = Σ P_ij R_i R_j +
    /// Σ G_i Q_i with P_ij ≥ |∂²g/∂y_i∂y_j| and Q_i the interpolant's acceleration bounds:
    /// - B: P_θθ = χW², P_θω = 2χW, P_ωω = 2χ;
    /// - the slip velocity and l − l_max: linear, no P;
    /// - Ĩ_CM B − F D: Ĩ_CM times B's, plus F times d²D/dθ² = 2χ² cos 2θ + σμ_kχ(sin θ +
    ///   2χ sin 2θ): P_θθ = 2χ² + μ_kχ(1 + 2χ).
    #[inline]
    fn change_bounds(
        &self,
        first: usize,
        dense: &DenseStep<5>,
        _: Option<SinCos>,
        out: &mut [Change],
    ) {
        let b = dense.bounds();
        let (value, rate, accel) = (b.value, b.rate, b.accel);
        let h = dense.h.abs();
        let r = &self.slipping.ramp;
        let (chi, mu) = (r.body.chi, self.slipping.mu_k);
        let w = value[1];
        let (r_theta, r_omega) = (rate[0], rate[1]);
        // L|h| + 4δ and the bend from M, the (G_i, component i) pairs and Σ P_ij R_i R_j.
        let bound = |m: f64, terms: &[(f64, usize)], second: f64| {
            let (mut slope, mut size, mut curvature) = (0.0, m, second);
            for &(g, i) in terms {
                slope += g * rate[i];
                size += g * value[i];
                curvature += g * accel[i];
            }
            Change {
                rate: slope * h,
                slack: 4.0 * size / (1u64 << 40) as f64,
                bend: curvature * (h * h) / 8.0,
                smooth: true,
            }
        };
        // B's terms (size, G_θ, G_ω, bend), which the switch's Ĩ_CM B − F D shares.
        let chi_w2 = chi * w * w;
        let (size_b, g_b) = (r.cos_a + chi_w2, [chi_w2, 2.0 * chi * w]);
        let second_b = chi_w2 * r_theta * r_theta
            + 4.0 * chi * w * r_theta * r_omega
            + 2.0 * chi * r_omega * r_omega;
        for (i, o) in out.iter_mut().enumerate() {
            *o = match SlipEvent::ALL[first + i] {
                SlipEvent::NormalForce => bound(size_b, &[(g_b[0], 0), (g_b[1], 1)], second_b),
                SlipEvent::Stops => bound(0.0, &[(1.0, 3), (1.0, 1)], 0.0),
                SlipEvent::Singular => {
                    let (icm, f) = (r.body.icm, F_SWITCH);
                    let g_d = chi * chi + mu * chi * (1.0 + chi);
                    let p_d = 2.0 * chi * chi + mu * chi * (1.0 + 2.0 * chi);
                    bound(
                        icm * size_b + f * (icm + g_d),
                        &[(icm * g_b[0] + f * g_d, 0), (icm * g_b[1], 1)],
                        icm * second_b + f * p_d * r_theta * r_theta,
                    )
                }
                SlipEvent::LLimit if self.l_max.is_finite() => {
                    bound(self.l_max.abs(), &[(1.0, 2)], 0.0)
                }
                SlipEvent::LLimit => Change::NONE,
            };
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::{Constraint, Cylinder};
    use crate::ode::events::{check_change_bounds, WalkAll};
    use crate::ode::{solve, Observation, SolverOptions};

    #[test]
    fn closed_form_is_newton_euler() {
        for &(chi, km, a, th, w, sigma, mu) in &[
            (0.5, 0.4, 0.5, 5.5f64, 1.2f64, -1.0, 0.7),
            (0.3, 0.1, 1.0, 2.0, 0.4, 1.0, 0.3),
            (0.8, 0.05, 1.3, 4.6, 0.9, -1.0, 1.0),
            (0.0, 0.5, 0.2, 1.0, 2.0, 1.0, 0.2),
        ] {
            let ramp = Ramp::new(Cylinder::new(chi, km).unwrap(), a).unwrap();
            let sl = Slipping::new(ramp, sigma, mu);
            let k = sl.kinematics(th, w);
            let ne = ramp
                .newton_euler(th, w, Constraint::Sliding { sigma, mu_k: mu })
                .unwrap();
            for (x, y) in [
                (k.theta_dd, ne.theta_dd),
                (k.l_dd, ne.l_dd),
                (k.fx, ne.fx),
                (k.fy, ne.fy),
            ] {
                assert!((x - y).abs() < 1e-12 * (1.0 + y.abs()), "{x} {y}");
            }
        }
    }

    /// Random slips (both friction directions, some with l_max) integrated to their first
    /// event, `steps` observing every accepted step.
    fn random_slips(mut each: impl FnMut(&Slipping, &SlipEvents, State<5>)) {
        let mut rng = crate::testing::Lcg(7);
        let mut next = || rng.next();
        let mut made = 0;
        while made < 200 {
            let chi = 0.05 + 0.9 * next();
            let km = (0.02 + 0.9 * next()) * (1.0 - chi);
            let ramp = Ramp::new(Cylinder::new(chi, km).unwrap(), 1.5 * next()).unwrap();
            let (theta, omega) = (12.0 * (next() - 0.5), 3.0 * (next() - 0.5));
            let v = 2.0 * (next() - 0.5);
            let sl = Slipping::new(ramp, -v.signum(), 0.05 + 0.6 * next());
            let k = sl.kinematics(theta, omega);
            if !(k.d > 0.0 && k.fy < F_SWITCH && k.load > 0.0) {
                continue;
            }
            made += 1;
            let l_max = if made % 3 == 0 { 0.5 } else { f64::INFINITY };
            let events = SlipEvents {
                slipping: sl,
                l_max,
            };
            each(
                &events.slipping,
                &events,
                State::<5>::new(theta, omega, 0.0, omega + v, 0.0),
            );
        }
    }

    #[test]
    fn change_bounds_bound_the_change_along_each_step() {
        let mut steps = 0;
        random_slips(|sl, events, y0| {
            let so = SolverOptions {
                dense_every_step: true,
                ..SolverOptions::default()
            };
            solve(sl, events, 0.0, y0, 20.0, &so, &mut |obs: Observation<
                '_,
                5,
            >| {
                let Observation::Step { dense, .. } = obs else {
                    return;
                };
                let dense = dense.expect("every step's dense output");
                steps += 1;
                let mut bound = [Change::NONE; 4];
                events.change_bounds(0, dense, None, &mut bound);
                let g = |t: f64| {
                    let y = if t == dense.t_old {
                        dense.y_old
                    } else {
                        dense.eval(t)
                    };
                    let mut g = [0.0; 4];
                    events.values(0, t, &y, &mut g);
                    g
                };
                check_change_bounds(dense.t_old, dense.h, g, &bound).unwrap();
            });
        });
        assert!(steps > 2000, "{steps}");
    }

    #[test]
    fn skipping_interior_samples_changes_nothing() {
        random_slips(|sl, events, y0| {
            let so = SolverOptions::default();
            let (mut a, mut b) = (Vec::new(), Vec::new());
            fn log(out: &mut Vec<(f64, [f64; 5])>) -> impl FnMut(Observation<'_, 5>) + '_ {
                move |obs| match obs {
                    Observation::Step { t, y, .. } | Observation::Event { t, y, .. } => {
                        out.push((t, [y[0], y[1], y[2], y[3], y[4]]))
                    }
                }
            }
            let skip = solve(sl, events, 0.0, y0, 20.0, &so, &mut log(&mut a));
            let walk = solve(sl, &WalkAll(events), 0.0, y0, 20.0, &so, &mut log(&mut b));
            assert_eq!(skip, walk);
            assert!(a.iter().zip(&b).all(|(x, y)| x.0.to_bits() == y.0.to_bits()
                && x.1
                    .iter()
                    .zip(&y.1)
                    .all(|(p, q)| p.to_bits() == q.to_bits())));
            assert_eq!(a.len(), b.len());
        });
    }
}

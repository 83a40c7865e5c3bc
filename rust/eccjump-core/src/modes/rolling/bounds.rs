//! Rigorous bounds on how much the contact functions of pure rolling can change within one
//! dense-output step: they let the event scan skip interior sign samples that provably
//! cannot show a crossing. Shared by the rolling run and the ODE route of the JARM
//! classification.

use crate::mechanics::Ramp;
use crate::ode::{Change, DenseStep, SinCos, StepEnds};

/// Bounds on how much the contact functions of pure rolling can change within one
/// dense-output step, in the sense of [`crate::ode::EventBounds::change_bounds`]: shared by the
/// rolling run ([`ContactEvents`](super::events::ContactEvents)) and the ODE route of the classification
/// (`jarm::ode_route`).
///
/// Along the interpolant (θ(t), θ̇(t)), |dg/dt| ≤ G_θ |dθ/dt| + G_ω |dθ̇/dt| with
/// G_θ ≥ |∂g/∂θ|, G_ω ≥ |∂g/∂θ̇| over the step. With W ≥ |θ̇|, s = sin θ, c = cos θ,
/// θ̈ = N/D, N = χθ̇²s + χ sin(α+θ) + sin α, D = Ĩ_C + 1 + 2χc ≥ D_min = Ĩ_C + 1 − 2χ:
///   |θ̈| ≤ A = (χW² + χ + sin α)/D_min,
///   |∂θ̈/∂θ| ≤ A_θ = (χW² + χ)/D_min + 2χ A/D_min,   |∂θ̈/∂θ̇| ≤ A_ω = 2χW/D_min;
/// lift-off χθ̇²c − cos α: G_θ = χW², G_ω = 2χW;
/// F_y = cos α − χθ̇²c − χθ̈s: G_θ = χW² + χA + χA_θ, G_ω = 2χW + χA_ω;
/// F_x = −sin α − χθ̇²s + (1 + χc)θ̈: G_θ = χW² + χA + (1+χ)A_θ, G_ω = 2χW + (1+χ)A_ω;
/// slip μF_y − |F_x|: μ G(F_y) + G(F_x); θ − θ_lim: G_θ = 1, G_ω = 0; θ̇: G_θ = 0,
/// G_ω = 1.
/// The rounding allowance δ = 2⁻⁴⁰ (M + G_θ Θ + G_ω W), with M the sum of the
/// magnitudes of g's terms and Θ ≥ |θ|, is hundreds of times the error of a few
/// roundings in g, of the 1-ulp sin_cos, and of the interpolant (including its
/// mismatch with the exact step end). The bound is L |h| + 4δ ([`Change`]).
/// A singular body (D_min ≤ 0) gives +∞ for the force events: never skipped.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct ContactBounds {
    /// Of the lift-off function χθ̇² cos θ − cos α.
    pub liftoff: Change,
    /// Of F_y.
    pub fy: Change,
    /// Of the slip margin μ_s F_y − |F_x|; none without μ_s (the event is then a constant).
    pub slip: Change,
    /// Of θ̇.
    pub omega: Change,
    /// Θ ≥ |θ|, |dθ/dt|, |d²θ/dt²| and |h| over the step, for
    /// [`ContactBounds::theta_above`].
    theta_max: f64,
    theta_rate: f64,
    theta_accel: f64,
    h: f64,
    /// How far the curve the bounds are for may stray from the one they were computed
    /// along, in θ (see [`ContactBounds::from_ends`]).
    stray_theta: f64,
}

impl ContactBounds {
    /// The bounds over the step `dense`; without an anchor with |sin θ|, |cos θ| ≤ 1 and
    /// D ≥ D_min, else tightened by the trigonometry at one angle
    /// θ_c (any, typically the step end): `anchor` = (θ_c, sin θ_c, cos θ_c). Every θ
    /// of the step is within Δ = |θ_old − θ_c| + |h| sup|dθ/dt| of θ_c, so (sin and cos
    /// being 1-Lipschitz) |sin θ| ≤ S = min(1, |sin θ_c| + Δ'), |cos θ| ≤ C = min(1,
    /// |cos θ_c| + Δ'), and D ≥ max(D_min, Ĩ_C + 1 + 2χ(cos θ_c − Δ')), where Δ' adds
    /// to Δ a relative 2⁻⁴⁰ and an absolute 2⁻⁴⁰(1 + Θ), far above the rounding of θ
    /// along the interpolant and of sin_cos. The bounds of [`ContactBounds`] then hold
    /// with each |sin|, |cos| ≤ 1 replaced by S or C:
    ///   A = (χW²S + χ + sin α)/D_lo, A_θ = (χW²C + χ)/D_lo + 2χSA/D_lo, A_ω = 2χWS/D_lo;
    /// lift-off: G_θ = χW²S, G_ω = 2χWC; F_y: G_θ = χW²S + χAC + χSA_θ,
    /// G_ω = 2χWC + χSA_ω; F_x: G_θ = χW²C + χSA + (1+χC)A_θ, G_ω = 2χWS + (1+χC)A_ω
    /// (and M, the magnitudes of the terms, likewise). With S = C = 1, D_lo = D_min
    /// these are exactly the plain bounds.
    #[inline]
    pub(crate) fn near(
        ramp: &Ramp,
        mu_s: Option<f64>,
        dense: &DenseStep<2>,
        anchor: Option<SinCos>,
    ) -> Self {
        Self::straying(ramp, mu_s, dense, anchor, [0.0; 2], true)
    }

    /// Bounds from a step's ends alone, before its dense output is made
    /// ([`crate::ode::EventBounds::change_bounds_ends`]): those of [`Self::near`] along
    /// the quintic Hermite interpolant of the ends ([`StepEnds::second_order_hermite`]),
    /// widened for the dense output the pair would make, which strays from it by at most
    /// the interpolant's own error (its estimate, doubled) plus the pair's (ten times the
    /// step's error scale): along a curve within (Δθ, Δθ̇) of the interpolant, a contact
    /// function differs from its value there by at most G_θ Δθ + G_ω Δθ̇, with G_θ, G_ω
    /// its partials' bounds, taken with Θ and W raised by the same (Δθ, Δθ̇). Without
    /// `bends`, every contact function's bend is +∞ (not computed) and its rate and slack
    /// are the same bits as with them: the cheap first test of [`crate::ode::quiet_step`].
    #[inline]
    pub(crate) fn from_ends(
        ramp: &Ramp,
        mu_s: Option<f64>,
        ends: &StepEnds<2>,
        anchor: Option<SinCos>,
        bends: bool,
    ) -> Self {
        let (hermite, err) = ends.second_order_hermite();
        let stray = [
            2.0 * err[0] + 10.0 * ends.scale[0],
            2.0 * err[1] + 10.0 * ends.scale[1],
        ];
        Self::straying(ramp, mu_s, &hermite, anchor, stray, bends)
    }

    /// [`Self::near`] for every curve within `stray` = (Δθ, Δθ̇) of `dense` (zero: `dense`
    /// itself, the bounds of [`Self::near`] bit for bit); the bends only with `bends` (else
    /// +∞: the second partials were a fifth of its instructions, 421 → 345 a call, and most
    /// steps need none).
    #[inline]
    fn straying(
        ramp: &Ramp,
        mu_s: Option<f64>,
        dense: &DenseStep<2>,
        anchor: Option<SinCos>,
        stray: [f64; 2],
        bends: bool,
    ) -> Self {
        let bounds = dense.bounds();
        let (theta_max, w) = (bounds.value[0] + stray[0], bounds.value[1] + stray[1]);
        let (theta_rate, omega_rate) = (bounds.rate[0], bounds.rate[1]);
        let (theta_accel, omega_accel) = (bounds.accel[0], bounds.accel[1]);
        let h = dense.h.abs();
        let chi = ramp.body.chi;
        let (sa, ca) = (ramp.sin_a, ramp.cos_a);
        let eps40 = 1.0 / (1u64 << 40) as f64;
        // δ = 2⁻⁴⁰ (M + G_θ Θ + G_ω W); the bound is L |h| + 4δ. Along the interpolant
        // g'' = g_θθ θ'² + 2 g_θω θ'θ̇' + g_ωω θ̇'² + g_θ θ'' + g_ω θ̇'', so with P_.. ≥ the
        // second partials' magnitudes the bend is (P_θθ R_θ² + 2P_θω R_θ R_ω + P_ωω R_ω²
        // + G_θ Q_θ + G_ω Q_ω) |h|²/8 (R, Q: the interpolant's rate and acceleration bounds).
        let bound = |(m, g_theta, g_omega): (f64, f64, f64),
                     second: Option<(f64, f64, f64)>,
                     smooth: bool| {
            let mut delta = (m + g_theta * theta_max + g_omega * w) * eps40;
            if stray != [0.0; 2] {
                delta += g_theta * stray[0] + g_omega * stray[1];
            }
            let bend = second.map_or(f64::INFINITY, |(p_tt, p_tw, p_ww)| {
                let curvature = p_tt * theta_rate * theta_rate
                    + 2.0 * p_tw * theta_rate * omega_rate
                    + p_ww * omega_rate * omega_rate
                    + g_theta * theta_accel
                    + g_omega * omega_accel;
                curvature * (h * h) / 8.0
            });
            Change {
                rate: (g_theta * theta_rate + g_omega * omega_rate) * h,
                slack: 4.0 * delta,
                bend,
                smooth,
            }
        };
        let d_min = ramp.contact_inertia(-1.0);
        let (s_max, c_max, d_lo) = match anchor {
            Some(SinCos {
                theta: theta_c,
                sin: s_c,
                cos: c_c,
            }) => {
                let reach = (dense.y_old[0] - theta_c).abs() + h * theta_rate + stray[0];
                let reach = reach * (1.0 + eps40) + (1.0 + theta_max) * eps40;
                // NaN (never expected) falls back to the plain bounds through min/max.
                let s_max = (s_c.abs() + reach).min(1.0);
                let c_max = (c_c.abs() + reach).min(1.0);
                let d_lo = ramp.contact_inertia(c_c - reach).max(d_min);
                (s_max, c_max, d_lo)
            }
            None => (1.0, 1.0, d_min),
        };
        let chi_w2 = chi * w * w;
        let (chi_w, chi_s, chi_c) = (chi * w, chi * s_max, chi * c_max);
        let liftoff = bound(
            (chi_w2 * c_max + ca, chi_w2 * s_max, 2.0 * chi_w * c_max),
            bends.then_some((chi_w2 * c_max, 2.0 * chi_w * s_max, 2.0 * chi_c)),
            true,
        );
        let (fy, slip) = if d_lo > 0.0 {
            // θ̈ = a = N/D and its partials (aD = N differentiated; D_ω = 0). One division:
            // the products with 1/D_lo err by an ulp or two, which the scan's relative margin
            // on every bound covers.
            let inv_d = 1.0 / d_lo;
            let a = (chi_w2 * s_max + chi + sa) * inv_d;
            let a_theta = ((chi_w2 * c_max + chi) + 2.0 * chi * s_max * a) * inv_d;
            let a_omega = 2.0 * chi * w * s_max * inv_d;
            let lever = 1.0 + chi * c_max;
            // (M, G_θ, G_ω) of F_y and F_x.
            let fy = (
                ca + chi_w2 * c_max + chi * a * s_max,
                chi_w2 * s_max + chi * a * c_max + chi * s_max * a_theta,
                2.0 * chi * w * c_max + chi * s_max * a_omega,
            );
            let fx = (
                sa + chi_w2 * s_max + lever * a,
                chi_w2 * c_max + chi * s_max * a + lever * a_theta,
                2.0 * chi * w * s_max + lever * a_omega,
            );
            // (P_θθ, P_θω, P_ωω) of F_y and F_x, from θ̈'s second partials.
            let second = bends.then(|| {
                let a_tt = (chi_w2 * s_max + chi + 4.0 * chi_s * a_theta + 2.0 * chi_c * a) * inv_d;
                let a_tw = (2.0 * chi_w * c_max + 2.0 * chi_s * a_omega) * inv_d;
                let a_ww = 2.0 * chi_s * inv_d;
                let fy2 = (
                    chi_w2 * c_max + chi * (a_tt * s_max + 2.0 * a_theta * c_max + a * s_max),
                    2.0 * chi_w * s_max + chi * (a_tw * s_max + a_omega * c_max),
                    2.0 * chi_c + chi * a_ww * s_max,
                );
                let fx2 = (
                    chi_w2 * s_max + chi_c * a + 2.0 * chi_s * a_theta + lever * a_tt,
                    2.0 * chi_w * c_max + chi_s * a_omega + lever * a_tw,
                    2.0 * chi_s + lever * a_ww,
                );
                (fy2, fx2)
            });
            // μF_y − |F_x| = min(μF_y − F_x, μF_y + F_x): each branch has these bounds.
            let slip = mu_s.map_or(Change::NONE, |mu| {
                bound(
                    (mu * fy.0 + fx.0, mu * fy.1 + fx.1, mu * fy.2 + fx.2),
                    second.map(|(fy2, fx2)| {
                        (mu * fy2.0 + fx2.0, mu * fy2.1 + fx2.1, mu * fy2.2 + fx2.2)
                    }),
                    false,
                )
            });
            (bound(fy, second.map(|(fy2, _)| fy2), true), slip)
        } else {
            let slip = if mu_s.is_some() {
                Change::ANY
            } else {
                Change::NONE
            };
            (Change::ANY, slip)
        };
        let omega = bound((w, 0.0, 1.0), bends.then_some((0.0, 0.0, 0.0)), true);
        Self {
            liftoff,
            fy,
            slip,
            omega,
            theta_max,
            theta_rate,
            theta_accel,
            h,
            stray_theta: stray[0],
        }
    }

    /// Of θ − θ_lim (θ_lim finite).
    #[inline]
    pub(crate) fn theta_above(&self, theta_lim: f64) -> Change {
        let mut delta =
            (self.theta_max + theta_lim.abs() + self.theta_max) * (1.0 / (1u64 << 40) as f64);
        if self.stray_theta != 0.0 {
            delta += self.stray_theta;
        }
        Change {
            rate: self.theta_rate * self.h,
            slack: 4.0 * delta,
            bend: self.theta_accel * (self.h * self.h) / 8.0,
            smooth: true,
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::Cylinder;
    use crate::ode::{OdeSystem, State};
    use crate::testing::Lcg;

    /// Without the bends, the bounds from a step's ends keep the rates and slacks of the
    /// whole bounds bit for bit (so `quiet_step`'s first test agrees with the whole one) and
    /// leave every bend +∞ (a test by the bend never passes on them).
    #[test]
    fn bounds_without_bends_keep_the_rates_bit_for_bit() {
        let mut rng = Lcg(11);
        for i in 0..2000 {
            let chi = 0.95 * rng.next();
            let km = (1.0 - chi) * rng.next();
            let ramp = Ramp::new(Cylinder::new(chi, km).unwrap(), 1.5 * rng.next()).unwrap();
            let y_old = State::<2>::new(20.0 * rng.next() - 10.0, 6.0 * rng.next() - 3.0);
            let h = 0.5 * rng.next() - 0.1;
            // The ends of one explicit Euler step, with their exact derivatives: any two
            // states will do for the property.
            let f_old = ramp.rhs(0.0, &y_old);
            let y_new = y_old + f_old * h;
            let ends = StepEnds {
                t_old: 0.0,
                t_new: h,
                h,
                y_old,
                f_old,
                y_new,
                f_new: ramp.rhs(h, &y_new),
                scale: State::<2>::new(1e-9, 1e-9),
            };
            let mu_s = (i % 2 == 0).then(|| 2.0 * rng.next());
            let theta = y_new[0];
            let anchor = (i % 3 != 0).then(|| SinCos {
                theta,
                sin: theta.sin(),
                cos: theta.cos(),
            });
            let whole = ContactBounds::from_ends(&ramp, mu_s, &ends, anchor, true);
            let rates = ContactBounds::from_ends(&ramp, mu_s, &ends, anchor, false);
            let pairs = [
                (whole.liftoff, rates.liftoff),
                (whole.fy, rates.fy),
                (whole.slip, rates.slip),
                (whole.omega, rates.omega),
            ];
            for (k, (a, b)) in pairs.into_iter().enumerate() {
                assert_eq!(a.rate.to_bits(), b.rate.to_bits(), "case {i}, bound {k}");
                assert_eq!(a.slack.to_bits(), b.slack.to_bits(), "case {i}, bound {k}");
                assert_eq!(a.smooth, b.smooth, "case {i}, bound {k}");
                let constant = b == Change::NONE;
                assert!(
                    constant || b.bend == f64::INFINITY,
                    "case {i}, bound {k}: {b:?}"
                );
            }
        }
    }
}

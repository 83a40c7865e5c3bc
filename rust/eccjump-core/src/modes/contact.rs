//! Which mode a body in contact (b = 1, ḃ = 0) is in: the consistency test of
//! `docs/motion.md`, used at the start of a run, after every event that ends a contact
//! mode and after every impact. Each mode is tried as a constraint on Newton–Euler and kept
//! only if its forces are admissible (F_y > 0, friction inside the cone or against the
//! slip, D > 0, not Painlevé); flight only where the free normal acceleration
//! L = χθ̇² cos θ − cos α does not push the body into the ramp.

use crate::mechanics::friction::slip_margin;
use crate::mechanics::{BodyState, Ramp, Rule};
use crate::modes::slipping::Slipping;

named_enum! {
    /// A mode of motion.
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum Mode {
        /// Pure rolling.
        Roll = 0 => "ROLL",
        /// Contact with sliding.
        Slip = 1 => "SLIP",
        /// No contact.
        Flight = 2 => "FLIGHT",
    }
}

named_enum! {
    /// Why a mode began (the reasons of `docs/motion.md`).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    pub enum TransitionReason {
        /// The initial mode.
        Start = 0 => "start",
        /// The rolling branch left the friction cone and sliding is consistent.
        Slip = 1 => "slip",
        /// The paper's lift-off: L reached 0 rising (or is positive in contact).
        Liftoff = 2 => "liftoff",
        /// The normal force reached 0.
        NormalForce = 3 => "normal_force",
        /// No sliding mode is consistent (Painlevé at onset) and L ≥ 0 allows flight.
        SlipInconsistent = 4 => "slip_inconsistent",
        /// The slip velocity reached 0 and static friction holds.
        Stick = 5 => "stick",
        /// The slip velocity reached 0 and the body slides the other way.
        Reverse = 6 => "reverse",
        /// The body landed (impact law, then the consistency test).
        Impact = 7 => "impact",
        /// The body landed and the separation speed was below the settling threshold.
        Settle = 8 => "settle",
    }
}

/// The contact law of a run: friction coefficients and the lift-off rule.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ContactLaw {
    /// Static friction coefficient.
    pub mu_s: f64,
    /// Kinetic friction coefficient, ≤ μ_s.
    pub mu_k: f64,
    /// The lift-off rule.
    pub rule: Rule,
}

/// The outcome of the consistency test.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Verdict {
    /// Pure rolling is consistent.
    Roll,
    /// Sliding with friction direction σ is consistent.
    Slip {
        /// Direction of the friction force (−sign of the slip velocity).
        sigma: f64,
    },
    /// The body flies, for this reason.
    Flight(TransitionReason),
    /// No contact mode is consistent and L < 0 forbids flight: the rigid model needs an
    /// impulsive tangential impact (a dynamic jam). The run ends.
    Jam,
}

/// Is sliding with friction direction σ consistent at `s`? D above 0 (where F_y is above
/// [`crate::modes::slipping::F_SWITCH`] it goes on in the normal impulse), a positive
/// normal force (B > 0) and, at onset (v = 0), a slip acceleration along −σ. With μ_k = μ_s
/// that acceleration is exactly 0 at onset (sliding and rolling coincide there), so a
/// rounding-sized value counts as agreeing.
fn slides(ramp: &Ramp, law: &ContactLaw, s: &BodyState, sigma: f64, onset: bool) -> bool {
    let sl = Slipping::new(*ramp, sigma, law.mu_k);
    let k = sl.kinematics(s.theta, s.omega);
    if !(k.d > 0.0 && k.load > 0.0) {
        return false;
    }
    if !onset {
        return true;
    }
    let scale = 1.0 + ramp.sin_a + k.fx.abs() + k.l_dd.abs() + k.theta_dd.abs();
    -sigma * k.slip_acceleration() >= -1e-12 * scale
}

/// The mode of the contact state `s` (b = 1, ḃ = 0). `rolling_excluded` is set after the
/// rolling branch has just left its conditions (a slip or normal-force event), where a
/// rounding-sized margin must not send it back to rolling.
pub fn decide(ramp: &Ramp, law: &ContactLaw, s: &BodyState, rolling_excluded: bool) -> Verdict {
    let rolling = ramp.kinematics(s.theta, s.omega);
    let lift = rolling.lift;
    let fly = |reason| {
        if lift >= 0.0 {
            Verdict::Flight(reason)
        } else {
            Verdict::Jam
        }
    };
    let v = s.slip_velocity();
    if v != 0.0 {
        let sigma = -v.signum();
        if slides(ramp, law, s, sigma, false) {
            return Verdict::Slip { sigma };
        }
        return fly(TransitionReason::SlipInconsistent);
    }
    if law.rule == Rule::Paper && lift >= 0.0 {
        return Verdict::Flight(TransitionReason::Liftoff);
    }
    if !rolling_excluded && rolling.fy > 0.0 && slip_margin(law.mu_s, rolling.fx, rolling.fy) > 0.0
    {
        return Verdict::Roll;
    }
    // Slip onset: friction in the direction the rolling branch needs it.
    let sigma = if rolling.fx < 0.0 { -1.0 } else { 1.0 };
    if slides(ramp, law, s, sigma, true) {
        return Verdict::Slip { sigma };
    }
    fly(if rolling.fy <= 0.0 {
        TransitionReason::NormalForce
    } else {
        TransitionReason::SlipInconsistent
    })
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::Cylinder;

    fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
        Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
    }

    #[test]
    fn rest_on_a_gentle_ramp_rolls_and_on_ice_slides() {
        let r = ramp(0.3, 0.3, 10.0);
        let s = BodyState::rolling(0.0, 0.0, 0.0);
        let grip = ContactLaw {
            mu_s: 1.0,
            mu_k: 1.0,
            rule: Rule::Paper,
        };
        assert_eq!(decide(&r, &grip, &s, false), Verdict::Roll);
        let ice = ContactLaw {
            mu_s: 0.01,
            mu_k: 0.01,
            ..grip
        };
        // Rolling down needs friction up the ramp (F_x < 0): sliding with σ = −1.
        assert_eq!(decide(&r, &ice, &s, false), Verdict::Slip { sigma: -1.0 });
        // A fast spin with the centre of mass up flies at once under the paper's rule.
        let fast = BodyState::rolling(0.0, 3.0, 0.0);
        assert_eq!(
            decide(&r, &grip, &fast, false),
            Verdict::Flight(TransitionReason::Liftoff)
        );
        // A slip velocity down the ramp: friction up the ramp.
        let mut sliding = s;
        sliding.ldot = 0.5;
        assert_eq!(
            decide(&r, &grip, &sliding, false),
            Verdict::Slip { sigma: -1.0 }
        );
    }
}

//! A landing, as a map from the state before it to the state after: the impact law
//! ([`crate::mechanics::impact`]), then the Zeno rule of `docs/motion.md`. The driver applies
//! it at every landing; the sensitivities differentiate it.

use crate::mechanics::impact::{resolve, Ending, ImpactLaw, ImpactMatrix};
use crate::mechanics::{BodyState, Ramp};
use crate::motion::options::SimOptions;

/// The state after a landing, with the impulse that made it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub(crate) struct Landed {
    /// The state after the impact (and the plastic impulse of the Zeno rule).
    pub state: BodyState,
    /// The tangential impulse, the Zeno rule's included.
    pub pt: f64,
    /// The normal impulse, the Zeno rule's included.
    pub pn: f64,
    /// The contact point ended the impact stuck.
    pub sticking: bool,
    /// The separation speed exceeds the Zeno rule's threshold: the body flies off.
    pub flies: bool,
    /// The Zeno rule discarded a separation speed of a body with restitution (a settle).
    pub settled: bool,
}

/// The landing of the body in state `before` (b = 1, ḃ < 0) under the run's contact law and
/// restitution. None where the impact matrix is singular (Ĩ_CM = 0, refused by simulate).
pub(crate) fn land(ramp: &Ramp, opts: &SimOptions, before: &BodyState) -> Option<Landed> {
    let law = &opts.law;
    let (sin_t, cos_t) = crate::trig::sin_cos(before.theta);
    let w = ImpactMatrix::new(&ramp.body, sin_t, cos_t)?;
    let imp = resolve(
        &w,
        &ImpactLaw {
            mu_s: law.mu_s,
            mu_k: law.mu_k,
            restitution: opts.restitution,
        },
        before.slip_velocity(),
        before.bdot,
    );
    let flies = imp.un > opts.settle_speed;
    let sticking = imp.ending == Ending::Sticking;
    // The Zeno rule (docs/motion.md): a separation speed at or below the threshold is
    // ended by one plastic impulse at the contact point in place of the bounces that
    // would follow: ΔP = W⁻¹Δu with Δu = (0, −u_n) when the impact ended stuck (so it
    // stays stuck), else the normal impulse −u_n/W_nn. It dissipates ½ΔuᵀW⁻¹Δu ≥ 0.
    // Setting ḃ = 0 (or, after a normal-only impulse, l̇ = θ̇) directly would be an
    // impulse at the centre, not at the contact point, and change the energy at first
    // order (~θ̇ u_n), either way: hypothesis found −6.3e-7 that way.
    let (settle_t, settle_n) = if !flies && imp.un > 0.0 {
        if sticking {
            (w.tn() * imp.un / w.det(), -w.tt() * imp.un / w.det())
        } else {
            (0.0, -imp.un / w.nn())
        }
    } else {
        (0.0, 0.0)
    };
    let (pt, pn) = (imp.pt + settle_t, imp.pn + settle_n);
    let (omega, ldot, bdot) =
        ramp.body
            .apply_impulse(before.theta, before.omega, before.ldot, before.bdot, pt, pn);
    let mut state = BodyState {
        omega,
        ldot,
        bdot,
        ..*before
    };
    if sticking {
        // Zero up to rounding after the impulses: the rolling state.
        state.ldot = state.omega;
    }
    if !flies {
        // u_n is 0 up to rounding after the plastic impulse: the contact state.
        state.bdot = 0.0;
    }
    Some(Landed {
        state,
        pt,
        pn,
        sticking,
        flies,
        settled: settle_n != 0.0 && opts.restitution > 0.0,
    })
}

//! The one catalogue of events that end pure rolling, shared by the rolling run, the
//! closed-form path scan and the ODE route of the JARM classification: the paper's
//! lift-off (L = χθ̇² cos θ − cos α rising through 0), loss of normal force (F_y falling
//! through 0), slip (the margin μ_s F_y − |F_x| falling through 0), the body stopping
//! (θ̇² back to 0: it rocks back) and θ reaching its limit (a run's θ_max, the end of a
//! search).
//!
//! Ties are resolved in the order of [`ContactEvent::ALL`]; a condition already violated at
//! the start is found by [`violated_at_start`], the same test for both routes.

named_enum! {
    /// An event that ends pure rolling, in tie order (the index is the discriminant, and the
    /// index of its event function in a run and in the ODE route).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash)]
    #[repr(u8)]
    pub enum ContactEvent {
        /// The paper's lift-off: L reaches 0 from below.
        Liftoff = 0 => "liftoff",
        /// F_y reaches 0.
        NormalForce = 1 => "normal_force_zero",
        /// μ_s F_y − |F_x| reaches 0: the rolling branch leaves the friction cone.
        Slip = 2 => "slip",
        /// θ̇² returns to 0: the body stops and rolls back (watched by a search; a run rolls
        /// back and on).
        RocksBack = 3 => "rocks_back",
        /// θ reaches its limit: a run's θ_max, or the end of a search (nothing happened
        /// before it).
        ThetaLimit = 4 => "theta_limit",
    }
}

/// Which of the conditions a search watches (the stop and the end are always watched).
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub struct Watched {
    /// The paper's lift-off (only under the paper's rule).
    pub liftoff: bool,
    /// Loss of normal force.
    pub normal_force: bool,
    /// The friction cone.
    pub friction: bool,
}

/// The contact functions at the start of a search.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct StartValues {
    /// L and dL/dθ.
    pub lift: f64,
    /// dL/dθ along rolling.
    pub lift_slope: f64,
    /// F_x and F_y.
    pub fx: f64,
    /// F_y.
    pub fy: f64,
    /// The kinetic energy ½Ĩ_Pθ̇² and its slope dE/dθ = sin α + χ sin(α + θ).
    pub kinetic: f64,
    /// dE/dθ.
    pub kinetic_slope: f64,
}

/// The first condition (in tie order) already violated at the start, if any; NaN counts
/// as a violation. Lift-off: L ≥ 0 and not falling; normal force: F_y ≤ 0; friction:
/// μ_s F_y ∓ F_x < 0; stop: no kinetic energy and no forward acceleration.
pub fn violated_at_start(w: Watched, mu_s: f64, v: &StartValues) -> Option<ContactEvent> {
    if w.liftoff && liftoff_at_start(v.lift, v.lift_slope) {
        return Some(ContactEvent::Liftoff);
    }
    if w.normal_force && (v.fy.is_nan() || v.fy <= 0.0) {
        return Some(ContactEvent::NormalForce);
    }
    let m = mu_s * v.fy;
    let (mp, mm) = (m - v.fx, m + v.fx);
    if w.friction && (mp.is_nan() || mm.is_nan() || mp < 0.0 || mm < 0.0) {
        return Some(ContactEvent::Slip);
    }
    let (e, de) = (v.kinetic, v.kinetic_slope);
    if e < 0.0 || (e == 0.0 && (de.is_nan() || de <= 0.0)) {
        return Some(ContactEvent::RocksBack);
    }
    None
}

/// The paper's lift-off already at the start: L ≥ 0 (or NaN) and not falling from L = 0.
#[inline]
pub fn liftoff_at_start(lift: f64, lift_slope: f64) -> bool {
    (lift.is_nan() || lift >= 0.0) && !(lift == 0.0 && lift_slope < 0.0)
}

/// A start from rest in equilibrium (θ̈0 = 0 inside the contact conditions): nothing ever
/// happens (e.g. α = 0 from rest).
pub fn equilibrium_start(omega0: f64, omega_dot: f64, fx: f64, fy: f64, mu_s: f64) -> bool {
    omega0 == 0.0 && omega_dot == 0.0 && fy > 0.0 && mu_s * fy >= fx.abs()
}

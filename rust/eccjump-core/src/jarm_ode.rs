//! The second, independent route to the JARM classification: integrate the rolling equation
//! with the Dormand–Prince core and let its events decide (to be written).

use crate::jarm::{JarmOptions, JarmResult, Reason};

/// Classifies one point by integration (same semantics and reasons as `jarm::classify`).
pub fn classify_ode(
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    opts: &JarmOptions,
    rtol: f64,
    atol: f64,
) -> JarmResult {
    let _ = (alpha, chi, km, mu_s, opts, rtol, atol);
    JarmResult::new(Reason::InvalidParams)
}

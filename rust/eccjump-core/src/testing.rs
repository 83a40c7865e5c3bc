//! What the unit tests share (compiled for tests only).

use crate::mechanics::{BodyState, Ramp};

impl Ramp {
    /// The energy of the pure-rolling state (θ, θ̇) with l = θ, b = 1.
    pub(crate) fn rolling_energy(&self, theta: f64, omega: f64) -> f64 {
        self.energy_of(&BodyState::rolling(theta, omega, theta))
    }
}

/// A small deterministic generator (Knuth's MMIX LCG), uniform in [0, 1): reproducible
/// random test points.
pub(crate) struct Lcg(pub u64);

impl Lcg {
    /// The next number, uniform in [0, 1).
    pub(crate) fn next(&mut self) -> f64 {
        self.0 = self
            .0
            .wrapping_mul(6364136223846793005)
            .wrapping_add(1442695040888963407);
        (self.0 >> 11) as f64 / (1u64 << 53) as f64
    }
}

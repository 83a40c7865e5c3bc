//! The body on a ramp: the cylinder, the ramp angle α ∈ [0, π/2] and the trigonometry of α,
//! shared by every mode of motion (rolling, slipping, flight).
//!
//! Coordinates (units g = R = M = 1): x down the ramp, y along the ramp's outward normal;
//! l is the position of the geometric centre C along x, b its height above the ramp (b = 1
//! in contact), θ the angle of the vector C → CM from the normal, growing as the body rolls
//! down. Gravity is (sin α, −cos α) in these coordinates.

use crate::error::{Error, Result};
use crate::mechanics::body::Cylinder;
use std::f64::consts::FRAC_PI_2;

/// A body on a ramp of angle α ∈ [0, π/2], with the trigonometry of α precomputed.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Ramp {
    /// The validated body.
    pub body: Cylinder,
    /// The ramp angle α (rad).
    pub alpha: f64,
    /// sin α.
    pub sin_a: f64,
    /// cos α, exactly 0 at α = π/2.
    pub cos_a: f64,
}

impl Ramp {
    /// Validates α ∈ [0, π/2] and precomputes its sine and cosine.
    pub fn new(body: Cylinder, alpha: f64) -> Result<Self> {
        if !(0.0..=FRAC_PI_2).contains(&alpha) {
            // Radians: the API's unit (the command line's is degrees), said so, as a ramp of
            // 40 meant as degrees is a likely mistake.
            let allowed = "[0, pi/2] rad (math.radians(deg) for degrees)";
            return Err(Error::invalid("alpha", alpha, allowed));
        }
        // One `sin_cos` of the kernels' own library (the same bits with every C library).
        let (sin_a, cos_a) = crate::trig::sin_cos(alpha);
        // cos(π/2) in floating point is 6e-17, not 0: keep it exact at the end point.
        let cos_a = if alpha == FRAC_PI_2 { 0.0 } else { cos_a };
        Ok(Self {
            body,
            alpha,
            sin_a,
            cos_a,
        })
    }

    /// Ĩ_P(θ) = Ĩ_C + 1 + 2χ cos θ, the moment of inertia about the contact point (given
    /// cos θ). It vanishes only for χ = 1, k_m = 0 at θ = π.
    #[inline]
    pub fn contact_inertia(&self, cos_t: f64) -> f64 {
        self.body.ic + 1.0 + 2.0 * self.body.chi * cos_t
    }

    /// (sin(α + θ), cos(α + θ)) from (sin θ, cos θ), reusing the one `sin_cos` of θ.
    #[inline]
    pub fn shifted(&self, s: f64, c: f64) -> (f64, f64) {
        (
            self.sin_a * c + self.cos_a * s,
            self.cos_a * c - self.sin_a * s,
        )
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn vertical_ramp_has_exact_zero_cosine() {
        let r = Ramp::new(Cylinder::new(0.2, 0.1).unwrap(), FRAC_PI_2).unwrap();
        assert_eq!(r.cos_a, 0.0);
        assert!(Ramp::new(Cylinder::new(0.2, 0.1).unwrap(), 1.6).is_err());
    }

    #[test]
    fn shifted_angles() {
        let r = Ramp::new(Cylinder::new(0.2, 0.1).unwrap(), 0.7).unwrap();
        let th: f64 = 2.3;
        let (sa, ca) = r.shifted(th.sin(), th.cos());
        assert!((sa - (0.7 + th).sin()).abs() < 1e-15 && (ca - (0.7 + th).cos()).abs() < 1e-15);
    }
}

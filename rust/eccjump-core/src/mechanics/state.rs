//! The full state of the body, (θ, θ̇, l, l̇, b, ḃ), shared by every mode of motion and by
//! the impact law, with the velocity of the material point at the contact.
//!
//! The material point of the body at P = C − (0, 1) moves with (u_t, u_n) = (l̇ − θ̇, ḃ)
//! (see [`crate::mechanics::newton_euler`]): u_t is the slip velocity, u_n the normal
//! velocity of the contact point.

/// The state of the body: angle, position of the centre C along the ramp, height of C, and
/// their rates (units g = R = M = 1).
#[derive(Debug, Clone, Copy, PartialEq, Default)]
pub struct BodyState {
    /// θ (rad), the angle of C → CM from the ramp normal.
    pub theta: f64,
    /// θ̇.
    pub omega: f64,
    /// l, the position of C along the ramp (down the ramp).
    pub l: f64,
    /// l̇.
    pub ldot: f64,
    /// b, the height of C above the ramp (1 in contact).
    pub b: f64,
    /// ḃ.
    pub bdot: f64,
}

impl BodyState {
    /// A contact state rolling without slip at (θ, θ̇) with C at l.
    pub fn rolling(theta: f64, omega: f64, l: f64) -> Self {
        Self::in_contact(theta, omega, l, omega)
    }

    /// A contact state (b = 1, ḃ = 0) at (θ, θ̇) with C at l moving at l̇ (sliding if l̇ ≠ θ̇).
    pub fn in_contact(theta: f64, omega: f64, l: f64, ldot: f64) -> Self {
        Self {
            theta,
            omega,
            l,
            ldot,
            b: 1.0,
            bdot: 0.0,
        }
    }

    /// (θ, θ̇, l, l̇, b, ḃ): the order of every full state handed on as numbers.
    pub fn values(&self) -> [f64; 6] {
        [self.theta, self.omega, self.l, self.ldot, self.b, self.bdot]
    }

    /// The state of the values (θ, θ̇, l, l̇, b, ḃ).
    pub fn from_values([theta, omega, l, ldot, b, bdot]: [f64; 6]) -> Self {
        Self {
            theta,
            omega,
            l,
            ldot,
            b,
            bdot,
        }
    }

    /// The slip velocity u_t = l̇ − θ̇ of the contact point.
    #[inline]
    pub fn slip_velocity(&self) -> f64 {
        self.ldot - self.omega
    }
}

//! When the body leaves the ramp: the two lift-off rules and the free-flight normal
//! acceleration they are built on. Shared by the rolling runs and both JARM routes.
//!
//! Released from the contact (F = 0), Newton–Euler ([`crate::mechanics::newton_euler`])
//! gives the centre C the normal acceleration
//!
//!   b̈_free = χ θ̇² cos θ − cos α,
//!
//! the paper's lift-off function L (Eq. jumpcondition): the body would separate where it
//! turns positive. Along pure rolling (θ̈ from the rolling equation) its derivative in θ is
//! dL/dθ = (2χ θ̈ cos θ − χ θ̇² sin θ) (using dθ̇²/dθ = 2θ̈).

named_enum! {
    /// When the body leaves the ramp (see `docs/jarm.md` and the physics notes).
    #[derive(Debug, Clone, Copy, PartialEq, Eq, Hash, Default)]
    pub enum Rule {
        /// The paper's rule (and its reference \[gomes\]): lift-off at the first rising zero of
        /// the free-flight normal acceleration χ θ̇² cos θ − cos α. The default: it reproduces
        /// the paper.
        #[default]
        Paper = 0 => "paper",
        /// The classical unilateral-contact rule: keep rolling while F_y > 0 and |F_x| ≤ μ_s
        /// F_y; lift-off when F_y reaches 0, or at slip onset when no sliding contact is
        /// consistent.
        NormalForce = 1 => "normal_force",
    }
}

impl Rule {
    /// The rule named `name` ("paper" or "normal_force").
    pub fn from_name(name: &str) -> Option<Rule> {
        Rule::ALL.into_iter().find(|r| r.name() == name)
    }
}

/// The lift-off function L = b̈_free = χ θ̇² cos θ − cos α, given χθ̇² (computed once by the
/// caller, who also needs it for the forces), cos θ and cos α.
#[inline(always)]
pub fn free_normal_acceleration(chi_w2: f64, cos_t: f64, cos_a: f64) -> f64 {
    chi_w2 * cos_t - cos_a
}

/// dL/dθ along pure rolling: 2χθ̈ cos θ − χθ̇² sin θ (θ̈ = `omega_dot`).
#[inline(always)]
pub fn liftoff_slope(chi: f64, chi_w2: f64, omega_dot: f64, sin_t: f64, cos_t: f64) -> f64 {
    2.0 * chi * omega_dot * cos_t - chi_w2 * sin_t
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::newton_euler::Constraint;
    use crate::mechanics::{Cylinder, Ramp};

    #[test]
    fn is_the_free_normal_acceleration_of_newton_euler() {
        let r = Ramp::new(Cylinder::new(0.35, 0.2).unwrap(), 0.6).unwrap();
        for &(th, w) in &[(0.2f64, 0.9f64), (5.9, 2.5), (3.0, 0.1)] {
            let free = r.newton_euler(th, w, Constraint::Free).unwrap();
            let l = free_normal_acceleration(r.body.chi * w * w, th.cos(), r.cos_a);
            assert!((l - free.b_dd).abs() < 1e-14);
        }
        assert_eq!(
            Rule::from_name(Rule::NormalForce.name()),
            Some(Rule::NormalForce)
        );
        assert_eq!(Rule::from_name("x"), None);
    }
}

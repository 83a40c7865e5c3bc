//! Newton–Euler for the cylinder on the ramp in its general form, with l and b free: the
//! one statement of the dynamics from which every mode follows by a constraint.
//!
//! With the contact force (F_x, F_y) acting at the lowest point P = C − (0, 1) of the circle
//! (per M g; x down the ramp, y normal to it), the centre of mass at C + χ(sin θ, cos θ) and
//! θ̇ = −ω_z (θ grows as the body rolls down):
//!
//!   F_x = l̈ + χ(cos θ θ̈ − sin θ θ̇²) − sin α          (Newton along the ramp)
//!   F_y = b̈ − χ(sin θ θ̈ + cos θ θ̇²) + cos α          (Newton along the normal)
//!   Ĩ_CM θ̈ = χ sin θ F_y − (1 + χ cos θ) F_x           (Euler about the centre of mass)
//!
//! The velocity of the material point at P is (l̇ − θ̇, ḃ): its tangential part is the slip
//! velocity, its normal part the approach speed. A mode adds two equations:
//! - rolling: l̈ = θ̈ and b̈ = 0 (no slip, contact kept);
//! - sliding: b̈ = 0 and F_x = σ μ_k F_y (Coulomb friction against the slip, σ = −sign v);
//! - flight: F_x = F_y = 0.
//!
//! `Ramp::newton_euler` solves the five linear equations for (θ̈, l̈, b̈, F_x, F_y) by LU
//! decomposition. It is the reference every fast path is tested against, so it is built for
//! the tests only (the closed forms of rolling in [`crate::modes::rolling`], of sliding in
//! [`crate::mechanics::friction`], the lift-off function in [`crate::mechanics::liftoff`]);
//! the kernels use those closed forms.

use crate::dual::{Dual, Number};
use nalgebra::{Matrix5, Vector5};

/// The two equations a mode of motion adds to Newton–Euler.
#[derive(Debug, Clone, Copy, PartialEq)]
pub enum Constraint<T = f64> {
    /// Contact without slip: l̈ = θ̈, b̈ = 0.
    Ramp,
    /// Contact with sliding friction F_x = σ μ_k F_y (σ = −sign of the slip velocity).
    Sliding {
        /// Direction of the friction force along x, ±1.
        sigma: f64,
        /// Kinetic friction coefficient μ_k ≥ 0.
        mu_k: T,
    },
    /// No contact: F_x = F_y = 0.
    Free,
}

/// Accelerations and contact force at one state.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Response<T = f64> {
    /// θ̈.
    pub theta_dd: T,
    /// l̈, the acceleration of C along the ramp.
    pub l_dd: T,
    /// b̈, the acceleration of C along the normal.
    pub b_dd: T,
    /// Friction force on the body along the ramp [M g].
    pub fx: T,
    /// Normal force on the body [M g].
    pub fy: T,
}

/// What Newton–Euler needs of the body and the ramp: χ, Ĩ_CM, sin α and cos α.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Setting<T> {
    /// χ.
    pub chi: T,
    /// Ĩ_CM.
    pub icm: T,
    /// sin α.
    pub sin_a: T,
    /// cos α.
    pub cos_a: T,
}

/// Newton–Euler with `constraint` at (θ, θ̇) as the linear system M x = r in the unknowns
/// x = (θ̈, l̈, b̈, F_x, F_y): written once, for f64 and for the dual numbers the
/// sensitivities differentiate it with.
pub(crate) fn equations<T: Number>(
    q: &Setting<T>,
    theta: T,
    omega: T,
    constraint: Constraint<T>,
) -> ([[T; 5]; 5], [T; 5]) {
    let (zero, one) = (T::of(0.0), T::of(1.0));
    let chi = q.chi;
    let (s, c) = Number::sin_cos(theta);
    let w = omega * omega;
    let (row4, row5) = match constraint {
        Constraint::Ramp => ([-one, one, zero, zero, zero], [zero, zero, one, zero, zero]),
        Constraint::Sliding { sigma, mu_k } => (
            [zero, zero, one, zero, zero],
            [zero, zero, zero, one, -(T::of(sigma) * mu_k)],
        ),
        Constraint::Free => ([zero, zero, zero, one, zero], [zero, zero, zero, zero, one]),
    };
    let m = [
        [chi * c, one, zero, -one, zero],
        [-(chi * s), zero, one, zero, -one],
        [q.icm, zero, zero, one + chi * c, -(chi * s)],
        row4,
        row5,
    ];
    let r = [
        q.sin_a + chi * s * w,
        chi * c * w - q.cos_a,
        zero,
        zero,
        zero,
    ];
    (m, r)
}

/// Newton–Euler in dual numbers: the response and its partials. With M x = r, each partial
/// solves M ∂x = ∂r − (∂M) x, by the one LU decomposition of M.
pub(crate) fn newton_euler_dual<const N: usize>(
    q: &Setting<Dual<N>>,
    theta: Dual<N>,
    omega: Dual<N>,
    constraint: Constraint<Dual<N>>,
) -> Option<Response<Dual<N>>> {
    let (m, r) = equations(q, theta, omega, constraint);
    let lu = Matrix5::from_fn(|i, j| m[i][j].v).lu();
    let x = lu.solve(&Vector5::from_fn(|i, _| r[i].v))?;
    let mut out = [Dual::<N>::constant(0.0); 5];
    for (i, o) in out.iter_mut().enumerate() {
        o.v = x[i];
    }
    for k in 0..N {
        let rhs =
            Vector5::from_fn(|i, _| r[i].d[k] - (0..5).map(|j| m[i][j].d[k] * x[j]).sum::<f64>());
        let dx = lu.solve(&rhs)?;
        for (i, o) in out.iter_mut().enumerate() {
            o.d[k] = dx[i];
        }
    }
    out.iter()
        .all(|x| x.v.is_finite() && x.d.iter().all(|d| d.is_finite()))
        .then_some(Response {
            theta_dd: out[0],
            l_dd: out[1],
            b_dd: out[2],
            fx: out[3],
            fy: out[4],
        })
}

#[cfg(test)]
impl crate::mechanics::Ramp {
    /// Solves Newton–Euler with `constraint` at angle θ and rate θ̇ (the general form; see
    /// the module notes). None where the system is singular: sliding with D = 0 (Painlevé),
    /// or rolling/sliding of a body with Ĩ_CM = 0 at a singular angle.
    pub fn newton_euler(&self, theta: f64, omega: f64, constraint: Constraint) -> Option<Response> {
        let q = Setting {
            chi: self.body.chi,
            icm: self.body.icm,
            sin_a: self.sin_a,
            cos_a: self.cos_a,
        };
        let (m, r) = equations(&q, theta, omega, constraint);
        let x = Matrix5::from_fn(|i, j| m[i][j])
            .lu()
            .solve(&Vector5::from(r))?;
        x.iter().all(|v| v.is_finite()).then(|| Response {
            theta_dd: x[0],
            l_dd: x[1],
            b_dd: x[2],
            fx: x[3],
            fy: x[4],
        })
    }
}

#[cfg(test)]
mod tests {
    use super::*;
    use crate::mechanics::body::Cylinder;
    use crate::mechanics::Ramp;

    fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
        Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
    }

    #[test]
    fn flight_is_free_fall_with_constant_spin() {
        let r = ramp(0.4, 0.3, 25.0);
        for &(th, w) in &[(0.3, 0.2), (2.0, 1.5), (4.0, -0.7)] {
            let x = r.newton_euler(th, w, Constraint::Free).unwrap();
            assert_eq!((x.fx, x.fy, x.theta_dd), (0.0, 0.0, 0.0));
            // The centre of mass falls with g: l̈ + χ(c θ̈ − s θ̇²) = sin α.
            assert!((x.l_dd - r.body.chi * w * w * th.sin() - r.sin_a).abs() < 1e-14);
            assert!((x.b_dd - (r.body.chi * w * w * th.cos() - r.cos_a)).abs() < 1e-14);
        }
    }

    #[test]
    fn rolling_and_sliding_keep_their_constraints() {
        let r = ramp(0.6, 0.2, 40.0);
        let x = r.newton_euler(1.1, 0.8, Constraint::Ramp).unwrap();
        assert!((x.l_dd - x.theta_dd).abs() < 1e-15 && x.b_dd.abs() < 1e-15);
        let y = r
            .newton_euler(
                1.1,
                0.8,
                Constraint::Sliding {
                    sigma: -1.0,
                    mu_k: 0.3,
                },
            )
            .unwrap();
        assert!(y.b_dd.abs() < 1e-15 && (y.fx + 0.3 * y.fy).abs() < 1e-15);
    }
}

//! Exact derivatives of the lift-off angle θ_J, of the forces at the jump and of the paper's
//! friction ratio μ_J = −F_x,J/F_y,J with respect to p = (α, χ, k_m), χ and k_m independent,
//! at fixed μ_s and start (θ0, θ̇0), derived in `docs/jarm.md` ("Derivatives").
//!
//! θ_J is a root in θ of the rule's g(θ; p) along pure rolling, θ̇² by the energy integral
//! (exact on either route, so the ODE route's derivatives carry only its error in θ_J), and
//! dθ_J/dp = −(∂g/∂p)/(∂g/∂θ), the partials by forward-mode differentiation ([`crate::dual`])
//! of the formulas as written. Not differentiable (`singular`, every derivative NaN): a
//! double root, |∂g/∂θ| ≤ √ε s with s = 1 + χ(θ̇² + |θ̈|), where the rounding of θ_J alone
//! leaves no correct digit; and under the classical rule a tie F_x = F_y = 0 with k_m > 0.
//! At k_m = 0 the k_m column is NaN (one-sided: k_m < 0 is no body), the others stand.

use crate::dual::{sin, sin_cos};
use crate::jarm::decision::point_ramp;
use crate::jarm::result::JarmOptions;
use crate::mechanics::Rule;

/// A rolling quantity with its partials in (θ, α, χ, k_m).
pub(crate) type Dual = crate::dual::Dual<4>;
use std::f64::consts::TAU;

/// √ε: below √ε times the size of its terms, ∂g/∂θ is zero within rounding.
const TANGENT: f64 = 1.490_116_119_384_765_6e-8;

/// The derivatives at one point, each with respect to (α, χ, k_m).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct JumpDerivatives {
    /// dθ_J/dp [rad per unit of p].
    pub theta_j: [f64; 3],
    /// dF_x,J/dp [M g per unit of p].
    pub fx_j: [f64; 3],
    /// dF_y,J/dp.
    pub fy_j: [f64; 3],
    /// dμ_J/dp, μ_J = −F_x,J/F_y,J (Eq. ineq2 at a jump of the paper's rule; NaN where
    /// F_y,J = 0, the classical rule's normal-force lift-off).
    pub mu_j: [f64; 3],
    /// θ_J is finite but not differentiable (a double root or a tie, see the module notes).
    pub singular: bool,
}

impl JumpDerivatives {
    /// At k_m = 0 the derivatives in k_m are one-sided (k_m < 0 is no body): NaN, as the
    /// physics notes ask ("Derivatives at a rule's switch"); the other columns stand.
    fn one_sided_in_km(mut self, km: f64) -> Self {
        if km == 0.0 {
            for d in [
                &mut self.theta_j,
                &mut self.fx_j,
                &mut self.fy_j,
                &mut self.mu_j,
            ] {
                d[2] = f64::NAN;
            }
        }
        self
    }

    /// Every derivative NaN, with the flag `singular`.
    fn nan(singular: bool) -> Self {
        Self {
            theta_j: [f64::NAN; 3],
            fx_j: [f64::NAN; 3],
            fy_j: [f64::NAN; 3],
            mu_j: [f64::NAN; 3],
            singular,
        }
    }
}

/// The rolling quantities at θ with their partials in (θ, α, χ, k_m).
#[derive(Debug, Clone, Copy)]
pub(crate) struct Rolling {
    /// θ̇², by energy.
    pub omega_sq: Dual,
    /// θ̈.
    pub omega_dot: Dual,
    /// The lift-off function L = χ θ̇² cos θ − cos α.
    pub lift: Dual,
    /// F_x.
    pub fx: Dual,
    /// F_y.
    pub fy: Dual,
}

impl Rolling {
    /// The state at θ along pure rolling from (θ0, θ̇0) on the ramp α with the body (χ, k_m).
    /// Needs 1 − k_m > 0 unless χ = 0.
    pub(crate) fn at(theta: f64, (alpha, chi, km): (f64, f64, f64), start: (f64, f64)) -> Self {
        let (theta0, omega0) = start;
        let th = Dual::variable(theta, 0);
        let a = Dual::variable(alpha, 1);
        let x = Dual::variable(chi, 2);
        let k = Dual::variable(km, 3);
        // Ĩ_C = k_m + χ²/(1 − k_m); k_m = 1 forces χ = 0, where Ĩ_C = k_m.
        let ic = if km < 1.0 { k + x * x / (1.0 - k) } else { k };
        let (s, c) = sin_cos(th);
        let (sa, ca) = sin_cos(a);
        let ip = ic + (x * c).scale(2.0) + 1.0;
        let c0 = Dual::constant(crate::trig::sin_cos(theta0).1);
        let k0 = (ic + (x * c0).scale(2.0) + 1.0).scale(0.5 * omega0 * omega0);
        // χ(cos(α + θ0) − cos(α + θ)) = 2χ sin(α + (θ + θ0)/2) sin((θ − θ0)/2), as in the
        // energy module (no cancellation at small θ − θ0).
        let d = th + (-theta0);
        let mid = sin(a + (th + theta0).scale(0.5));
        let energy = k0 + d * sa + (x * mid * sin(d.scale(0.5))).scale(2.0);
        let omega_sq = energy.scale(2.0) / ip;
        let chi_w2 = x * omega_sq;
        let sin_at = sa * c + ca * s;
        let omega_dot = (chi_w2 * s + x * sin_at + sa) / ip;
        let lift = chi_w2 * c - ca;
        Self {
            omega_sq,
            omega_dot,
            lift,
            fx: -sa - chi_w2 * s + (x * c + 1.0) * omega_dot,
            fy: -lift - x * omega_dot * s,
        }
    }

    /// The size s of the terms of the θ-slopes (module notes).
    fn scale(&self, chi: f64) -> f64 {
        1.0 + chi * (self.omega_sq.v.abs() + self.omega_dot.v.abs())
    }

    /// The derivatives of θ_J (given, found as the root of `root`) and of the forces and μ_J
    /// along it.
    fn along(&self, dtheta: [f64; 3], root: Root) -> JumpDerivatives {
        let total = |q: Dual| std::array::from_fn(|i| q.d[0] * dtheta[i] + q.d[i + 1]);
        let (fx, fy) = (self.fx.v, self.fy.v);
        let (dfx, dfy): ([f64; 3], [f64; 3]) = (total(self.fx), total(self.fy));
        let mu_j = match root {
            // F_y,J = 0: no ratio.
            Root::NormalForce => [f64::NAN; 3],
            // On the cone μ_J = −σ μ_s whatever p: exactly 0, not a difference of two large
            // terms (which left up to 3 at μ_s = 1e6).
            Root::Cone => [0.0; 3],
            Root::Lift => std::array::from_fn(|i| -(dfx[i] * fy - fx * dfy[i]) / (fy * fy)),
        };
        JumpDerivatives {
            theta_j: dtheta,
            fx_j: dfx,
            fy_j: dfy,
            mu_j,
            singular: false,
        }
    }
}

/// Which function's root θ_J is.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
enum Root {
    /// The paper's lift-off function L (or the start itself).
    Lift,
    /// The classical rule's F_y.
    NormalForce,
    /// The classical rule's friction cone, μ_s F_y − σ F_x.
    Cone,
}

/// The function g that vanishes at θ_J under `rule` (module notes) and which it is; None for the classical rule's tie F_x = F_y = 0 (within `tol`).
/// Under the classical rule the cone decides where F_y > 0 at θ_J (physics notes,
/// "Derivatives at a rule's switch"): g is then the margin μ_s F_y − σ F_x, and F_y only where
/// it vanishes. For k_m = 0 (Ĩ_CM = 0) the contact force points at the centre of mass, so
/// F_x ∝ F_y and both vanish together at a normal-force lift-off: a simple root of F_y, not a
/// tie; but the ratio F_x/F_y moves with θ, so the cone can still be reached first, at F_y > 0.
fn vanishing(q: &Rolling, rule: Rule, km: f64, mu_s: f64, tol: f64) -> Option<(Dual, Root)> {
    match rule {
        Rule::Paper => Some((q.lift, Root::Lift)),
        Rule::NormalForce => {
            let (fx, fy) = (q.fx.v, q.fy.v);
            let margin = q.fy.scale(mu_s) - q.fx.scale(fx.signum());
            if km == 0.0 {
                // F_x ∝ F_y: the margin is no measure of which root this is, F_y itself is.
                return Some(if fy.abs() <= tol {
                    (q.fy, Root::NormalForce)
                } else {
                    (margin, Root::Cone)
                });
            }
            if fx.abs() <= tol && fy.abs() <= tol {
                return None;
            }
            if fy.abs() <= margin.v.abs() {
                Some((q.fy, Root::NormalForce))
            } else {
                Some((margin, Root::Cone))
            }
        }
    }
}

/// The derivatives of θ_J, F_x,J, F_y,J and μ_J with respect to (α, χ, k_m) at the lift-off
/// angle `theta_j` that a classification of (α, χ, k_m, μ_s) with options `o` (its rule and
/// start) reported. Every derivative is NaN where θ_J is NaN or a parameter is invalid, and
/// where `singular` (module notes). A lift-off at the start itself (θ_J = θ0, reported as
/// `LiftoffEarlier`) does not move with p: dθ_J/dp = 0 there.
pub fn jump_derivatives(
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    theta_j: f64,
    o: &JarmOptions,
) -> JumpDerivatives {
    if !theta_j.is_finite() || point_ramp(alpha, chi, km, mu_s, o).is_none() {
        return JumpDerivatives::nan(false);
    }
    let q = Rolling::at(theta_j, (alpha, chi, km), (o.theta0, o.omega0));
    // A start shifted into [0, 2π) and back (`classify_with`) may be a few ulps off θ0.
    if (theta_j - o.theta0).abs() <= 64.0 * f64::EPSILON * (o.theta0.abs() + TAU) {
        return q.along([0.0; 3], Root::Lift).one_sided_in_km(km);
    }
    let tol = TANGENT * q.scale(chi);
    let Some((g, root)) = vanishing(&q, o.rule, km, mu_s, tol) else {
        return JumpDerivatives::nan(true);
    };
    let slope = g.d[0];
    if !slope.is_finite() || slope.abs() <= tol {
        return JumpDerivatives::nan(true);
    }
    q.along(std::array::from_fn(|i| -g.d[i + 1] / slope), root)
        .one_sided_in_km(km)
}

#[cfg(test)]
mod tests;

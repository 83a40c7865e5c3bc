//! The body: a cylinder of radius R whose centre of mass sits at distance d = χR from
//! its geometric centre C. Its dynamics depend only on χ and Ĩ_C = I_C/(MR²); the paper
//! parameterises Ĩ_C by the shell mass fraction k_m of its shell-plus-line-mass model:
//!
//!   Ĩ_C = k_m + χ²/(1 − k_m),   Ĩ_CM = Ĩ_C − χ² = k_m (1 − k_m + χ²)/(1 − k_m),
//!
//! with 0 ≤ χ ≤ 1 and 0 ≤ k_m ≤ 1 − χ (the line mass must lie inside the shell).

use crate::dual::Number;
use crate::error::{check_positive, check_range, short, Error, Result};
use std::f64::consts::PI;

/// A validated body, in units where M = R = 1.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Cylinder {
    /// χ = d/R, the offset of the centre of mass from the geometric centre.
    pub chi: f64,
    /// k_m = m_C/M, the mass fraction of the uniform shell.
    pub km: f64,
    /// Ĩ_C = I_C/(MR²), moment of inertia about the geometric centre.
    pub ic: f64,
    /// Ĩ_CM = I_CM/(MR²), moment of inertia about the centre of mass.
    pub icm: f64,
}

/// (Ĩ_C, Ĩ_CM) = (k_m + χ²/(1 − k_m), k_m (1 − k_m + χ²)/(1 − k_m)) given 1 − k_m, the
/// module's formulas written once for f64 and for the dual numbers of the sensitivities.
pub(crate) fn inertias<T: Number>(chi: T, km: T, one_minus_km: T) -> (T, T) {
    (
        km + chi * chi / one_minus_km,
        km * (one_minus_km + chi * chi) / one_minus_km,
    )
}

impl Cylinder {
    /// Validates (χ, k_m) and derives the inertias.
    ///
    /// The χ = 0 limit is handled explicitly: then Ĩ_C = Ĩ_CM = k_m for any k_m in [0, 1]
    /// (the 0/0 of χ²/(1 − k_m) at k_m = 1 is taken as 0, its limit along χ ≤ 1 − k_m).
    pub fn new(chi: f64, km: f64) -> Result<Self> {
        check_range("chi", chi, 0.0, 1.0)?;
        // 1 − χ is itself rounded (1 − 0.9 < 0.1 in binary), so allow a few ulps above it:
        // users write Cylinder(0.9, 0.1) and mean the boundary.
        if !(km.is_finite() && km >= 0.0 && km <= 1.0 - chi + 4.0 * f64::EPSILON) {
            let allowed = format!("[0, 1 - chi] = [0, {}]", short(1.0 - chi));
            return Err(Error::invalid("km", km, allowed));
        }
        let (ic, icm) = if chi == 0.0 {
            (km, km)
        } else {
            // 1 − k_m ≥ χ > 0 for valid input; the max() only absorbs the rounding slack
            // allowed above, so the division is always safe.
            let one_minus = (1.0 - km).max(chi);
            inertias(chi, km, one_minus)
        };
        Ok(Self { chi, km, ic, icm })
    }

    /// A body from physical quantities: mass M, radius R, offset d and moment of inertia
    /// I_C about the geometric centre. Valid iff 0 ≤ d ≤ R and M d² ≤ I_C ≤ M R².
    ///
    /// k_m is the smaller root of k_m² − (1 + Ĩ_C) k_m + (Ĩ_C − χ²) = 0 (Ĩ_C = k_m + χ²/(1 − k_m)
    /// solved for k_m), written without cancellation.
    pub fn from_inertia(m: f64, r: f64, d: f64, i_c: f64) -> Result<Self> {
        check_positive("M", m)?;
        check_positive("R", r)?;
        check_range("d", d, 0.0, r)?;
        let chi = (d / r).min(1.0);
        let ic = i_c / (m * r * r);
        let lo = chi * chi;
        // Allow a few ulps of round-off in the bounds, then clamp.
        let slack = 8.0 * f64::EPSILON;
        if !i_c.is_finite() || ic < lo * (1.0 - slack) || ic > 1.0 + slack {
            let allowed = format!(
                "[M d^2, M R^2] = [{}, {}]",
                short(m * d * d),
                short(m * r * r)
            );
            return Err(Error::invalid("I_C", i_c, allowed));
        }
        let ic = ic.clamp(lo, 1.0);
        let disc = ((1.0 - ic) * (1.0 - ic) + 4.0 * lo).max(0.0);
        let km = 2.0 * (ic - lo) / ((1.0 + ic) + disc.sqrt());
        Self::new(chi, km.max(0.0))
    }

    /// The paper's model: a uniform thin shell of mass m_C and radius R plus a line mass
    /// m_P, placed so that the centre of mass is at distance d from the axis.
    pub fn from_shell_and_line(m_c: f64, m_p: f64, r: f64, d: f64) -> Result<Self> {
        check_range("m_C", m_c, 0.0, f64::MAX)?;
        check_range("m_P", m_p, 0.0, f64::MAX)?;
        check_positive("M = m_C + m_P", m_c + m_p)?;
        check_positive("R", r)?;
        let m = m_c + m_p;
        let km = m_c / m;
        // The line sits at distance d/(1 − k_m) from C: it must lie inside the shell.
        // A few ulps of slack absorb the round-off of d = χR computed by the caller.
        let limit = r * (1.0 - km);
        check_range("d", d, 0.0, limit * (1.0 + 8.0 * f64::EPSILON))?;
        Self::new((d / r).min(1.0 - km), km)
    }

    /// γ = (Ĩ_C + 1 + 2χ)/(4πχ), the paper's Eq. (dega2); infinite for χ = 0.
    pub fn gamma(&self) -> f64 {
        if self.chi == 0.0 {
            f64::INFINITY
        } else {
            (self.ic + 1.0 + 2.0 * self.chi) / (4.0 * PI * self.chi)
        }
    }
}

#[cfg(test)]
mod tests {
    use super::*;

    #[test]
    fn inertia_of_the_shell_plus_line_model() {
        // I_C = m_C R² + m_P (d + s)², s = k_m χ R/(1 − k_m): direct from the geometry.
        let (chi, km) = (0.3, 0.4);
        let s = km / (1.0 - km) * chi;
        let direct = km + (1.0 - km) * (chi + s) * (chi + s);
        let b = Cylinder::new(chi, km).unwrap();
        assert!((b.ic - direct).abs() < 1e-15);
        assert!((b.icm - (b.ic - chi * chi)).abs() < 1e-15);
    }

    #[test]
    fn limits_are_finite() {
        let centred = Cylinder::new(0.0, 1.0).unwrap();
        assert_eq!((centred.ic, centred.icm), (1.0, 1.0));
        let point = Cylinder::new(1.0, 0.0).unwrap();
        assert_eq!((point.ic, point.icm), (1.0, 0.0));
        assert!(Cylinder::new(0.0, 0.5).unwrap().gamma().is_infinite());
    }

    #[test]
    fn rejects_out_of_range() {
        assert!(Cylinder::new(1.1, 0.0).is_err());
        assert!(Cylinder::new(0.5, 0.6).is_err());
        assert!(Cylinder::new(f64::NAN, 0.0).is_err());
        assert!(Cylinder::from_inertia(1.0, 1.0, 0.5, 0.2).is_err());
    }

    #[test]
    fn from_inertia_round_trips() {
        for &(chi, km) in &[(0.0, 0.3), (0.15, 0.02), (0.5, 0.4), (0.9, 0.1), (0.3, 0.7)] {
            let b = Cylinder::new(chi, km).unwrap();
            let (m, r) = (2.5, 0.3);
            let c = Cylinder::from_inertia(m, r, chi * r, b.ic * m * r * r).unwrap();
            assert!((c.km - km).abs() < 1e-12, "{chi} {km} {}", c.km);
            let s = Cylinder::from_shell_and_line(km * m, (1.0 - km) * m, r, chi * r).unwrap();
            assert!((s.km - km).abs() < 1e-15 && (s.chi - chi).abs() < 1e-15);
        }
    }

    #[test]
    fn gamma_matches_the_papers_printed_form() {
        let (chi, km): (f64, f64) = (0.5, 0.4);
        let printed = (km * km + 2.0 * km * chi - chi * chi - 2.0 * chi - 1.0)
            / (4.0 * PI * (km - 1.0) * chi);
        assert!((Cylinder::new(chi, km).unwrap().gamma() - printed).abs() < 1e-14);
    }
}

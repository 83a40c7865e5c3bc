//! The landing: a planar rigid-body impact at the contact point P with Coulomb friction,
//! resolved exactly by Routh's method with Stronge's energetic restitution
//! (`docs/impact_law.md` derives and justifies every step).
//!
//! An impulse (P_t, P_n) at P = C − (0, 1) changes the centre-of-mass velocity by (P_t, P_n)
//! and, about the centre of mass, Ĩ_CM Δθ̇ = χ sin θ P_n − (1 + χ cos θ) P_t (Euler of
//! [`crate::mechanics::newton_euler`], integrated over the impact). The contact point's
//! velocity u = (u_t, u_n) = (l̇ − θ̇, ḃ) then changes by Δu = W P with, for a = 1 + χ cos θ,
//! s = χ sin θ, I = Ĩ_CM,
//!
//!   W = [[1 + a²/I, −a s/I], [−a s/I, 1 + s²/I]],   det W = 1 + (a² + s²)/I,
//!
//! symmetric and positive definite for I > 0. Along the normal impulse p, u is piecewise
//! linear (the friction direction changes only where u_t = 0), so every segment of Routh's
//! method is solved in closed form: no time stepping, at most four segments.

use crate::error::{check_finite, check_range, Error, Result};
use crate::mechanics::body::Cylinder;

/// The inverse effective mass W of the contact point (Δu = W P), symmetric positive definite.
///
/// Built only by [`ImpactMatrix::new`], so its invariants (finite, W_tt ≥ 1, det W ≥ 1,
/// computed without cancellation) hold for every value: read it through the accessors.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactMatrix {
    tt: f64,
    tn: f64,
    nn: f64,
    det: f64,
}

impl ImpactMatrix {
    /// W for `body` at the angle with sine `sin_t` and cosine `cos_t`. None for Ĩ_CM = 0
    /// (k_m = 0: a point mass on a massless hoop, W is singular; the impulse must then pass
    /// through the centre of mass and the law below does not apply) and for a Ĩ_CM so small
    /// (subnormal) that W overflows.
    pub fn new(body: &Cylinder, sin_t: f64, cos_t: f64) -> Option<Self> {
        let i = body.icm;
        let (a, s) = (1.0 + body.chi * cos_t, body.chi * sin_t);
        // det W written out: tt·nn − tn² cancels catastrophically when Ĩ_CM is small.
        let w = Self {
            tt: 1.0 + a * a / i,
            tn: -a * s / i,
            nn: 1.0 + s * s / i,
            det: 1.0 + (a * a + s * s) / i,
        };
        (i > 0.0 && [w.tt, w.tn, w.nn, w.det].iter().all(|x| x.is_finite())).then_some(w)
    }

    /// W_tt = 1 + a²/Ĩ_CM ≥ 1.
    pub fn tt(&self) -> f64 {
        self.tt
    }

    /// W_tn = W_nt = −a s/Ĩ_CM.
    pub fn tn(&self) -> f64 {
        self.tn
    }

    /// W_nn = 1 + s²/Ĩ_CM ≥ 1.
    pub fn nn(&self) -> f64 {
        self.nn
    }

    /// det W = W_tt W_nn − W_tn² = 1 + (a² + s²)/Ĩ_CM ≥ 1.
    pub fn det(&self) -> f64 {
        self.det
    }

    /// λ = −W_tn/W_tt: the ratio P_t/P_n that keeps u_t = 0 (sticking needs |λ| ≤ μ_s).
    pub fn stick_ratio(&self) -> f64 {
        -self.tn / self.tt
    }
}

/// Coulomb friction and Stronge's energetic restitution at the contact.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct ImpactLaw {
    /// Static friction coefficient μ_s ≥ 0 (decides sticking when u_t reaches 0).
    pub mu_s: f64,
    /// Kinetic friction coefficient 0 ≤ μ_k ≤ μ_s (while the contact point slides).
    pub mu_k: f64,
    /// Stronge's energetic coefficient e ∈ [0, 1]: e² = −(work of the normal impulse in
    /// restitution)/(its work in compression).
    pub restitution: f64,
}

impl ImpactLaw {
    /// Checks μ_s ≥ 0, 0 ≤ μ_k ≤ μ_s and e ∈ [0, 1] (all finite), naming a bad parameter.
    pub fn validate(&self) -> Result<()> {
        check_range("mu_s", self.mu_s, 0.0, f64::MAX)?;
        check_range("mu_k", self.mu_k, 0.0, self.mu_s)?;
        check_range("restitution", self.restitution, 0.0, 1.0)?;
        Ok(())
    }
}

/// How the contact point ends the impact tangentially.
#[derive(Debug, Clone, Copy, PartialEq, Eq)]
pub enum Ending {
    /// u_t = 0 exactly: the body leaves the impact rolling (if it stays in contact).
    Sticking,
    /// u_t ≠ 0: the contact point still slides.
    Sliding,
}

/// The result of one impact: the impulse, the contact velocity after it and its works (all
/// per M, in units of √(gR) and M g R; the energy it removes is −(normal + friction work)).
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Impulse {
    /// Tangential impulse P_t (along x, down the ramp).
    pub pt: f64,
    /// Normal impulse P_n ≥ 0.
    pub pn: f64,
    /// Slip velocity u_t = l̇ − θ̇ after the impact (exactly 0 when sticking).
    pub ut: f64,
    /// Normal velocity u_n = ḃ after the impact (exactly 0 for e = 0).
    pub un: f64,
    /// How the contact point ends the impact tangentially.
    pub ending: Ending,
    /// ∫ u_n dp over compression, ≤ 0.
    pub compression_work: f64,
    /// ∫ u_n dp over the whole impact, = (1 − e²) × compression_work.
    pub normal_work: f64,
    /// ∫ u_t dP_t over the whole impact, ≤ 0 (friction dissipates).
    pub friction_work: f64,
}

/// What the contact point does along a segment of constant slopes.
#[derive(Debug, Clone, Copy, PartialEq)]
enum Mode {
    /// Sliding with friction dP_t = σ μ_k dp, σ = −sign u_t.
    Slide(f64),
    /// Sticking: u_t stays 0, dP_t = λ dp.
    Stick,
}

/// The mode at u_t = 0: stick if static friction can hold the stick ratio λ, else slide
/// the way λ pushes (σ = sign λ; the only consistent direction when μ_k ≤ μ_s).
fn at_zero_slip(lambda: f64, mu_s: f64) -> Mode {
    if lambda.abs() <= mu_s {
        Mode::Stick
    } else {
        Mode::Slide(lambda.signum())
    }
}

/// Resolves an impact with the contact point arriving at (u_t, u_n) = (`ut0`, `un0`):
/// Routh's method in the normal impulse p with Coulomb friction, until Stronge's energetic
/// restitution ends it. `law` should be validated ([`ImpactLaw::validate`]); μ_k > μ_s is
/// read as μ_s = μ_k. No impact (a zero impulse, velocities unchanged) unless `un0` < 0 and
/// both velocities are finite.
///
/// The problem is homogeneous in the velocities and W enters only through its direction,
/// so both are normalised (|u| ≤ 1, W/k with k = W_tt + W_nn): every intermediate stays of
/// order 1 (times μ) for any finite input, μ up to f64::MAX and any Ĩ_CM > 0.
pub fn resolve(w: &ImpactMatrix, law: &ImpactLaw, ut0: f64, un0: f64) -> Impulse {
    let mut out = Impulse {
        pt: 0.0,
        pn: 0.0,
        ut: ut0,
        un: un0,
        ending: if ut0 == 0.0 {
            Ending::Sticking
        } else {
            Ending::Sliding
        },
        compression_work: 0.0,
        normal_work: 0.0,
        friction_work: 0.0,
    };
    if !(un0 < 0.0 && un0.is_finite() && ut0.is_finite()) {
        return out;
    }
    let v = ut0.abs().max(-un0);
    let k = w.tt + w.nn;
    let (tt, tn, nn) = (w.tt / k, w.tn / k, w.nn / k);
    let stick_slope = (w.det / k) / w.tt; // du_n/dq while sticking: det W/(k W_tt) > 0
    let lambda = w.stick_ratio();
    let (mu_k, mu_s) = (law.mu_k, law.mu_s.max(law.mu_k));
    let e2 = law.restitution * law.restitution;

    // Scaled state: u = v·(ut, un), p = v·q/k, P_t = v·qt/k, works = v²/k·(work).
    let (mut ut, mut un) = (ut0 / v, un0 / v);
    let (mut q, mut qt) = (0.0f64, 0.0f64);
    let (mut compression, mut restitution, mut friction) = (0.0f64, 0.0f64, 0.0f64);
    let mut compressing = true;
    let mut mode = if ut == 0.0 {
        at_zero_slip(lambda, mu_s)
    } else {
        Mode::Slide(-ut.signum())
    };
    // Slide → (stick | reverse slide), each possibly cut once by the end of compression:
    // at most four segments (docs/impact_law.md); the bound only guards a broken invariant.
    for _ in 0..8 {
        // Slopes along q: dq_t/dq = f, du/dq = (gt, gn).
        let (f, gt, gn) = match mode {
            Mode::Slide(sigma) => {
                let f = sigma * mu_k;
                (f, f * tt + tn, f * tn + nn)
            }
            Mode::Stick => (lambda, 0.0, stick_slope),
        };
        // Where the slip velocity reaches 0 (only while sliding towards it).
        let dq_slip = if ut * gt < 0.0 {
            -ut / gt
        } else {
            f64::INFINITY
        };
        // Where the phase ends: u_n = 0 in compression; in restitution, where the normal
        // work since compression reaches −e²·(compression work): un·dq + gn·dq²/2 = rest,
        // solved by the root formula without cancellation (un ≥ 0 there).
        let dq_phase = if compressing {
            if gn > 0.0 {
                -un / gn
            } else {
                f64::INFINITY
            }
        } else {
            let rest = -e2 * compression - restitution;
            let denom = un + (un * un + 2.0 * gn * rest).max(0.0).sqrt();
            if denom > 0.0 {
                2.0 * rest / denom
            } else {
                f64::INFINITY
            }
        };
        // max(0): a rounding can leave u_n a hair above 0 before the phase event.
        let dq = dq_slip.min(dq_phase).max(0.0);
        if !dq.is_finite() {
            break; // unreachable with W positive definite (docs/impact_law.md)
        }
        let normal_work = dq * (un + 0.5 * gn * dq);
        if compressing {
            compression += normal_work;
        } else {
            restitution += normal_work;
        }
        friction += f * dq * (ut + 0.5 * gt * dq);
        q += dq;
        qt += f * dq;
        ut += gt * dq;
        un += gn * dq;
        if dq_phase <= dq_slip {
            if compressing {
                un = 0.0;
                compressing = false;
                if e2 > 0.0 {
                    continue;
                }
            }
            break;
        }
        ut = 0.0;
        mode = at_zero_slip(lambda, mu_s);
    }

    if mode == Mode::Stick {
        ut = 0.0;
        out.ending = Ending::Sticking;
    } else {
        out.ending = Ending::Sliding;
    }
    let work = |x: f64| v * (v * (x / k));
    out.pn = v * (q / k);
    out.pt = v * (qt / k);
    out.ut = v * ut;
    out.un = v * un;
    out.compression_work = work(compression);
    out.normal_work = work(compression + restitution);
    out.friction_work = work(friction);
    out
}

impl Cylinder {
    /// The velocities (θ̇', l̇', ḃ') after an impulse (P_t, P_n) at the contact point, from
    /// (θ̇, l̇, ḃ) at angle θ: Δv_CM = P, Ĩ_CM Δθ̇ = χ sin θ P_n − (1 + χ cos θ) P_t, and
    /// (l̇, ḃ) = v_CM − χθ̇(cos θ, −sin θ). For Ĩ_CM = 0 an impulse with a moment about the
    /// centre of mass gives an infinite spin (no NaN: a zero moment changes nothing).
    #[allow(clippy::too_many_arguments)] // the angle, three velocities and two impulses
    pub fn apply_impulse(
        &self,
        theta: f64,
        omega: f64,
        ldot: f64,
        bdot: f64,
        pt: f64,
        pn: f64,
    ) -> (f64, f64, f64) {
        let (s, c) = crate::trig::sin_cos(theta);
        let (a, s) = (1.0 + self.chi * c, self.chi * s);
        let moment = s * pn - a * pt;
        let d_omega = if moment == 0.0 {
            0.0
        } else {
            moment / self.icm
        };
        // Δl̇ = P_t − χ cos θ Δθ̇, Δḃ = P_n + χ sin θ Δθ̇.
        (
            omega + d_omega,
            ldot + pt - self.chi * c * d_omega,
            bdot + pn + s * d_omega,
        )
    }
}

/// One validated impact of the body at a state: W, the impulse and the velocities after it.
#[derive(Debug, Clone, Copy, PartialEq)]
pub struct Landing {
    /// The inverse effective mass of the contact point.
    pub w: ImpactMatrix,
    /// The impulse, the contact velocity after it and the works.
    pub impulse: Impulse,
    /// θ̇ after the impact.
    pub omega: f64,
    /// l̇ after the impact, = θ̇ + u_t.
    pub ldot: f64,
    /// ḃ after the impact, = u_n.
    pub bdot: f64,
}

/// The impact of `body` at angle θ with velocities (θ̇, l̇, ḃ), after validating every
/// input (an error names the parameter): `law` by [`ImpactLaw::validate`], the state
/// finite, and Ĩ_CM > 0 (k_m > 0; see [`ImpactMatrix::new`]).
pub fn impact(
    body: &Cylinder,
    law: &ImpactLaw,
    theta: f64,
    omega: f64,
    ldot: f64,
    bdot: f64,
) -> Result<Landing> {
    law.validate()?;
    for (name, x) in [
        ("theta", theta),
        ("omega", omega),
        ("ldot", ldot),
        ("bdot", bdot),
    ] {
        check_finite(name, x)?;
    }
    let (s, c) = crate::trig::sin_cos(theta);
    let w = ImpactMatrix::new(body, s, c).ok_or_else(|| {
        Error::invalid("km", body.km, "(0, 1 - chi]: the impact law needs I_CM > 0")
    })?;
    let impulse = resolve(&w, law, ldot - omega, bdot);
    let (omega, _, _) = body.apply_impulse(theta, omega, ldot, bdot, impulse.pt, impulse.pn);
    // (l̇, ḃ) from the contact velocity, so that u_t = 0 (sticking) and u_n = 0 (e = 0) hold
    // exactly after the impact; apply_impulse gives the same to rounding.
    Ok(Landing {
        w,
        impulse,
        omega,
        ldot: omega + impulse.ut,
        bdot: impulse.un,
    })
}

//! Tests of the rolling path's scan through the public API (`eccjump_core::jarm::path`):
//! the reported event angles, the forces against the paper's formulas, a reference slip and
//! a violation thinner than the grid step.

use eccjump_core::jarm::path::{
    ContactEvent, RollingPath, Watch, G_FY, G_MMINUS, G_MPLUS, G_NOLIFT,
};
use eccjump_core::{Cylinder, Ramp};
use std::f64::consts::{FRAC_PI_2, TAU};

fn ramp(chi: f64, km: f64, alpha_deg: f64) -> Ramp {
    Ramp::new(Cylinder::new(chi, km).unwrap(), alpha_deg.to_radians()).unwrap()
}

/// xorshift64*: a uniform in [0, 1) (reproducible test points).
fn uniform(s: &mut u64) -> f64 {
    *s ^= *s >> 12;
    *s ^= *s << 25;
    *s ^= *s >> 27;
    (s.wrapping_mul(0x2545_f491_4f6c_dd1d) >> 11) as f64 / (1u64 << 53) as f64
}

#[test]
fn event_angles_are_the_roots_of_their_constraints_to_the_last_bits() {
    // The crossings are found by Newton on the analytic slope; bisection on the sign of
    // the violated constraint (to the last bit) is the independent route. The two must
    // agree to within the root's conditioning: a few ulp, plus the noise of g over its
    // slope.
    use eccjump_core::ode::roots::bisect;
    let mut s = 20_261_125u64;
    let (mut checked, mut close) = (0, 0);
    for i in 0..2000 {
        let chi = 0.001 + 0.998 * uniform(&mut s);
        let km = uniform(&mut s) * (1.0 - chi);
        let alpha = FRAC_PI_2 * uniform(&mut s);
        let r = Ramp::new(Cylinder::new(chi, km).unwrap(), alpha).unwrap();
        let (th0, w0) = if i % 2 == 0 {
            (0.0, 0.0)
        } else {
            (4.0 * uniform(&mut s) - 2.0, uniform(&mut s))
        };
        let p = RollingPath::new(&r, th0, w0, 0.2 + 1.5 * uniform(&mut s));
        let sc = p.scan(th0 + 8.0 * TAU, Watch::ALL);
        let k = match sc.event {
            ContactEvent::Liftoff => G_NOLIFT,
            ContactEvent::NormalForce => G_FY,
            ContactEvent::Slip if sc.at.fx > 0.0 => G_MPLUS,
            ContactEvent::Slip => G_MMINUS,
            _ => continue,
        };
        let x = sc.at.theta;
        if x <= th0 + 1e-6 {
            continue; // at the start: no crossing
        }
        let g = |t: f64| p.eval(t).g[k];
        let (lo, hi) = (x - 1e-7 * (1.0 + x), x + 1e-7 * (1.0 + x));
        let (glo, ghi) = (g(lo), g(hi));
        if !(glo > 0.0 && ghi < 0.0) {
            continue; // a tangential or multiple root: no sign change to bisect
        }
        let b = bisect(g, lo, hi, glo, ghi).unwrap().x;
        let q = p.eval(x);
        let noise = 1e-15 * (1.0 + q.g[k].abs() + q.fy.abs() + q.fx.abs() + q.lift.abs());
        let tol = 8.0 * f64::EPSILON * x.abs() + noise / q.dg[k].abs();
        assert!(
            (x - b).abs() <= tol,
            "{x} vs bisection {b}: chi {chi} km {km} alpha {alpha} th0 {th0} w0 {w0} k {k}"
        );
        if (x - b).abs() <= 4.0 * f64::EPSILON * x.abs() {
            close += 1;
        }
        checked += 1;
    }
    assert!(checked > 1000, "{checked} crossings checked");
    // Most roots are well conditioned: there the two routes agree to 4 ε|θ| (Newton
    // extrapolates through the rounding noise of g, bisection follows its sign, so where
    // the noise over the slope exceeds a few ulp they differ within that bound).
    assert!(close as f64 > 0.85 * checked as f64, "{close} of {checked}");
}

/// The paper's FxL2 and FyL2, typed exactly as printed (g = M = 1).
fn fx_l2(alpha: f64, chi: f64, gamma: f64, th: f64) -> f64 {
    use std::f64::consts::PI;
    let (sa, ca) = eccjump_core::trig::sin_cos(alpha);
    let pg = PI * gamma;
    -1.0 / (4.0 * chi * (2.0 * pg + th.cos() - 1.0).powi(2))
        * (sa
            * (16.0 * PI * PI * gamma * gamma * chi - 16.0 * pg * chi - 4.0 * pg - chi * chi
                + 3.0 * chi
                + 2.0
                + 2.0 * pg * chi * chi
                + 2.0 * (-1.0 + (-3.0 + 6.0 * pg) * chi) * th.cos()
                + chi * (2.0 * th).cos()
                - 2.0 * th * th.sin()
                - 4.0 * th * chi * th.sin()
                + 8.0 * pg * th * chi * th.sin()
                + th * chi * (2.0 * th).sin())
            + chi
                * (2.0 * ca * (-1.0 - 2.0 * chi + 4.0 * pg * chi + chi * th.cos()) * th.sin()
                    - (-2.0 + 4.0 * pg + chi) * (alpha + th).sin()
                    - chi
                        * ((-3.0 + 6.0 * pg) * (alpha + 2.0 * th).sin()
                            + (alpha + 3.0 * th).sin())))
}

fn fy_l2(alpha: f64, chi: f64, gamma: f64, th: f64) -> f64 {
    use std::f64::consts::PI;
    let (sa, ca) = eccjump_core::trig::sin_cos(alpha);
    let pg = PI * gamma;
    1.0 / (4.0 * (2.0 * pg + th.cos() - 1.0).powi(2))
        * (ca
            * (6.0 - 16.0 * pg + 16.0 * PI * PI * gamma * gamma - 4.0 * chi
                + 2.0 * pg * chi
                + (-8.0 - 8.0 * pg * (-2.0 + chi) + 7.0 * chi) * th.cos()
                + (2.0 - 4.0 * chi + 6.0 * pg * chi) * (2.0 * th).cos()
                + chi * (3.0 * th).cos())
            - sa * (3.0 * th + 4.0 * (-1.0 + 2.0 * pg) * th * th.cos() + th * (2.0 * th).cos()
                - 2.0 * th.sin()
                + 4.0 * pg * th.sin()
                + 3.0 * chi * th.sin()
                + (2.0 * th).sin()
                - 3.0 * chi * (2.0 * th).sin()
                + 6.0 * pg * chi * (2.0 * th).sin()
                + chi * (3.0 * th).sin()))
}

#[test]
fn forces_match_the_papers_fxl2_fyl2() {
    for &(chi, km, a) in &[
        (0.15, 0.02, 40.0),
        (0.5, 0.4, 30.0),
        (0.8, 0.1, 12.0),
        (0.05, 0.9, 80.0),
    ] {
        let r = ramp(chi, km, a);
        let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
        let gamma = r.body.gamma();
        for i in 1..200 {
            let th = 0.05 * i as f64;
            let q = p.eval(th);
            let (fx, fy) = (
                fx_l2(r.alpha, chi, gamma, th),
                fy_l2(r.alpha, chi, gamma, th),
            );
            assert!(
                (q.fx - fx).abs() < 1e-10 * (1.0 + fx.abs()),
                "{chi} {th}: {} {fx}",
                q.fx
            );
            assert!(
                (q.fy - fy).abs() < 1e-10 * (1.0 + fy.abs()),
                "{chi} {th}: {} {fy}",
                q.fy
            );
        }
    }
}

#[test]
fn reference_slip_near_316_degrees() {
    let r = ramp(0.5, 0.4, 30.0);
    let p = RollingPath::new(&r, 0.0, 0.0, 1.0);
    let s = p.scan(2.0 * TAU, Watch::ALL);
    assert_eq!(s.event, ContactEvent::Slip);
    assert!(
        (s.at.theta.to_degrees() - 316.47).abs() < 0.01,
        "{}",
        s.at.theta.to_degrees()
    );
    assert!((s.at.ratio() - 1.0).abs() < 1e-9);
}

#[test]
fn thin_violation_between_samples_is_found() {
    // Choose μ_s just below the interior maximum of the friction ratio on the path, so
    // that the margin dips below 0 on a sliver much thinner than the grid step.
    let r = ramp(0.3, 0.1, 20.0);
    let big = RollingPath::new(&r, 0.0, 0.0, 1e6);
    let w = Watch {
        normal_force: true,
        friction: false,
        ..Watch::ALL
    };
    let s = big.scan(4.0 * TAU, w);
    // Find an interior local maximum of the ratio well before the event.
    let (mut best, mut th_best) = (0.0, 0.0);
    let n = 200_000;
    for i in 1..n {
        let th = 0.8 * s.at.theta * i as f64 / n as f64;
        let q = big.eval(th);
        if q.ratio() > best {
            best = q.ratio();
            th_best = th;
        }
    }
    assert!(th_best > 0.1 && th_best < 0.79 * s.at.theta, "{th_best}");
    let mu = best * (1.0 - 1e-9);
    let p = RollingPath::new(&r, 0.0, 0.0, mu);
    let sc = p.scan(4.0 * TAU, Watch::ALL);
    assert_eq!(sc.event, ContactEvent::Slip);
    assert!(
        (sc.at.theta - th_best).abs() < 1e-3,
        "{} {th_best}",
        sc.at.theta
    );
    // The violation is thinner than the grid step by orders of magnitude.
    let width = {
        let (mut lo, mut hi) = (th_best, th_best);
        while p.eval(lo).g[G_MPLUS].min(p.eval(lo).g[G_MMINUS]) < 0.0 {
            lo -= 1e-7;
        }
        while p.eval(hi).g[G_MPLUS].min(p.eval(hi).g[G_MMINUS]) < 0.0 {
            hi += 1e-7;
        }
        hi - lo
    };
    assert!(width < 1e-3, "{width}");
}

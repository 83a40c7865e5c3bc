//! The paper's Section 3: does the cylinder jump straight out of pure rolling (a JARM), and
//! if not, why. Two independent routes share one decision tree ([`decision`]), one catalogue
//! of contact events ([`crate::modes::rolling::events`]) and one check of the start:
//!
//! - [`jump_point`]: Sec. 3.1, forces and friction at a jump point (any start);
//! - [`from_rest`]: Sec. 3.2, J(θ), its brackets and θ_{n,J} for the start from rest;
//! - [`path`]: the rigorous scan of the contact conditions along rolling (closed form);
//! - [`mod@classify`]: the closed-form route (path scan + jump-point formulas);
//! - [`ode_route`]: the route by integration of the rolling equation with events;
//! - [`turns`]: the turn of an angle and the search bound n*;
//! - [`derivatives`]: exact derivatives of θ_J and the jump forces in (α, χ, k_m);
//! - [`result`]: reasons, options and the per-point result.

pub mod classify;
pub mod decision;
pub mod derivatives;
pub mod from_rest;
pub mod jump_point;
pub mod ode_route;
pub mod path;
pub mod result;
pub mod turns;

pub use crate::mechanics::Rule;
pub use classify::classify;
pub use ode_route::classify_ode;
pub use result::{JarmOptions, JarmResult, Method, Reason};

/// Classifies one point by the chosen route (never panics; invalid points give
/// `InvalidParams`).
///
/// The motion is 2π-periodic in θ0, but both routes number the turn windows from turn 1
/// (θ ≥ 0, with the lift-off windows 2πn − α < θ < 2πn): from θ0 < 0 the windows of turns
/// ≤ 0 were never searched, and a lift-off in (−α, 0) went uncounted. So a start below 0 is
/// classified from θ0 + 2πk ∈ [0, 2π) and its angles are shifted back by 2πk; its turns (the
/// requested n and the reported one) count in that frame.
#[inline]
pub fn classify_with(
    method: Method,
    alpha: f64,
    chi: f64,
    km: f64,
    mu_s: f64,
    opts: &JarmOptions,
) -> JarmResult {
    let (o, shift) = in_first_turn(opts);
    let r = match method {
        Method::ClosedForm => classify(alpha, chi, km, mu_s, &o),
        Method::Ode { rtol, atol, pair } => {
            classify_ode(alpha, chi, km, mu_s, &o, (rtol, atol), pair)
        }
    };
    shifted_back(r, shift)
}

/// [`classify_with`] of many points, `point(i)` = (α, χ, k_m, μ_s, options) for each
/// `out[i]`: the same results bit for bit, the ODE route integrating its points side by side
/// ([`ode_route::classify_ode_batch`]). `stop` as there; the closed form asks it before each
/// point (points take microseconds, but a few take milliseconds).
pub fn classify_many(
    method: Method,
    point: impl Fn(usize) -> (f64, f64, f64, f64, JarmOptions),
    out: &mut [JarmResult],
    stop: &dyn Fn() -> bool,
) {
    match method {
        Method::ClosedForm => {
            for (i, o) in out.iter_mut().enumerate() {
                if stop() {
                    return;
                }
                let (alpha, chi, km, mu_s, opts) = point(i);
                *o = classify_with(method, alpha, chi, km, mu_s, &opts);
            }
        }
        Method::Ode { rtol, atol, pair } => {
            let shifted = |i: usize| {
                let (alpha, chi, km, mu_s, opts) = point(i);
                (alpha, chi, km, mu_s, in_first_turn(&opts).0)
            };
            ode_route::classify_ode_batch(shifted, (rtol, atol), pair, out, stop);
            for (i, o) in out.iter_mut().enumerate() {
                *o = shifted_back(*o, in_first_turn(&point(i).4).1);
            }
        }
    }
}

/// The options with θ0 moved into [0, 2π) by 2πk, and the shift 2πk (see
/// [`classify_with`]).
#[inline]
fn in_first_turn(opts: &JarmOptions) -> (JarmOptions, f64) {
    let k = if opts.theta0 < 0.0 {
        (-opts.theta0 / std::f64::consts::TAU).ceil()
    } else {
        0.0
    };
    let shift = k * std::f64::consts::TAU;
    let o = JarmOptions {
        theta0: opts.theta0 + shift,
        ..*opts
    };
    (o, shift)
}

/// A result's angles moved back by `shift` into the frame of the original θ0.
#[inline]
fn shifted_back(mut r: JarmResult, shift: f64) -> JarmResult {
    if shift != 0.0 {
        for theta in [
            &mut r.theta_j,
            &mut r.theta_event,
            &mut r.theta_max_ratio,
            &mut r.theta_min_fy,
        ] {
            *theta -= shift;
        }
    }
    r
}

#[cfg(test)]
mod tests {
    use super::*;
    use std::f64::consts::{PI, TAU};

    #[test]
    fn many_closed_form_points_stop_between_points_when_asked() {
        let point = |i: usize| (0.3 + 0.01 * i as f64, 0.4, 0.2, 1.0, JarmOptions::default());
        let asked = std::cell::Cell::new(0);
        let stop = || {
            asked.set(asked.get() + 1);
            asked.get() > 3
        };
        let blank = JarmResult::new(Reason::SolverFailed);
        let mut out = vec![blank; 10];
        classify_many(Method::ClosedForm, point, &mut out, &stop);
        let bits = |r: &JarmResult| r.as_f64s().map(f64::to_bits);
        let (a, c, k, m, o) = point(2);
        assert_eq!(
            bits(&out[2]),
            bits(&classify_with(Method::ClosedForm, a, c, k, m, &o))
        );
        assert!(out[3..].iter().all(|r| bits(r) == bits(&blank)));
    }

    #[test]
    fn many_points_are_each_point_by_itself() {
        // Both routes, starts below 0 (shifted into the first turn and back) and above.
        let point = |i: usize| {
            let x = i as f64;
            let o = JarmOptions {
                theta0: [0.0, -2.5, 7.0, -13.0][i % 4],
                omega0: [0.0, 0.4][i % 2],
                ..JarmOptions::default()
            };
            let chi = 0.05 + (x * 0.37).fract() * 0.9;
            (
                0.2 + (x * 0.61).fract() * 1.2,
                chi,
                (x * 0.13).fract() * (1.0 - chi),
                0.8,
                o,
            )
        };
        let methods = [
            Method::ClosedForm,
            Method::Ode {
                rtol: 1e-10,
                atol: 1e-12,
                pair: crate::ode::Integrator::Dop853,
            },
        ];
        for method in methods {
            let mut out = vec![JarmResult::new(Reason::NoRoot); 40];
            classify_many(method, point, &mut out, &|| false);
            for (i, r) in out.iter().enumerate() {
                let (a, c, k, m, o) = point(i);
                let one = classify_with(method, a, c, k, m, &o);
                assert_eq!(
                    r.as_f64s().map(f64::to_bits),
                    one.as_f64s().map(f64::to_bits)
                );
            }
        }
    }

    #[test]
    fn the_classification_is_periodic_in_theta0() {
        // From θ0 = −π and +π (the same orientation) every verdict is the same and the angles
        // differ by 2π; before the fix 1002 of 8000 such points lost their JARM (a lift-off in
        // the green window (−α, 0) of turn 0).
        let o = |theta0| JarmOptions {
            theta0,
            omega0: 1.0,
            ..JarmOptions::default()
        };
        let mut jarms = 0;
        for method in [
            Method::ClosedForm,
            Method::Ode {
                rtol: 1e-10,
                atol: 1e-12,
                pair: crate::ode::Integrator::Rk45,
            },
        ] {
            for i in 0..12 {
                for j in 0..12 {
                    let (a, chi) = (0.05 + 0.12 * i as f64, 0.05 + 0.075 * j as f64);
                    let km = 0.3 * (1.0 - chi);
                    let neg = classify_with(method, a, chi, km, 1.0, &o(-PI));
                    let pos = classify_with(method, a, chi, km, 1.0, &o(PI));
                    assert_eq!(neg.reason, pos.reason, "alpha {a} chi {chi}");
                    assert_eq!(neg.n, pos.n);
                    for (x, y) in [
                        (neg.theta_j, pos.theta_j),
                        (neg.theta_event, pos.theta_event),
                    ] {
                        assert!(
                            x.is_nan() && y.is_nan() || (x + TAU - y).abs() < 1e-9,
                            "{x} {y}"
                        );
                    }
                    jarms += usize::from(pos.is_jarm);
                }
            }
        }
        assert!(
            jarms > 10,
            "{jarms} JARM points: the test would not see the defect"
        );
    }

    /// `stop_at_slip` changes exactly the paper rule's slips, to `Slip`, and nothing else: the
    /// same bits in every other field and at every other point, for both routes, both
    /// rules, the first jump and an explicit turn, from rest and from a moving start.
    #[test]
    fn stopping_at_a_slip_changes_only_the_label_of_a_slip() {
        let ode = Method::Ode {
            rtol: 1e-10,
            atol: 1e-12,
            pair: crate::ode::Integrator::Dop853,
        };
        let mut slips = [0usize; 2];
        for (m, method) in [Method::ClosedForm, ode].into_iter().enumerate() {
            for rule in [Rule::Paper, Rule::NormalForce] {
                for (n, theta0, omega0) in [(0, 0.0, 0.0), (2, 0.0, 0.0), (0, -1.0, 0.7)] {
                    let full = JarmOptions {
                        rule,
                        n,
                        theta0,
                        omega0,
                        ..JarmOptions::default()
                    };
                    let stop = JarmOptions {
                        stop_at_slip: true,
                        ..full
                    };
                    for i in 0..10 {
                        for j in 0..8 {
                            let (a, chi) = (0.1 + 0.145 * i as f64, 0.06 + 0.11 * j as f64);
                            let km = (1.0 - chi) * ((i + j) % 5) as f64 / 5.0;
                            let mu_s = [0.3, 1.0, 2.0][(i + 2 * j) % 3];
                            let f = classify_with(method, a, chi, km, mu_s, &full);
                            let s = classify_with(method, a, chi, km, mu_s, &stop);
                            let slip = matches!(f.reason, Reason::SlipBefore | Reason::SlipAtJump);
                            if rule == Rule::Paper && slip {
                                slips[m] += 1;
                                assert_eq!(s.reason, Reason::Slip, "{a} {chi} {km} {mu_s}");
                                let relabelled = JarmResult {
                                    reason: f.reason,
                                    theta_j: f.theta_j,
                                    ..s
                                };
                                assert!(bits_eq(&relabelled, &f), "{f:?} {s:?}");
                                assert!(s.theta_j.is_nan());
                            } else {
                                assert!(bits_eq(&s, &f), "{rule:?} {a} {chi}: {f:?} {s:?}");
                            }
                        }
                    }
                }
            }
        }
        assert!(slips.iter().all(|&s| s > 100), "{slips:?}");
    }

    fn bits_eq(x: &JarmResult, y: &JarmResult) -> bool {
        x.as_f64s().map(f64::to_bits) == y.as_f64s().map(f64::to_bits)
    }
}

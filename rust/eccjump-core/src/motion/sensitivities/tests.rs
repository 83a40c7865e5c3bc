//! The sensitivities against central differences of `simulate` itself at tight tolerances
//! (the Python tests check them against the independent model of `tests/`).

use super::*;
use crate::modes::contact::ContactLaw;
use crate::motion::simulate::simulate;
use crate::ode::SolverOptions;

/// A case: (χ, k_m, α [deg], μ_s, μ_k, e, θ0, θ̇0, t_max).
type Case = (f64, f64, f64, f64, f64, f64, f64, f64, f64);

fn setup(c: Case, p: [f64; P]) -> (Ramp, SimOptions) {
    let r = Ramp::new(Cylinder::new(p[1], p[2]).unwrap(), p[0]).unwrap();
    let o = SimOptions {
        law: ContactLaw {
            mu_s: p[3],
            mu_k: p[4],
            rule: crate::mechanics::Rule::Paper,
        },
        restitution: p[5],
        theta0: p[6],
        omega0: p[7],
        t_max: c.8,
        solver: SolverOptions {
            rtol: 1e-13,
            atol: 1e-14,
            ..SolverOptions::default()
        },
        ..SimOptions::default()
    };
    (r, o)
}

fn params(c: Case) -> [f64; P] {
    [c.2.to_radians(), c.0, c.1, c.3, c.4, c.5, c.6, c.7]
}

/// The transitions' (t, θ) and their modes.
fn transitions(c: Case, p: [f64; P]) -> Vec<(f64, f64, Mode)> {
    let (r, o) = setup(c, p);
    let run = simulate(&r, &o).unwrap();
    run.transitions
        .iter()
        .map(|t| (t.t, t.state.theta, t.to))
        .collect()
}

/// Checks every differentiable transition's derivatives against central differences
/// (step h), to `tol` relative to 1 + |derivative|; returns how many were compared.
fn check(c: Case, h: f64, tol: f64) -> usize {
    let p = params(c);
    let (r, o) = setup(c, p);
    let run = simulate(&r, &o).unwrap();
    let sens = sensitivities(&r, &o, &run, &|| false).unwrap();
    let base = transitions(c, p);
    let mut compared = 0;
    for k in 0..P {
        let (mut up, mut down) = (p, p);
        up[k] += h;
        down[k] -= h;
        let (tu, td) = (transitions(c, up), transitions(c, down));
        for (i, b) in base.iter().enumerate() {
            let (Some(u), Some(d)) = (tu.get(i), td.get(i)) else {
                break;
            };
            if sens.singular[i] || u.2 != b.2 || d.2 != b.2 {
                break;
            }
            for (q, (fu, fd)) in [(u.0, d.0), (u.1, d.1)].into_iter().enumerate() {
                let diff = (fu - fd) / (2.0 * h);
                let exact = sens.transitions[i][q][k];
                assert!(
                    (exact - diff).abs() <= tol * (1.0 + diff.abs()),
                    "{c:?} transition {i} ({:?}) d{}/d{}: {exact} vs {diff}",
                    b.2,
                    ["t", "theta"][q],
                    PARAMETERS[k]
                );
                compared += 1;
            }
        }
    }
    compared
}

#[test]
fn roll_lift_off_flight_and_landings_against_central_differences() {
    // The paper's body: rolls, jumps, lands and bounces; a fast spin on a gentle ramp.
    // 20 transitions: stick, slip, normal force, bounces down to a settle.
    let n = check(
        (0.15, 0.02, 40.0, 1.0, 0.9, 0.1, 0.0, 0.0, 12.0),
        1e-6,
        1e-5,
    );
    assert!(n >= 270, "{n}");
    let n = check((0.5, 0.2, 20.0, 1.0, 0.8, 0.5, 0.0, 2.0, 12.0), 1e-6, 1e-5);
    assert!(n >= 240, "{n}");
}

#[test]
fn slips_against_central_differences() {
    // Little friction: slip from rest, then a jump.
    let n = check((0.3, 0.2, 30.0, 0.2, 0.15, 0.2, 0.5, 0.0, 12.0), 1e-6, 1e-5);
    assert!(n >= 220, "{n}");
}

#[test]
fn what_follows_a_slip_through_the_normal_impulse_is_flagged_and_nan() {
    // A bounce settles into a slip whose F_y rises above F_SWITCH: it goes on in the normal
    // impulse, where the sensitivities do not follow (module notes).
    let p: [f64; P] = [
        0.97549785, 0.81050848, 0.08156572, 1.22005392, 1.09488566, 0.07081708, 5.19246307,
        3.31312160,
    ];
    let c = (
        p[1],
        p[2],
        p[0].to_degrees(),
        p[3],
        p[4],
        p[5],
        p[6],
        p[7],
        10.0,
    );
    let (r, o) = setup(c, p);
    let run = simulate(&r, &o).unwrap();
    let s = sensitivities(&r, &o, &run, &|| false).unwrap();
    let first = s.singular.iter().position(|&x| x).unwrap();
    assert_eq!(run.segments[first - 1].crossing, Some(Crossing::Impulse));
    assert!(s.singular[first..].iter().all(|&x| x));
    assert!(s.transitions[first..]
        .iter()
        .flatten()
        .flatten()
        .all(|v| v.is_nan()));
    assert!(s.transitions[..first]
        .iter()
        .flatten()
        .flatten()
        .all(|v| v.is_finite()));
    assert_eq!(s.transitions[0], {
        let mut d = [[0.0; P]; 2];
        d[1][6] = 1.0;
        d
    });
}

#[test]
fn a_slow_landing_keeps_its_derivatives() {
    // The paper's body bounces until the Zeno rule settles it: the last landings approach
    // at ~1e-6, on branches narrower than the first difference step (module notes).
    let c = (0.15, 0.02, 40.0, 1.0, 0.9, 0.1, 0.0, 0.0, 12.0);
    let (r, o) = setup(c, params(c));
    let run = simulate(&r, &o).unwrap();
    let s = sensitivities(&r, &o, &run, &|| false).unwrap();
    let settle = crate::modes::contact::TransitionReason::Settle;
    assert!(run.transitions.iter().any(|t| t.reason == settle));
    assert!(s.singular.iter().all(|&x| !x));
}

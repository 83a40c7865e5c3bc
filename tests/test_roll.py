"""Pure rolling through the Rust RK45 core, checked against independent routes."""

import math
from fractions import Fraction
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference_points import JARM, JARM_ALPHA_DEG, JARM_BODY, ROLLS, SLIP_FIRST
from scipy.integrate import solve_ivp
from scipy.optimize import brentq

from eccjump import Cylinder, Units, roll
from eccjump.testing import strategies


def rolling_rhs(alpha, chi, ic):
    """The rolling equation, written again here from the Lagrangian of the rolling body."""

    def f(_t, y):
        th, w = y
        a = ic + 1 + 2 * chi * math.cos(th)
        return [w, (chi * w * w * math.sin(th) + chi * math.sin(alpha + th) + math.sin(alpha)) / a]

    return f


def rolling_rhs_as_in_the_core(alpha, chi, ic):
    """The same equation with the core's exact floating-point operations: step sizes depend on
    an error estimate that cancels ~7 digits, so step-for-step comparisons need identical
    rounding of the right-hand side."""
    sa, ca = math.sin(alpha), math.cos(alpha)

    def f(_t, y):
        th, w = y
        s, c = math.sin(th), math.cos(th)
        return [w, (chi * w * w * s + chi * (sa * c + ca * s) + sa) / (ic + 1.0 + 2.0 * chi * c)]

    return f


def energy(alpha, chi, ic, th, w):
    height = -(th + chi * np.sin(th)) * math.sin(alpha) + chi * np.cos(th) * math.cos(alpha)
    return 0.5 * (ic + 1 + 2 * chi * np.cos(th)) * w**2 + height


def setups():
    starts = strategies.starts(min_theta0=-math.pi, max_theta0=math.pi, max_omega0=2.0)
    return st.tuples(strategies.bodies(max_chi=0.95), strategies.ramps(), starts).map(
        lambda s: (s[0], s[1], s[2].theta0, s[2].omega0)
    )


@settings(max_examples=60, deadline=None)
@given(setups())
def test_energy_is_conserved(s):
    body, alpha, theta0, omega0 = s
    r = roll(body, alpha, theta0=theta0, omega0=omega0, t_max=20.0, theta_max=theta0 + 30)
    assert r.success, r.message
    e = energy(alpha, body.chi, body.Ic, r.theta, r.omega)
    assert np.max(np.abs(e - e[0])) < 1e-7 * max(1.0, np.max(np.abs(r.omega)) ** 2)


@settings(max_examples=40, deadline=None)
@given(setups())
def test_agrees_with_scipy_dop853(s):
    body, alpha, theta0, omega0 = s
    r = roll(body, alpha, theta0=theta0, omega0=omega0, t_max=10.0, theta_max=theta0 + 20)
    ref = solve_ivp(
        rolling_rhs(alpha, body.chi, body.Ic),
        (0, r.t[-1]),
        [theta0, omega0],
        method="DOP853",
        rtol=1e-12,
        atol=1e-12,
        dense_output=True,
    )
    th, w = ref.sol(r.t)
    # Both are accurate to ~1e-10 locally; near chi = 1, km = 0 the contact inertia almost
    # vanishes at theta = pi and the motion amplifies local errors over many turns.
    scale = (1 + np.max(np.abs(th))) / (body.Ic + 1 - 2 * body.chi)
    assert np.max(np.abs(th - r.theta)) < 1e-8 * scale
    assert np.max(np.abs(w - r.omega)) < 1e-8 * scale


def test_scale_invariance_against_an_si_integration():
    # Integrate the dimensional equation in SI for a real body (R = 0.3 m, g = 9.81) with
    # scipy, and compare with the dimensionless run converted by to_si.
    g, R, M = 9.81, 0.3, 2.0
    body = Cylinder(0.4, 0.3)
    alpha = math.radians(25)
    r = roll(body, alpha, theta_max=4.0).to_si(g=g, R=R, M=M)
    d, ic = body.chi * R, body.Ic * M * R * R

    # theta'' (I_C + M R^2 + 2 M R d cos) = M R d w^2 sin + M g (d sin(a+th) + R sin a)
    def f2(_t, y):
        th, w = y
        den = ic + M * R * R + 2 * M * R * d * math.cos(th)
        num = M * R * d * w * w * math.sin(th) + M * g * (
            d * math.sin(alpha + th) + R * math.sin(alpha)
        )
        return [w, num / den]

    ref = solve_ivp(
        f2, (0, r.t[-1]), [0, 0], method="DOP853", rtol=1e-12, atol=1e-12, dense_output=True
    )
    th, w = ref.sol(r.t)
    assert np.allclose(th, r.theta, atol=1e-8)
    assert np.allclose(w, r.omega, atol=1e-8 * math.sqrt(g / R))
    # Forces scale with M g: Fy at the start is M g cos(alpha).
    assert r.Fy[0] == pytest.approx(M * g * math.cos(alpha), rel=1e-12)
    assert r.units == Units(g, R, M)


def J(theta, alpha, chi, km):
    """The paper's Eq. (Jta), typed in independently of the package."""
    gamma = (km**2 + 2 * km * chi - chi**2 - 2 * chi - 1) / (4 * math.pi * (km - 1) * chi)
    num = chi * math.cos(alpha) - chi * math.cos(alpha + theta) + theta * math.sin(alpha)
    return -1 + num * math.cos(theta) / (
        (2 * math.pi * gamma + math.cos(theta) - 1) * math.cos(alpha)
    )


@pytest.mark.parametrize(
    ("alpha_deg", "chi", "km"),
    [(JARM_ALPHA_DEG, *JARM_BODY), (60, 0.1, 0.5), (75, 0.05, 0.01), (20, 0.1, 0.1)],
)
def test_liftoff_from_rest_is_the_first_root_of_J(alpha_deg, chi, km):
    # Points where the paper's lift-off comes first (elsewhere F_y = 0 is met earlier).
    alpha = math.radians(alpha_deg)
    r = roll(Cylinder(chi, km), alpha)
    assert r.terminal_event == "liftoff", r.message
    th_j = r.event("liftoff").theta
    # The first rising zero of J: scan J on a fine grid up to just past the event, bracket.
    grid = np.linspace(1e-9, th_j + 0.05, 20001)
    vals = np.array([J(t, alpha, chi, km) for t in grid])
    k = int(np.argmax((vals[:-1] < 0) & (vals[1:] >= 0)))
    root = brentq(J, grid[k], grid[k + 1], args=(alpha, chi, km), xtol=1e-15, rtol=1e-15)
    assert th_j == pytest.approx(root, abs=1e-9)


def test_reference_point_of_the_physics_notes():
    r = roll(*JARM, mu_s=1.0)
    assert r.terminal_event == "liftoff"
    assert math.degrees(r.theta[-1]) == pytest.approx(334.344, abs=1e-3)
    assert r.Fy[-1] == pytest.approx(0.01543, abs=1e-5)
    assert r.Fx[-1] == pytest.approx(-0.00516, abs=1e-5)
    assert r.event("slip") is None


def test_slips_first_at_the_second_reference_point():
    r = roll(*SLIP_FIRST, mu_s=1.0)
    assert r.terminal_event == "slip"
    assert math.degrees(r.theta[-1]) == pytest.approx(316.47, abs=0.01)
    assert abs(r.Fx[-1]) == pytest.approx(r.Fy[-1], rel=1e-8)


@settings(max_examples=30, deadline=None)
@given(setups())
def test_forces_satisfy_newton_euler_recomputed_from_the_trajectory(s):
    body, alpha, theta0, omega0 = s
    r = roll(
        body,
        alpha,
        theta0=theta0,
        omega0=omega0,
        t_max=5.0,
        theta_max=theta0 + 10,
        dense_output=True,
    )
    if len(r.t) < 3 or r.t[-1] < 0.1:  # below, the differences' rounding eps/h^2 passes 2e-4
        return
    chi = body.chi
    # Centre of mass: x = l + chi sin(theta), y = 1 + chi cos(theta), l = theta - theta0.
    ts = np.linspace(r.t[0], r.t[-1], 7)[1:-1]
    h = 1e-4 * max(1e-3, r.t[-1])
    ts = ts[(ts - 2 * h > r.t[0]) & (ts + 2 * h < r.t[-1])]
    for t in ts:
        pts = np.array([r.sol(t + k * h)[0] for k in (-2, -1, 0, 1, 2)])
        x = pts - theta0 + chi * np.sin(pts)
        y = 1 + chi * np.cos(pts)
        d2 = np.array([-1, 16, -30, 16, -1]) / (12 * h * h)
        ax, ay = d2 @ x, d2 @ y
        th, w = r.sol(t)
        fx_ne = ax - math.sin(alpha)  # F = M (a_cm - g), g = (sin a, -cos a)
        fy_ne = ay + math.cos(alpha)
        # The package's forces at the same state, by the interpolated state:
        k = body.Ic + 1 + 2 * chi * math.cos(th)
        acc = (chi * w * w * math.sin(th) + chi * math.sin(alpha + th) + math.sin(alpha)) / k
        fx = -math.sin(alpha) - chi * w * w * math.sin(th) + (1 + chi * math.cos(th)) * acc
        fy = math.cos(alpha) - chi * w * w * math.cos(th) - chi * acc * math.sin(th)
        assert fx_ne == pytest.approx(fx, abs=2e-4)
        assert fy_ne == pytest.approx(fy, abs=2e-4)
        # Torque about the CM: Icm theta'' = chi sin(th) Fy - (1 + chi cos th) Fx.
        assert body.Icm * acc == pytest.approx(
            chi * math.sin(th) * fy - (1 + chi * math.cos(th)) * fx, abs=1e-12
        )
    # The arrays returned are the same formulas at the step points.
    i = len(r.t) // 2
    th, w = r.theta[i], r.omega[i]
    k = body.Ic + 1 + 2 * chi * math.cos(th)
    acc = (chi * w * w * math.sin(th) + chi * math.sin(alpha + th) + math.sin(alpha)) / k
    assert r.omega_dot[i] == pytest.approx(acc, rel=1e-12, abs=1e-14)
    assert r.Fy[i] == pytest.approx(
        math.cos(alpha) - chi * w * w * math.cos(th) - chi * acc * math.sin(th),
        rel=1e-12,
        abs=1e-14,
    )


def test_accepted_steps_match_scipy_rk45_step_for_step():
    """The same algorithm as scipy's RK45 (first step, controller, tableau, nfev accounting),
    checked against live scipy without relying on numpy's BLAS summing like our core.

    scipy forms the stage sums and the error estimate with np.dot, whose summation order
    depends on the BLAS kernel picked for the CPU (OpenBLAS: OPENBLAS_CORETYPE=SkylakeX or
    Sandybridge vs Haswell). The error estimate cancels ~8 digits (sum of E = 0), so the
    first step not capped by MAX_FACTOR moves by ~5e-9 relative and later steps inherit the
    shift: the step times of two correct runs differ by ~3e-9, not by rounding."""
    body, alpha = Cylinder(0.3, 0.2), math.radians(35)
    rtol, atol = 1e-6, 1e-9
    r = roll(body, alpha, t_max=3.0, rtol=rtol, atol=atol, theta_max=1e9)
    ref = solve_ivp(
        rolling_rhs_as_in_the_core(alpha, body.chi, body.Ic),
        (0, 3.0),
        [0.0, 0.0],
        method="RK45",
        rtol=rtol,
        atol=atol,
        dense_output=True,
    )
    assert r.status == 0
    # Counts exactly: they change only if an accept/reject test (err < 1) or the clip of the
    # last step to t_bound flips. All 15 attempted steps here have error norms >= 3.9 % away
    # from 1 (measured with a recording RK45 subclass) and the last step is clipped by ~40 %,
    # while the summation order moves error norms by ~1e-8 relative.
    assert len(r.t) == len(ref.t)
    assert r.nfev == ref.nfev
    # Step times to 1e-6 relative: ~300x the BLAS-order shift above (3e-9, measured with
    # OpenBLAS's SkylakeX, Sandybridge, Katmai, Nehalem and Haswell kernels); any change of
    # the algorithm (safety 0.9, exponent -1/5, factor limits, first-step rule, tableau)
    # moves the steps by 1e-3 or more.
    np.testing.assert_allclose(r.t, ref.t, rtol=1e-6, atol=0)
    # The trajectory at the same times, through scipy's dense output at our step times: both
    # runs take the same steps up to a relative change eps <= 1e-6 of h, which changes each
    # step's local error (~ rtol |y| + atol <= 2.2e-6 here, |y| <= 2.13) by ~5 eps of itself,
    # so over 13 steps the states differ by ~13 * 5e-6 * 2.2e-6 ~ 1.4e-10 (measured: 2e-15).
    th, w = ref.sol(r.t)
    np.testing.assert_allclose(r.theta, th, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.omega, w, rtol=0, atol=1e-9)


def test_dense_output_matches_the_steps():
    r = roll(*ROLLS, dense_output=True)
    y = r.sol(r.t)
    np.testing.assert_allclose(y[0], r.theta, rtol=1e-13, atol=1e-13)
    assert r.sol(float(r.t[1])).shape == (2,)
    with pytest.raises(ValueError, match="outside"):
        r.sol(r.t[-1] + 1.0)


def test_dense_output_ends_at_the_terminal_event():
    # The README case: lift-off at t = 4.18302 inside a step that ends later; sol must not
    # return rolling states past the lift-off.
    r = roll(*JARM, mu_s=1.0, dense_output=True)
    assert r.terminal_event == "liftoff"
    t_end = r.event("liftoff").t
    assert r.sol.t_max == t_end == r.t[-1]
    assert r.sol(t_end)[0] == pytest.approx(r.theta[-1], abs=1e-12)
    with pytest.raises(ValueError, match=r"t\[0\] = .* outside"):
        r.sol(np.nextafter(t_end, math.inf))


def test_dense_kinematics_are_the_recorded_ones_and_l_is_the_distance_rolled():
    r = roll(*ROLLS, mu_s=1.0, theta0=0.4, omega0=0.3, dense_output=True)
    k = r.sol.kinematics(r.t)
    for name, rec in (("theta", r.theta), ("omega", r.omega), ("Fx", r.Fx), ("Fy", r.Fy)):
        np.testing.assert_allclose(k[name], rec, rtol=0, atol=1e-12, err_msg=name)
    np.testing.assert_allclose(k["ratio"], np.abs(r.Fx) / r.Fy, rtol=1e-12)
    np.testing.assert_allclose(r.friction_ratio, np.abs(r.Fx) / r.Fy, rtol=1e-15)
    # pure rolling without slip: l - l0 = R (theta - theta0)
    np.testing.assert_array_equal(r.l, r.theta - r.theta[0])
    assert r.to_si(R=0.5).l == pytest.approx(0.5 * r.l)


def test_si_conversion_keeps_angles_and_scales_the_rest():
    r = roll(*ROLLS)
    si = r.to_si(g=9.81, R=0.5, M=2.0)
    np.testing.assert_array_equal(si.theta, r.theta)
    np.testing.assert_allclose(si.t, r.t * math.sqrt(0.5 / 9.81))
    np.testing.assert_allclose(si.Fy, r.Fy * 2 * 9.81)
    np.testing.assert_allclose(si.l, r.l * 0.5)


def test_rule_normal_force_rolls_past_the_papers_liftoff():
    body, alpha = JARM
    paper = roll(body, alpha, mu_s=1.0)
    classical = roll(body, alpha, mu_s=1.0, rule="normal_force")
    assert classical.event("liftoff").theta == pytest.approx(paper.theta[-1], abs=1e-12)
    assert classical.terminal_event in ("slip", "normal_force_zero")
    assert classical.theta[-1] > paper.theta[-1]


@settings(max_examples=40, deadline=None)
@given(
    setups(),
    st.sampled_from([None, 0.3, 1.0]),
    st.sampled_from(["paper", "normal_force"]),
    st.sampled_from(["DOP853", "Vern9"]),
)
def test_dense_output_is_skipped_only_where_it_changes_nothing(s, mu_s, rule, integrator):
    """Without dense_output, DOP853 and Vern9 make a step's dense output (3 and 4 more
    evaluations of f) only where the step's ends cannot clear it of events: the same steps,
    states, forces and events, bit for bit, as when every step's dense output is made."""
    body, alpha, theta0, omega0 = s
    kw = dict(theta0=theta0, omega0=omega0, mu_s=mu_s, rule=rule, t_max=20.0)
    kw.update(theta_max=theta0 + 30, integrator=integrator)
    lean, full = roll(body, alpha, **kw), roll(body, alpha, dense_output=True, **kw)
    for name in ("t", "theta", "omega", "omega_dot", "Fx", "Fy", "l", "friction_ratio"):
        assert getattr(lean, name).tobytes() == getattr(full, name).tobytes(), name
    assert (lean.events, lean.status, lean.message) == (full.events, full.status, full.message)
    assert lean.nfev <= full.nfev
    # Each step cleared from its ends saves 3, 5 or 4 evaluations: a long run has such steps.
    if len(lean.t) > 20:
        assert lean.nfev < full.nfev


def test_dop853_rolling_from_rest_makes_few_dense_outputs():
    # From rest to the lift-off at alpha = 40 deg: 27 of the 28 steps are cleared.
    kw = dict(integrator="DOP853")
    lean = roll(*JARM, **kw)
    full = roll(*JARM, dense_output=True, **kw)
    assert lean.theta.tobytes() == full.theta.tobytes()
    assert full.nfev - lean.nfev >= 3 * (len(lean.t) - 4)


def test_bit_reproducible():
    a = roll(Cylinder(0.41, 0.22), 0.7, mu_s=0.9)
    b = roll(Cylinder(0.41, 0.22), 0.7, mu_s=0.9)
    assert a.theta.tobytes() == b.theta.tobytes() and a.t.tobytes() == b.t.tobytes()


def test_singular_body_ends_with_a_status_not_a_crash():
    r = roll(Cylinder(1.0, 0.0), 0.01, theta0=3.0, omega0=0.0, t_max=50.0, max_steps=20000)
    assert r.status in (-1, 0, 1)
    assert isinstance(r.message, str) and r.message


def test_step_limit_gives_status_minus_one():
    r = roll(*ROLLS, max_steps=3, rtol=1e-12)
    assert r.status == -1 and "max_steps" in r.message


@pytest.mark.parametrize(
    ("kwargs", "name"),
    [
        ({"alpha": -0.1}, "alpha"),
        ({"alpha": 2.0}, "alpha"),
        ({"alpha": math.nan}, "alpha"),
        ({"theta0": math.inf}, "theta0"),
        ({"mu_s": -1.0}, "mu_s"),
        ({"t_max": 0.0}, "t_max"),
        ({"rtol": 0.0}, "rtol"),
        ({"atol": -1.0}, "atol"),
        ({"theta_max": -1.0}, "theta_max"),
        ({"max_steps": 0}, "max_steps"),
        ({"rule": "bogus"}, "rule"),
    ],
)
def test_invalid_input_raises_value_error(kwargs, name):
    body, alpha = ROLLS
    args = {"alpha": alpha, **kwargs}
    alpha = args.pop("alpha")
    with pytest.raises(ValueError, match=name):
        roll(body, alpha, **args)


def test_vertical_ramp_and_flat_ramp():
    flat = roll(Cylinder(0.0, 0.5), 0.0, t_max=5.0)
    assert flat.status == 0 and np.all(flat.theta == 0.0)
    wall = roll(Cylinder(0.2, 0.1), math.pi / 2)
    assert wall.terminal_event == "normal_force_zero" and len(wall.t) == 1


@pytest.mark.parametrize(
    ("alpha_deg", "chi", "km"),
    [("40", "0.15", "0.02"), ("60", "0.1", "0.5"), ("75", "0.05", "0.01")],
)
def test_liftoff_matches_the_30_digit_reference(alpha_deg, chi, km):
    import reference_physics as ref

    alpha = ref.mp.radians(ref.mp.mpf(alpha_deg))
    expected = ref.first_liftoff(alpha, chi, km)[0]
    r = roll(Cylinder(float(chi), float(km)), float(alpha), rtol=1e-12, atol=1e-14)
    assert r.terminal_event == "liftoff"
    assert r.theta[-1] == pytest.approx(expected, abs=1e-9)


def test_fast_result_construction_equals_the_dataclass_init():
    # roll makes its RollResult without the dataclass __init__ (_arrays.frozen_result): the
    # same object as the ordinary way, every field filled, still frozen.
    import dataclasses

    from eccjump.motion.roll import Event, RollResult

    r = roll(*JARM)
    names = [f.name for f in dataclasses.fields(RollResult)]
    assert set(vars(r)) == set(names)  # every field (in the order the bridge gives them)
    again = RollResult(**{n: getattr(r, n) for n in names})
    assert repr(again) == repr(r) and hash(again.events) == hash(r.events)
    for n in names:  # the repr is a summary: compare every field itself
        a, b = getattr(again, n), getattr(r, n)
        assert a.tobytes() == b.tobytes() if isinstance(a, np.ndarray) else a == b, n
    assert all(type(e) is Event for e in r.events)
    with pytest.raises(dataclasses.FrozenInstanceError):
        r.status = 0


def test_the_bridge_takes_rolls_options_by_their_names():
    # The bridge's convention: the body and the ramp positionally, every option keyword-only
    # under roll's own name for it (so no two floats can be swapped on the way).
    import inspect

    from eccjump import _core

    def options(f):
        ps = inspect.signature(f).parameters.values()
        return sorted(p.name for p in ps if p.kind is p.KEYWORD_ONLY)

    assert options(_core.roll) == options(roll)
    positional = [
        p for p in inspect.signature(_core.roll).parameters.values() if p.kind != p.KEYWORD_ONLY
    ]
    assert [p.name for p in positional] == ["chi", "km", "alpha"]


def test_the_bridge_gives_the_run_by_the_names_of_its_result():
    # One output convention (as the maps): the run by RollResult's field names, the events
    # one list per field of Event, so that the field order is written in the classes only.
    import dataclasses

    from eccjump import _core
    from eccjump.motion.roll import Event, RollResult

    opts = {"rtol": 1e-10, "atol": 1e-12, "max_steps": 10**6, "rule": "paper"}
    raw = _core.roll(
        0.15, 0.02, 0.7, theta0=0.0, omega0=0.0, mu_s=1.0, t_max=1e3, theta_max=math.inf,
        dense_output=True, integrator="RK45", **opts,
    )  # fmt: skip
    added = {"body", "alpha", "mu_s", "rule", "units"}  # roll's own
    assert set(raw) == {f.name for f in dataclasses.fields(RollResult)} - added
    assert set(raw["events"]) == set(Event._fields)
    r = roll(Cylinder(0.15, 0.02), 0.7, mu_s=1.0)
    assert r.events == tuple(
        map(Event._make, zip(*(raw["events"][f] for f in Event._fields), strict=True))
    )
    assert r.terminal_event == raw["terminal_event"] == "liftoff"


def test_arguments_of_any_accepted_type_give_the_run_of_plain_ones():
    # roll's checks make every accepted type plain (float, int, bool, str, None) before the
    # bridge sees it: any accepted type gives the run of the plain value.
    class Name(str):
        pass

    body = Cylinder(*JARM_BODY)
    kw = dict(theta0=0.1, omega0=0.2, t_max=50.0, rtol=1e-9, atol=1e-11, dense_output=True)
    plain = roll(body, 0.7, mu_s=1.0, max_steps=10_000, rule="normal_force", **kw)
    other = roll(
        body,
        np.float64(0.7),
        theta0=np.array(0.1),
        omega0=Fraction(1, 5),
        mu_s=1,
        t_max=np.int64(50),
        rtol=np.float64(1e-9),
        atol=1e-11,
        max_steps=np.int32(10_000),
        dense_output=np.True_,
        rule=Name("normal_force"),
    )
    assert other == plain and other.sol is not None
    assert type(other.alpha) is float and type(other.mu_s) is float
    # With several bad arguments the first checked is reported: alpha, mu_s, rule, the rest.
    with pytest.raises(TypeError, match="alpha"):
        roll(body, "0.7", mu_s="1", rule=3)
    with pytest.raises(TypeError, match="rule"):
        roll(body, 0.7, theta0="0", rule=3)
    with pytest.raises(TypeError, match="dense_output"):
        roll(body, 0.7, dense_output=1, integrator=None)


def test_dop853_takes_scipys_dop853_steps():
    """integrator="DOP853" is scipy's DOP853 (first step, controller, the combined 5th/3rd
    order error norm, tableau): the same step count and evaluations (scipy's with
    dense_output=True, whose three extra stages per step eccjump always computes for its
    events), step times to 1e-4. Looser than the RK45 test above: DOP853's error estimate is
    ~1e-10 of the stages it sums, so a one-ulp difference of sin/cos (the core's portable
    libm against the platform's) moves an error norm by ~1e-5 and, through err^(-1/8), a step
    by ~3e-6 (measured); a change of the algorithm (exponent, safety, factor limits,
    tableau, first step) moves steps by 1e-2 or more."""
    body, alpha = Cylinder(0.3, 0.2), math.radians(35)
    rtol, atol = 1e-6, 1e-9
    r = roll(body, alpha, t_max=3.0, rtol=rtol, atol=atol, theta_max=1e9, integrator="DOP853")
    ref = solve_ivp(
        rolling_rhs_as_in_the_core(alpha, body.chi, body.Ic),
        (0, 3.0),
        [0.0, 0.0],
        method="DOP853",
        rtol=rtol,
        atol=atol,
        dense_output=True,
    )
    ref.sol(ref.t[-1])  # scipy builds each step's interpolant once it is asked for
    assert r.status == 0
    assert len(r.t) == len(ref.t)
    np.testing.assert_allclose(r.t, ref.t, rtol=1e-4, atol=0)
    th, w = ref.sol(r.t)
    np.testing.assert_allclose(r.theta, th, rtol=0, atol=1e-9)
    np.testing.assert_allclose(r.omega, w, rtol=0, atol=1e-9)


#: Verner's pairs as (stages, order, error estimator order, interpolant's extra stages, the
#: rtol of the comparison with scipy).
VERNER = {"Vern9": (16, 9, 8, 4, 1e-5)}


def verner_for_scipy(name: str):
    """scipy's explicit Runge–Kutta machinery (first step, controller, error norm) with
    Verner's tableau `name`, read from the 40-digit data the core's tableau is generated from
    (scripts/vern9_coefficients.txt), in float64 by numpy: an
    implementation of integrator=name that shares none of the core's code."""
    from scipy.integrate._ivp.rk import RungeKutta

    stages, q, q_hat, *_ = VERNER[name]
    a, c = np.zeros((stages, stages)), np.zeros(stages)
    b, d = [Fraction(0)] * stages, [Fraction(0)] * stages
    bh: list[Fraction] | None = None
    data = Path(__file__).parents[1] / "scripts" / f"{name.lower()}_coefficients.txt"
    for line in data.read_text().splitlines():
        if not line.split() or line.startswith("#"):
            continue
        kind, *idx, value = line.split()
        i = [int(x) for x in idx]
        if kind == "c" and i[0] < stages:
            c[i[0]] = float(value)
        elif kind == "a" and i[0] < stages:
            a[i[0], i[1]] = float(value)
        elif kind == "b":
            b[i[0]] = Fraction(value)
        elif kind == "bh":
            bh = bh or [Fraction(0)] * stages
            bh[i[0]] = Fraction(value)
        elif kind == "d":  # b̂ − b
            d[i[0]] = Fraction(value)
    bh = bh or [x + y for x, y in zip(b, d, strict=True)]
    # b − b̂ exactly, then rounded once (as the core's tableau): the error estimate is a
    # small difference of stages, which a float64 difference would move by ~1e-3.
    e = [float(x - y) for x, y in zip(b, bh, strict=True)]

    class Verner(RungeKutta):
        order, error_estimator_order, n_stages = q, q_hat, stages
        C, A, B, E = c, a, np.array([float(x) for x in b]), np.array([*e, 0.0])
        P = np.zeros((stages + 1, 1))  # no dense output

    return Verner


@pytest.mark.parametrize("name", list(VERNER))
def test_verners_pairs_take_the_steps_of_scipys_runge_kutta_with_verners_tableaus(
    monkeypatch, name
):
    """integrator="Vern9" against scipy's RungeKutta class given Verner's
    tableaus, with their own safety factor 0.75 (scipy's module constant, patched) and their
    first step (scipy's estimate probed again from rest: tested in the core): the same steps,
    step times to 1e-4, end states to 1e-9. The error estimate is a small difference of
    stages: where the step control lets it fall to the stages' rounding (tight rtol), the
    order of a sum moves step sizes by percents, so the cases are at rtol 1e-5 (at 1e-6
    the first step's estimate is at that rounding). The core's
    step-size factor err^(−1/q) is a quartic fit (within 3e-5 of scipy's power, which
    needs two Newton steps more on the path from one step to the next): the step times
    agree to 2e-5, the end states to 2e-10 (measured; 1e-12 with the exact power)."""
    import scipy.integrate._ivp.rk as rk

    *_, extra_stages, rtol = VERNER[name]
    monkeypatch.setattr(rk, "SAFETY", 0.75)
    for chi, km, deg, t_max in [(*JARM_BODY, JARM_ALPHA_DEG, 4.0), (0.05, 0.5, 20, 10.0)]:
        body, alpha = Cylinder(chi, km), math.radians(deg)
        kw = dict(rtol=rtol, atol=rtol / 1000)
        r = roll(
            body, alpha, t_max=t_max, theta_max=1e9, rule="normal_force", integrator=name, **kw
        )
        rhs = rolling_rhs_as_in_the_core(alpha, body.chi, body.Ic)
        first = float(r.t[1])
        ref = solve_ivp(
            rhs, (0, t_max), [0.0, 0.0], method=verner_for_scipy(name), first_step=first, **kw
        )
        assert (r.status, len(r.t)) == (0, len(ref.t))
        np.testing.assert_allclose(r.t, ref.t, rtol=1e-4, atol=0)
        # nfev: scipy's `stages` per attempt (its first step given), 1-3 probes of the first
        # step, and the interpolant's extra stages where events needed it.
        extra = r.nfev - ref.nfev
        assert any(
            0 <= extra - p <= extra_stages * len(r.t) and (extra - p) % extra_stages == 0
            for p in (1, 2, 3)
        )
        np.testing.assert_allclose(r.theta[-1], ref.y[0, -1], rtol=0, atol=1e-9)
        np.testing.assert_allclose(r.omega[-1], ref.y[1, -1], rtol=0, atol=1e-9)


@settings(max_examples=40, deadline=None)
@given(setups(), st.sampled_from(["DOP853", "Vern9"]))
def test_the_integrators_agree_and_the_high_order_ones_take_fewer_steps(s, integrator):
    body, alpha, theta0, omega0 = s
    # theta_max and t_max not reached together by uniform rotation (theta = theta0 + 2 t).
    kw = dict(theta0=theta0, omega0=omega0, t_max=10.0, theta_max=theta0 + 19.7, dense_output=True)
    a = roll(body, alpha, **kw)
    b = roll(body, alpha, integrator=integrator, **kw)
    assert (a.status, a.terminal_event) == (b.status, b.terminal_event)
    if a.sol is None or b.sol is None:  # ended at the start: no step
        assert len(a.t) == len(b.t) == 1
        return
    t_end = min(a.t[-1], b.t[-1])
    t = np.linspace(0.0, t_end, 50)
    # Both carry global errors ~1e-10 per unit of |theta|; near chi = 1, km = 0 the contact
    # inertia almost vanishes at theta = pi and amplifies them (as in the scipy test above).
    scale = (1 + np.max(np.abs(a.theta))) / (body.Ic + 1 - 2 * body.chi)
    assert np.max(np.abs(a.sol(t) - b.sol(t))) < 1e-8 * scale
    if len(a.t) > 30:
        assert len(b.t) < len(a.t)
    e = energy(alpha, body.chi, body.Ic, b.theta, b.omega)
    assert np.max(np.abs(e - e[0])) < 1e-7 * max(1.0, np.max(np.abs(b.omega)) ** 2)


@pytest.mark.parametrize("route", ["roll", "simulate"])
def test_vern7_is_refused_naming_the_integrators_left(route):
    """Vern7 was removed in 0.2.0 (slower than Vern9 on every benchmark, docs/performance.md)."""
    from eccjump import simulate

    run = roll if route == "roll" else simulate
    allowed = r"integrator = .Vern7. .*'RK45', 'DOP853', 'Vern9'"
    with pytest.raises(ValueError, match=allowed) as err:
        run(Cylinder(*JARM_BODY), 0.7, mu_s=1.0, integrator="Vern7")  # type: ignore[arg-type]
    assert len(str(err.value)) < 200


@pytest.mark.parametrize("integrator", ["DOP853", "Vern9"])
def test_liftoff_by_a_high_order_pair_matches_the_closed_form_root(integrator):
    from eccjump import jarm

    for alpha_deg, chi, km in [(JARM_ALPHA_DEG, *JARM_BODY), (70, 0.1, 0.27), (30, 0.1, 0.09)]:
        alpha = math.radians(alpha_deg)
        r = roll(Cylinder(chi, km), alpha, integrator=integrator)
        exact = jarm(alpha, chi, km, 1e9, rule="paper").theta_J
        assert r.terminal_event == "liftoff"
        assert r.theta[-1] == pytest.approx(float(exact), abs=1e-8)


def test_an_angle_in_degrees_is_refused_naming_the_unit():
    # The API takes radians (the command line degrees): 40 is far outside [0, pi/2] rad.
    with pytest.raises(ValueError, match=r"alpha = 40.*\[0, pi/2\] rad.*math.radians") as err:
        roll(Cylinder(*JARM_BODY), 40.0, mu_s=1.0)
    assert len(str(err.value)) < 200

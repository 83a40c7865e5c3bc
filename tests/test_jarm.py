"""JARM analysis (the paper's Section 3) through the Python API, against independent routes:
the paper's printed formulas (sympy, typed as printed), the 30-digit mpmath reference, and the
integrator (`roll`)."""

import math

import numpy as np
import pytest
import reference_physics as ref
import sympy as sp
import test_paper_formulas as paper
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from properties import reach_rate
from reference_points import (
    JARM_ALPHA,
    JARM_BODY,
    JARM_FX_J,
    JARM_FY_J,
    JARM_THETA_J_DEG,
    SLIP_FIRST_ALPHA,
    SLIP_FIRST_BODY,
    SLIP_FIRST_THETA_DEG,
    jump_points,
)

import eccjump
from eccjump import Cylinder, Reason, jarm, region, roll
from eccjump.classification import closed_form
from eccjump.testing import assert_maps_equal

DEG = math.pi / 180


def printed(expr):
    """A printed formula of the paper as a numpy function of (theta, alpha, chi, km)."""
    e = expr.subs({paper.g: 1, paper.M: 1, paper.R: 1})
    return sp.lambdify((paper.theta, paper.alpha, paper.chi, paper.k_m), e, "numpy")


@st.composite
def bodies(draw, chi_min=0.01):
    chi = draw(st.floats(chi_min, 0.99))
    km = draw(st.floats(0.0, 0.99)) * (1 - chi)
    return chi, km


# --- reference points of the physics notes -----------------------------------------------


def test_reference_jarm_point():
    r = jarm(JARM_ALPHA, *JARM_BODY, 1.0)
    assert bool(r.is_jarm) and Reason(int(r.reason)) == Reason.JARM and int(r.n) == 1
    assert float(r.theta_J) == pytest.approx(JARM_THETA_J_DEG * DEG, abs=1e-12)
    assert float(r.Fy_J) == pytest.approx(JARM_FY_J, abs=1e-12)
    assert float(r.Fx_J) == pytest.approx(JARM_FX_J, abs=1e-12)


def test_reference_slip_point():
    r = jarm(SLIP_FIRST_ALPHA, *SLIP_FIRST_BODY, 1.0)
    assert Reason(int(r.reason)) == Reason.SLIP_BEFORE
    assert float(r.theta_event) == pytest.approx(SLIP_FIRST_THETA_DEG * DEG, abs=1e-10)


def test_reference_mu_s_min():
    m, phi = closed_form.mu_s_min(*SLIP_FIRST_BODY)
    assert float(m) == pytest.approx(1.391618525237494122, rel=1e-12)
    assert float(phi) + 2 * math.pi == pytest.approx(302.48574753796158606 * DEG, abs=1e-9)


# --- the paper's printed formulas against ours ---------------------------------------------


@settings(max_examples=40, deadline=None)
@given(bodies(), st.floats(0.05, math.pi / 2 - 0.05), st.floats(0.05, 6.2))
def test_printed_FxL2_FyL2_match_path_forces(body, alpha, theta):
    chi, km = body
    fx_p, fy_p = (printed(e) for e in paper._fl2_printed())
    fx, fy = closed_form.path_forces(theta, alpha, chi, km)
    scale = 1 + abs(fx_p(theta, alpha, chi, km))
    assert float(fx) == pytest.approx(fx_p(theta, alpha, chi, km), abs=1e-10 * scale)
    assert float(fy) == pytest.approx(fy_p(theta, alpha, chi, km), abs=1e-10 * scale)


@settings(max_examples=40, deadline=None)
@given(bodies(), st.floats(0.05, math.pi / 2 - 0.05), st.floats(-1.5, -0.01))
def test_printed_jump6_Njumpfn_ineq2_Jta_dega2(body, alpha, phi):
    chi, km = body
    theta = 2 * math.pi + phi
    # jump forces from the 30-digit reference, itself checked symbolically against the paper
    fx_r, fy_r = ref.forces_at_jump(theta, alpha, chi, km)
    fx, fy = closed_form.jump_forces(alpha, chi, km, theta)
    assert float(fx) == pytest.approx(fx_r, rel=1e-9, abs=1e-12)
    assert float(fy) == pytest.approx(fy_r, rel=1e-9, abs=1e-12)
    mu_p = printed(paper.MU_PRINTED)(theta, alpha, chi, km)
    assert float(closed_form.mu(chi, km, theta)) == pytest.approx(mu_p, rel=1e-9)
    j_p = printed(paper._J_printed(paper.theta))(theta, alpha, chi, km)
    assert float(closed_form.J(theta, alpha, chi, km)) == pytest.approx(j_p, rel=1e-9, abs=1e-12)
    g_p = printed(paper.GAMMA_PRINTED)(theta, alpha, chi, km)
    assert float(closed_form.gamma(chi, km)) == pytest.approx(g_p, rel=1e-13)
    # J = L / cos(alpha) with L the lift-off function
    lift = closed_form.liftoff_function(theta, alpha, chi, km)
    assert float(lift) == pytest.approx(
        float(closed_form.J(theta, alpha, chi, km)) * math.cos(alpha), abs=1e-12
    )


@settings(max_examples=30, deadline=None)
@given(st.sampled_from(jump_points()))
def test_theta_nJ_against_brackets_and_reference(point):
    # Points whose jump from rolling lies on turn n: the brackets hold a root there.
    alpha, chi, km, n, _ = point
    c1, c2 = closed_form.J_brackets(alpha, chi, km, n)
    assert c1 < 0 < c2
    th = float(closed_form.theta_nJ(alpha, chi, km, n))
    assert 2 * math.pi * n - alpha <= th <= 2 * math.pi * n
    assert abs(float(closed_form.liftoff_function(th, alpha, chi, km))) < 1e-12
    assert th == pytest.approx(ref.theta_jump(n, alpha, chi, km), abs=1e-11)


NO_BRACKET = st.tuples(bodies(), st.floats(0.2, math.pi / 2 - 0.05), st.integers(1, 3))


def brackets_no_root(draw) -> bool:
    (chi, km), alpha, n = draw
    c1, c2 = closed_form.J_brackets(alpha, chi, km, n)
    return not c1 < 0 < c2


@settings(max_examples=30, deadline=None)
@given(NO_BRACKET)
def test_theta_nJ_is_nan_without_a_bracket(draw):
    assume(brackets_no_root(draw))
    (chi, km), alpha, n = draw
    assert math.isnan(float(closed_form.theta_nJ(alpha, chi, km, n)))


def test_the_filtered_property_reaches_its_assertion():
    # Over the whole space a turn's window brackets no root in most draws.
    assert reach_rate(NO_BRACKET, brackets_no_root) >= 0.9


# --- invariants ------------------------------------------------------------------------------


@settings(max_examples=60, deadline=None)
@given(bodies(chi_min=0.0), st.floats(0.0, 10.0))
def test_alpha_zero_never_jarm(body, mu_s):
    chi, km = body
    for rule in ("paper", "normal_force"):
        assert not bool(jarm(0.0, chi, km, mu_s, rule=rule).is_jarm)


@settings(max_examples=80, deadline=None)
@given(st.sampled_from(jump_points()), st.floats(1e-9, 2.0), st.floats(0.0, 3.0))
def test_region_grows_monotonically_with_mu_s(point, above, more):
    # A point that jumps from rolling is JARM from the friction its path needs on, and
    # for any more friction; just below that it slips first.
    alpha, chi, km, _, needed = point
    lo = needed * (1 + above)
    assert bool(jarm(alpha, chi, km, lo).is_jarm)
    assert bool(jarm(alpha, chi, km, lo + more).is_jarm)
    assert not bool(jarm(alpha, chi, km, needed * (1 - 1e-9)).is_jarm)


@settings(max_examples=60, deadline=None)
@given(bodies(), st.floats(0.02, math.pi / 2 - 0.02), st.sampled_from([0.7, 1.0, 2.0]))
def test_classification_agrees_with_the_integrator(body, alpha, mu_s):
    """The closed-form verdict and what `roll` (RK45 with events) sees along the path."""
    chi, km = body
    # k_m = 0 (I_CM = 0): F_y and the friction margin vanish together, a tie by construction.
    assume(km > 1e-3)
    r = jarm(alpha, chi, km, mu_s)
    reason = Reason(int(r.reason))
    run = roll(Cylinder(chi, km), alpha, mu_s=mu_s, t_max=1e4)
    decided = {
        "liftoff": Reason.JARM,
        "normal_force_zero": Reason.NORMAL_FORCE_LOST,
        "slip": Reason.SLIP_BEFORE,
    }
    # Skip points whose deciding events are nearly simultaneous (a boundary).
    assume(run.terminal_event in decided)
    e = run.event(run.terminal_event)
    th_event = r.theta_J if reason == Reason.JARM else r.theta_event
    assume(abs(float(th_event) - e.theta) < 1e-6)
    if reason == Reason.SLIP_AT_JUMP:
        assert run.terminal_event == "slip"
    else:
        assert decided[run.terminal_event] == reason
    if reason == Reason.JARM:
        # rtol = 1e-10 per step, over up to tens of turns
        assert e.theta == pytest.approx(float(r.theta_J), abs=1e-9 * (1 + e.theta))


def test_first_jump_semantics_turns_do_not_overlap():
    a = np.linspace(0.5, 89.5, 60) * DEG
    c = np.linspace(0.02, 0.6, 25)
    f = np.linspace(0.0, 0.9, 10)
    auto = region(mu_s=1.0, alpha=a, chi=c, km_frac=f)
    seen = np.zeros(auto.result.n.shape, dtype=int)
    for n in (1, 2, 3, 4):
        rn = region(mu_s=1.0, n=n, alpha=a, chi=c, km_frac=f)
        seen += rn.is_jarm
        # a JARM on turn n is exactly an automatic JARM whose turn is n
        np.testing.assert_array_equal(rn.is_jarm, auto.is_jarm & (auto.result.n == n))
    assert seen.max() <= 1


def test_region_is_bit_identical_for_any_thread_count():
    a = np.linspace(1, 89, 23) * DEG
    c = np.linspace(0.01, 0.9, 17)
    f = np.linspace(0.0, 0.95, 13)
    r1 = region(mu_s=0.7, alpha=a, chi=c, km_frac=f, n_threads=1)
    assert_maps_equal(region(mu_s=0.7, alpha=a, chi=c, km_frac=f, n_threads=2), r1)
    assert_maps_equal(region(mu_s=0.7, alpha=a, chi=c, km_frac=f, n_threads=3), r1)


@settings(max_examples=25, deadline=None)
@given(
    st.floats(0.02, math.pi / 2),
    st.sampled_from([0.3, 1.0, 2.0]),
    st.sampled_from(["closed_form", "ode"]),
    st.sampled_from(["paper", "normal_force"]),
)
def test_stop_at_slip_only_relabels_the_slips(alpha, mu_s, method, rule):
    """stop_at_slip=True: every SLIP_BEFORE/SLIP_AT_JUMP of the paper rule becomes SLIP with
    theta_J NaN; every other point and field is the same to the bit, and is_jarm everywhere."""
    c = np.linspace(0.02, 0.98, 9)[:, None]
    km = np.linspace(0.0, 0.95, 7)[None, :] * (1 - c)
    kw = {"method": method, "rule": rule, "integrator": "DOP853"}
    full = jarm(alpha, c, km, mu_s, **kw)
    stop = jarm(alpha, c, km, mu_s, stop_at_slip=True, **kw)
    slip = np.isin(full.reason, [Reason.SLIP_BEFORE, Reason.SLIP_AT_JUMP]) & (rule == "paper")
    assert (stop.reason[slip] == Reason.SLIP).all()
    assert np.isnan(stop.theta_J[slip]).all()
    np.testing.assert_array_equal(stop.is_jarm, full.is_jarm)
    for name in eccjump.classification.FIELDS:
        a, b = getattr(full, name), getattr(stop, name)
        keep = ~slip if name in ("reason", "theta_J") else np.ones_like(slip)
        assert a[keep].tobytes() == b[keep].tobytes(), name
    assert Reason.SLIP not in set(full.reason.ravel().tolist())


def test_stop_at_slip_is_recorded_and_makes_slip_maps_of_the_same_region():
    a = np.linspace(5, 85, 9) * DEG
    c = np.linspace(0.05, 0.9, 6)
    f = np.linspace(0.0, 0.9, 4)
    full = region(mu_s=1.0, alpha=a, chi=c, km_frac=f)
    stop = region(mu_s=1.0, alpha=a, chi=c, km_frac=f, stop_at_slip=True)
    assert stop.attrs["stop_at_slip"] is True and full.attrs["stop_at_slip"] is False
    np.testing.assert_array_equal(stop.is_jarm, full.is_jarm)
    slips = np.isin(full.result.reason, [Reason.SLIP_BEFORE, Reason.SLIP_AT_JUMP])
    assert slips.any()
    np.testing.assert_array_equal(stop.result.reason == Reason.SLIP, slips)


def test_region_grid_matches_pointwise_jarm():
    a = np.array([30, 40, 60]) * DEG
    c = np.array([0.1, 0.15, 0.5])
    f = np.array([0.0, 0.5])
    g = region(mu_s=1.0, alpha=a, chi=c, km_frac=f)
    A, C, F = np.meshgrid(a, c, f, indexing="ij")
    p = jarm(A, C, F * (1 - C), 1.0, refine_extrema=False)
    np.testing.assert_array_equal(g.result.reason, p.reason)
    assert g.km.shape == (3, 2)


@settings(max_examples=12, deadline=None)
@given(
    st.floats(0.01, math.pi / 2),
    st.sampled_from([0.3, 1.0]),
    st.sampled_from(["RK45", "DOP853", "Vern9"]),
    st.sampled_from(["paper", "normal_force"]),
    st.booleans(),
)
def test_ode_route_on_arrays_is_each_point_alone(alpha, mu_s, integrator, rule, stop):
    """On arrays the ODE route integrates 8 points side by side (vector instructions): every
    field of every point is, to the bit, what the point alone gives."""
    c = np.linspace(0.02, 0.98, 6)[:, None]
    km = np.linspace(0.0, 0.95, 6)[None, :] * (1 - c)
    kw = {"method": "ode", "integrator": integrator, "rule": rule, "stop_at_slip": stop}
    grid = jarm(alpha, c, km, mu_s, **kw)
    for i in range(6):
        for j in range(6):
            one = jarm(alpha, float(c[i, 0]), float(km[i, j]), mu_s, **kw)
            for name in eccjump.classification.FIELDS:
                a, b = np.asarray(getattr(grid, name))[i, j], np.asarray(getattr(one, name))
                assert a.tobytes() == b.tobytes(), (name, i, j)


def test_boundaries_bracket_the_region_exactly():
    (intervals,) = eccjump.alpha_intervals(*JARM_BODY, 1.0, n=1)
    assert intervals
    for lo, hi in intervals:
        assert bool(jarm(lo, *JARM_BODY, 1.0, n=1).is_jarm)
        assert bool(jarm(hi, *JARM_BODY, 1.0, n=1).is_jarm)
        if lo > 0.01:
            assert not bool(jarm(lo - 2e-12, *JARM_BODY, 1.0, n=1).is_jarm)
        if hi < math.pi / 2:
            assert not bool(jarm(hi + 2e-12, *JARM_BODY, 1.0, n=1).is_jarm)
    assert any(lo < JARM_ALPHA < hi for lo, hi in intervals)


def test_mu_s_min_path_is_the_jarm_threshold():
    m = float(eccjump.mu_s_min_path(JARM_ALPHA, *JARM_BODY))
    assert bool(jarm(JARM_ALPHA, *JARM_BODY, m).is_jarm)
    assert not bool(jarm(JARM_ALPHA, *JARM_BODY, m * (1 - 1e-9)).is_jarm)
    r = jarm(JARM_ALPHA, *JARM_BODY, 10.0)
    assert m == pytest.approx(float(r.max_ratio), rel=1e-9)


def test_invalid_points_are_flagged_not_raised():
    r = jarm([40 * DEG, -1.0, 40 * DEG, math.nan], [0.15, 0.15, 1.5, 0.15], 0.02, 1.0)
    assert [Reason(int(x)) for x in r.reason] == [
        Reason.JARM,
        Reason.INVALID_PARAMS,
        Reason.INVALID_PARAMS,
        Reason.INVALID_PARAMS,
    ]


@pytest.mark.parametrize(
    ("kwargs", "match"),
    [
        ({"n": 0}, "n = 0"),
        ({"rule": "bogus"}, "rule"),
        ({"method": "euler"}, "method"),
        ({"n_threads": -1}, "n_threads"),
        ({"omega0": -1.0}, "omega0"),
    ],
)
def test_whole_call_errors(kwargs, match):
    with pytest.raises(ValueError, match=match):
        jarm(0.5, 0.2, 0.1, 1.0, **kwargs)


def test_shape_errors():
    with pytest.raises(ValueError, match="broadcast"):
        jarm(np.zeros(3), np.zeros(4), 0.1, 1.0)
    with pytest.raises(ValueError, match="1-D"):
        region(mu_s=1.0, alpha=np.zeros((2, 2)), chi=[0.1], km_frac=[0.1])
    with pytest.raises(ValueError, match="index 1"):
        closed_form.mu([0.1, 2.0], 0.0, 5.0)


def test_broadcasting_keeps_shapes():
    r = jarm(np.linspace(0.1, 1.5, 4)[:, None], np.array([0.1, 0.2, 0.3]), 0.01, 1.0)
    assert r.shape == (4, 3) and r.theta_J.shape == (4, 3)
    fx, fy = closed_form.jump_forces(0.7, *JARM_BODY, np.linspace(5.6, 6.2, 5))
    assert fx.shape == fy.shape == (5,)


# --- a turn n per point --------------------------------------------------------------------

# A grid where the turn matters: first jumps on turns 1 and 2, LIFTOFF_EARLIER for n >= 2.
N_ALPHA = np.radians(np.linspace(2.0, 60.0, 8))[:, None, None]
N_CHI = np.linspace(0.3, 0.95, 8)[None, :, None]
N_KM = np.array([0.0, 0.02, 0.05])[None, None, :] * (1 - N_CHI)


def assert_same_bits(x, y):
    for name in eccjump.classification.fields.FIELDS:
        a, b = getattr(x, name), getattr(y, name)
        assert a.dtype == b.dtype and a.shape == b.shape, name
        assert a.tobytes() == b.tobytes(), name  # NaNs compared by bytes


def test_n_array_broadcasts_and_equals_per_n_calls():
    turns = np.array([1, 2, 3])
    both = jarm(N_ALPHA[None], N_CHI[None], N_KM[None], 2.0, n=turns[:, None, None, None])
    assert both.shape == (3, 8, 8, 3)
    for i, n in enumerate(turns):
        one = jarm(N_ALPHA, N_CHI, N_KM, 2.0, n=int(n))
        assert_same_bits(
            eccjump.JarmResult(
                **{k: getattr(both, k)[i] for k in eccjump.classification.fields.FIELDS}
            ),
            one,
        )
    assert len({int(both.is_jarm[i].sum()) for i in range(3)}) == 3  # n does matter here


def test_n_per_point_is_one_core_call(monkeypatch):
    rng = np.random.default_rng(7)
    n = rng.integers(1, 4, size=(8, 8, 3))
    calls = []
    real = eccjump._core.jarm_points

    def counting(*args, **options):
        calls.append(args[0].size)
        return real(*args, **options)

    monkeypatch.setattr(eccjump._core, "jarm_points", counting)
    mixed = jarm(N_ALPHA, N_CHI, N_KM, 2.0, n=n)
    assert calls == [n.size]  # the core takes a turn per point: one call for all
    for v in (1, 2, 3):
        one = jarm(N_ALPHA, N_CHI, N_KM, 2.0, n=v)
        mask = n == v
        for name in eccjump.classification.fields.FIELDS:
            a, b = getattr(mixed, name)[mask], getattr(one, name)[mask]
            assert a.tobytes() == b.tobytes(), (v, name)


def test_n_scalar_forms_and_lists():
    ref_ = jarm(N_ALPHA, N_CHI, N_KM, 2.0, n=2)
    for n in (np.int64(2), np.uint8(2), np.array(2), np.full((8, 8, 3), 2), [[[2]]]):
        assert_same_bits(jarm(N_ALPHA, N_CHI, N_KM, 2.0, n=n), ref_)
    r = jarm(JARM_ALPHA, *JARM_BODY, 1.0, n=[1, 2])
    assert r.shape == (2,) and bool(r.is_jarm[0]) and int(r.n[0]) == 1
    assert jarm(np.zeros(0), *JARM_BODY, 1.0, n=np.zeros(0, dtype=int)).shape == (0,)


@pytest.mark.parametrize("n", [0, -1, [0, 1], [1, -2], 2**32, 10**400, [1, 10**400]])
def test_bad_n_is_rejected_with_its_range(n):
    with pytest.raises(ValueError, match=r"n\b.*\[1, 4294967295\]"):
        jarm([0.5, 0.6], 0.2, 0.1, 1.0, n=n)


@pytest.mark.parametrize(
    "n", [1.0, True, [1.5, 2.0], [None, 1], [True, False], "2", [[1], [1, 2]], 1 + 0j]
)
def test_n_that_is_not_integers_is_a_type_error(n):
    with pytest.raises(TypeError, match=r"^n\b"):
        jarm([0.5, 0.6], 0.2, 0.1, 1.0, n=n)


def test_n_shape_errors_name_n():
    with pytest.raises(ValueError, match=r"broadcast.*n\(3,\)"):
        jarm([0.5, 0.6], 0.2, 0.1, 1.0, n=[1, 2, 3])


# --- the second, independent route: integration with events --------------------------------


@settings(max_examples=60, deadline=None)
@given(
    bodies(),
    st.floats(3 * DEG, math.pi / 2),
    st.sampled_from([0.7, 1.0, 1.5]),
    st.sampled_from(["paper", "normal_force"]),
    st.sampled_from([(0.0, 0.0), (0.0, 0.5), (0.3, 0.0), (2.0, 1.0)]),
    st.sampled_from(["RK45", "DOP853", "Vern9"]),
)
def test_ode_route_agrees_with_the_closed_form(body, alpha, mu_s, rule, start, integrator):
    chi, km = body
    assume(km > 1e-3)  # k_m = 0: F_y and the friction margin vanish together (a tie)
    theta0, omega0 = start
    kw = {"rule": rule, "theta0": theta0, "omega0": omega0}
    cf = jarm(alpha, chi, km, mu_s, **kw)
    # away from boundaries: the verdict must not change under a tiny change of alpha
    near = jarm(
        np.array([alpha * (1 - 1e-6), alpha * (1 + 1e-6)]).clip(0, math.pi / 2), chi, km, mu_s, **kw
    )
    assume(np.all(near.reason == cf.reason))
    # The ODE route finds events by sign samples on each step: over hundreds of turns (small
    # alpha, small chi) it can miss a slip window narrower than the sample spacing, which the
    # closed form's derivative test cannot (ode_route.rs, "Events are found by sign sampling").
    # Such a counterexample: chi = 0.01, km = 0.4613, alpha = 3 deg, slip on turn 211 vs 212.
    assume(int(cf.n) <= 50)
    ode = jarm(alpha, chi, km, mu_s, method="ode", integrator=integrator, **kw)
    assert Reason(int(ode.reason)) == Reason(int(cf.reason))
    assert int(ode.n) == int(cf.n)
    if bool(cf.is_jarm):
        tol = 1e-9 + 2e-10 * float(cf.theta_J)
        tol *= 20 if rule == "normal_force" else 1
        assert float(ode.theta_J) == pytest.approx(float(cf.theta_J), abs=tol)


GRID12 = {
    "alpha": np.radians(np.linspace(1, 89, 12)),
    "chi": np.linspace(0.02, 0.98, 12),
    "km_frac": np.linspace(0.0, 0.98, 12),
}


@pytest.mark.parametrize("mu_s", [0.5, 0.7, 1.0, 1.5])
@pytest.mark.parametrize("rule", ["paper", "normal_force"])
def test_every_pair_and_the_closed_form_map_the_same_region(mu_s, rule):
    """region(method="ode") with RK45, DOP853 and Vern9 against the closed form on a 12^3
    grid: the same reason and turn at every point. Until the ODE route's event scan tested
    dips between its samples (docs/jarm.md), DOP853's longer steps missed narrow slip windows
    at 0 to 5 points per map; now 0 of 13 824 (Vern9's steps are longer still)."""
    rk = region(mu_s=mu_s, **GRID12, rule=rule, method="ode").result
    cf = region(mu_s=mu_s, **GRID12, rule=rule).result
    for pair in ("DOP853", "Vern9"):
        other = region(mu_s=mu_s, **GRID12, rule=rule, method="ode", integrator=pair).result
        assert rk.theta_event.tobytes() != other.theta_event.tobytes()  # another pair ran
        for ode in (rk, other):
            differ = (ode.reason != cf.reason) | (ode.n != cf.n)
            assert not differ.any(), [
                (pair, idx, Reason(int(ode.reason[idx])), Reason(int(cf.reason[idx])))
                for idx in zip(*np.nonzero(differ), strict=True)
            ]
        same = rk.is_jarm
        assert np.allclose(rk.theta_J[same], other.theta_J[same], rtol=1e-8, atol=1e-9)
    assert np.allclose(rk.theta_J[same], cf.theta_J[same], rtol=1e-8, atol=1e-9)


def test_ode_route_reference_points():
    r = jarm(JARM_ALPHA, *JARM_BODY, 1.0, method="ode")
    assert bool(r.is_jarm)
    assert float(r.theta_J) == pytest.approx(JARM_THETA_J_DEG * DEG, abs=1e-9)
    s = jarm(SLIP_FIRST_ALPHA, *SLIP_FIRST_BODY, 1.0, method="ode")
    assert Reason(int(s.reason)) == Reason.SLIP_BEFORE
    assert float(s.theta_event) == pytest.approx(SLIP_FIRST_THETA_DEG * DEG, abs=1e-9)


def test_ode_region_is_bit_identical_for_any_thread_count():
    a = np.linspace(5, 85, 7) * DEG
    c = np.linspace(0.05, 0.6, 5)
    f = np.linspace(0.0, 0.5, 3)
    r1 = region(mu_s=1.0, alpha=a, chi=c, km_frac=f, method="ode", n_threads=1)
    r2 = region(mu_s=1.0, alpha=a, chi=c, km_frac=f, method="ode", n_threads=2)
    assert_maps_equal(r2, r1)


def test_reason_codes_include_solver_failed_and_slip():
    # An integrator failure of the ODE route has its own code, never a physical verdict
    # (the failure itself is provoked in the Rust tests: jarm::ode_route, step budget);
    # SLIP is only given with stop_at_slip=True (test_stop_at_slip_only_relabels_the_slips).
    assert Reason.SOLVER_FAILED == 9 and Reason.SLIP == 10
    assert [r.value for r in Reason] == list(range(11))


def test_the_classification_is_periodic_in_theta0():
    """theta0 = -pi and +pi are the same start: the same verdicts, angles 2 pi apart (a
    lift-off in (-alpha, 0), turn 0's window, used to be missed from theta0 < 0)."""
    g = {"alpha": np.radians(np.linspace(2, 88, 12)), "chi": np.linspace(0.03, 0.97, 12)}
    g["km_frac"] = np.linspace(0.03, 0.97, 6)
    neg = eccjump.region(mu_s=1.0, **g, theta0=-math.pi, omega0=1.0)
    pos = eccjump.region(mu_s=1.0, **g, theta0=math.pi, omega0=1.0)
    assert pos.result.is_jarm.sum() > 20
    assert np.array_equal(neg.result.reason, pos.result.reason)
    assert np.array_equal(neg.result.n, pos.result.n)
    j = pos.result.is_jarm
    assert np.allclose(neg.result.theta_J[j] + 2 * math.pi, pos.result.theta_J[j], atol=1e-9)

"""Initial conditions (``eccjump.classification.starts``, ``docs/initial_conditions.md``): the
JARM fraction against the start, the optimal start, and the starts that block a JARM."""

from __future__ import annotations

import contextlib
import io
import json
import math

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import eccjump
from eccjump import Reason
from eccjump.classification.starts import _DIRECTIONS, _MULTIPLES, _Objective
from eccjump.cli import main

TWO_PI = 2 * math.pi


def midpoint_axes(g: int) -> dict[str, np.ndarray]:
    """The grid of the fraction, written out independently of the module."""
    u = (np.arange(g) + 0.5) / g
    return {"alpha": u * (math.pi / 2), "chi": u, "km_frac": u}


# --- the fraction --------------------------------------------------------------------------


@pytest.mark.parametrize("mu_s", [0.7, 1.0])
@pytest.mark.parametrize("grid", [7, 16])
def test_at_rest_the_fraction_is_the_regions(mu_s, grid):
    reg = eccjump.region(mu_s=mu_s, **midpoint_axes(grid))
    assert eccjump.jarm_fraction(mu_s, 0.0, 0.0, grid=grid) == reg.fraction()
    assert eccjump.jarm_fraction(mu_s, grid=grid) == reg.fraction()
    shares = eccjump.reason_shares(mu_s, grid=grid)
    assert shares[Reason.JARM] == reg.fraction()
    counts = reg.result.counts()
    for r in Reason:
        assert shares[r] == counts.get(r, 0) / reg.result.reason.size
    assert shares[Reason.LIFTOFF_EARLIER] == 0 and shares[Reason.ROCKS_BACK] == 0


def test_a_general_start_is_the_regions_at_that_start():
    g = 9
    reg = eccjump.region(mu_s=1.0, **midpoint_axes(g), theta0=4.7, omega0=1.0)
    assert eccjump.jarm_fraction(1.0, 4.7, 1.0, grid=g) == reg.fraction()


@settings(max_examples=12)
@given(
    theta0=st.floats(0.0, TWO_PI, exclude_max=True),
    omega0=st.floats(0.0, 2.0),
    turns=st.integers(-3, 3),
)
def test_the_fraction_is_periodic_in_theta0(theta0, omega0, turns):
    """The physics is periodic in theta0; the start is taken modulo 2 pi (the core alone is
    not periodic for theta0 < 0: see the module docs)."""
    shifted = theta0 + turns * TWO_PI
    reduced = math.fmod(shifted, TWO_PI) % TWO_PI
    if abs(reduced - theta0) > 1e-15 and abs(abs(reduced - theta0) - TWO_PI) > 1e-15:
        return  # the shift itself rounded theta0 to another float: not the same start
    assert eccjump.jarm_fraction(1.0, shifted, omega0, grid=6) == eccjump.jarm_fraction(
        1.0, theta0, omega0, grid=6
    )


def test_the_fraction_changes_with_the_start():
    rest = eccjump.jarm_fraction(1.0, grid=12)
    assert 0 < rest < eccjump.jarm_fraction(1.0, math.radians(270.0), 1.0, grid=12)


def test_start_map_agrees_with_the_fraction():
    th, om = [0.0, 4.7, -1.0], [0.0, 1.0]
    m = eccjump.start_map(0.7, th, om, grid=5)
    assert m.shares.shape == (3, 2, len(Reason))
    assert m.theta0[2] == pytest.approx(TWO_PI - 1.0, abs=1e-15)
    for i, t in enumerate(th):
        for j, o in enumerate(om):
            assert m.fraction[i, j] == eccjump.jarm_fraction(0.7, t, o, grid=5)
    best = m.best()
    assert best[2] == m.fraction.max()
    assert "StartMap(3 x 2 starts" in repr(m)


# --- the optimum ---------------------------------------------------------------------------


@pytest.fixture(scope="module", params=[0.7, 1.0], ids=["mu0.7", "mu1"])
def optimum(request):
    return eccjump.optimal_start(request.param, grid=6, lattice=(16, 8))


def test_the_optimum_is_a_local_maximum_on_both_grids(optimum):
    """Perturbing the start by 1--3 search steps along each axis and diagonal does not raise
    the fraction (on the grid and on twice the grid); far perturbations lower it."""
    o = optimum
    for grid, (t0, w0, f0) in (
        (o.grid, (o.theta0_coarse, o.omega0_coarse, o.fraction_coarse)),
        (2 * o.grid, (o.theta0, o.omega0, o.fraction)),
    ):
        assert eccjump.jarm_fraction(o.mu_s, t0, w0, grid=grid) == f0
        for dx, dy in _DIRECTIONS:
            for m in _MULTIPLES:
                w = w0 + m * dy * o.step_omega0
                if 0 <= w <= o.omega_max:
                    t = t0 + m * dx * o.step_theta0
                    assert eccjump.jarm_fraction(o.mu_s, t, w, grid=grid) <= f0
    for dt, dw in ((0.3, 0), (-0.3, 0), (0, 0.3), (0, -0.3)):
        f = eccjump.jarm_fraction(o.mu_s, o.theta0 + dt, max(o.omega0 + dw, 0), grid=2 * o.grid)
        assert f < o.fraction


def test_the_optimum_beats_rest_and_its_uncertainty_is_the_grid_difference(optimum):
    o = optimum
    assert o.fraction_at_rest == eccjump.jarm_fraction(o.mu_s, grid=2 * o.grid)
    assert o.fraction > 10 * o.fraction_at_rest
    assert o.fraction_err == abs(o.fraction - o.fraction_coarse)
    d = abs(o.theta0 - o.theta0_coarse) % TWO_PI
    assert o.theta0_err == min(d, TWO_PI - d)
    assert o.omega0_err == abs(o.omega0 - o.omega0_coarse)
    assert 0 <= o.theta0 < TWO_PI and 0 <= o.omega0 <= o.omega_max
    assert o.as_dict()["theta0_deg"] == math.degrees(o.theta0)


def test_the_starts_searched_stay_inside_the_bounds_after_rounding():
    # The search rounds each start to 12 decimals (its cache key); found by the fuzz
    # campaign (seed 9281): omega_max = 1.1127219999999998 came back as omega0 = 1.112722.
    opt = eccjump.optimal_start(
        2.787, grid=2, omega_max=1.1127219999999998, lattice=(4, 2), n_starts=1,
        rule="normal_force", max_evaluations=400,
    )  # fmt: skip
    assert 0.0 <= opt.omega0 <= opt.omega_max and 0.0 <= opt.omega0_coarse <= opt.omega_max
    f = _Objective(1.0, 2, "paper", 1, 1.0207449999999998, [10])
    assert f.key(1.0, 5.0) == (1.0, 1.0207449999999998)
    assert f.key(TWO_PI - 1e-14, -1.0) == (0.0, 0.0)
    assert f.key(-1e-14, 0.5) == (0.0, 0.5)


def test_a_small_budget_is_a_clear_error():
    with pytest.raises(ValueError, match="max_evaluations"):
        eccjump.optimal_start(1.0, grid=2, lattice=(4, 3), max_evaluations=5)


# --- starts that block a JARM --------------------------------------------------------------


def test_immediate_flight_is_liftoff_earlier_at_the_start_and_flies_in_the_simulator():
    """Paper's rule: chi omega0^2 cos theta0 > cos alpha leaves the ramp at theta0: never a
    JARM (LIFTOFF_EARLIER at theta0), and the simulator starts in flight."""
    g = 8
    ax = midpoint_axes(g)
    for th0, om0 in ((0.2, 1.5), (5.9, 0.8), (math.radians(280), 1.0)):
        reg = eccjump.region(mu_s=1.0, **ax, theta0=th0, omega0=om0)
        a, c, f = np.meshgrid(ax["alpha"], ax["chi"], ax["km_frac"], indexing="ij")
        flies = c * om0**2 * math.cos(th0) > np.cos(a)
        assert flies.any()
        res = reg.result
        assert ((res.reason == Reason.LIFTOFF_EARLIER) == flies).all()
        assert not res.is_jarm[flies].any()
        assert (res.theta_event[flies] == th0).all()
        share = eccjump.reason_shares(1.0, th0, om0, grid=g)[Reason.LIFTOFF_EARLIER]
        assert share == flies.mean()
        for i, j, k in np.argwhere(flies)[:: max(1, int(flies.sum()) // 4)][:4]:
            body = eccjump.Cylinder(c[i, j, k], f[i, j, k] * (1 - c[i, j, k]))
            run = eccjump.simulate(
                body, a[i, j, k], mu_s=1.0, theta0=th0, omega0=om0, t_max=1.0, max_transitions=2
            )
            assert run.transitions[0].to_mode == "FLIGHT"


def test_rocking_back_is_never_a_jarm_and_rolls_back_in_the_simulator():
    """From rest at theta0 = 3.5 rad (past the bottom), part of the cube rolls back up."""
    g, th0 = 8, 3.5
    ax = midpoint_axes(g)
    reg = eccjump.region(mu_s=1.0, **ax, theta0=th0, omega0=0.0)
    back = reg.result.reason == Reason.ROCKS_BACK
    assert back.any() and not reg.result.is_jarm[back].any()
    a, c, f = np.meshgrid(ax["alpha"], ax["chi"], ax["km_frac"], indexing="ij")
    picks = np.argwhere(back)
    for i, j, k in picks[:: max(1, len(picks) // 5)][:5]:
        body = eccjump.Cylinder(c[i, j, k], f[i, j, k] * (1 - c[i, j, k]))
        run = eccjump.simulate(
            body, a[i, j, k], mu_s=1.0, theta0=th0, t_max=30.0, max_transitions=3
        )
        first = run.segments[0]
        assert first.mode == "ROLL"
        rolling = (run.t <= first.t_end) & (run.mode == 0)
        assert run.omega[rolling].min() < 0, "it should roll back up the ramp"


def test_starts_with_no_jarm_exist_and_the_map_marks_them():
    m = eccjump.start_map(1.0, [0.0, 0.5], [0.0, 3.0], grid=6)
    assert m.impossible[1, 1] and not m.impossible[0, 0]
    assert m.immediate_flight[1, 1] > 0.5
    assert eccjump.jarm_fraction(1.0, 0.5, 3.0, grid=6) == 0


# --- input ---------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("call", "exc", "name"),
    [
        (lambda: eccjump.jarm_fraction(-1.0), ValueError, "mu_s"),
        (lambda: eccjump.jarm_fraction(math.inf), ValueError, "mu_s"),
        (lambda: eccjump.jarm_fraction(1.0, math.nan), ValueError, "theta0"),
        (lambda: eccjump.jarm_fraction(1.0, 1e15), ValueError, "theta0"),
        (lambda: eccjump.jarm_fraction(1.0, 0.0, -0.5), ValueError, "omega0"),
        (lambda: eccjump.jarm_fraction(1.0, 0.0, math.nan), ValueError, "omega0"),
        (lambda: eccjump.jarm_fraction(1.0, grid=1), ValueError, "grid"),
        (lambda: eccjump.jarm_fraction(1.0, grid=129), ValueError, "grid"),
        (lambda: eccjump.jarm_fraction(1.0, grid=2.5), TypeError, "grid"),
        (lambda: eccjump.jarm_fraction(1.0, rule="bogus"), ValueError, "rule"),
        (lambda: eccjump.jarm_fraction("1"), TypeError, "mu_s"),
        (lambda: eccjump.reason_shares(1.0, True), TypeError, "theta0"),
        (lambda: eccjump.start_map(1.0, np.zeros(101), np.zeros(100)), ValueError, "theta0"),
        (lambda: eccjump.start_map(1.0, [], [0.0]), ValueError, "theta0"),
        (lambda: eccjump.start_map(1.0, [[0.0]], [0.0]), ValueError, "theta0"),
        (lambda: eccjump.start_map(1.0, [0.0], [0.0], progress=3), TypeError, "progress"),
        (lambda: eccjump.optimal_start(1.0, grid=65), ValueError, "grid"),
        (lambda: eccjump.optimal_start(1.0, omega_max=0.0), ValueError, "omega_max"),
        (lambda: eccjump.optimal_start(1.0, lattice=(1, 5)), ValueError, "lattice"),
        (lambda: eccjump.optimal_start(1.0, lattice="ab"), TypeError, "lattice"),
        (lambda: eccjump.optimal_start(1.0, n_starts=0), ValueError, "n_starts"),
        (lambda: eccjump.optimal_start(1.0, max_evaluations=10**6), ValueError, "max_evaluations"),
        (lambda: eccjump.optimal_start(1.0, rule="x"), ValueError, "rule"),
    ],
)
def test_bad_input_names_the_parameter(call, exc, name):
    with pytest.raises(exc) as info:
        call()
    assert type(info.value) is exc
    msg = str(info.value)
    assert name in msg and len(msg) <= 200, msg


# --- the command line and the figure -------------------------------------------------------


def run_cli(argv):
    out, err = io.StringIO(), io.StringIO()
    with contextlib.redirect_stdout(out), contextlib.redirect_stderr(err):
        code = main(argv)
    return code, out.getvalue(), err.getvalue()


SMALL = ["--grid", "3", "--lattice", "6", "3", "--map-grid", "3", "--map-size", "4", "3", "-q"]


def test_cli_json_matches_the_api():
    code, out, _ = run_cli(["starts", "--mu-s", "1", *SMALL, "--json"])
    assert code == 0
    (r,) = json.loads(out)
    opt = eccjump.optimal_start(1.0, grid=3, lattice=(6, 3))
    assert r["fraction"] == opt.fraction and r["theta0_deg"] == math.degrees(opt.theta0)
    assert r["map"]["starts"] == [4, 3]


def test_cli_writes_the_figures(tmp_path):
    pytest.importorskip("matplotlib")
    code, out, _ = run_cli(["starts", "--mu-s", "0.7", *SMALL, "-o", str(tmp_path)])
    assert code == 0 and "optimum" in out and "from rest" in out
    names = sorted(p.name for p in tmp_path.iterdir())
    assert names == [
        "starts_mu0p7.png",
        "starts_region_optimum_mu0p7.png",
        "starts_region_rest_mu0p7.png",
    ]


def test_cli_bad_input_is_one_line(tmp_path, capsys):
    code, _, err = run_cli(["starts", "--mu-s", "-1", *SMALL])
    assert code == 2 and "mu_s" in err
    code, _, err = run_cli(["starts", *SMALL, "-o", str(tmp_path / "missing")])
    assert code == 2 and "outdir" in err


def test_fraction_map_figure():
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    import matplotlib.pyplot as plt

    from eccjump import plot

    m = eccjump.start_map(1.0, [0.0, 4.7], [0.0, 1.0], grid=3)
    opt = eccjump.optimal_start(1.0, grid=2, lattice=(3, 2))
    fig = plot.fraction_map(m, optimum=opt)
    assert len(fig.axes) >= 3
    plt.close(fig)
    with pytest.raises(TypeError, match="smap"):
        plot.fraction_map(None)
    with pytest.raises(TypeError, match="optimum"):
        plot.fraction_map(m, optimum=3)


def test_a_rim_point_mass_loses_the_normal_force_at_the_start_above_omega0_one():
    """For chi = 1, k_m = 0 (derived by hand, docs/initial_conditions.md):
    F_y = ((1 + cos theta)(cos alpha - omega^2) - sin theta sin alpha) / 2, so on a gentle ramp
    a start with omega0 > 1 loses the normal force at once: the cliff of the fraction at
    omega0 = 1."""
    th = np.radians([200.0, 250.0, 270.0, 290.0, 330.0])
    for a in np.radians([1.0, 30.0, 70.0]):
        for om in (0.5, 1.0, 1.1):
            for t in th:
                _, fy = eccjump.closed_form.path_forces(t, a, 1.0, 0.0, theta0=t, omega0=om)
                expected = (
                    (1 + math.cos(t)) * (math.cos(a) - om**2) - math.sin(t) * math.sin(a)
                ) / 2
                assert fy == pytest.approx(expected, rel=1e-12, abs=1e-14)
    for t in np.radians([200.0, 270.0]):
        above = eccjump.jarm(0.01, 0.999, 0.0, 1.0, theta0=t, omega0=1.05)
        below = eccjump.jarm(0.01, 0.999, 0.0, 1.0, theta0=t, omega0=0.95)
        assert above.reason == Reason.NORMAL_FORCE_LOST and above.theta_event == t
        assert not (below.reason == Reason.NORMAL_FORCE_LOST and below.theta_event == t)


@pytest.mark.parametrize("omega_max", [5e-324, 1e-7, 0.0, -1.0, 101.0, math.nan])
def test_omega_max_outside_its_range_names_it(omega_max):
    # 5e-324 made the lattice's step 0: a ZeroDivisionError.
    with pytest.raises(ValueError, match=r"omega_max = .* \[1e-6, 100\]"):
        eccjump.optimal_start(1.0, grid=3, omega_max=omega_max)


def test_the_smallest_omega_max_searches():
    opt = eccjump.optimal_start(1.0, grid=2, omega_max=1e-6, lattice=(4, 2), n_starts=1)
    assert 0.0 <= opt.omega0 <= 1e-6

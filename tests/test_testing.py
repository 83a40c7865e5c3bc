"""eccjump.testing: every value its strategies draw is accepted by eccjump, the edges of the
valid ranges are drawn, the keywords narrow and are checked; the assertions pass on good
results and say where bad ones go wrong; hypothesis stays optional."""

from __future__ import annotations

import dataclasses
import importlib
import math
import sys

import numpy as np
import pytest
from hypothesis import HealthCheck, find, given, settings

import eccjump
from eccjump import Reason
from eccjump.testing import assert_ledger_closes, assert_maps_equal, strategies
from eccjump.testing.strategies import MOTION_MIN_KM

HALF_PI = math.pi / 2


def test_without_hypothesis_the_import_names_the_extra(monkeypatch):
    monkeypatch.setitem(sys.modules, "hypothesis", None)  # as if not installed
    for name in [m for m in sys.modules if m.startswith("eccjump.testing")]:
        monkeypatch.delitem(sys.modules, name)
    with pytest.raises(ImportError, match=r"hypothesis .*pip install eccjump\[testing\]"):
        importlib.import_module("eccjump.testing")


# --- every drawn value is accepted ------------------------------------------------------------


@settings(max_examples=150, deadline=None)
@given(
    strategies.bodies(),
    strategies.ramps(),
    strategies.frictions(),
    strategies.starts(max_theta0=4 * math.pi),
)
def test_jarm_and_roll_take_every_drawn_point(body, alpha, friction, start):
    r = eccjump.jarm(alpha, body.chi, body.km, friction.mu_s, theta0=start.theta0,
                     omega0=start.omega0)  # fmt: skip
    assert Reason(int(r.reason)) is not Reason.INVALID_PARAMS
    run = eccjump.roll(body, alpha, theta0=start.theta0, omega0=start.omega0, t_max=5.0)
    assert run.t.size >= 1


@settings(max_examples=100, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(strategies.motion_inputs())
def test_simulate_takes_every_drawn_motion(m):
    r = eccjump.simulate(m.body, m.alpha, **m.keywords(), t_max=5.0, max_transitions=20)
    assert r.status in {"t_max", "max_transitions", "painleve", "jam", "failed"}
    assert m.body.km >= MOTION_MIN_KM and m.mu_k <= m.mu_s


def test_the_smallest_motion_km_is_accepted_with_any_chi():
    for chi in (0.0, 0.5, 1.0 - MOTION_MIN_KM):
        body = eccjump.Cylinder(chi, MOTION_MIN_KM)
        eccjump.simulate(body, 0.5, mu_s=1.0, t_max=1.0)
    with pytest.raises(ValueError, match="km"):  # what bodies() alone may draw
        eccjump.simulate(eccjump.Cylinder(0.5, 0.0), 0.5, mu_s=1.0, t_max=1.0)


@pytest.mark.slow
@settings(max_examples=4, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(strategies.tracks(max_frames=40))
def test_analyze_takes_every_drawn_track(t):
    # analyze fits the model: up to seconds for a track of 60 frames
    assert 12 <= t.track.n <= 40
    res = eccjump.analyze(t.track, **t.keywords(), profile_mu_k=False)
    assert res.verdict in {"jarm", "slip_first", "undetermined"}


# --- the edges are drawn ----------------------------------------------------------------------

EDGES = {
    "chi = 0": (strategies.bodies(), lambda b: b.chi == 0.0),
    "chi = 1": (strategies.bodies(), lambda b: b.chi == 1.0 and b.km == 0.0),
    "km = 0": (strategies.bodies(), lambda b: b.km == 0.0 and 0 < b.chi < 1),
    "km = 1 - chi": (strategies.bodies(), lambda b: b.km == 1.0 - b.chi and 0 < b.chi < 1),
    "km = 1": (strategies.bodies(), lambda b: b.km == 1.0),
    "alpha = 0": (strategies.ramps(), lambda a: a == 0.0),
    "alpha = pi/2": (strategies.ramps(), lambda a: a == HALF_PI),
    "mu_k = mu_s": (strategies.frictions(), lambda f: f.mu_k == f.mu_s > 0),
    "mu_k = 0": (strategies.frictions(), lambda f: f.mu_k == 0 < f.mu_s),
    "rest": (strategies.starts(), lambda s: s.theta0 == s.omega0 == 0.0),
    "e = 0": (strategies.motion_inputs(), lambda m: m.restitution == 0.0),
    "e = 1": (strategies.motion_inputs(), lambda m: m.restitution == 1.0),
    "motion km min": (strategies.motion_inputs(), lambda m: m.body.km == MOTION_MIN_KM),
    "motion chi max": (
        strategies.motion_inputs(),
        lambda m: m.body.chi == 1.0 - MOTION_MIN_KM and m.body.km == MOTION_MIN_KM,
    ),
    "slip either way": (strategies.motion_inputs(), lambda m: m.slip0 == -1.0),
}


@pytest.mark.parametrize("edge", sorted(EDGES))
def test_the_edges_are_drawn(edge):
    strategy, condition = EDGES[edge]
    find(strategy, condition, settings=settings(max_examples=2000, database=None))


# --- the keywords narrow, and are checked -----------------------------------------------------


@settings(max_examples=50, deadline=None)
@given(
    strategies.bodies(min_chi=0.2, max_chi=0.6, min_km=0.1, max_km=0.3),
    strategies.bodies(chi=0.5),
    strategies.bodies(km=0.25),
    strategies.ramps(min_alpha=0.3, max_alpha=0.4),
    strategies.frictions(min_mu_s=0.5, max_mu_s=0.7, min_ratio=0.8),
    strategies.starts(
        min_theta0=-1.0, max_theta0=1.0, min_omega0=-0.5, max_omega0=0.5, max_slip0=0.1
    ),
)
def test_the_keywords_narrow_the_draws(narrow, fixed_chi, fixed_km, alpha, friction, start):
    assert 0.2 <= narrow.chi <= 0.6 and 0.1 <= narrow.km <= 0.3
    assert fixed_chi.chi == 0.5 and 0 <= fixed_chi.km <= 0.5
    assert fixed_km.km == 0.25 and 0 <= fixed_km.chi <= 0.75
    assert 0.3 <= alpha <= 0.4
    assert 0.5 <= friction.mu_s <= 0.7 and 0.8 * friction.mu_s <= friction.mu_k <= friction.mu_s
    assert -1 <= start.theta0 <= 1 and -0.5 <= start.omega0 <= 0.5 and abs(start.slip0) <= 0.1


@pytest.mark.parametrize(
    ("make", "name"),
    [
        (lambda: strategies.bodies(min_chi=0.7, max_chi=0.2), "min_chi"),
        (lambda: strategies.bodies(max_km=1.5), "max_km"),
        (lambda: strategies.bodies(chi=0.6, min_km=0.5), "min_km"),
        (lambda: strategies.bodies(chi=math.nan), "min_chi"),
        (lambda: strategies.ramps(max_alpha=40.0), "max_alpha"),
        (lambda: strategies.frictions(min_mu_s=-1.0), "min_mu_s"),
        (lambda: strategies.frictions(min_ratio=1.5), "min_ratio"),
        (lambda: strategies.starts(max_omega0=math.inf), "max_omega0"),
        (lambda: strategies.starts(max_slip0=-1.0), "max_slip0"),
        (lambda: strategies.motion_inputs(max_restitution=2.0), "max_restitution"),
        (lambda: strategies.tracks(max_frames=5), "max_frames"),
    ],
)
def test_a_bad_keyword_is_named(make, name):
    with pytest.raises(ValueError, match=rf"^{name} ") as err:
        make()
    assert len(str(err.value)) < 200


# --- the assertions ---------------------------------------------------------------------------


def test_the_ledger_assertion_says_where_it_fails():
    r = eccjump.simulate(eccjump.Cylinder(0.5, 0.4), math.radians(30), mu_s=1.0, t_max=20.0)
    assert_ledger_closes(r)
    energy = r.energy.copy()
    energy[7:] += 1e-3
    bad = dataclasses.replace(r, energy=energy)
    with pytest.raises(AssertionError, match=rf"E \+ dissipated - E0 = 0.001 at t = {r.t[7]:.9g}"):
        assert_ledger_closes(bad)
    mode = r.mode.copy()
    mode[:] = 1  # sliding the way it turns: friction would push the slip along
    sliding = dataclasses.replace(r, mode=mode, ldot=r.omega + np.sign(r.Fx))
    with pytest.raises(AssertionError, match="friction works along the slip"):
        assert_ledger_closes(sliding)


@pytest.fixture(scope="module")
def region_map() -> eccjump.Region:
    return eccjump.region(np.radians([35.0, 40.0]), [0.15, 0.5], [0.0, 0.1], 1.0)


def test_equal_maps_pass_and_a_changed_point_is_named(region_map):
    assert_maps_equal(eccjump.region(*region_map.coords.values(), 1.0, n_threads=2), region_map)
    theta = region_map.result.theta_J.copy()
    theta[1, 0, 1] = np.nextafter(theta[1, 0, 1], 10.0)  # one ulp
    changed = dataclasses.replace(
        region_map, result=dataclasses.replace(region_map.result, theta_J=theta)
    )
    with pytest.raises(AssertionError) as err:
        assert_maps_equal(changed, region_map)
    line = str(err.value).splitlines()[1]
    assert line.startswith(
        "  fields['theta_J']: 1 of 8 points differ, first at alpha = 0.698132, chi = 0.15, "
        "km_frac = 0.1: "
    )


def test_the_bits_of_nan_and_zero_count():
    a = eccjump.motion_map([0.5], [0.2], [0.0, 0.3], 1.0, t_max=5.0)
    fields = {k: v.copy() for k, v in a.fields.items()}
    floats = next(k for k, v in fields.items() if v.dtype.kind == "f" and np.isnan(v).any())
    assert a == dataclasses.replace(a, fields=fields)
    first = np.unravel_index(np.flatnonzero(np.isnan(fields[floats]))[0], a.shape)
    fields[floats][first] = -fields[floats][first]  # equal by ==, not by its bits
    b = dataclasses.replace(a, fields=fields)
    assert a == b
    with pytest.raises(AssertionError, match=rf"fields\['{floats}'\]: 1 of 2 .*nan \(bits "):
        assert_maps_equal(b, a)
    zero = next(k for k, v in fields.items() if v.dtype.kind == "f" and (v == 0).any())
    fields[zero] = np.where(fields[zero] == 0, -0.0, fields[zero])
    with pytest.raises(AssertionError, match=rf"\['{zero}'\]: .*: -0\.0 != 0\.0"):
        assert_maps_equal(dataclasses.replace(a, fields=fields), a)


def test_maps_of_two_kinds_or_other_settings_differ(region_map):
    motion = eccjump.motion_map(*region_map.coords.values(), 1.0, t_max=5.0)
    with pytest.raises(AssertionError, match="a MotionMap and a Region"):
        assert_maps_equal(motion, region_map)
    other = eccjump.region(*region_map.coords.values(), 0.5)
    with pytest.raises(AssertionError, match=r"maps differ:\n  mu_s: 0.5 != 1.0\n"):
        assert_maps_equal(other, region_map)
    with pytest.raises(TypeError, match="two maps"):
        assert_maps_equal(region_map.result, region_map)  # type: ignore[arg-type]


def test_a_saved_and_loaded_map_is_the_map(region_map, tmp_path):
    back = eccjump.load_map(eccjump.maps.save(region_map, tmp_path / "m.npz"))
    assert_maps_equal(back, region_map)

"""Units that cannot be mixed up (issue 49 item 1): every entry point that takes a ramp angle
refuses a scalar that cannot be radians of [0, pi/2] (naming radians and ``math.radians``),
and where an array's invalid points are the contract, warns once when its values look like
degrees; ``km=`` to a map, in any call form, is the TypeError that explains km_frac. The
command line's side (a degree option that looks like radians) is in test_cli_hardening.py."""

from __future__ import annotations

import math
import warnings

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st

import eccjump
from eccjump._base.units import AngleUnitWarning

BODY = eccjump.Cylinder(0.15, 0.02)
#: Every entry point with a ramp angle, called with ``a`` as that angle.
SCALAR_CALLS = {
    "jarm": lambda a: eccjump.jarm(a, 0.15, 0.02, 1.0),
    "region": lambda a: eccjump.region(a, [0.15], [0.1], 1.0),
    "motion_map": lambda a: eccjump.motion_map(a, [0.15], [0.1], 1.0, t_max=1.0),
    "motion_points": lambda a: eccjump.motion_points(a, 0.15, 0.02, 1.0, t_max=1.0),
    "mu_s_min_path": lambda a: eccjump.mu_s_min_path(a, 0.15, 0.02),
    "alpha_interval_around": lambda a: eccjump.alpha_interval_around(a, 0.15, 0.02, 1.0),
    "uncertainty": lambda a: eccjump.uncertainty(BODY, a, 1.0, n=4),
    "design": lambda a: eccjump.design([0.1, a], 0.6, 0.1, grid=4),
    "roll": lambda a: eccjump.roll(BODY, a, mu_s=1.0),
    "simulate": lambda a: eccjump.simulate(BODY, a, mu_s=1.0, t_max=1.0),
    "closed_form.theta_nJ": lambda a: eccjump.closed_form.theta_nJ(a, 0.15, 0.02),
}
#: The entry points whose array input marks a point invalid (the warning's place).
ARRAY_CALLS = {
    "jarm": lambda a: eccjump.jarm(a, 0.15, 0.02, 1.0),
    "region": lambda a: eccjump.region(a, [0.15], [0.1], 1.0),
    "motion_map": lambda a: eccjump.motion_map(a, [0.15], [0.1], 1.0, t_max=1.0),
    "motion_points": lambda a: eccjump.motion_points(a, 0.15, 0.02, 1.0, t_max=1.0),
    "mu_s_min_path": lambda a: eccjump.mu_s_min_path(a, 0.15, 0.02),
    "alpha_interval_around": lambda a: eccjump.alpha_interval_around(a, 0.15, 0.02, 1.0),
}


@pytest.mark.parametrize("name", sorted(SCALAR_CALLS))
@pytest.mark.parametrize("value", [40.0, 2.0, -0.1, math.nan, np.float64(66.0)])
def test_a_scalar_ramp_angle_out_of_range_is_an_error_that_says_radians(name, value):
    with pytest.raises(ValueError) as err:
        SCALAR_CALLS[name](value)
    message = str(err.value)
    param = "seed" if name == "alpha_interval_around" else "alpha"
    assert param in message and "rad" in message and "math.radians" in message, message
    assert len(message) <= 200


def test_jarm_of_a_scalar_in_degrees_is_no_longer_a_silent_invalid_point():
    """The issue's reproducer: ``jarm(40, ...)`` returned JarmResult(INVALID_PARAMS)."""
    with pytest.raises(ValueError, match=r"alpha = 40 .*\[0, pi/2\] rad.*math\.radians"):
        eccjump.jarm(40, 0.15, 0.02, 1.0)
    assert bool(eccjump.jarm(math.radians(40), 0.15, 0.02, 1.0).is_jarm)


@pytest.mark.parametrize("name", sorted(ARRAY_CALLS))
def test_an_array_in_degrees_warns_once_and_keeps_its_invalid_points(name):
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        ARRAY_CALLS[name]([40.0, 0.7, 66.0])
    ours = [w for w in seen if issubclass(w.category, AngleUnitWarning)]
    assert len(ours) == 1, [str(w.message) for w in seen]
    message = str(ours[0].message)
    assert "alpha" in message or "seed" in message
    assert "radians" in message and "math.radians" in message and len(message) <= 200
    assert issubclass(ours[0].category, UserWarning)
    assert ours[0].filename == __file__  # it points at the user's call


def test_the_warned_points_stay_invalid_and_the_others_are_computed():
    with pytest.warns(AngleUnitWarning):
        r = eccjump.jarm([40.0, math.radians(40)], 0.15, 0.02, 1.0)
    assert [eccjump.Reason(int(c)).name for c in r.reason] == ["INVALID_PARAMS", "JARM"]


@settings(max_examples=50, deadline=None)
@given(
    st.lists(st.floats(0.0, math.pi / 2), min_size=1, max_size=6),
    st.lists(st.floats(math.pi / 2, 90.0, exclude_min=True), max_size=3),
    st.lists(st.sampled_from([-1.0, 91.0, 1e6, math.nan, math.inf]), max_size=2),
)
def test_the_warning_comes_exactly_when_values_look_like_degrees(radians, degrees, other):
    """Radians in range never warn; values in (pi/2, 90] always do, once; other invalid
    values (negative, above 90, NaN) are invalid points without the warning."""
    alpha = np.array(radians + degrees + other)
    with warnings.catch_warnings(record=True) as seen:
        warnings.simplefilter("always")
        r = eccjump.jarm(alpha, 0.15, 0.02, 1.0)
    ours = [w for w in seen if issubclass(w.category, AngleUnitWarning)]
    assert len(ours) == (1 if degrees else 0)
    invalid = r.reason == eccjump.Reason.INVALID_PARAMS
    assert not invalid[: len(radians)].any() and invalid[len(radians) :].all()


def test_radians_in_range_never_warn():
    with warnings.catch_warnings():
        warnings.simplefilter("error", AngleUnitWarning)
        for call in ARRAY_CALLS.values():
            call(np.radians([0.0, 40.0, 90.0]))


MAPS = {
    "region": eccjump.region,
    "motion_map": eccjump.motion_map,
    "region_dataset": eccjump.region_dataset,
}


@pytest.mark.parametrize("name", sorted(MAPS))
@pytest.mark.parametrize("form", ["km alone", "km and km_frac", "positional and km"])
def test_km_on_a_map_explains_km_frac_in_any_call_form(name, form):
    """``region(alpha=a, chi=c, km=k, mu_s=1)`` said "missing 1 required positional argument:
    'km_frac'"; only km= beside km_frac= explained."""
    if name == "region_dataset":
        pytest.importorskip("xarray")
    fn, a, c = MAPS[name], [0.7], [0.15]
    with pytest.raises(TypeError, match=r"km is the body's k_m; a map's axis is km_frac"):
        if form == "km alone":
            fn(alpha=a, chi=c, km=[0.1], mu_s=1.0)
        elif form == "km and km_frac":
            fn(alpha=a, chi=c, km_frac=[0.1], km=[0.1], mu_s=1.0)
        else:
            fn(a, c, [0.1], 1.0, km=0.1)


def test_km_none_is_still_the_default():
    assert eccjump.region([0.7], [0.15], [0.1], 1.0, km=None).result.shape == (1, 1, 1)

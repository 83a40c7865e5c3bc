"""The body model: derived inertias against the geometry, constructors, validation."""

import math
import pickle

import pytest
from hypothesis import assume, given
from hypothesis import strategies as st

from eccjump import Cylinder, Units
from eccjump.testing.strategies import bodies


@given(bodies())
def test_inertia_from_the_shell_plus_line_geometry(b):
    chi, km = b.chi, b.km
    # Independent route: I_C = m_C R^2 + m_P (d + s)^2 with s = km chi R / (1 - km); the line
    # sits at distance chi/(1 - km) from C (or at C when chi = 0).
    r_line = 0.0 if chi == 0 else chi / max(1.0 - km, chi)
    assert b.Ic == pytest.approx(km + (1 - km) * r_line**2, rel=1e-12, abs=1e-15)
    assert b.Icm == pytest.approx(b.Ic - chi**2, rel=1e-9, abs=1e-12)
    assert chi**2 - 1e-15 <= b.Ic <= 1.0 + 1e-15
    assert b.Icm >= 0.0


@given(bodies(), st.floats(0.1, 10.0), st.floats(0.01, 3.0))
def test_from_inertia_and_from_shell_and_line_round_trip(b, M, R):
    chi, km = b.chi, b.km
    assume(1.0 - km >= chi)  # 1 - (1 - chi) can round below chi at km = 1 - chi
    c = Cylinder.from_inertia(M, R, chi * R, b.Ic * M * R * R)
    assert c.chi == pytest.approx(chi, abs=1e-12)
    assert c.Ic == pytest.approx(b.Ic, rel=1e-12, abs=1e-14)
    s = Cylinder.from_shell_and_line(km * M, (1 - km) * M, R, chi * R)
    assert s.km == pytest.approx(km, abs=1e-12)
    assert s.chi == pytest.approx(chi, abs=1e-12)


def test_gamma_is_the_papers_dega2():
    chi, km = 0.5, 0.4
    printed = (km**2 + 2 * km * chi - chi**2 - 2 * chi - 1) / (4 * math.pi * (km - 1) * chi)
    assert Cylinder(chi, km).gamma == pytest.approx(printed, rel=1e-14)


def test_limits():
    assert Cylinder(0.0, 1.0).Ic == 1.0
    assert math.isinf(Cylinder(0.0, 0.3).gamma)
    point = Cylinder(1.0, 0.0)
    assert (point.Ic, point.Icm) == (1.0, 0.0)
    assert Cylinder(0.9, 0.1).km == 0.1  # 1 - 0.9 < 0.1 in binary: still the boundary


def test_frozen_hashable_picklable():
    b = Cylinder(0.15, 0.02)
    assert pickle.loads(pickle.dumps(b)) == b
    assert hash(b) == hash(Cylinder(0.15, 0.02))
    assert len({b, Cylinder(0.15, 0.02), Cylinder(0.2, 0.02)}) == 2
    with pytest.raises(AttributeError):
        b.chi = 0.3  # type: ignore[misc]
    assert "chi=0.15" in repr(b)


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((1.5, 0.0), "chi"),
        ((-0.1, 0.0), "chi"),
        ((math.nan, 0.0), "chi"),
        ((0.5, 0.6), "km"),
        ((0.5, math.inf), "km"),
        ((0.5, -1e-3), "km"),
    ],
)
def test_invalid_bodies_name_the_parameter(args, name):
    with pytest.raises(ValueError, match=rf"^{name} = .* allowed range"):
        Cylinder(*args)


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((1.0, 1.0, 0.5, 0.2), "I_C"),  # below M d^2
        ((1.0, 1.0, 0.5, 1.2), "I_C"),  # above M R^2
        ((1.0, 1.0, 1.5, 0.5), "d"),
        ((0.0, 1.0, 0.5, 0.5), "M"),
        ((1.0, -1.0, 0.5, 0.5), "R"),
    ],
)
def test_impossible_inertia(args, name):
    with pytest.raises(ValueError, match=name):
        Cylinder.from_inertia(*args)


def test_units_scale_factors():
    u = Units(g=9.81, R=0.2, M=3.0)
    assert u.time == pytest.approx(math.sqrt(0.2 / 9.81))
    assert u.force == pytest.approx(3.0 * 9.81)
    assert u.rate * u.time == pytest.approx(1.0)
    with pytest.raises(ValueError, match="R"):
        Units(R=0.0)

"""One map type: JARM maps and motion maps answer the same questions the same way
(``eccjump.Map``: coords, fields, shape, fraction, to_xarray); ``maps.save`` writes either
and ``load_map`` reads it back as its own type."""

from __future__ import annotations

import numpy as np
import pytest

import eccjump
from eccjump import Map, MotionMap, Region


@pytest.fixture(scope="module")
def both() -> dict[str, Map]:
    alpha, chi, km_frac = np.radians([30.0, 45.0, 60.0]), [0.1, 0.3], [0.02, 0.1]
    return {
        "jarm": eccjump.region(alpha, chi, km_frac, 2.0),
        "motion": eccjump.motion_map(alpha, chi, km_frac, 2.0, t_max=20.0),
    }


@pytest.mark.parametrize("kind", ["jarm", "motion"])
def test_the_shared_interface(both, kind):
    m = both[kind]
    assert isinstance(m, Map) and m.kind == kind
    assert list(m.coords) == ["alpha", "chi", "km_frac"]
    assert m.shape == (3, 2, 2)
    assert all(np.shape(v) == m.shape for v in m.fields.values())
    # fraction: the share of grid points that are a JARM, by the kind's own JARM field
    jarm = np.asarray(m.fields[m.jarm_field], dtype=bool)
    assert m.fraction() == jarm.sum() / 12


def test_both_kinds_agree_on_which_points_are_jarm(both):
    """The same grid, the same start, the paper's rule: the motion map's first lift-off
    straight out of rolling is the JARM classification (the routes are independent: closed
    form against integration)."""
    assert np.array_equal(both["jarm"].fields["is_jarm"], both["motion"].fields["jarm"])
    assert both["jarm"].fraction() == both["motion"].fraction() > 0


@pytest.mark.parametrize("suffix", [".npz", ".nc"])
@pytest.mark.parametrize("kind", ["jarm", "motion"])
def test_save_and_load_map_round_trip(both, kind, suffix, tmp_path):
    pytest.importorskip("xarray")
    m = both[kind]
    path = eccjump.maps.save(m, tmp_path / f"m{suffix}")
    back = eccjump.load_map(path)
    assert type(back) is type(m)
    assert {k: v.tolist() for k, v in back.coords.items()} == {
        k: v.tolist() for k, v in m.coords.items()
    }
    for name, values in m.fields.items():
        np.testing.assert_array_equal(back.fields[name], values, err_msg=name)


def test_to_xarray_has_the_same_dims(both):
    pytest.importorskip("xarray")
    for m in both.values():
        ds = m.to_xarray()
        field = next(iter(m.fields))
        assert ds[field].dims == tuple(m.coords)


def test_load_map_refuses_a_swept_jarm_file_naming_it(tmp_path):
    pytest.importorskip("xarray")
    ds = eccjump.region([0.5], [0.2], [0.3], [0.8, 1.0], output="xarray")
    path = eccjump.store.save(ds, tmp_path / "swept.nc")
    with pytest.raises(ValueError, match=r"swept\.nc.*open_dataset"):
        eccjump.load_map(path)


def test_region_and_motion_map_take_the_grid_then_mu_s_positionally():
    r = eccjump.region([0.5], [0.2], [0.3], 1.0)
    m = eccjump.motion_map([0.5], [0.2], [0.3], 1.0)
    assert isinstance(r, Region) and isinstance(m, MotionMap)
    with pytest.raises(TypeError, match="km_frac"):
        eccjump.motion_map([0.5], [0.2], mu_s=1.0, km=[0.1])

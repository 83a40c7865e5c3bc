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
    ds = eccjump.region_dataset([0.5], [0.2], [0.3], [0.8, 1.0])
    path = eccjump.store.save(ds, tmp_path / "swept.nc")
    with pytest.raises(ValueError, match=r"swept\.nc.*open_dataset"):
        eccjump.load_map(path)


def test_region_and_motion_map_take_the_grid_then_mu_s_positionally():
    r = eccjump.region([0.5], [0.2], [0.3], 1.0)
    m = eccjump.motion_map([0.5], [0.2], [0.3], 1.0)
    assert isinstance(r, Region) and isinstance(m, MotionMap)
    with pytest.raises(TypeError, match="km_frac"):
        eccjump.motion_map([0.5], [0.2], mu_s=1.0, km=[0.1])


# --- issue 46, 13: maps survive a save and a load, and compare ----------------------------

SUFFIXES = (".npz", ".nc", ".zarr")


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_map_of_eccjump_map_can_be_saved_again(tmp_path, suffix):
    """Its loaded ``attrs['alpha_done']`` (an array of bools, which netCDF cannot store as an
    attribute) goes back to the variable it came from, in every format."""
    pytest.importorskip("xarray")
    from fuzz_cases import run_cli_inprocess

    first = tmp_path / "first.zarr"
    argv = ["map", "--mu-s", "1", "--grid", "3", "--chunk", "1", "--stop-after", "2", "-q"]
    assert run_cli_inprocess([*argv, "-o", str(first)])[0] == 130  # 2 of 3 slices
    loaded = eccjump.load_map(first)
    assert loaded.attrs["alpha_done"].tolist() == [True, True, False]
    again = eccjump.maps.save(loaded, tmp_path / f"again{suffix}")
    back = eccjump.load_map(again)
    assert back == loaded and back.attrs["alpha_done"].tolist() == [True, True, False]


def test_motion_maps_compare_field_by_field(both):
    m = both["motion"]
    same = eccjump.motion_map(*m.coords.values(), 2.0, t_max=20.0)
    assert m == same and not (m != same)  # NaN fields equal NaN
    assert np.isnan(m.fields["slip_t"]).any()
    other = eccjump.motion_map(*m.coords.values(), 2.0, t_max=10.0)
    assert m != other and m != both["jarm"]
    with pytest.raises(TypeError, match="unhashable"):
        hash(m)


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_motion_map_is_equal_after_save_and_load(both, tmp_path, suffix):
    """``scalars['mu_k']`` None (mu_k = mu_s) came back as mu_s's value."""
    pytest.importorskip("xarray")
    m = both["motion"]
    assert m.scalars["mu_k"] is None
    back = eccjump.load_map(eccjump.maps.save(m, tmp_path / f"m{suffix}"))
    assert back.scalars["mu_k"] is None and back == m
    given = eccjump.motion_map(*m.coords.values(), 2.0, mu_k=2.0, t_max=20.0)
    back = eccjump.load_map(eccjump.maps.save(given, tmp_path / f"k{suffix}"))
    assert back.scalars["mu_k"] == 2.0 and back == given


def test_a_third_kind_of_map_needs_no_change_to_the_map_layer(tmp_path, monkeypatch):
    """What ``maps/kinds.py`` tells a newcomer: a kind (``register(MapKind(...))``) and a
    result class (``class M(Map, kind=...)`` with ``to_layout``/``from_layout``) are all a
    kind needs for ``maps.save``, the checks, ``maps.load`` and ``to_xarray``."""
    from dataclasses import dataclass

    from eccjump.maps import kinds

    monkeypatch.setattr(kinds, "KINDS", dict(kinds.KINDS))  # leave the registries as found
    monkeypatch.setattr(Map, "_classes", dict(Map._classes))
    dtypes, fill = {"hit": np.dtype(bool)}, {"hit": False}
    axes = (("alpha", "alpha"),)
    toy = kinds.register(
        kinds.MapKind("toy", ("hit",), dtypes, fill, lambda _: {}, (), axes, (), {})
    )

    @dataclass(frozen=True, eq=False)
    class ToyMap(Map, kind=toy):
        jarm_field = "hit"  # no annotation: a class attribute, not a field
        alpha: np.ndarray
        hit: np.ndarray

        @property
        def coords(self):
            return {"alpha": self.alpha}

        @property
        def fields(self):
            return {"hit": self.hit}

        def to_layout(self):
            coords = {"alpha": (("alpha",), self.alpha, {})}
            attrs = {"kind": "toy", "eccjump_version": "0"}
            return {
                "coords": coords,
                "data_vars": {"hit": (("alpha",), self.hit, {})},
                "attrs": attrs,
            }

        @classmethod
        def from_layout(cls, lay, source):
            return cls(lay["coords"]["alpha"][1], lay["data_vars"]["hit"][1])

    m = ToyMap(np.array([0.1, 0.2, 0.3]), np.array([True, False, True]))
    back = eccjump.load_map(eccjump.maps.save(m, tmp_path / "toy.npz"))
    assert type(back) is ToyMap and back.kind == "toy" and back.fraction() == 2 / 3
    assert back.hit.tolist() == [True, False, True] and back.alpha.tolist() == [0.1, 0.2, 0.3]
    with pytest.raises(ValueError, match=r"toy.*registered already"):
        kinds.register(toy._replace(fields=()))
    with pytest.raises(TypeError, match=r"toy.*class already"):
        type("Other", (Map,), {}, kind=toy)
    # the kind has no invalid mark: a coordinate out of its range has valid points
    with pytest.raises(ValueError, match=r"coordinate alpha = 2 \(above 1.5708\)"):
        eccjump.maps.save(ToyMap(np.array([2.0]), np.array([True])), tmp_path / "bad.npz")
    if pytest.importorskip("xarray"):
        assert m.to_xarray().hit.dims == ("alpha",)

"""Every result travels (issue 49 item 2): to xarray with units, to pandas, to a file and back
with ``eccjump.load`` as its own type, bit for bit; files that are no result are refused
naming the file, and no file of the user's is replaced or lost."""

from __future__ import annotations

import json
import math
from pathlib import Path

import numpy as np
import pytest
from hypothesis import given, settings
from hypothesis import strategies as st
from reference_points import JARM_BODY

import eccjump
from eccjump._base import records
from eccjump.maps import results, store

pytest.importorskip("xarray")
try:
    store.netcdf_engine()
except ImportError:  # pragma: no cover
    pytest.skip("no netCDF engine (h5netcdf or netCDF4)", allow_module_level=True)

FEW = settings(max_examples=4, deadline=None, database=None)
SUFFIXES = st.sampled_from([".nc", ".json"])


def bits(obj: object) -> tuple[str, dict[str, tuple[str, tuple[int, ...], bytes]]]:
    """The fields of a result as its file holds them: the tree as JSON text (floats exact,
    -0.0 and NaN kept) and every array's dtype, shape and bytes."""
    arrays: dict[str, np.ndarray] = {}
    tree = records.encode(obj, arrays, "", getattr(obj, "_unsaved", ()))
    raw = {k: (a.dtype.str, a.shape, a.tobytes()) for k, a in arrays.items()}
    return json.dumps(tree), raw


def round_trip(obj: object, tmp_path: Path, suffix: str) -> object:
    path = tmp_path / f"result{suffix}"
    obj.save(path, overwrite=True)  # type: ignore[attr-defined]
    back = eccjump.load(path)
    assert type(back) is type(obj)
    assert bits(back) == bits(obj)
    return back


@st.composite
def bodies(draw: st.DrawFn) -> eccjump.Cylinder:
    """Bodies with some inertia about the centre of mass (simulate's impact law needs it)."""
    chi = draw(st.floats(0.01, 0.9))
    return eccjump.Cylinder(chi, draw(st.floats(0.01, 1.0 - chi)))


@FEW
@given(bodies(), st.floats(0.05, 1.5), st.none() | st.floats(0.1, 2.0), st.booleans(), SUFFIXES)
def test_a_roll_comes_back_bit_for_bit(tmp_path_factory, body, alpha, mu_s, si, suffix):
    run = eccjump.roll(body, alpha, mu_s=mu_s, t_max=20.0)
    run = run.to_si(R=0.05) if si else run
    assert round_trip(run, tmp_path_factory.mktemp("r"), suffix) == run


@FEW
@given(bodies(), st.floats(0.1, 1.2), st.floats(0.2, 1.5), st.sampled_from([0.0, 1.0]), SUFFIXES)
def test_a_motion_comes_back_bit_for_bit(tmp_path_factory, body, alpha, mu_s, e, suffix):
    run = eccjump.simulate(body, alpha, mu_s=mu_s, restitution=e, t_max=8.0, sensitivities=e == 0)
    assert round_trip(run, tmp_path_factory.mktemp("m"), suffix) == run


shapes = st.sampled_from([(), (1,), (3,), (2, 2), (0,)])


@FEW
@given(shapes, st.booleans(), SUFFIXES)
def test_jarm_points_come_back_bit_for_bit(tmp_path_factory, shape, derivatives, suffix):
    alpha = np.linspace(0.3, 1.2, math.prod(shape)).reshape(shape)
    res = eccjump.jarm(alpha, 0.15, 0.02, 1.0, derivatives=derivatives)
    assert round_trip(res, tmp_path_factory.mktemp("j"), suffix) == res


@FEW
@given(shapes, SUFFIXES)
def test_motion_points_come_back_bit_for_bit(tmp_path_factory, shape, suffix):
    alpha = np.linspace(0.3, 1.2, math.prod(shape)).reshape(shape)
    res = eccjump.motion_points(alpha, 0.5, 0.4, 1.0, t_max=8.0)
    assert round_trip(res, tmp_path_factory.mktemp("p"), suffix) == res


def test_a_design_and_an_analysis_come_back_bit_for_bit(tmp_path):
    from eccjump.studies.experiment.synthetic import synthetic_track

    d = eccjump.design((0.3, 0.9), 0.8, radius=0.05, mass=0.2, tolerances={"mu_s": 0.05})
    assert round_trip(d, tmp_path, ".json") == d
    body = eccjump.Cylinder(0.1, 0.3)
    st_ = synthetic_track(body, 0.2, mu_s=1.0, fps=240.0, duration=0.3, seed=1)
    a = eccjump.analyze(st_.track, radius=0.05, chi=0.1, km=0.3, alpha=0.2, profile_mu_k=False)
    for suffix in (".nc", ".json"):
        assert round_trip(a, tmp_path, suffix).to_dict() == a.to_dict()  # type: ignore[attr-defined]


def test_load_reads_maps_and_uncertainty_studies_as_their_type(tmp_path):
    reg = eccjump.region([0.5, 0.7], [0.2], [0.1], 1.0)
    mm = eccjump.motion_map([0.5, 0.7], [0.2, 0.5], 0.4, mu_s=[0.5, 1.0], t_max=5.0)
    u = eccjump.uncertainty(eccjump.Cylinder(*JARM_BODY), 0.7, 1.0, sd={"chi": 0.01}, n=20)
    for obj, suffixes in ((reg, (".npz", ".nc")), (mm, (".nc",)), (u, (".nc", ".csv"))):
        for suffix in suffixes:
            path = obj.save(tmp_path / f"{type(obj).__name__}{suffix}")  # type: ignore[attr-defined]
            back = eccjump.load(path)
            assert type(back) is type(obj) and back == obj


def test_a_dense_solution_is_not_saved(tmp_path):
    run = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0, dense_output=True)
    back = eccjump.load(run.save(tmp_path / "r.nc"))
    assert back.sol is None and bits(back) == bits(run)


def results_of_every_kind() -> list[object]:
    body = eccjump.Cylinder(*JARM_BODY)
    return [
        eccjump.roll(body, 0.7, mu_s=1.0),
        eccjump.roll(body, 0.7, mu_s=1.0).to_si(R=0.1),
        eccjump.simulate(eccjump.Cylinder(0.5, 0.4), 0.5, mu_s=1.0, t_max=9.0, sensitivities=True),
        eccjump.jarm([0.5, 0.7], 0.2, 0.1, 1.0, derivatives=True),
        eccjump.motion_points([0.5, 0.7], 0.5, 0.4, 1.0, t_max=8.0),
        eccjump.region([0.5, 0.7], [0.2], [0.1], 1.0),
        eccjump.motion_map([0.5, 0.7], 0.5, 0.4, mu_s=[0.5, 1.0], mu_k=[0.2, 0.4], t_max=5.0),
    ]


def test_every_series_and_coordinate_has_units():
    for obj in results_of_every_kind():
        ds = obj.to_xarray()  # type: ignore[attr-defined]
        numeric = [k for k, v in ds.variables.items() if v.dtype.kind in "fiu" and v.ndim]
        counts = ("segment_nfev", "d_transitions")  # a count; units per parameter
        missing = [k for k in numeric if k not in counts and "units" not in ds[k].attrs]
        assert not missing, f"{type(obj).__name__}: no units on {missing}"
        assert all("units" in ds[k].attrs for k in ds.coords if ds[k].dtype.kind == "f")


def test_si_results_say_si_units():
    run = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    assert run.to_xarray()["t"].attrs["units"] == "sqrt(R/g)"
    assert run.to_si(R=0.1).to_xarray()["t"].attrs["units"] == "s"


def test_tables_are_one_call_away():
    run = eccjump.simulate(eccjump.Cylinder(0.5, 0.4), 0.5, mu_s=1.0, t_max=9.0)
    series = run.to_dataframe()
    assert len(series) == run.t.size and series.attrs["units"]["theta"] == "rad"
    assert list(run.to_dataframe("transitions")["transition_to_mode"]) == run.mode_names()
    with pytest.raises(ValueError, match="table"):
        run.to_dataframe("frames")
    roll = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0).to_dataframe()
    assert roll.index.name == "t" and roll.attrs["units"]["Fy"] == "M g"
    points = eccjump.motion_points(np.full((2, 3), 0.6), 0.5, 0.4, 1.0, t_max=5.0)
    assert len(points.to_dataframe()) == 6
    assert len(eccjump.jarm(0.7, 0.2, 0.1, 1.0).to_dataframe()) == 1


def test_a_file_that_is_no_result_is_refused_naming_it(tmp_path):
    foreign = {"a.json": '{"a": 1}', "b.json": "not json", "c.json": "[]"}
    for name, text in foreign.items():
        (tmp_path / name).write_text(text)
    import xarray as xr

    xr.Dataset({"a": ("x", [1, 2])}).to_netcdf(tmp_path / "d.nc")
    for name in (*foreign, "d.nc"):
        with pytest.raises(ValueError, match=f"path: .*{name}") as err:
            eccjump.load(tmp_path / name)
        assert len(str(err.value)) <= 200
    with pytest.raises(ValueError, match="suffix"):
        eccjump.load(tmp_path / "x.txt")


def test_no_file_of_the_users_is_replaced_or_lost(tmp_path, monkeypatch):
    run = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    mine = tmp_path / "mine.json"
    mine.write_text("my notes")
    with pytest.raises(ValueError, match="overwrite=True"):
        run.save(mine)
    assert mine.read_text() == "my notes"

    def broken(*args: object) -> None:
        raise OSError(28, "No space left on device")

    monkeypatch.setattr(results, "_write", broken)
    with pytest.raises(OSError, match=r"mine\.json"):
        run.save(mine, overwrite=True)
    assert mine.read_text() == "my notes"
    assert [p.name for p in tmp_path.iterdir()] == ["mine.json"]  # no temporary file left


def test_save_writes_no_json_that_load_would_refuse_as_too_large(tmp_path, monkeypatch):
    monkeypatch.setattr(results, "MAX_BYTES", 1000)
    run = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    with pytest.raises(ValueError, match=r"path: .*save it as \.nc"):
        run.save(tmp_path / "big.json")
    assert not list(tmp_path.iterdir())


def test_a_damaged_netcdf_result_is_refused_not_read_as_numbers(tmp_path):
    run = eccjump.roll(eccjump.Cylinder(*JARM_BODY), 0.7, mu_s=1.0)
    path = run.save(tmp_path / "run.nc")
    data = bytearray(path.read_bytes())
    data[data.find(run.theta.tobytes()) + 100] ^= 0x10
    path.write_bytes(bytes(data))
    with pytest.raises(ValueError, match=r"run\.nc"):
        eccjump.load(path)

"""``eccjump map --kind motion``: every format holds exactly ``motion_map(...)``, an
interrupted .zarr map resumes to the uninterrupted result, the kinds are never mixed, and the
summary counts the sequences."""

from __future__ import annotations

import re
from pathlib import Path

import numpy as np
import pytest

from eccjump.classification import load as load_region
from eccjump.cli import main
from eccjump.motion import maps as motion_maps
from eccjump.motion.fields import FIELDS, sequence_name

MOTION = ("map", "--kind", "motion", "--mu-s", "0.8", "--restitution", "0.3", "--grid", "8")


@pytest.fixture(scope="module")
def reference() -> motion_maps.MotionMap:
    # The motion kind's default axes: chi up to 0.99 and km_frac from 0.01 (k_m > 0).
    chi, frac = np.linspace(0.0, 0.99, 8), np.linspace(0.01, 1.0, 8)
    m = motion_maps.motion_map(
        alpha=np.radians(np.linspace(0.0, 90.0, 8)),
        chi=chi,
        km_frac=frac,
        mu_s=0.8,
        restitution=0.3,
    )
    assert isinstance(m, motion_maps.MotionMap)
    return m


def assert_same(a: motion_maps.MotionMap, b: motion_maps.MotionMap) -> None:
    for k in ("alpha", "chi", "km_frac"):
        assert a.coords[k].tobytes() == b.coords[k].tobytes(), k
    for f in FIELDS:
        assert a.fields[f].dtype == b.fields[f].dtype and a.fields[f].shape == b.fields[f].shape
        assert a.fields[f].tobytes() == b.fields[f].tobytes(), f


def run(tmp_path: Path, name: str, *args: str) -> tuple[int, Path]:
    path = tmp_path / name
    return main([*MOTION, "-o", str(path), "-q", *args]), path


@pytest.mark.parametrize("suffix", [".npz", ".nc", ".zarr"])
def test_each_format_holds_the_map(tmp_path, reference, suffix, capsys):
    if suffix != ".npz":
        pytest.importorskip("xarray")
    code, path = run(tmp_path, "m" + suffix)
    assert code == 0
    m = motion_maps.load(str(path))
    assert_same(m, reference)
    assert m.scalars["mu_s"] == 0.8 and m.scalars["restitution"] == 0.3
    out = capsys.readouterr().out
    top_code, (name, count) = next(iter(reference.sequences().items()))
    assert re.search(rf"^  {re.escape(name or '(not run)')}\s+[\d.]+ \({count}\)$", out, re.M)
    assert sequence_name(top_code) == name
    with pytest.raises(ValueError, match="motion map"):
        load_region(path)  # a JARM loader refuses a motion map, naming it


def test_interrupted_zarr_resumes_to_the_same_map(tmp_path, reference):
    pytest.importorskip("zarr")
    code, path = run(tmp_path, "m.zarr", "--chunk", "3", "--stop-after", "1")
    assert code == 130
    partial = motion_maps.load(str(path))
    assert (partial.status[3:] == motion_maps.INVALID).all()  # fill values where not run
    code, _ = run(tmp_path, "m.zarr", "--resume")
    assert code == 0
    assert_same(motion_maps.load(str(path)), reference)


def test_kinds_and_options_are_never_mixed_on_resume(tmp_path, capsys):
    pytest.importorskip("zarr")
    code, path = run(tmp_path, "m.zarr", "--chunk", "3", "--stop-after", "1")
    assert code == 130
    code = main(["map", "--mu-s", "0.8", "--grid", "8", "-o", str(path), "-q", "--resume"])
    assert code == 2
    assert "holds a motion map" in capsys.readouterr().err
    code = main([*MOTION, "--restitution", "0.5", "-o", str(path), "-q", "--resume"])
    assert code == 2
    assert "restitution: store 0.3, now 0.5" in capsys.readouterr().err
    code = main([*MOTION, "--integrator", "DOP853", "-o", str(path), "-q", "--resume"])
    assert code == 2
    assert "integrator: store 'RK45', now 'DOP853'" in capsys.readouterr().err


def test_the_integrator_reaches_the_map_and_is_recorded(tmp_path):
    code, path = run(tmp_path, "d.npz", "--integrator", "DOP853")
    assert code == 0
    m = motion_maps.load(str(path))
    assert m.options["integrator"] == "DOP853"
    ref = motion_maps.motion_map(
        alpha=np.radians(np.linspace(0.0, 90.0, 8)),
        chi=np.linspace(0.0, 0.99, 8),
        km_frac=np.linspace(0.01, 1.0, 8),
        mu_s=0.8,
        restitution=0.3,
        integrator="DOP853",
    )
    assert isinstance(ref, motion_maps.MotionMap)
    assert_same(m, ref)


def test_jarm_options_are_refused_for_motion(tmp_path, capsys):
    assert main([*MOTION, "--route", "ode", "-o", str(tmp_path / "x.npz")]) == 2
    assert "--route" in capsys.readouterr().err


def test_figure_of_the_sequences(tmp_path):
    pytest.importorskip("matplotlib")
    import matplotlib

    matplotlib.use("Agg")
    code, _ = run(tmp_path, "m.npz", "--figure", str(tmp_path / "m.png"))
    assert code == 0 and (tmp_path / "m.png").stat().st_size > 10_000


def test_a_jarm_map_is_not_loaded_as_a_motion_map(tmp_path):
    path = tmp_path / "j.npz"
    assert main(["map", "--mu-s", "1", "--grid", "3", "-o", str(path), "-q"]) == 0
    with pytest.raises(ValueError, match="JARM map"):
        motion_maps.load(str(path))


def test_the_default_grid_has_no_invalid_point(reference):
    # Before, the default axes held k_m = 0 (chi = 1, km_frac = 0): 4.9 % of a 40^3 map.
    assert not (reference.status == motion_maps.INVALID).any()

"""Labelled maps, map files and ``eccjump map``: every format holds exactly ``region(...)``,
interrupted maps resume to the uninterrupted result, the summary is right, and ``.npz``
needs neither xarray nor zarr."""

from __future__ import annotations

import os
import re
import signal
import subprocess
import sys
import time
from pathlib import Path

import numpy as np
import pytest

import eccjump
from eccjump import store
from eccjump.classification import FIELDS, Reason, region
from eccjump.cli import main

xr = pytest.importorskip("xarray")

MU_S = 0.7
GRID = ("--grid", "20")


def grid(n: int = 20, na: int | None = None):
    """The axes of `eccjump map` with default ranges."""
    return {
        "alpha": np.radians(np.linspace(0.0, 90.0, na or n)),
        "chi": np.linspace(0.0, 1.0, n),
        "km": np.linspace(0.0, 1.0, n),
    }


def assert_same(a, b) -> None:
    """Bit-identical results (NaNs compared by bytes) and coordinates."""
    for name in ("alpha", "chi", "km_frac"):
        assert getattr(a, name).tobytes() == getattr(b, name).tobytes(), name
    for f in FIELDS:
        x, y = getattr(a.result, f), getattr(b.result, f)
        assert x.dtype == y.dtype and x.shape == y.shape, f
        assert x.tobytes() == y.tobytes(), f


@pytest.fixture(scope="module")
def reference():
    return region(MU_S, **grid())


def run_map(tmp_path: Path, name: str, *args: str) -> tuple[int, Path]:
    path = tmp_path / name
    return main(["map", "--mu-s", str(MU_S), *GRID, "-o", str(path), "-q", *args]), path


# --- labelled results ---------------------------------------------------------------


def test_to_xarray_labels_units_and_reason_table():
    reg = region(MU_S, 2, **grid(5))
    ds = reg.to_xarray()
    assert ds.is_jarm.dims == ("alpha", "chi", "km_frac")
    assert ds.alpha.attrs["units"] == "rad"
    np.testing.assert_array_equal(ds.alpha_deg, np.linspace(0, 90, 5))
    np.testing.assert_array_equal(ds.km, reg.km)
    assert ds.km.dims == ("chi", "km_frac")
    assert ds.attrs["mu_s"] == MU_S and ds.attrs["n"] == 2 and ds.attrs["rule"] == "paper"
    assert ds.attrs["eccjump_version"] == eccjump.__version__
    assert "2: liftoff_earlier" in ds.attrs["reason_codes"]
    assert ds.reason.attrs["flag_meanings"].split()[Reason.SLIP_BEFORE] == "slip_before"
    assert ds.theta_J.attrs["units"] == "rad" and ds.Fy_J.attrs["units"] == "M g"
    for f in FIELDS:
        assert ds[f].values.tobytes() == getattr(reg.result, f).tobytes()


def test_sweeps_are_extra_dimensions_one_map_each():
    g = grid(6)
    ds = region([0.5, 0.9], **g, theta0=[0.0, 0.2], omega0=0.1, output="xarray")
    assert ds.is_jarm.dims == ("mu_s", "theta0", "alpha", "chi", "km_frac")
    assert "mu_s" not in ds.attrs and ds.attrs["omega0"] == 0.1
    for mu in (0.5, 0.9):
        for th in (0.0, 0.2):
            one = region(mu, **g, theta0=th, omega0=0.1)
            sel = ds.sel(mu_s=mu, theta0=th)
            for f in FIELDS:
                assert sel[f].values.tobytes() == getattr(one.result, f).tobytes()
    with pytest.raises(ValueError, match="output='xarray'"):
        region([0.5, 0.9], **g)


@pytest.mark.parametrize("suffix", [".nc", ".zarr", ".npz"])
def test_save_and_load_round_trip_bit_for_bit(tmp_path, suffix):
    reg = region(MU_S, **grid(6))
    path = store.save(reg, tmp_path / f"r{suffix}")
    back = store.load(path)
    assert_same(reg, back)
    assert (back.mu_s, back.n, back.rule, back.method) == (MU_S, None, "paper", "closed_form")
    sweep = region([0.5, 0.9], **grid(4), output="xarray")
    spath = store.save(sweep, tmp_path / f"s{suffix}")
    xr.testing.assert_equal(store.open_dataset(spath), sweep)


# --- eccjump map ----------------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".nc", ".zarr", ".npz"])
def test_cli_writes_each_format_equal_to_region(tmp_path, reference, suffix):
    code, path = run_map(tmp_path, f"map{suffix}", "--chunk", "3")
    assert code == 0
    back = store.load(path)
    assert_same(reference, back)
    assert back.attrs["complete"] == 1 and back.attrs["alpha_done"].all()
    ds = store.open_dataset(path)
    assert {"alpha_deg", "km"} <= set(ds.coords) and ds.attrs["mu_s"] == MU_S


def test_cli_options_reach_region(tmp_path):
    args = ["--n-alpha", "4", "--n-chi", "3", "--n-km", "5", "--alpha-min", "20"]
    args += ["--alpha-max", "60", "--chi-min", "0.1", "--chi-max", "0.6", "--km-min", "0.2"]
    args += ["--route", "ode", "--rule", "normal_force", "--theta0", "10", "--omega0", "0.3"]
    args += ["--n", "2", "--threads", "1"]
    code, path = run_map(tmp_path, "o.npz", *args)
    assert code == 0
    ref = region(
        0.7,
        2,
        alpha=np.radians(np.linspace(20, 60, 4)),
        chi=np.linspace(0.1, 0.6, 3),
        km=np.linspace(0.2, 1.0, 5),
        method="ode",
        rule="normal_force",
        theta0=np.radians(10.0),
        omega0=0.3,
    )
    back = store.load(path)
    assert_same(ref, back)
    assert (back.method, back.rule, back.n) == ("ode", "normal_force", 2)


def test_summary_fractions_are_right(tmp_path, reference, capsys):
    code, path = run_map(tmp_path, "s.npz")
    assert code == 0
    out = capsys.readouterr().out
    jarm = reference.result.is_jarm
    assert jarm.any(), "the test grid should hold JARM points"
    m = re.search(r"^JARM\s+([\d.]+) of the finished points \((\d+)\)", out, re.M)
    assert m and int(m[2]) == jarm.sum()
    assert float(m[1]) == pytest.approx(reference.fraction(), abs=1e-6)
    turns = reference.result.n[jarm]
    for v in np.unique(turns)[:10]:
        m = re.search(rf"^  n = {v}\s+([\d.]+) \((\d+)\)", out, re.M)
        assert m, f"no line for n = {v}"
        assert int(m[2]) == (turns == v).sum()
        assert float(m[1]) == pytest.approx((turns == v).sum() / jarm.size, abs=1e-6)
    assert f"{jarm.size} of {jarm.size} finished" in out and "points/s" in out
    assert str(path) in out


def test_interrupted_zarr_resumes_to_the_uninterrupted_result(tmp_path, reference, capsys):
    code, path = run_map(tmp_path, "r.zarr", "--chunk", "3", "--stop-after", "2")
    assert code == 130
    assert "--resume" in capsys.readouterr().err
    part = store.load(path)
    assert part.attrs["complete"] == 0
    np.testing.assert_array_equal(part.attrs["alpha_done"], np.arange(20) < 6)
    assert (part.result.reason[6:] == 255).all() and np.isnan(part.result.theta_J[6:]).all()
    for f in FIELDS:
        assert getattr(part.result, f)[:6].tobytes() == getattr(reference.result, f)[:6].tobytes()
    # a second interruption, then the rest: only missing chunks are computed
    code, _ = run_map(tmp_path, "r.zarr", "--resume", "--stop-after", "1")
    assert code == 130
    assert "computed      1200 points this run, 3600 of 8000 finished" in capsys.readouterr().out
    code, _ = run_map(tmp_path, "r.zarr", "--resume")
    assert code == 0
    out = capsys.readouterr().out
    assert "computed      4400 points this run, 8000 of 8000 finished" in out
    back = store.load(path)
    assert back.attrs["complete"] == 1
    assert_same(reference, back)
    assert f"JARM          {reference.fraction():.6f}" in out  # over the whole map


def test_resume_checks_the_options(tmp_path, capsys):
    code, _ = run_map(tmp_path, "r.zarr", "--chunk", "5", "--stop-after", "1")
    assert code == 130
    code, _ = run_map(tmp_path, "r.zarr", "--resume", "--rule", "normal_force")
    assert code == 2
    err = capsys.readouterr().err
    assert "options differ" in err and "rule: store 'paper', now 'normal_force'" in err
    code, _ = run_map(tmp_path, "r.zarr", "--resume", "--alpha-max", "80")
    assert code == 2 and "alpha grid" in capsys.readouterr().err
    code, _ = run_map(tmp_path, "r.zarr")
    assert code == 2 and "--overwrite or --resume" in capsys.readouterr().err
    code, _ = run_map(tmp_path, "r.nc", "--resume")
    assert code == 2 and "needs a .zarr" in capsys.readouterr().err


@pytest.mark.parametrize("suffix", [".nc", ".npz"])
def test_interrupted_file_keeps_finished_slices_with_a_flag(tmp_path, reference, suffix, capsys):
    code, path = run_map(tmp_path, f"i{suffix}", "--chunk", "4", "--stop-after", "2")
    assert code == 130
    assert "complete = 0" in capsys.readouterr().err
    part = store.load(path)
    assert part.attrs["complete"] == 0
    np.testing.assert_array_equal(part.attrs["alpha_done"], np.arange(20) < 8)
    for f in FIELDS:
        assert getattr(part.result, f)[:8].tobytes() == getattr(reference.result, f)[:8].tobytes()
    assert (part.result.reason[8:] == 255).all()


def test_npz_works_without_xarray(tmp_path, reference, monkeypatch, capsys):
    for mod in ("xarray", "zarr", "h5netcdf", "netCDF4"):
        monkeypatch.setitem(sys.modules, mod, None)  # import raises ImportError
    with pytest.raises(ImportError):
        import xarray  # noqa: F401
    code, path = run_map(tmp_path, "plain.npz")
    assert code == 0
    assert_same(reference, store.load(path))
    code, _ = run_map(tmp_path, "needs.nc")
    assert code == 2
    assert "pip install eccjump[xarray]" in capsys.readouterr().err
    with pytest.raises(ImportError, match=re.escape("pip install eccjump[xarray]")):
        reference.to_xarray()


def test_ctrl_c_in_a_subprocess_keeps_finished_chunks_and_resumes(tmp_path):
    """A real SIGINT: exit 130, finished chunks kept, --resume completes the same map."""
    zarr = pytest.importorskip("zarr")
    path = tmp_path / "sig.zarr"
    env = {**os.environ, "PYTHONPATH": str(Path(eccjump.__file__).parents[1])}
    cmd = [sys.executable, "-m", "eccjump.cli", "map", "--mu-s", str(MU_S), "--grid", "40"]
    cmd += ["--chunk", "1", "--threads", "1", "-o", str(path)]
    proc = subprocess.Popen(cmd, env=env, stdout=subprocess.PIPE, stderr=subprocess.PIPE)
    deadline = time.monotonic() + 15
    while time.monotonic() < deadline and proc.poll() is None:
        try:
            if zarr.open_group(path, mode="r")["alpha_done"][:].any():
                break
        except Exception:  # not created yet
            pass
        time.sleep(0.02)
    assert proc.poll() is None, "the map finished before the interrupt; enlarge the grid"
    proc.send_signal(signal.SIGINT)
    _, err = proc.communicate(timeout=15)
    assert proc.returncode == 130, err
    part = store.load(path)
    assert part.attrs["complete"] == 0 and 0 < part.attrs["alpha_done"].sum() < 40
    p = subprocess.run([*cmd, "--resume"], env=env, capture_output=True, timeout=30, check=False)
    assert p.returncode == 0, p.stderr
    assert_same(region(MU_S, **grid(40)), store.load(path))

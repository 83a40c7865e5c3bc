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
import warnings
from pathlib import Path

import numpy as np
import pytest

import eccjump
from eccjump.classification import load as load_region
from eccjump.classification.classify import FIELDS, Reason, region
from eccjump.classification.dataset import region_dataset
from eccjump.classification.fields import JARM, map_attrs
from eccjump.cli import main
from eccjump.maps import runner, store

xr = pytest.importorskip("xarray")

MU_S = 0.7
GRID = ("--grid", "20")


def grid(n: int = 20, na: int | None = None):
    """The axes of `eccjump map` with default ranges."""
    return {
        "alpha": np.radians(np.linspace(0.0, 90.0, na or n)),
        "chi": np.linspace(0.0, 1.0, n),
        "km_frac": np.linspace(0.0, 1.0, n),
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
    return region(mu_s=MU_S, **grid())


def run_map(tmp_path: Path, name: str, *args: str) -> tuple[int, Path]:
    path = tmp_path / name
    return main(["map", "--mu-s", str(MU_S), *GRID, "-o", str(path), "-q", *args]), path


# --- labelled results ---------------------------------------------------------------


def test_to_xarray_labels_units_and_reason_table():
    reg = region(mu_s=MU_S, n=2, **grid(5))
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
    ds = region_dataset(mu_s=[0.5, 0.9], **g, theta0=[0.0, 0.2], omega0=0.1)
    assert ds.is_jarm.dims == ("mu_s", "theta0", "alpha", "chi", "km_frac")
    assert "mu_s" not in ds.attrs and ds.attrs["omega0"] == 0.1
    for mu in (0.5, 0.9):
        for th in (0.0, 0.2):
            one = region(mu_s=mu, **g, theta0=th, omega0=0.1)
            sel = ds.sel(mu_s=mu, theta0=th)
            for f in FIELDS:
                assert sel[f].values.tobytes() == getattr(one.result, f).tobytes()
    with pytest.raises(ValueError, match=r"mu_s must be a number here; region_dataset\(\.\.\.\)"):
        region(mu_s=[0.5, 0.9], **g)


def test_output_xarray_is_deprecated_for_to_xarray_and_region_dataset():
    """region no longer calls up to region_dataset: output="xarray" is the map's own
    to_xarray() for one release, with a warning; a sweep is region_dataset's."""
    g = grid(5)
    deprecated = r"region\(output='xarray'\) is deprecated: use region\(\.\.\.\)\.to_xarray\(\)"
    with pytest.warns(DeprecationWarning, match=deprecated) as seen:
        ds = region(mu_s=MU_S, **g, output="xarray")
    assert seen[0].filename == __file__  # the warning points to the caller
    xr.testing.assert_identical(ds, region(mu_s=MU_S, **g).to_xarray())
    with pytest.warns(DeprecationWarning), pytest.raises(ValueError, match="region_dataset"):
        region(mu_s=[0.5, 0.9], **g, output="xarray")
    with pytest.raises(ValueError, match="output = 'labels'; use 'region'"):
        region(mu_s=MU_S, **g, output="labels")


@pytest.mark.parametrize("suffix", [".nc", ".zarr", ".npz"])
def test_save_and_load_round_trip_bit_for_bit(tmp_path, suffix):
    reg = region(mu_s=MU_S, **grid(6))
    path = store.save(reg, tmp_path / f"r{suffix}")
    back = load_region(path)
    assert_same(reg, back)
    assert (back.mu_s, back.n, back.rule, back.method) == (MU_S, None, "paper", "closed_form")
    sweep = region_dataset(mu_s=[0.5, 0.9], **grid(4))
    spath = store.save(sweep, tmp_path / f"s{suffix}")
    xr.testing.assert_equal(store.open_dataset(spath), sweep)


# --- eccjump map ----------------------------------------------------------------------


@pytest.mark.parametrize("suffix", [".nc", ".zarr", ".npz"])
def test_cli_writes_each_format_equal_to_region(tmp_path, reference, suffix):
    code, path = run_map(tmp_path, f"map{suffix}", "--chunk", "3")
    assert code == 0
    back = load_region(path)
    assert_same(reference, back)
    assert back.attrs["complete"] == 1 and back.attrs["alpha_done"].all()
    ds = store.open_dataset(path)
    assert {"alpha_deg", "km"} <= set(ds.coords) and ds.attrs["mu_s"] == MU_S


def test_cli_options_reach_region(tmp_path):
    args = ["--n-alpha", "4", "--n-chi", "3", "--n-km-frac", "5", "--alpha-min", "20"]
    args += ["--alpha-max", "60", "--chi-min", "0.1", "--chi-max", "0.6", "--km-frac-min", "0.2"]
    args += ["--route", "ode", "--rule", "normal_force", "--theta0", "10", "--omega0", "0.3"]
    args += ["--n", "2", "--threads", "1"]
    code, path = run_map(tmp_path, "o.npz", *args)
    assert code == 0
    ref = region(
        mu_s=0.7,
        n=2,
        alpha=np.radians(np.linspace(20, 60, 4)),
        chi=np.linspace(0.1, 0.6, 3),
        km_frac=np.linspace(0.2, 1.0, 5),
        method="ode",
        rule="normal_force",
        theta0=np.radians(10.0),
        omega0=0.3,
    )
    back = load_region(path)
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
    part = load_region(path)
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
    back = load_region(path)
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


@pytest.mark.parametrize("suffix", [".nc", ".zarr", ".npz"])
def test_the_integrator_is_recorded_in_every_form_of_a_map(tmp_path, suffix):
    g = grid(4)
    rk = region(mu_s=MU_S, **g, method="ode")
    dop = region(mu_s=MU_S, **g, method="ode", integrator="DOP853")
    assert rk.attrs["integrator"] == "RK45" and dop.attrs["integrator"] == "DOP853"
    # the option reaches the core: another pair, other bits (the same verdicts here)
    assert rk.result.theta_J.tobytes() != dop.result.theta_J.tobytes()
    assert (rk.result.reason == dop.result.reason).all()
    assert dop.to_xarray().attrs["integrator"] == "DOP853"
    back = load_region(store.save(dop, tmp_path / f"d{suffix}"))
    assert_same(dop, back)
    assert back.attrs["integrator"] == "DOP853" and back.method == "ode"
    assert store.open_dataset(tmp_path / f"d{suffix}").attrs["integrator"] == "DOP853"
    # as rtol and atol, recorded (and checked) for the closed form too, which ignores it
    closed = region(mu_s=MU_S, **g, integrator="DOP853")
    assert closed.attrs["integrator"] == "DOP853"
    assert_same(closed, region(mu_s=MU_S, **g))
    sweep = region_dataset(mu_s=[0.5, 0.9], **g, method="ode", integrator="DOP853")
    assert sweep.attrs["integrator"] == "DOP853"
    assert (
        sweep.reason.sel(mu_s=0.9).values.tobytes()
        == region(mu_s=0.9, **g, method="ode", integrator="DOP853").result.reason.tobytes()
    )


@pytest.mark.parametrize("bad", ["rk45", "", "DOP54", None, 45, b"RK45"])
def test_a_bad_integrator_is_refused_naming_it(bad):
    with pytest.raises((ValueError, TypeError), match="integrator") as err:
        region(mu_s=MU_S, **grid(2), method="ode", integrator=bad)
    assert len(str(err.value)) < 200
    with pytest.raises((ValueError, TypeError), match="integrator"):
        region(mu_s=MU_S, **grid(2), integrator=bad)  # the closed form checks it too, as rtol


def test_cli_ode_route_takes_the_integrator_and_records_it(tmp_path):
    args = ["--n-alpha", "5", "--n-chi", "4", "--n-km-frac", "3", "--alpha-min", "10"]
    args += ["--route", "ode", "--integrator", "DOP853", "--threads", "1"]
    code, path = run_map(tmp_path, "d.npz", *args)
    assert code == 0
    ref = region(
        mu_s=MU_S,
        alpha=np.radians(np.linspace(10, 90, 5)),
        chi=np.linspace(0.0, 1.0, 4),
        km_frac=np.linspace(0.0, 1.0, 3),
        method="ode",
        integrator="DOP853",
    )
    back = load_region(path)
    assert_same(ref, back)
    assert (back.method, back.attrs["integrator"]) == ("ode", "DOP853")
    code, path = run_map(tmp_path, "r.npz", *args[:-4], "--route", "ode")
    assert load_region(path).attrs["integrator"] == "RK45"  # the default


def test_resume_refuses_another_integrator(tmp_path, capsys):
    pytest.importorskip("zarr")
    code, path = run_map(tmp_path, "r.zarr", "--chunk", "5", "--stop-after", "1")
    assert code == 130
    assert load_region(path).attrs["integrator"] == "RK45"
    code, _ = run_map(tmp_path, "r.zarr", "--resume", "--integrator", "DOP853")
    assert code == 2
    err = capsys.readouterr().err
    assert "options differ" in err and "integrator: store 'RK45', now 'DOP853'" in err
    # a store written before the integrator was recorded was made with RK45
    zarr = pytest.importorskip("zarr")
    group = zarr.open_group(path, mode="r+")
    del group.attrs["integrator"]
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # consolidated metadata is not in the zarr v3 spec
        zarr.consolidate_metadata(str(path))
    code, _ = run_map(tmp_path, "r.zarr", "--resume", "--integrator", "DOP853", "--stop-after", "1")
    assert code == 2 and "integrator: store 'RK45', now 'DOP853'" in capsys.readouterr().err
    code, _ = run_map(tmp_path, "r.zarr", "--resume")
    assert code == 0


def test_stop_at_slip_reaches_the_map_is_recorded_and_checked_on_resume(tmp_path, capsys):
    code, path = run_map(tmp_path, "s.npz", "--stop-at-slip")
    assert code == 0
    back = load_region(path)
    ref = region(mu_s=MU_S, **grid(), stop_at_slip=True)
    assert_same(ref, back)
    assert back.attrs["stop_at_slip"] and (back.result.reason == Reason.SLIP).any()
    np.testing.assert_array_equal(back.is_jarm, region(mu_s=MU_S, **grid()).is_jarm)
    pytest.importorskip("zarr")
    code, path = run_map(tmp_path, "s.zarr", "--chunk", "5", "--stop-after", "1")
    assert code == 130
    code, _ = run_map(tmp_path, "s.zarr", "--resume", "--stop-at-slip")
    assert code == 2
    assert "stop_at_slip: store 0, now 1" in capsys.readouterr().err


@pytest.mark.parametrize("suffix", [".nc", ".npz"])
def test_interrupted_file_keeps_finished_slices_with_a_flag(tmp_path, reference, suffix, capsys):
    code, path = run_map(tmp_path, f"i{suffix}", "--chunk", "4", "--stop-after", "2")
    assert code == 130
    assert "complete = 0" in capsys.readouterr().err
    part = load_region(path)
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
    assert_same(reference, load_region(path))
    code, _ = run_map(tmp_path, "needs.nc")
    assert code == 2
    assert "pip install eccjump[xarray]" in capsys.readouterr().err
    with pytest.raises(ImportError, match=re.escape("pip install eccjump[xarray]")):
        reference.to_xarray()


@pytest.mark.slow
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
    part = load_region(path)
    assert part.attrs["complete"] == 0 and 0 < part.attrs["alpha_done"].sum() < 40
    p = subprocess.run([*cmd, "--resume"], env=env, capture_output=True, timeout=30, check=False)
    assert p.returncode == 0, p.stderr
    assert_same(region(mu_s=MU_S, **grid(40)), load_region(path))


class _RegionJob:
    """A job for the runner made here, not by the command line: the runner computes what
    its caller gives it (it knows no kind's physics)."""

    kind = JARM
    matched = ("mu_s",)
    counted = ("is_jarm",)

    def __init__(self) -> None:
        self.unrecorded: dict = {}
        self.attrs = map_attrs(MU_S, None, "paper", "closed_form", 0.0, 0.0)
        self.calls: list[int] = []
        self.points = 0

    def compute(self, alpha, chi, km, threads):
        self.calls.append(alpha.size)
        r = region(mu_s=MU_S, alpha=alpha, chi=chi, km_frac=km, n_threads=threads)
        return {f: getattr(r.result, f) for f in FIELDS}

    def count(self, part) -> None:
        self.points += part["is_jarm"].size


@pytest.mark.parametrize("suffix", [".npz", ".zarr"])
def test_the_runner_computes_the_callers_job_in_chunks(tmp_path, suffix):
    job, notes = _RegionJob(), []
    axes = tuple(grid(6).values())
    options = runner.Options(threads=1, chunk=2, progress=False)
    out = runner.run(tmp_path / f"m{suffix}", axes, job, options, notes.append)
    assert (out.complete, out.interrupted, out.done, out.computed) == (True, False, 6, 6**3)
    assert job.calls == [1, 2, 2, 2] and job.points == 6**3 and notes == []  # a probe first
    assert_same(region(mu_s=MU_S, **grid(6)), load_region(tmp_path / f"m{suffix}"))


# --- a map is never lost: crashes, full disks, bad paths, foreign files -------------------

SMALL = ("--grid", "6", "--chunk", "2", "--threads", "1")  # 3 chunks of 2 alpha slices
OLD_MU_S = 0.5  # the map that --overwrite replaces, told apart by mu_s


@pytest.fixture(scope="module")
def small():
    return {mu: region(mu_s=mu, **grid(6)) for mu in (MU_S, OLD_MU_S)}


def map_cli(out: Path, *args: str, kill_at=None, fsize=None) -> subprocess.CompletedProcess:
    """`eccjump map` in a subprocess on the small grid. ``kill_at``: the step at which it
    SIGKILLs itself (store.KILL_AT_ENV, a test hook); ``fsize``: a file-size limit in bytes
    (RLIMIT_FSIZE, SIGXFSZ ignored so that writes fail with EFBIG): a full disk."""
    env = {**os.environ, "PYTHONPATH": str(Path(eccjump.__file__).parents[1])}
    env.pop(store.KILL_AT_ENV, None)
    if kill_at:
        env[store.KILL_AT_ENV] = kill_at

    def limit() -> None:
        import resource

        signal.signal(signal.SIGXFSZ, signal.SIG_IGN)
        resource.setrlimit(resource.RLIMIT_FSIZE, (fsize, fsize))

    cmd = [sys.executable, "-m", "eccjump.cli", "map", "--mu-s", str(MU_S), *SMALL, "-q"]
    return subprocess.run(
        [*cmd, "-o", str(out), *args],
        env=env,
        capture_output=True,
        text=True,
        timeout=60,
        check=False,
        preexec_fn=limit if fsize else None,
    )


def map_here(out: Path, *args: str) -> int:
    return main(["map", "--mu-s", str(MU_S), *SMALL, "-q", "-o", str(out), *args])


def one_error_line(err: str) -> str:
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("eccjump: error: "), err
    return lines[0]


def test_the_steps_of_the_write_protocol_are_reached(tmp_path, monkeypatch):
    """The kill tests below are only as good as their step names: each one is reached."""
    seen = []
    monkeypatch.setattr(store, "_step", seen.append)
    assert map_here(tmp_path / "s.zarr") == 0
    assert map_here(tmp_path / "s.zarr", "--overwrite") == 0
    assert set(seen) == set(store.STEPS)


NEW_ZARR_STEPS = [
    ("create", False),  # skeleton half built under the temporary name
    ("created", False),
    ("chunk-data", False),  # the first chunk, still in the temporary store
    ("chunk-done", False),
    ("published", True),  # renamed into place after its first chunk
    ("chunk-data:2", True),  # the second chunk's data written, alpha_done not yet
    ("chunk-done:2", True),
    ("finish", True),
    ("finished", True),
]


@pytest.mark.parametrize(("step", "resumable"), NEW_ZARR_STEPS)
def test_sigkill_of_a_new_zarr_map_leaves_nothing_or_a_resumable_map(
    tmp_path, small, step, resumable, capsys
):
    path = tmp_path / "k.zarr"
    p = map_cli(path, kill_at=step)
    assert p.returncode == -signal.SIGKILL, p.stderr
    assert path.exists() == resumable
    code = map_here(path, "--resume")
    if resumable:
        assert code == 0
    else:  # nothing to resume: a clear error, then a fresh run works
        assert code == 2
        assert "does not exist" in one_error_line(capsys.readouterr().err)
        assert map_here(path) == 0
    back = load_region(path)
    assert back.attrs["complete"] == 1
    assert_same(small[MU_S], back)
    assert os.listdir(tmp_path) == ["k.zarr"]  # the killed run's temporary store is gone


OVERWRITE_STEPS = [
    *(s for s, _ in NEW_ZARR_STEPS if ":" not in s and s != "published"),
    "written",  # the new map complete under its temporary name
    "replaced",  # swapped into place, the old one not yet removed
    "published",
]


@pytest.mark.parametrize("step", OVERWRITE_STEPS)
def test_sigkill_during_overwrite_of_a_zarr_map_keeps_a_whole_map(tmp_path, small, step):
    path = tmp_path / "o.zarr"
    assert map_here(path, "--mu-s", str(OLD_MU_S)) == 0
    p = map_cli(path, "--overwrite", kill_at=step)
    assert p.returncode == -signal.SIGKILL, p.stderr
    new = OVERWRITE_STEPS.index(step) >= OVERWRITE_STEPS.index("replaced")
    back = load_region(path)
    assert back.attrs["complete"] == 1
    assert_same(small[MU_S if new else OLD_MU_S], back)  # old intact, or the new one whole
    # the next run removes what the killed one left behind
    assert map_here(path, *(("--resume",) if new else ("--overwrite",))) == 0
    assert_same(small[MU_S], load_region(path))
    assert os.listdir(tmp_path) == ["o.zarr"]


@pytest.mark.parametrize("suffix", [".nc", ".npz"])
def test_sigkill_before_the_rename_of_a_file_keeps_the_old_one(tmp_path, small, suffix):
    path = tmp_path / f"o{suffix}"
    assert map_here(path, "--mu-s", str(OLD_MU_S)) == 0
    p = map_cli(path, "--overwrite", kill_at="written")
    assert p.returncode == -signal.SIGKILL, p.stderr
    assert_same(small[OLD_MU_S], load_region(path))
    assert map_here(path, "--overwrite") == 0
    assert_same(small[MU_S], load_region(path))
    assert os.listdir(tmp_path) == [path.name]


@pytest.mark.parametrize("suffix", [".zarr", ".nc", ".npz"])
def test_overwrite_on_a_full_disk_keeps_the_old_map(tmp_path, small, suffix):
    path = tmp_path / f"full{suffix}"
    assert map_here(path, "--mu-s", str(OLD_MU_S)) == 0
    before = sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*"))
    p = map_cli(path, "--overwrite", fsize=300)  # smaller than any map file's metadata
    assert p.returncode == 1, p.stderr
    line = one_error_line(p.stderr)
    assert f"cannot write {path}" in line
    assert_same(small[OLD_MU_S], load_region(path))
    assert sorted(p.relative_to(tmp_path) for p in tmp_path.rglob("*")) == before


@pytest.mark.parametrize("suffix", [".zarr", ".nc", ".npz"])
def test_a_new_map_on_a_full_disk_leaves_nothing(tmp_path, suffix):
    p = map_cli(tmp_path / f"full{suffix}", fsize=300)
    assert p.returncode == 1, p.stderr
    one_error_line(p.stderr)
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("suffix", [".zarr", ".nc", ".npz"])
@pytest.mark.parametrize("parent", ["missing/dir", "a-file"])
def test_a_missing_parent_directory_is_an_error_not_created(tmp_path, suffix, parent, capsys):
    (tmp_path / "a-file").write_text("not a directory")
    code = map_here(tmp_path / parent / f"m{suffix}")
    assert code == 2
    assert "cannot write" in one_error_line(capsys.readouterr().err)
    assert os.listdir(tmp_path) == ["a-file"]


@pytest.mark.skipif(
    not hasattr(os, "geteuid") or os.geteuid() == 0,
    reason="root writes to a chmod 0o555 directory anyway (full-disk tests cover failed writes)",
)
@pytest.mark.parametrize("suffix", [".zarr", ".nc", ".npz"])
def test_a_read_only_directory_is_one_error_line(tmp_path, suffix, capsys):
    ro = tmp_path / "ro"
    ro.mkdir()
    ro.chmod(0o555)
    try:
        assert map_here(ro / f"m{suffix}") == 1
        assert "Permission denied" in one_error_line(capsys.readouterr().err)
        assert os.listdir(ro) == []
    finally:
        ro.chmod(0o755)


@pytest.mark.parametrize("suffix", [".zarr", ".npz"])
@pytest.mark.parametrize("precheck", [True, False])
def test_a_grid_too_big_for_memory_is_one_error_line(
    tmp_path, suffix, precheck, monkeypatch, capsys
):
    if not precheck:  # numpy's own MemoryError (909 TiB: refused at once, nothing touched)
        monkeypatch.setattr(runner, "memory_limit", lambda: None)
    code = map_here(tmp_path / f"big{suffix}", "--grid", "100000")
    assert code == 1
    assert "out of memory" in one_error_line(capsys.readouterr().err)
    assert os.listdir(tmp_path) == []


def test_ctrl_c_while_the_store_is_created_writes_nothing(tmp_path, monkeypatch, capsys):
    """The SIGINT handler is in place before creation: a Ctrl-C then stops before the
    first chunk, and nothing is left behind."""
    create = store.ZarrMap.create

    def interrupted_create(*a, **k):
        os.kill(os.getpid(), signal.SIGINT)
        return create(*a, **k)

    monkeypatch.setattr(store.ZarrMap, "create", interrupted_create)
    assert map_here(tmp_path / "c.zarr") == 130
    assert "nothing written" in capsys.readouterr().err
    assert os.listdir(tmp_path) == []


def test_foreign_files_are_a_clear_value_error(tmp_path, capsys):
    foreign = xr.Dataset({"foo": ("x", np.arange(3))})
    np.savez(tmp_path / "empty.npz")
    (tmp_path / "zero.npz").write_bytes(b"")
    foreign.to_netcdf(tmp_path / "foreign.nc", engine=store.netcdf_engine())
    (tmp_path / "zero.nc").write_bytes(b"")
    (tmp_path / "random.zarr").mkdir()
    (tmp_path / "random.zarr" / "x").write_text("hi")
    with warnings.catch_warnings():  # zarr: consolidated metadata is not in the v3 spec
        warnings.simplefilter("ignore", UserWarning)
        foreign.to_zarr(tmp_path / "foreign.zarr")
    expect = {
        "empty.npz": "no __layout__",
        "zero.npz": "not a readable npz map",
        "foreign.nc": "missing coordinates alpha, chi, km_frac; variables is_jarm",
        "zero.nc": "not a readable netcdf map",
        "random.zarr": "not a readable zarr map",
        "foreign.zarr": "missing coordinates alpha, chi, km_frac; variables is_jarm",
    }
    for name, what in expect.items():
        with pytest.raises(ValueError, match=re.escape(what)) as info:
            load_region(tmp_path / name)
        assert name in str(info.value)
    for name in ("random.zarr", "foreign.zarr"):
        assert map_here(tmp_path / name, "--resume") == 2
        line = one_error_line(capsys.readouterr().err)
        assert name in line and "not" in line


def test_replacing_a_store_without_renameat2_sets_the_old_one_aside(tmp_path, monkeypatch, small):
    """Where directories cannot be swapped atomically the old map is renamed aside first;
    a crash in between leaves it as .<name>.old-<pid>, which recover() puts back."""
    monkeypatch.setattr(store, "_renameat2", lambda *a: False)
    path = tmp_path / "s.zarr"
    store.save(small[OLD_MU_S], path)
    store.save(small[MU_S], path)
    assert_same(small[MU_S], load_region(path))
    assert os.listdir(tmp_path) == ["s.zarr"]
    dead = subprocess.run([sys.executable, "-c", "import os; print(os.getpid())"], **_out)
    aside = tmp_path / f".s.zarr.old-{int(dead.stdout)}"
    path.rename(aside)
    (tmp_path / f".s.zarr.tmp-{int(dead.stdout)}").mkdir()
    assert store.recover(path) and sorted(os.listdir(tmp_path)) == ["s.zarr"]
    assert_same(small[MU_S], load_region(path))


_out = {"capture_output": True, "text": True, "check": True, "timeout": 30}

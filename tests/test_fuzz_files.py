"""Fuzzing of the map files (issue 35): every loader on damaged, foreign and special files,
every writer on faulty targets; and the bad videos of ``eccjump.track`` (issue 48).

The contract is that of ``fuzz_cases.py``: a loader returns a valid map or raises ValueError/
TypeError naming the file in at most MAX_MESSAGE characters -- never another exception, a
hang or a traceback; a writer (``store.save``, ``eccjump map -o``) fails with one clean
error (exit status != 0 on the command line) and leaves what was at its target untouched.
What could hang (a FIFO) runs in a subprocess with a time limit, and every in-process load
runs under an alarm, so that a regression fails instead of hanging the suite. Budgets are
small (about 30 s in all); hypothesis is derandomized (conftest.py).
"""

from __future__ import annotations

import errno
import os
import shutil
import subprocess
import sys
import tempfile
from collections.abc import Callable
from pathlib import Path

import pytest
import xarray as xr
from fuzz_cases import (
    BAD_VIDEOS,
    MAX_MESSAGE,
    VIDEO_MARKER,
    alarm,
    run_cli_inprocess,
    videos,
)
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from test_store_hardening import JARM_BAD, MOTION_BAD, _edited, _write_raw, tree

import eccjump
from eccjump import maps
from eccjump.classification import load as load_region
from eccjump.maps import store
from eccjump.motion import maps as motion_maps

pytest.importorskip("zarr")

SUFFIXES = (".npz", ".nc", ".zarr")
LOADERS: dict[str, Callable] = {
    "classification.load": load_region,
    "store.open_dataset": store.open_dataset,
    "motion_maps.load": motion_maps.load,
    "maps.load": maps.load,
}
#: The loader of each kind of map (the other loaders refuse it).
NATIVE = {"jarm": "classification.load", "motion": "motion_maps.load"}
#: Hypothesis examples of damaged files per format (a .nc file costs a probe subprocess).
BUDGET = {".npz": 40, ".zarr": 25, ".nc": 15}
MAP = ["map", "--mu-s", "1", "--grid", "3", "-q"]


@pytest.fixture(scope="module")
def maps(tmp_path_factory) -> dict[tuple[str, str], Path]:
    """A good JARM and motion map in each format."""
    where = tmp_path_factory.mktemp("maps")
    region = eccjump.region(mu_s=1.0, alpha=[0.3, 0.6, 0.9], chi=[0.2, 0.5], km_frac=[0.1, 0.4])
    motion = eccjump.motion_map(alpha=[0.5, 0.7], chi=0.3, km_frac=[0.2, 0.6], mu_s=1.0, t_max=20.0)
    out = {}
    for suffix in SUFFIXES:
        for kind, obj in (("jarm", region), ("motion", motion)):
            out[kind, suffix] = store.save(obj, where / f"{kind}{suffix}")
    return out


def judge(loader: str, path: Path, *, must_fail: bool = False) -> None:
    """The contract of a loader on ``path``: a result, or a ValueError/TypeError naming the
    file in at most MAX_MESSAGE characters."""
    try:
        with alarm(30):
            LOADERS[loader](path)
    except (ValueError, TypeError) as err:
        msg = str(err)
        assert len(msg) <= MAX_MESSAGE, f"{loader}: {len(msg)} characters: {msg[:150]}"
        assert path.name[-40:] in msg, f"{loader}: names no file: {msg}"
        return
    assert not must_fail, f"{loader}({path.name}) accepted it"


# --- loaders: damaged bytes ------------------------------------------------------------------


def _damage(data: bytes, d: st.DataObject, can_delete: bool) -> bytes | None:
    """``data`` truncated, with a range zeroed or replaced by garbage (None: deleted, for a
    file in a store: a missing map is a FileNotFoundError)."""
    hows = ("truncate", "zero", "garbage", "delete")
    how = d.draw(st.sampled_from(hows if can_delete else hows[:-1]))
    if how == "delete" or not data:
        return None
    start = d.draw(st.integers(0, len(data) - 1))
    if how == "truncate":
        return data[:start]
    end = d.draw(st.integers(start + 1, min(len(data), start + 600)))
    size = end - start
    fill = bytes(size) if how == "zero" else d.draw(st.binary(min_size=size, max_size=size))
    return data[:start] + fill + data[end:]


def _damaged_copy(source: Path, d: st.DataObject, where: Path) -> Path:
    path = where / source.name
    if source.is_dir():
        shutil.copytree(source, path)
        files = sorted(p for p in path.rglob("*") if p.is_file())
        target = d.draw(st.sampled_from(files))
    else:
        shutil.copyfile(source, path)
        target = path
    damaged = _damage(target.read_bytes(), d, target != path)
    if damaged is None:
        target.unlink()
    else:
        target.write_bytes(damaged)
    return path


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_loaders_keep_the_contract_on_damaged_files(maps, suffix):
    @settings(
        max_examples=BUDGET[suffix],
        deadline=None,
        suppress_health_check=[HealthCheck.too_slow, HealthCheck.data_too_large],
    )
    @given(st.data())
    def run(d):
        kind = d.draw(st.sampled_from(("jarm", "motion")))
        loader = d.draw(st.sampled_from(sorted(LOADERS)))
        with tempfile.TemporaryDirectory() as where:
            judge(loader, _damaged_copy(maps[kind, suffix], d, Path(where)))

    run()


# --- loaders: special and foreign files ------------------------------------------------------


def test_every_loader_refuses_a_fifo_in_time(tmp_path):
    for suffix in SUFFIXES:
        os.mkfifo(tmp_path / f"fifo{suffix}")
    code = f"""
from pathlib import Path
from eccjump import store, motion_maps
from eccjump.classification import load as load_region
for p in sorted(Path({str(tmp_path)!r}).iterdir()):
    for load in (load_region, store.open_dataset, motion_maps.load):
        try:
            load(p)
            print("accepted", p.name)
        except (ValueError, TypeError) as err:
            print(len(str(err)), p.name in str(err))
"""
    p = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr[-500:]
    lines = p.stdout.split("\n")[:-1]
    assert len(lines) == 9
    assert all(int(n) <= MAX_MESSAGE and named == "True" for n, named in map(str.split, lines))


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("loader", sorted(LOADERS))
def test_a_directory_where_a_file_is_expected_and_back(tmp_path, loader, suffix):
    path = tmp_path / f"m{suffix}"
    if suffix == ".zarr":
        path.write_bytes(b"a file, not a store")
    else:
        path.mkdir()
        (path / "notes.txt").write_text("x")
    judge(loader, path, must_fail=True)


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("loader", sorted(LOADERS))
def test_a_map_of_the_other_kind_is_refused(maps, loader, suffix):
    for kind, native in NATIVE.items():
        if loader not in (native, "store.open_dataset", "maps.load"):
            judge(loader, maps[kind, suffix], must_fail=True)


@pytest.mark.slow
@pytest.mark.parametrize("suffix", SUFFIXES)
def test_nan_coordinates_and_codes_out_of_their_tables(maps, tmp_path, suffix):
    for kind, bad in (("jarm", JARM_BAD), ("motion", MOTION_BAD)):
        good = store.load_layout(maps[kind, suffix])
        for what, (part, name, edit) in bad.items():
            path = tmp_path / f"{kind}-{what.replace(' ', '-')}{suffix}"
            _write_raw(_edited(good, part, name, edit), path)
            for loader in LOADERS:
                judge(loader, path, must_fail=True)


# --- writers ---------------------------------------------------------------------------------

#: Where each format's bytes are written (argument index of the path): a fault is injected
#: there, after a partial write, as a full disk or a read-only directory would.
WRITE_POINTS = (
    (store, "save_npz", 1),
    (xr.Dataset, "to_netcdf", 1),
    (xr.Dataset, "to_zarr", 1),
)


def _inject(monkeypatch, code: int) -> None:
    def fail(index: int) -> Callable:
        def write(*args, **kwargs):
            path = Path(args[index])
            if path.suffix == ".zarr" or ".zarr." in path.name:
                path.mkdir(exist_ok=True)
                (path / "zarr.json").write_text("{}")
            else:
                path.write_bytes(b"partial")
            raise OSError(code, os.strerror(code), str(path))

        return write

    for owner, name, index in WRITE_POINTS:
        monkeypatch.setattr(owner, name, fail(index))
    monkeypatch.setattr(store.ZarrMap, "_build", staticmethod(fail(1)))


FAULTS = (
    "missing-parent", "exists", "user-directory", "user-file", "read-only", "full-disk", "long-name"
)  # fmt: skip


def _target(tmp_path: Path, fault: str, suffix: str, maps) -> tuple[Path, list[str]]:
    """The output path of ``fault`` (made ready) and the extra command-line options."""
    if fault == "missing-parent":
        return tmp_path / "no" / f"m{suffix}", []
    if fault == "long-name":
        return tmp_path / (("x" * 250) + suffix), []
    path = tmp_path / f"m{suffix}"
    if fault == "user-directory":
        path.mkdir()
        (path / "notes.txt").write_text("mine")
        return path, ["--overwrite"]
    if fault == "user-file":  # issue 46, 8: kept without overwrite, whatever its suffix
        path.write_bytes(b"PK\x03\x04 the user's own data")
        return path, []
    source = maps["jarm", suffix]
    (shutil.copytree if source.is_dir() else shutil.copyfile)(source, path)
    return path, [] if fault == "exists" else ["--overwrite"]


@pytest.mark.parametrize("suffix", SUFFIXES)
@pytest.mark.parametrize("fault", FAULTS)
@pytest.mark.parametrize("writer", ["store.save", "eccjump map"])
def test_writers_fail_cleanly_and_keep_what_was_there(
    maps, tmp_path, monkeypatch, writer, fault, suffix
):
    if writer == "store.save" and fault == "exists":
        pytest.skip("store.save replaces a map file by design (no --overwrite)")
    path, options = _target(tmp_path, fault, suffix, maps)
    before = {p.name: tree(p) for p in tmp_path.iterdir()}
    if fault in ("read-only", "full-disk"):
        _inject(monkeypatch, errno.EACCES if fault == "read-only" else errno.ENOSPC)
    if writer == "store.save":
        region = load_region(maps["jarm", suffix])
        with pytest.raises((ValueError, TypeError, OSError)) as info:
            with alarm(30):
                store.save(region, path)
        assert len(str(info.value)) <= MAX_MESSAGE, str(info.value)
    else:
        code, _, err = run_cli_inprocess([*MAP, "-o", str(path), *options])
        assert "Traceback" not in err, err[-800:]
        lines = err.strip().splitlines()
        assert code in (1, 2) and len(lines) == 1, err
        assert lines[0].startswith("eccjump: error: ") and len(lines[0]) <= MAX_MESSAGE
    assert {p.name: tree(p) for p in tmp_path.iterdir()} == before


def test_writers_refuse_a_fifo_in_time(tmp_path, maps):
    for suffix in SUFFIXES:
        os.mkfifo(tmp_path / f"fifo{suffix}")
    code = f"""
from pathlib import Path
from eccjump import store
from eccjump.classification import load as load_region
from eccjump.cli import main
region = load_region({str(maps["jarm", ".npz"])!r})
for p in sorted(Path({str(tmp_path)!r}).iterdir()):
    try:
        store.save(region, p)
        print("accepted", p.name)
    except ValueError as err:
        print("refused", len(str(err)))
    print("exit", main({MAP!r} + ["-o", str(p), "--overwrite"]))
"""
    p = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert p.returncode == 0 and "Traceback" not in p.stderr, p.stderr[-500:]
    out = p.stdout.split()  # refused <length> exit <status>, per FIFO
    assert out[0::4] == ["refused"] * 3 and out[2::4] == ["exit"] * 3, out
    assert out[3::4] == ["2"] * 3 and all(int(n) <= MAX_MESSAGE for n in out[1::4])
    assert p.stderr.count("eccjump: error: ") == 3
    assert all((tmp_path / f"fifo{s}").is_fifo() for s in SUFFIXES)


# --- videos: eccjump.track, eccjump track, eccjump analyze VIDEO -----------------------------


@pytest.mark.parametrize("name", sorted(BAD_VIDEOS))
def test_a_bad_video_is_one_line_naming_the_file_and_what_is_wrong(name, tmp_path):
    """Not a video, no frames, one dot, both dots of one colour (and a cut file, an audio
    file): a ValueError of one line that names the file and says what is wrong, from Python
    and from both commands, and no track written."""
    pytest.importorskip("av")
    path = videos()[name]
    with pytest.raises(ValueError) as info, alarm(60):
        eccjump.track(path, marker_radius=VIDEO_MARKER)
    msg = str(info.value)
    assert "\n" not in msg and len(msg) <= MAX_MESSAGE, msg
    assert name in msg and BAD_VIDEOS[name] in msg, msg
    out = tmp_path / "track.csv"
    body = ["--radius", "0.05", "--chi", "0.10927", "--km", "0.0777", "--alpha", "66.087"]
    for argv in (["track", str(path), "-o", str(out)], ["analyze", str(path), *body]):
        code, _, err = run_cli_inprocess([*argv, "--marker-radius", str(VIDEO_MARKER)])
        lines = err.strip().splitlines()
        assert code == 2 and len(lines) == 1 and "Traceback" not in err, err
        assert name in lines[0] and BAD_VIDEOS[name] in lines[0] and len(lines[0]) <= 200
    assert not out.exists()

"""Issue 35, the files: regression tests of the second hardening round of the loaders and
writers of maps (eccjump.store, eccjump.motion.maps, ``eccjump map -o``).

1. A writer replaces only a map of its own kind: never a directory of user files, a FIFO.
2. No loader hangs: a FIFO is refused before it is opened, a damaged .nc file is read by the
   netCDF library in a subprocess with a time limit.
3. ``--resume`` computes again every chunk that does not read back whole and valid, and never
   ends with exit 0 and a map that ``classification.load`` refuses; a motion map refuses a NaN mu_s.
4. One checked loader path: codes out of their tables, NaN coordinates, wrong shapes, foreign
   files are ValueErrors naming the file in < 200 characters, even for long paths.
5. ``eccjump map``: --grid bounded, a too long output name, both one-line errors.
"""

from __future__ import annotations

import contextlib
import io
import math
import os
import random
import shutil
import signal
import subprocess
import sys
import time
import warnings
from pathlib import Path

import numpy as np
import pytest
from fuzz_cases import MAX_MESSAGE, run_cli_inprocess

import eccjump
from eccjump.classification import load as load_region
from eccjump.cli import main
from eccjump.maps import store
from eccjump.motion import maps as motion_maps

xr = pytest.importorskip("xarray")
pytest.importorskip("zarr")

SUFFIXES = (".npz", ".nc", ".zarr")
MAP = ["map", "--mu-s", "1", "--grid", "3", "-q"]


def one_line(err: str) -> str:
    """The one ``eccjump: error:`` line of stderr (no traceback), at most MAX_MESSAGE long."""
    lines = err.strip().splitlines()
    assert len(lines) == 1 and lines[0].startswith("eccjump: error: "), err[-500:]
    assert len(lines[0]) <= MAX_MESSAGE, lines[0]
    return lines[0]


def cli(*argv: str) -> tuple[int, str, str]:
    code, out, err = run_cli_inprocess(list(argv))
    assert "Traceback" not in err, err[-800:]
    return code, out, err


def tree(path: Path) -> dict[str, bytes]:
    """Every file under ``path`` (or ``path`` itself) with its bytes."""
    if path.is_file():
        return {"": path.read_bytes()}
    return {str(p.relative_to(path)): p.read_bytes() for p in path.rglob("*") if p.is_file()}


def refused(fn, path, *args, **kwargs) -> str:
    """The message of the ValueError that ``fn`` raises, checked to name the file ``path``
    and to be short."""
    with pytest.raises(ValueError) as info:
        fn(*args, **kwargs)
    msg = str(info.value)
    assert Path(path).name[-40:] in msg and len(msg) < MAX_MESSAGE, msg
    return msg


@pytest.fixture(scope="module")
def region():
    return eccjump.region(mu_s=1.0, alpha=[0.3, 0.6, 0.9], chi=[0.2, 0.5], km_frac=[0.1, 0.4])


def motion(**axes):
    kw = {"alpha": [0.5, 0.7], "chi": 0.3, "km_frac": [0.2, 0.6], "mu_s": 1.0, **axes}
    return eccjump.motion_map(**kw, t_max=20.0)


# --- 1. writers replace only what they could have written -----------------------------------


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_overwrite_never_deletes_a_directory_of_user_files(tmp_path, region, suffix):
    path = tmp_path / f"d{suffix}"
    path.mkdir()
    (path / "notes.txt").write_text("x")
    code, _, err = cli(*MAP, "-o", str(path), "--overwrite")
    assert code == 2 and "not replaced" in one_line(err) and "-o" in err
    refused(store.save, path, region, path)
    assert tree(path) == {"notes.txt": b"x"}
    assert sorted(os.listdir(tmp_path)) == [path.name]


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_fifo_at_the_output_is_refused_not_opened(tmp_path, region, suffix):
    path = tmp_path / f"f{suffix}"
    os.mkfifo(path)
    code = (
        "import sys\nfrom eccjump.cli import main\n"
        f"sys.exit(main({[*MAP, '-o', str(path), '--overwrite']!r}))"
    )
    p = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=60, check=False
    )
    assert p.returncode == 2 and "a FIFO" in one_line(p.stderr)
    refused(store.save, path, region, path)
    assert path.is_fifo()


def test_a_map_of_ours_is_still_replaced(tmp_path, region):
    for suffix in SUFFIXES:
        path = tmp_path / f"m{suffix}"
        assert cli(*MAP, "-o", str(path))[0] == 0
        assert cli(*MAP, "-o", str(path), "--overwrite", "--grid", "2")[0] == 0
        store.save(region, path)
        assert load_region(path).alpha.size == 3


@pytest.mark.parametrize("suffix", [".npz", ".nc"])
def test_save_keeps_a_users_file_unless_overwrite_is_given(tmp_path, region, suffix):
    """Issue 46, 8: ``maps.save`` replaced any regular file at the path (a user's
    ``mydata.npz``), though its docstring says only a map is replaced. A map is recognised by
    its content: a user's HDF5 file or zip named like a map is not one."""
    path = tmp_path / f"mydata{suffix}"
    user = {".npz": _users_zip, ".nc": _users_hdf5}[suffix](path)
    for save in (store.save, eccjump.maps.save):
        with pytest.raises(FileExistsError) as info:
            save(region, path)
        msg = str(info.value)
        assert isinstance(info.value, ValueError) and len(msg) < MAX_MESSAGE
        assert "mydata" in msg and "overwrite=True" in msg
    code, _, err = cli(*MAP, "-o", str(path))
    assert code == 2 and "--overwrite" in one_line(err) and "not a map" in err
    assert path.read_bytes() == user and sorted(os.listdir(tmp_path)) == [path.name]
    store.save(region, path, overwrite=True)
    assert load_region(path).alpha.size == 3
    store.save(region, path)  # a map of ours now: replaced without being asked
    with pytest.raises(TypeError, match="overwrite"):
        store.save(region, path, overwrite="yes")


def _users_zip(path: Path) -> bytes:
    np.savez(path, data=np.arange(3))  # an .npz, but not a map
    return path.read_bytes()


def _users_hdf5(path: Path) -> bytes:
    xr.Dataset({"t": ("x", np.arange(3.0))}).to_netcdf(path, engine=store.netcdf_engine())
    return path.read_bytes()


def test_a_damaged_map_of_ours_is_still_replaced(tmp_path, region):
    for suffix in (".npz", ".nc"):
        path = tmp_path / f"m{suffix}"
        store.save(region, path)
        data = bytearray(path.read_bytes())
        data[-200:] = bytes(200)  # the data damaged, the head (whose file it is) not
        path.write_bytes(bytes(data))
        store.save(region, path)
        assert load_region(path) == region


def test_a_zarr_store_that_is_not_ours_is_not_replaced(tmp_path, region):
    path = tmp_path / "foreign.zarr"
    xr.Dataset({"foo": ("x", np.arange(3))}).to_zarr(path, zarr_format=3, consolidated=False)
    before = tree(path)
    refused(store.save, path, region, path)
    code, _, err = cli(*MAP, "-o", str(path), "--overwrite")
    assert code == 2 and "not a zarr map of eccjump" in one_line(err)
    assert tree(path) == before


# --- 2. no loader hangs ---------------------------------------------------------------------


def _in_subprocess(code: str, timeout: float = 60) -> str:
    p = subprocess.run(
        [sys.executable, "-c", code], capture_output=True, text=True, timeout=timeout, check=False
    )
    assert p.returncode == 0, p.stderr[-800:]
    return p.stdout.strip()


@pytest.mark.slow
def test_a_netcdf_map_with_zeroed_bytes_is_refused_not_a_hang(tmp_path):
    """The reproducer of the issue: HDF5 loops for ever on 512 zeroed bytes of the global heap
    of a motion map (deaf to Ctrl-C). The probe subprocess is given 2 s here."""
    path = tmp_path / "m.nc"
    _write_raw(store.layout_from_xarray(motion().to_xarray()), path)  # the layout of then
    data = bytearray(path.read_bytes())
    data[3939:4451] = bytes(512)
    path.write_bytes(bytes(data))
    code = f"""
from eccjump import store, motion_maps
from eccjump.classification import load as load_region
store.PROBE_SECONDS = 2
for load in (load_region, store.open_dataset, motion_maps.load):
    try:
        load({str(path)!r})
    except ValueError as err:
        print(err)
"""
    lines = _in_subprocess(code, timeout=90).splitlines()
    assert len(lines) == 3
    for line in lines:
        assert "m.nc" in line and "hangs" in line and len(line) < MAX_MESSAGE


def _children(pid: int) -> list[int]:
    path = Path(f"/proc/{pid}/task/{pid}/children")
    return [int(c) for c in path.read_text().split()] if path.exists() else []


def _gone(pid: int) -> bool:
    """Whether process ``pid`` has ended (a zombie not yet reaped counts as ended)."""
    try:
        return Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()[0] in "ZX"
    except (FileNotFoundError, ProcessLookupError, IndexError):
        return True


def _cpu_seconds(pid: int) -> float:
    fields = Path(f"/proc/{pid}/stat").read_text().rsplit(")", 1)[1].split()
    return (int(fields[11]) + int(fields[12])) / os.sysconf("SC_CLK_TCK")


@pytest.mark.skipif(not sys.platform.startswith("linux"), reason="/proc and PR_SET_PDEATHSIG")
@pytest.mark.parametrize("how", ["SIGKILL", "SIGTERM"])
def test_the_probe_child_dies_with_its_caller(tmp_path, region, how):
    """Issue 46, 2: a caller killed while the netCDF probe spins on a damaged file left the
    child spinning at 100 % CPU for ever, re-parented to init. The probe's reading is
    replaced by a spin (as HDF5 on the damaged file of the test above)."""
    path = tmp_path / "m.nc"
    store.save(region, path)
    code = (
        "from eccjump import store\n"
        "from eccjump.classification import load as load_region\n"
        "store._PROBE_BODY = 'while True: pass'\n"
        "store.PROBE_SECONDS = 600\n"
        f"load_region({str(path)!r})\n"
    )
    parent = subprocess.Popen([sys.executable, "-c", code])
    kids: list[int] = []
    try:
        deadline = time.monotonic() + 60
        while not (kids := _children(parent.pid)) or _cpu_seconds(kids[0]) < 0.5:
            assert time.monotonic() < deadline and parent.poll() is None
            time.sleep(0.05)
        parent.send_signal(getattr(signal, how))
        parent.wait(10)
        deadline = time.monotonic() + 2
        while not _gone(kids[0]) and time.monotonic() < deadline:
            time.sleep(0.02)
        assert _gone(kids[0]), f"the probe child {kids[0]} outlived its caller"
    finally:
        parent.kill()
        for kid in kids:  # a child left over by a failure
            with contextlib.suppress(ProcessLookupError):
                os.kill(kid, signal.SIGKILL)


@pytest.mark.skipif(os.name != "posix", reason="RLIMIT_CPU")
def test_the_probe_child_stops_after_its_cpu_time(tmp_path, monkeypatch):
    """The backstop where PR_SET_PDEATHSIG is missing: the child stops itself (SIGXCPU, no
    core file) after its time, whoever waits for it."""
    monkeypatch.setattr(store, "_PROBE_BODY", "while True: pass")
    start = time.monotonic()
    proc = subprocess.run(
        store.probe_command("netcdf4", tmp_path / "x.nc", 0.5),
        cwd=tmp_path,
        capture_output=True,
        timeout=30,
        check=False,
    )
    assert proc.returncode in (-signal.SIGXCPU, -signal.SIGKILL), proc
    assert time.monotonic() - start < 10 and os.listdir(tmp_path) == []


def test_every_loader_refuses_a_fifo_without_opening_it(tmp_path):
    for suffix in SUFFIXES:
        os.mkfifo(tmp_path / f"f{suffix}")
    code = f"""
from pathlib import Path
from eccjump import store, motion_maps
from eccjump.classification import load as load_region
for p in sorted(Path({str(tmp_path)!r}).iterdir()):
    for load in (load_region, store.open_dataset, store.load_layout, motion_maps.load):
        try:
            load(p)
        except ValueError as err:
            print(err)
"""
    lines = _in_subprocess(code).splitlines()
    assert len(lines) == 12 and all("a FIFO" in line for line in lines), lines


# --- 3. resume validates what it reads -------------------------------------------------------


def _map_store(tmp_path: Path, *args: str) -> tuple[Path, xr.Dataset]:
    path = tmp_path / "c.zarr"
    assert cli(*MAP, "--chunk", "1", "-o", str(path), *args)[0] == 0
    return path, store.open_dataset(path)


def _same(path: Path, ref: xr.Dataset) -> bool:
    ds = store.open_dataset(path)
    return all(np.array_equal(ds[k].values, ref[k].values, equal_nan=True) for k in ref.data_vars)


def test_a_lost_chunk_is_computed_again_on_resume(tmp_path):
    """The reproducer: a deleted chunk of ``reason`` read as 255 and the resume ended with exit
    0 and a map of unfinished points."""
    path, ref = _map_store(tmp_path)
    (path / "reason" / "c" / "1" / "0" / "0").unlink()
    code, _, err = cli(*MAP, "-o", str(path), "--resume")
    assert code == 0 and "chunk 1 is damaged" in err
    assert _same(path, ref)
    load_region(path)


def test_a_garbage_chunk_is_computed_again_on_resume(tmp_path):
    """A garbage chunk raised RuntimeError from zstd."""
    path, ref = _map_store(tmp_path)
    chunk = path / "theta_J" / "c" / "0" / "0" / "0"
    chunk.write_bytes(random.Random(0).randbytes(chunk.stat().st_size))
    code, _, err = cli(*MAP, "-o", str(path), "--resume")
    assert code == 0 and "chunk 0 is damaged" in err
    assert _same(path, ref)


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["jarm", "motion"])
def test_a_resume_of_a_damaged_store_ends_whole_or_with_one_error_line(tmp_path, kind):
    """Each file of a store deleted, filled with garbage or zeros, or cut in half: a resume
    ends either with exit 0 and the map of a fresh run, or exit 2 and one error line."""
    args = ("--kind", "motion") if kind == "motion" else ()
    good, ref = _map_store(tmp_path, *args)
    files = sorted(p.relative_to(good) for p in good.rglob("*") if p.is_file())
    rng = random.Random(35)
    cases = [(f, how) for f in files for how in ("delete", "garbage", "zero", "cut")]
    load = load_region if kind == "jarm" else motion_maps.load
    for name, how in rng.sample(cases, 12):
        path = tmp_path / "d.zarr"
        shutil.rmtree(path, ignore_errors=True)
        shutil.copytree(good, path)
        target = path / name
        data = target.read_bytes()
        damaged = {
            "delete": None,
            "garbage": rng.randbytes(len(data)),
            "zero": bytes(len(data)),
            "cut": data[: len(data) // 2],
        }[how]
        target.unlink() if damaged is None else target.write_bytes(damaged)
        code, _, err = cli(*MAP, *args, "--chunk", "1", "-o", str(path), "--resume")
        if code == 0:
            load(path)
            assert _same(path, ref), (name, how)
        else:
            last = err.strip().splitlines()[-1]
            assert code == 2 and last.startswith("eccjump: error: "), (name, how, err)
            assert len(last) <= MAX_MESSAGE, last


def test_the_motion_kind_refuses_a_nan_mu_s_as_the_jarm_kind(tmp_path):
    for kind in ("jarm", "motion"):
        path = tmp_path / f"{kind}.npz"
        code, _, err = cli(*MAP, "--kind", kind, "--mu-s", "nan", "-o", str(path))
        assert code == 2 and "mu_s" in one_line(err)
        assert not path.exists()
    for bad in ({"mu_s": math.nan}, {"restitution": 2.0}, {"mu_k": -1.0}, {"chi": math.inf}):
        name = next(iter(bad))
        with pytest.raises(ValueError, match=rf"^{name} = ") as info:
            motion(**bad)
        assert len(str(info.value)) < MAX_MESSAGE
    m = motion(mu_s=[0.5, 1.0], mu_k=0.8)  # a swept axis may hold invalid points
    assert (m.status[..., 0] == motion_maps.INVALID).all()


# --- 4. one checked loader path --------------------------------------------------------------


def _write_raw(lay: dict, path: Path) -> None:
    """Write ``lay`` as it is, past the checks of store.save (a damaged or foreign file)."""
    if path.suffix == ".npz":
        store.save_npz(lay, path)
    elif path.suffix == ".nc":
        store.layout_to_xarray(lay).to_netcdf(path, engine=store.netcdf_engine())
    else:
        store.layout_to_xarray(lay).to_zarr(path, zarr_format=3, consolidated=False)


def _edited(lay: dict, part: str, name: str, edit) -> dict:
    dims, values, attrs = lay[part][name]
    values = np.array(values, copy=True)
    new = values if (new := edit(values)) is None else new
    return {**lay, part: {**lay[part], name: (dims[: new.ndim], new, attrs)}}


JARM_BAD = {
    "code out of its table": ("data_vars", "reason", lambda v: v.fill(200)),
    "NaN coordinate": ("coords", "alpha", lambda v: v.__setitem__(0, np.nan)),
    "wrong shape": ("data_vars", "theta_J", lambda v: v[:, :, 0]),
    "is_jarm against reason": ("data_vars", "is_jarm", lambda v: v.fill(True)),
}
MOTION_BAD = {
    "status out of its table": ("data_vars", "status", lambda v: v.fill(77)),
    "no sequence code": ("data_vars", "sequence", lambda v: v.fill(4)),
    "landing out of its table": ("data_vars", "landing", lambda v: v.fill(9)),
    "NaN coordinate": ("coords", "km_frac", lambda v: v.__setitem__(0, np.nan)),
}


@pytest.mark.slow
@pytest.mark.parametrize("suffix", SUFFIXES)
def test_loaders_refuse_bad_codes_nan_coordinates_and_wrong_shapes(tmp_path, region, suffix):
    good = {"jarm": region.to_layout(), "motion": store.layout_from_xarray(
        motion().to_xarray())}  # fmt: skip
    loaders = {
        "jarm": (load_region, store.open_dataset, store.load_layout),
        "motion": (motion_maps.load, store.open_dataset),
    }
    for kind, bad in (("jarm", JARM_BAD), ("motion", MOTION_BAD)):
        for what, (part, name, edit) in bad.items():
            path = tmp_path / f"{kind}-{what.replace(' ', '-')}{suffix}"
            _write_raw(_edited(good[kind], part, name, edit), path)
            for load in loaders[kind]:
                refused(load, path, path)
            with pytest.raises(ValueError, match="obj"):  # and save refuses to write it
                store.save(_edited(good[kind], part, name, edit), tmp_path / f"x{suffix}")


def _set(index, value):
    return lambda v: v.__setitem__(index, value)


#: Issue 46, 7: values outside their physical range, written with the raw library. A
#: coordinate out of its range is refused only with valid points there (a map keeps the
#: invalid points its computation marked so).
OUT_OF_RANGE = {
    "jarm": {
        "alpha 10 rad": {
            ("coords", "alpha"): _set(0, 10.0),
            ("coords", "alpha_deg"): _set(0, math.degrees(10.0)),
        },
        "theta_J -inf": {("data_vars", "theta_J"): lambda v: v.fill(-math.inf)},
        "a JARM without theta_J": {("data_vars", "theta_J"): lambda v: v.fill(math.nan)},
        "Fy_J < 0": {("data_vars", "Fy_J"): lambda v: np.negative(v, out=v)},
        "alpha_deg not alpha's": {("coords", "alpha_deg"): _set(1, 35.0)},
        "mu_s -1": {("attrs", "mu_s"): -1.0},
    },
    "motion": {
        "energy_lost -5": {("data_vars", "energy_lost"): lambda v: v.fill(-5.0)},
        "alpha 10 rad": {("coords", "alpha"): _set(0, 10.0)},
        "km_frac 2": {("coords", "km_frac"): _set(1, 2.0)},
        "liftoff_t lost": {("data_vars", "liftoff_t"): lambda v: v.fill(math.nan)},
        "negative time": {("data_vars", "slip_t"): lambda v: v.fill(-1.0)},
        "restitution 2": {("attrs", "restitution"): 2.0},
    },
}


def _edits(lay: dict, edits: dict) -> dict:
    lay = {part: dict(lay[part]) for part in ("coords", "data_vars", "attrs")}
    for (part, name), edit in edits.items():
        if part == "attrs":
            lay["attrs"][name] = edit
            continue
        dims, values, attrs = lay[part][name]
        values = np.array(values, dtype=np.float64, copy=True)
        edit(values)
        lay[part][name] = (dims, values, attrs)
    return lay


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_values_outside_their_physical_range_are_refused(tmp_path, suffix):
    region = eccjump.region(mu_s=1.0, alpha=[0.3, 0.6, 0.9], chi=[0.1, 0.2], km_frac=[0.01, 0.1])
    good = {"jarm": region.to_layout(), "motion": store.layout_from_xarray(
        motion(chi=[0.2, 0.4]).to_xarray())}  # fmt: skip
    assert region.result.is_jarm.any()  # a JARM to lose its theta_J
    assert (good["motion"]["data_vars"]["liftoff_reason"][1] != 255).any()
    loaders = {"jarm": (load_region, store.open_dataset), "motion": (motion_maps.load,)}
    for kind, cases in OUT_OF_RANGE.items():
        for what, edits in cases.items():
            path = tmp_path / f"{kind}-{what.replace(' ', '-')}{suffix}"
            _write_raw(_edits(good[kind], edits), path)
            for load in loaders[kind]:
                refused(load, path, path)
            with pytest.raises(ValueError, match=r"^obj"):
                store.save(_edits(good[kind], edits), tmp_path / f"x{suffix}")


def test_out_of_range_coordinates_of_invalid_points_are_kept(tmp_path):
    """region and motion_map mark the points of a coordinate out of range invalid and go
    on: such a map is saved and loaded as it is."""
    reg = eccjump.region([0.5, 10.0], [0.2, 1.5], [0.1], 1.0)
    m = eccjump.motion_map([0.5, 10.0], 0.3, [0.2, 2.0], [1.0, -1.0], t_max=5.0)
    for suffix in SUFFIXES:
        assert eccjump.load_map(store.save(reg, tmp_path / f"r{suffix}")) == reg
        assert eccjump.load_map(store.save(m, tmp_path / f"m{suffix}")) == m


def test_messages_stay_short_for_long_paths(tmp_path):
    deep = tmp_path / ("d" * 120) / ("e" * 120)
    deep.mkdir(parents=True)
    for suffix in SUFFIXES:
        path = deep / (("x" * 150) + suffix)
        (path.mkdir() if suffix == ".zarr" else path.write_bytes(b"garbage" * 10))
        for load in (load_region, store.open_dataset, motion_maps.load):
            refused(load, path, path)


def test_save_refuses_attrs_that_contradict_the_data(tmp_path, region):
    for attrs in ({"kind": "motion"}, {"kind": "other"}, {"mu_s": math.nan}, {"rule": 3}):
        with pytest.raises(ValueError, match=r"^attrs") as info:
            store.save(region, tmp_path / "h.npz", attrs=attrs)
        assert len(str(info.value)) < MAX_MESSAGE
    assert os.listdir(tmp_path) == []
    store.save(region, tmp_path / "h.npz", attrs={"note": "kept"})
    assert load_region(tmp_path / "h.npz").attrs["note"] == "kept"


@pytest.mark.parametrize(
    "attrs", [{"x": object()}, {"x": True}, {"x": {"a": 1}}, {"x": [[1]]}, {"x": [1, "a"]}, {3: 1}]
)
def test_save_of_attrs_no_format_stores_names_attrs(tmp_path, region, attrs):
    """Issue 46, 14: ``attrs={'x': object()}`` was a TypeError of json naming nothing (and a
    bool one of netCDF4's): the same refusal for every format, naming ``attrs``."""
    for suffix in SUFFIXES:
        with pytest.raises(ValueError, match=r"^attrs") as info:
            store.save(region, tmp_path / f"h{suffix}", attrs=attrs)
        assert len(str(info.value)) < MAX_MESSAGE
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("obj", [{}, {"coords": {}, "data_vars": {}, "attrs": {}}, [], 3])
def test_save_of_no_map_names_obj(tmp_path, obj):
    with pytest.raises((TypeError, ValueError), match=r"^obj") as info:
        store.save(obj, tmp_path / "x.npz")
    assert len(str(info.value)) < MAX_MESSAGE and os.listdir(tmp_path) == []


def test_open_dataset_wraps_the_readers_errors(tmp_path):
    (tmp_path / "empty.zarr").mkdir()  # GroupNotFoundError
    (tmp_path / "bad.npz").write_bytes(b"PK\x03\x04 not a zip")  # BadZipFile
    np.save(tmp_path / "cut.npy", np.arange(100))
    (tmp_path / "cut.npz").write_bytes(b"")  # EOFError
    for name in ("empty.zarr", "bad.npz", "cut.npz"):
        msg = refused(store.open_dataset, name, tmp_path / name)
        assert "not a readable" in msg


AXES = motion_maps.AXES
SWEPT = {
    "alpha": [0.5, 0.8],
    "chi": [0.2, 0.4],
    "km_frac": [0.3, 0.6],
    "mu_s": [0.5, 1.0],
    "mu_k": [0.3, 0.5],
    "restitution": [0.0, 0.5],
    "theta0": [0.0, 0.2],
    "omega0": [0.0, 0.3],
}
ONE = {"alpha": 0.6, "chi": 0.3, "km_frac": 0.5, "mu_s": 1.0, "restitution": 0.2, "theta0": 0.1}
ONE["omega0"] = 0.1


def _same_map(a: motion_maps.MotionMap, b: motion_maps.MotionMap) -> None:
    assert list(a.coords) == list(b.coords)
    for k in a.coords:
        assert a.coords[k].tobytes() == b.coords[k].tobytes(), k
    mu_s = a.scalars.get("mu_s")
    norm = [{k: (mu_s if k == "mu_k" and v is None else v) for k, v in m.scalars.items()}
            for m in (a, b)]  # fmt: skip
    assert norm[0] == norm[1]  # mu_k not given is mu_k = mu_s
    for k in motion_maps.FIELDS:
        assert a.fields[k].tobytes() == b.fields[k].tobytes(), k


@pytest.mark.parametrize("seed", range(12))
def test_motion_maps_with_any_axes_scalar_round_trip(tmp_path, seed):
    rng = random.Random(seed)
    swept = [a for a in AXES if rng.random() < 0.4]
    kw = {a: SWEPT[a] if a in swept else ONE.get(a) for a in AXES}
    m = eccjump.motion_map(**kw, t_max=5.0)
    assert list(m.coords) == swept
    _same_map(m, motion_maps.from_dataset(m.to_xarray()))
    path = tmp_path / f"m{SUFFIXES[seed % 3]}"
    store.save(m.to_xarray() if seed % 2 else m, path)
    _same_map(m, motion_maps.load(path))


def test_from_dataset_of_a_swept_mu_s(tmp_path):
    ds = motion(mu_s=[0.5, 1.0])
    back = motion_maps.from_dataset(motion(mu_s=[0.5, 1.0]).to_xarray())
    _same_map(ds, back)
    assert back.scalars["mu_k"] is None
    with pytest.raises(ValueError, match=r"^ds "):
        motion_maps.from_dataset(
            eccjump.region(mu_s=1.0, alpha=[0.5], chi=[0.2], km_frac=[0.1]).to_xarray()
        )


# --- 5. eccjump map: bounded grid, long names -----------------------------------------------


@pytest.mark.parametrize("option", ["--grid", "--n-alpha", "--n-chi", "--n-km-frac"])
def test_a_huge_grid_is_one_error_line_naming_the_option(tmp_path, option):
    err = io.StringIO()
    with contextlib.redirect_stderr(err), pytest.raises(SystemExit) as info:
        main([*MAP, option, "4294967296", "-o", str(tmp_path / "m.zarr")])
    assert info.value.code == 2
    last = err.getvalue().strip().splitlines()[-1]
    assert option in last and "[1, 1000000]" in last and len(last) <= MAX_MESSAGE
    assert os.listdir(tmp_path) == []


@pytest.mark.parametrize("suffix", SUFFIXES)
def test_a_too_long_output_name_is_one_error_line(tmp_path, region, suffix):
    for size in (300, 250):
        path = tmp_path / (("x" * size) + suffix)
        code, _, err = cli(*MAP, "-o", str(path))
        assert code == 2 and "name of" in one_line(err) and "-o" in err
        refused(store.save, path, region, path)
    assert os.listdir(tmp_path) == []


# --- 6. issue 46: checksums, lost chunks, bounded metadata ------------------------------------


@pytest.fixture(scope="module")
def maps_of_both_kinds() -> dict[str, eccjump.Map]:
    grid = {"alpha": [0.3, 0.6, 0.9], "chi": [0.1, 0.2], "km_frac": [0.01, 0.1]}
    return {"jarm": eccjump.region(mu_s=1.0, **grid), "motion": motion(chi=[0.2, 0.4])}


def _arrays(m: eccjump.Map) -> dict[str, np.ndarray]:
    return {**{k: np.asarray(v) for k, v in m.coords.items()}, **m.fields}


def _flip_in(path: Path, values: np.ndarray, zero: int = 0) -> None:
    """Flip a bit in the stored bytes of ``values`` in the file ``path`` (the first copy),
    or zero ``zero`` bytes there."""
    data = bytearray(path.read_bytes())
    at = data.find(values.tobytes())
    assert at >= 0, "the array is stored as it is"
    if zero:
        data[at : at + zero] = bytes(zero)
    else:
        data[at + values.nbytes // 2] ^= 0x10
    path.write_bytes(bytes(data))


@pytest.mark.slow
@pytest.mark.parametrize("kind", ["jarm", "motion"])
@pytest.mark.parametrize("suffix", [".npz", ".nc"])
def test_a_flipped_bit_or_a_zeroed_block_in_a_file_is_refused(
    tmp_path, maps_of_both_kinds, kind, suffix
):
    """Issue 46, 6: a 1-bit flip loaded alpha = 35 deg instead of 70, a zeroed block of a .nc
    other lift-off times. Each array's bytes damaged in turn: every load refuses the file
    (.npz: zip's CRC-32; .nc: Fletcher-32), none reads other numbers."""
    m = maps_of_both_kinds[kind]
    good = store.save(m, tmp_path / f"good{suffix}")
    for name, values in _arrays(m).items():
        if values.nbytes < 8 or values.dtype.kind == "b":
            continue  # a bool's bytes (0/1) are found anywhere: not located by value
        for zero in (0, min(values.nbytes, 512)):
            path = tmp_path / f"{name}-{zero}{suffix}"
            shutil.copyfile(good, path)
            _flip_in(path, values, zero)
            refused(eccjump.load_map, path, path)


@pytest.mark.parametrize("kind", ["jarm", "motion"])
def test_damaged_or_lost_zarr_chunks_are_refused(tmp_path, maps_of_both_kinds, kind):
    """Issue 46, 6: a flipped bit in a chunk read as other numbers, a deleted chunk of
    theta_J as a JARM with theta_J = NaN (zarr's fill value). Every chunk of every array:
    crc32c refuses the flip, a missing chunk is damage."""
    m = maps_of_both_kinds[kind]
    good = store.save(m, tmp_path / "good.zarr")
    chunks = sorted(p.relative_to(good) for p in good.rglob("c/**/*") if p.is_file())
    assert {c.parts[0] for c in chunks} >= set(m.fields) | set(m.coords)
    for chunk in chunks:
        for how in ("flip", "delete"):
            path = tmp_path / f"{how}.zarr"
            shutil.rmtree(path, ignore_errors=True)
            shutil.copytree(good, path)
            if how == "delete":
                (path / chunk).unlink()
            else:
                data = bytearray((path / chunk).read_bytes())
                data[len(data) // 2] ^= 0x01
                (path / chunk).write_bytes(bytes(data))
            msg = refused(eccjump.load_map, path, path)
            assert ("missing" if how == "delete" else "checksum") in msg, msg


def test_an_interrupted_zarr_map_loads_without_its_chunks_not_computed(tmp_path):
    """The chunks of slices not computed are not written: not damage; a chunk of a slice
    done is."""
    path = tmp_path / "part.zarr"
    assert cli(*MAP, "--chunk", "1", "--stop-after", "1", "-o", str(path))[0] == 130
    assert not (path / "theta_J" / "c" / "1" / "0" / "0").exists()
    assert load_region(path).attrs["alpha_done"].tolist() == [True, False, False]
    (path / "theta_J" / "c" / "0" / "0" / "0").unlink()
    assert "theta_J/c/0/0/0 is missing" in refused(load_region, path, path)


@pytest.mark.parametrize("suffix", [".nc", ".zarr"])
def test_a_map_written_without_checksums_loads_with_a_warning(tmp_path, region, suffix):
    """The files of earlier builds (no Fletcher-32, no crc32c) are read, with a warning that
    their damage cannot be found; saving them again adds the checksums."""
    old = tmp_path / f"old{suffix}"
    _write_raw(region.to_layout(), old)
    with pytest.warns(eccjump.store.UncheckedMapWarning, match="no checksums"):
        assert load_region(old) == region
    new = store.save(load_region(old), tmp_path / f"new{suffix}")
    with warnings.catch_warnings():
        warnings.simplefilter("error")
        assert load_region(new) == region


@pytest.mark.parametrize("where", ["zarr.json", "theta_J/zarr.json"])
def test_a_huge_sparse_zarr_json_is_refused_before_it_is_read(tmp_path, region, where):
    """Issue 46, 3: a 1 TB sparse zarr.json was a MemoryError with an empty message."""
    path = store.save(region, tmp_path / "big.zarr")
    with open(path / where, "r+b") as fh:
        fh.truncate(10**12)
    for load in (load_region, store.open_dataset, eccjump.load_map):
        msg = refused(load, path, path)
        assert where in msg and "1,000,000,000,000 bytes" in msg, msg
    code, _, err = cli(*MAP, "-o", str(path), "--resume")
    assert code == 2 and "1,000,000,000,000 bytes" in one_line(err)

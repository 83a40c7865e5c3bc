"""Maps of any kind on disk, the format chosen by the suffix: ``.nc`` (netCDF4, engine h5netcdf
or netCDF4), ``.zarr`` (zarr v3 directory store) or ``.npz`` (numpy; needs neither xarray nor
zarr).

This module reads and writes layouts (:mod:`eccjump.maps.layout`), whatever their kind
(:mod:`eccjump.maps.kinds`): :func:`save` writes a map, a dataset or a layout,
:func:`read_layout` reads one back with its kind, checked (:func:`eccjump.maps.load` makes it
the map's class, :func:`open_dataset` a dataset). :class:`ZarrMap`
writes a map chunk by chunk along α, recording finished α slices in the data
variable ``alpha_done`` (written after the data of its chunk), so that an interrupted map
keeps what was finished and can be resumed; the attribute ``complete`` (0/1) says whether
every slice is there. Points not computed hold the kind's fill values (a JARM map: NaN,
``is_jarm`` False, ``n`` 0 and ``reason`` 255, not a :class:`~eccjump.Reason`).

A map is never half there. Every new file or store is written under a temporary sibling name
(``.<name>.tmp-<pid>``, same directory) and renamed into place by :func:`install`; a map it
replaces is removed only after that (a directory is swapped in with one atomic
``renameat2(RENAME_EXCHANGE)`` on Linux, elsewhere the old one is renamed aside to
``.<name>.old-<pid>`` first). :func:`recover` removes what a killed process left behind and
puts back a map left aside. A missing parent directory is an error, never created. What may
be replaced is the one overwrite policy of :mod:`eccjump._base.overwrite` (:func:`is_map`: a map
of eccjump, by its content). Every format carries checksums and a missing zarr chunk is
damage (:mod:`eccjump.maps.integrity`); every value is checked against its physical range
(:mod:`eccjump.maps.check`).
"""

from __future__ import annotations

import ctypes
import errno
import json
import math
import os
import re
import shutil
import signal
import stat
import subprocess
import sys
import warnings
import zipfile
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any, Literal

import numpy as np
from numpy.typing import NDArray

from eccjump import _compat
from eccjump._base.checks import file_error, flag, mapping, shown
from eccjump._base.checks import path as check_path
from eccjump._base.overwrite import check_overwrite, file_type
from eccjump.maps.check import Invalid, attr_problem, check, check_layout
from eccjump.maps.integrity import UncheckedMapWarning as UncheckedMapWarning  # public here
from eccjump.maps.integrity import (
    check_metadata_size,
    check_netcdf,
    check_zarr,
    netcdf_encoding,
    zarr_codecs,
)
from eccjump.maps.kinds import MapKind, kind_of, upgrade_attrs
from eccjump.maps.layout import (
    COORD_ATTRS,
    DIMS,
    Layout,
    attrs_json,
    grid_coords,
    layout_from_xarray,
    layout_to_xarray,
    require,
)
from eccjump.maps.map import Map

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

FORMATS = {".nc": "netcdf", ".zarr": "zarr", ".npz": "npz"}


def format_of(path: str | os.PathLike) -> str:
    """The format of a map file by its suffix.

    Parameters
    ----------
    path : str or os.PathLike
        A path ending in ``.nc``, ``.zarr`` or ``.npz`` (any case).

    Returns
    -------
    str
        ``"netcdf"``, ``"zarr"`` or ``"npz"``.

    Raises
    ------
    ValueError
        For another suffix.

    Examples
    --------
    >>> from eccjump import store
    >>> store.format_of("region.nc"), store.format_of("map.NPZ")
    ('netcdf', 'npz')
    """
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(
            f"path {str(path)[-80:]!r}: unknown output format {suffix[:20]!r}; "
            "use .nc, .zarr or .npz"
        )
    return FORMATS[suffix]


def netcdf_engine() -> Literal["h5netcdf", "netcdf4"]:
    """h5netcdf if it and h5py are installed, else netCDF4."""
    engines: tuple[tuple[tuple[str, ...], Literal["h5netcdf", "netcdf4"]], ...] = (
        (("h5netcdf", "h5py"), "h5netcdf"),
        (("netCDF4",), "netcdf4"),
    )
    for modules, engine in engines:
        try:
            for module in modules:
                __import__(module)
            return engine
        except ImportError:
            continue
    require("h5netcdf")  # raises with the install hint
    raise AssertionError  # pragma: no cover


def _as_layout(obj: object) -> Layout:
    """The layout of ``obj``: a map (:class:`~eccjump.Map`, computed if lazy), a layout or a
    dataset; TypeError naming ``obj`` else."""
    if isinstance(obj, Map):
        return obj.compute().to_layout()
    if isinstance(obj, dict):
        return obj
    if hasattr(type(obj), "data_vars"):
        return layout_from_xarray(obj)  # type: ignore[arg-type]
    raise TypeError(
        f"obj must be a Region, a MotionMap, an xarray.Dataset or a layout, not {type(obj)}"
    )


def _valid_layout(obj: object, attrs: Mapping[str, Any] | None) -> Layout:
    """The layout of ``obj`` with ``attrs``, a valid map: ValueError naming ``obj`` if it is
    none, ``attrs`` if they make it none (another ``kind``, a NaN ``mu_s``, ...), so that
    :func:`save` writes nothing that :func:`load` refuses."""
    lay = _as_layout(obj)
    _check_given("obj", lay)
    if attrs:
        problem = attr_problem(attrs, "attrs")
        if problem:
            raise ValueError(problem[:180])
        lay = {**lay, "attrs": {**lay["attrs"], **attrs}}
        _check_given("attrs", lay)
    return lay


def _check_given(name: str, lay: Layout) -> None:
    try:
        check(lay)
        problem = attr_problem(lay["attrs"], "attrs")
        if problem:
            raise Invalid(problem)
    except Invalid as err:
        raise ValueError(f"{name}: the map {err}"[:180]) from None


#: Test hook, for tests/test_map.py only: ``ECCJUMP_TEST_KILL_AT=<step>`` (or ``<step>:<k>``,
#: the k-th time the step is reached) makes the process SIGKILL itself at that named step of
#: the write protocol, to check that a map survives a crash at every step. See STEPS.
KILL_AT_ENV = "ECCJUMP_TEST_KILL_AT"

#: The named steps of the write protocol, in order (see :func:`_step`): ``create`` (a new
#: zarr store half built, under its temporary name), ``created`` (built), ``chunk-data`` (a
#: chunk's data written, not yet marked in ``alpha_done``), ``chunk-done`` (marked),
#: ``published`` (a new zarr map renamed into place after its first chunk), ``finish`` (the
#: attributes updated, metadata not yet consolidated), ``finished``, ``written`` (a new file
#: or store complete under its temporary name), ``replaced`` (renamed into place, the map it
#: replaces not yet removed).
STEPS = (
    "create",
    "created",
    "chunk-data",
    "chunk-done",
    "published",
    "finish",
    "finished",
    "written",
    "replaced",
)
_step_counts: dict[str, int] = {}


def _step(name: str) -> None:
    """Reached step ``name`` of the write protocol: a no-op unless the test hook asks to die."""
    want = os.environ.get(KILL_AT_ENV)
    if not want:
        return
    _step_counts[name] = _step_counts.get(name, 0) + 1
    step, _, k = want.partition(":")
    if step == name and _step_counts[name] == int(k or 1):
        os.kill(os.getpid(), getattr(signal, "SIGKILL", signal.SIGTERM))


def temp_sibling(path: str | os.PathLike, tag: str = "tmp") -> Path:
    """``.<name>.<tag>-<pid>`` next to ``path``: where a new map is written before it is
    renamed into place (``tag`` ``"old"``: where a replaced map waits to be removed)."""
    path = Path(path)
    return path.with_name(f".{path.name}.{tag}-{os.getpid()}")


def remove(path: str | os.PathLike) -> None:
    """Remove a file or a directory tree if it exists."""
    path = Path(path)
    if path.is_dir() and not path.is_symlink():
        shutil.rmtree(path)
    else:
        path.unlink(missing_ok=True)


def check_parent(path: str | os.PathLike) -> None:
    """FileNotFoundError/NotADirectoryError unless the directory of ``path`` exists (it is
    never created)."""
    parent = Path(path).absolute().parent
    if not parent.exists():
        raise FileNotFoundError(errno.ENOENT, "no such directory", str(parent))
    if not parent.is_dir():
        raise NotADirectoryError(errno.ENOTDIR, "not a directory", str(parent))


def name_room(path: Path, tmp: Path) -> int:
    """The longest name (bytes) ``path`` may have in its directory so that ``tmp``, the name
    it is written under first, still fits: the file system's NAME_MAX less what ``tmp``
    adds."""
    try:
        name_max = os.pathconf(path.absolute().parent, "PC_NAME_MAX")
    except (OSError, ValueError, AttributeError):
        name_max = 255
    return name_max - (len(tmp.name) - len(path.name))


def check_name(path: str | os.PathLike) -> None:
    """ValueError naming ``path`` if its name is too long for its directory once made into the
    longer name of its temporary sibling (:func:`temp_sibling`)."""
    path = Path(path)
    longest = name_room(path, temp_sibling(path))
    size = len(os.fsencode(path.name))
    if size > longest:
        raise file_error(path, f"has a name of {size} bytes, more than the {longest} allowed here")


def _our_zarr_map(path: Path) -> bool:
    """Whether the directory ``path`` is a zarr map written by eccjump: a group whose
    attributes carry ``eccjump_version``, holding nothing but zarr arrays."""
    try:
        check_metadata_size(path)
        meta = json.loads((path / "zarr.json").read_text())
        entries = list(path.iterdir())
        attrs = meta["attributes"]
        ours = meta["node_type"] == "group" and "eccjump_version" in attrs
        return ours and all(
            e.name == "zarr.json"
            or (e.is_dir() and not e.is_symlink() and (e / "zarr.json").is_file())
            for e in entries
        )
    except (OSError, ValueError, TypeError, KeyError):
        return False


#: The first bytes of a map file that say whose it is: an HDF5 (netCDF4) map of eccjump has
#: its global attributes, ``eccjump_version`` among them, within them.
_HEAD_BYTES = 65536
_HDF5_SIGNATURE = b"\x89HDF\r\n\x1a\n"
#: The start of an .npz map (:func:`save_npz`): the zip header of its member __layout__.npy.
_ZIP_LAYOUT = re.compile(rb"PK\x03\x04.{22}\x0e\x00..__layout__\.npy", re.DOTALL)


def is_map(path: str | os.PathLike) -> bool:
    """Whether ``path`` holds a map of eccjump, by its content (never by its name): a zarr
    map (:func:`_our_zarr_map`), an .npz archive holding the member ``__layout__.npy``, or a
    netCDF4 (HDF5) file with ``eccjump_version`` among its first bytes. Damaged or not: a
    writer may replace it. Nothing but regular files and directories is opened."""
    path = Path(path)
    try:
        mode = os.stat(path).st_mode
        if stat.S_ISDIR(mode):
            return _our_zarr_map(path)
        if not stat.S_ISREG(mode):
            return False
        with open(path, "rb") as fh:
            head = fh.read(_HEAD_BYTES)
        if _ZIP_LAYOUT.match(head):  # the first member (a damaged end is no matter)
            return True
        if head.startswith(b"PK"):
            with zipfile.ZipFile(path) as z:
                return "__layout__.npy" in z.namelist()
    except (OSError, ValueError, EOFError, zipfile.BadZipFile):
        return False
    return head.startswith(_HDF5_SIGNATURE) and b"eccjump_version" in head


def check_replaceable(
    path: str | os.PathLike,
    by_directory: bool,
    *,
    overwrite: bool = False,
    option: str = "overwrite=True",
) -> None:
    """The overwrite policy (:mod:`eccjump._base.overwrite`) for a map written to ``path``: a new
    map file (``by_directory`` False) replaces a regular file that is a map of eccjump
    (:func:`is_map`), or any regular file with ``overwrite``; a zarr store (True) replaces
    only a zarr map of eccjump. Anything else is an :class:`~eccjump._base.overwrite.ExistsError`
    (a ValueError) naming ``path`` and ``option``."""
    what = "a zarr map of eccjump" if by_directory else "a map of eccjump"
    check_overwrite(
        path, overwrite=overwrite, option=option, ours=is_map, what=what, directory=by_directory
    )


def check_target(path: str | os.PathLike, fmt: str, *, overwrite: bool = False) -> None:
    """Before a map of ``fmt`` is written to ``path``: its directory exists
    (FileNotFoundError/NotADirectoryError), its name is not too long and what is there, if
    anything, may be replaced (:func:`check_replaceable`: ValueError naming ``path``)."""
    check_parent(path)
    check_name(path)
    if os.path.lexists(path):
        check_replaceable(path, fmt == "zarr", overwrite=overwrite)


def _alive(pid: int) -> bool:
    """Whether process ``pid`` may still be running (True when it cannot be told)."""
    if pid == os.getpid() or os.name != "posix":
        return True
    try:
        os.kill(pid, 0)
    except ProcessLookupError:
        return False
    except OSError:
        return True
    return True


def recover(path: str | os.PathLike) -> list[str]:
    """Clean up after a process killed while writing ``path``.

    Removes its temporary ``.<name>.tmp-<pid>``, and puts back a map it had set aside
    (``.<name>.old-<pid>``) if ``path`` is missing, else removes that too. Only names of
    processes no longer running are touched (POSIX; elsewhere nothing is done).

    Parameters
    ----------
    path : str or os.PathLike
        The map's path.

    Returns
    -------
    list of str
        Notes of what was put back.
    """
    path = Path(path)
    pattern = re.compile(rf"\.{re.escape(path.name)}\.(tmp|old)-(\d+)")
    notes: list[str] = []
    try:
        siblings = sorted(path.parent.iterdir())
    except OSError:
        return notes
    for sib in siblings:
        m = pattern.fullmatch(sib.name)
        if not m or _alive(int(m[2])):
            continue
        if m[1] == "old" and not os.path.lexists(path):
            os.rename(sib, path)
            notes.append(f"put back {path}, left aside as {sib.name} by an interrupted write")
        else:
            remove(sib)
    return notes


_RENAME_NOREPLACE, _RENAME_EXCHANGE = 1, 2


def _renameat2(src: Path, dst: Path, flags: int) -> bool:
    """Linux ``renameat2``; False where it is not available (other systems, old kernels or
    C libraries, file systems without the flag)."""
    if not sys.platform.startswith("linux"):
        return False
    try:
        fn = ctypes.CDLL(None, use_errno=True).renameat2
    except (AttributeError, OSError):
        return False
    fn.argtypes = (ctypes.c_int, ctypes.c_char_p, ctypes.c_int, ctypes.c_char_p, ctypes.c_uint)
    at_fdcwd = -100
    if fn(at_fdcwd, os.fsencode(src), at_fdcwd, os.fsencode(dst), flags) == 0:
        return True
    err = ctypes.get_errno()
    if err in (errno.ENOSYS, errno.EINVAL):
        return False
    raise OSError(err, os.strerror(err), str(src), None, str(dst))


def install(tmp: str | os.PathLike, path: str | os.PathLike, *, overwrite: bool = True) -> None:
    """Rename the finished ``tmp`` to ``path``; a map already at ``path`` is removed only once
    the new one is in place, and only if the overwrite policy allows it
    (:func:`check_replaceable`, checked again here in case something appeared meanwhile;
    ``overwrite`` True: the caller checked the target before, any regular file goes; else
    ValueError naming ``path``, and nothing is touched). A file replaces a file
    atomically (``os.replace``); a directory is swapped in atomically on Linux, elsewhere the
    old one is renamed aside first (a crash in between leaves it as ``.<name>.old-<pid>``,
    put back by :func:`recover`)."""
    tmp, path = Path(tmp), Path(path)
    if not os.path.lexists(path):
        if not _renameat2(tmp, path, _RENAME_NOREPLACE):
            if os.path.lexists(path):
                raise FileExistsError(errno.EEXIST, "appeared while writing", str(path))
            os.rename(tmp, path)
        return
    check_replaceable(path, tmp.is_dir(), overwrite=overwrite)  # where what was there goes
    if not tmp.is_dir():
        os.replace(tmp, path)
        return
    if _renameat2(tmp, path, _RENAME_EXCHANGE):
        _step("replaced")
        remove(tmp)  # now the old map
        return
    old = temp_sibling(path, "old")
    os.rename(path, old)
    try:
        os.rename(tmp, path)
    except BaseException:
        os.rename(old, path)
        raise
    _step("replaced")
    remove(old)


def _fsync(path: Path) -> None:
    with open(path, "rb") as fh:
        os.fsync(fh.fileno())


def save(
    obj: object,
    path: str | os.PathLike,
    *,
    attrs: Mapping[str, Any] | None = None,
    overwrite: bool = False,
) -> Path:
    """Write a map to ``path``, replacing a map there; the format by the suffix.

    Every format is written under a temporary name next to ``path`` and renamed into place
    (:func:`install`), so a map at ``path`` is always whole and the one it replaces is kept
    until then; on failure nothing is left behind. A map of eccjump at ``path`` (recognised
    by its content, :func:`is_map`) is replaced; another regular file only with
    ``overwrite=True``; a directory of other files, a FIFO or a device never.

    Parameters
    ----------
    obj : Map (Region, MotionMap), xarray.Dataset or layout
        The map: a result of :func:`eccjump.region` or :func:`eccjump.motion_map`, its
        dataset (``to_xarray()``, :func:`eccjump.region_dataset`) or a layout dict.
    path : str or os.PathLike
        ``.nc`` (netCDF4, needs xarray), ``.zarr`` (needs zarr) or ``.npz`` (numpy only); its
        directory must exist.
    attrs : mapping, optional
        Extra attributes to record in the file (numbers, text, lists of them).
    overwrite : bool, default False
        Replace a regular file at ``path`` that is not a map of eccjump.

    Returns
    -------
    pathlib.Path
        The path written.

    Raises
    ------
    ValueError
        For an unknown suffix, a target that may not be replaced (a
        ``FileExistsError`` too), or a map that :func:`load` would refuse (naming ``path``,
        ``obj`` or ``attrs``).
    OSError
        If the file cannot be written (its directory is missing, no space, ...).
    ImportError
        For ``.nc`` or ``.zarr`` without xarray or zarr.
    """
    path = Path(check_path("path", path))
    mapping("attrs", attrs)
    overwrite = flag("overwrite", overwrite)
    fmt = format_of(path)
    check_target(path, fmt, overwrite=overwrite)
    lay = _valid_layout(obj, attrs)
    tmp = temp_sibling(path)
    try:
        if fmt == "npz":
            save_npz(lay, tmp)
            _fsync(tmp)
        elif fmt == "netcdf":
            ds = layout_to_xarray(lay)
            encoding = netcdf_encoding(ds.variables.items())
            try:
                ds.to_netcdf(tmp, engine=netcdf_engine(), encoding=encoding)
            except RuntimeError as err:  # netCDF4 reports a failed write as "HDF error"
                raise OSError(errno.EIO, f"netCDF write failed ({err})", str(tmp)) from err
            _fsync(tmp)
        else:
            ds = layout_to_xarray(lay)
            require("zarr")
            codecs = {k: {"compressors": zarr_codecs()} for k in ds.variables}
            with _quiet_consolidation():  # every chunk stored: a missing one is damage
                ds.to_zarr(
                    tmp, mode="w-", consolidated=True, encoding=codecs, write_empty_chunks=True
                )
        _step("written")
        install(tmp, path, overwrite=overwrite)
    except BaseException:
        remove(tmp)
        raise
    return path


def save_npz(layout: Layout, path: str | os.PathLike) -> None:
    """A layout as ``.npz``: one array per variable, dims and attributes as JSON in the first
    member, ``__layout__`` (so that :func:`is_map` knows the file by its first bytes). Each
    member has its CRC-32, which numpy's reading checks."""
    arrays: dict[str, NDArray] = {}
    meta: dict[str, Any] = {"attrs": json.loads(attrs_json(layout["attrs"]))}
    for part in ("coords", "data_vars"):
        meta[part] = {}
        for name, (dims, values, attrs) in layout[part].items():
            arrays[f"{part}/{name}"] = np.asarray(values)
            meta[part][name] = {"dims": list(dims), "attrs": json.loads(attrs_json(attrs))}
    arrays = {"__layout__": np.array(json.dumps(meta)), **arrays}
    with open(path, "wb") as fh:
        np.savez(fh, **arrays)  # type: ignore[arg-type]  # numpy's stub: allow_pickle first


def load_npz(path: str | os.PathLike) -> Layout:
    """The layout in an ``.npz`` file (unchecked: see :func:`read_layout`)."""
    with np.load(path, allow_pickle=False) as z:
        if not isinstance(z, np.lib.npyio.NpzFile):
            raise Invalid("is a .npy array, not an .npz archive")
        if "__layout__" not in z.files:
            raise Invalid("is not an eccjump map: no __layout__ array in the archive")
        meta = json.loads(str(z["__layout__"]))
        lay: Layout = {"attrs": meta["attrs"]}
        for part in ("coords", "data_vars"):
            lay[part] = {
                name: (tuple(m["dims"]), z[f"{part}/{name}"], m["attrs"])
                for name, m in meta[part].items()
            }
    return lay


#: OSError numbers that are about reaching the file, not about what is in it.
_ACCESS_ERRNOS = (errno.EACCES, errno.EPERM)


def _check_source(path: str | os.PathLike, fmt: str) -> None:
    """FileNotFoundError if ``path`` does not exist; ValueError naming it unless it is what a
    map of ``fmt`` is read from: a regular file (.npz, .nc: a FIFO or a device would block the
    reader for ever) or a directory (.zarr)."""
    try:
        mode = os.stat(path).st_mode
    except FileNotFoundError:
        raise FileNotFoundError(errno.ENOENT, "no such map", shown(path)) from None
    except OSError as err:
        if err.errno in _ACCESS_ERRNOS:
            raise
        raise file_error(path, f"cannot be read: {err.strerror}") from None
    if fmt == "zarr" and not stat.S_ISDIR(mode):
        raise file_error(path, f"is not a zarr map: {file_type(mode)}, not a directory")
    if fmt != "zarr" and not stat.S_ISREG(mode):
        raise file_error(path, f"is not a {fmt} map: {file_type(mode)}, not a regular file")


#: Seconds the netCDF library is given to read a file in :func:`probe_netcdf`, plus one per
#: :data:`PROBE_BYTES_PER_SECOND` of the file.
PROBE_SECONDS = 10.0
PROBE_BYTES_PER_SECOND = 50e6

#: The start of the probe child (argv: the caller's pid, its CPU-time limit in seconds, the
#: engine, the path). It dies with its caller: a caller killed by SIGKILL or SIGTERM (a job's
#: timeout, a kernel restart) cannot kill its child, which, re-parented to init, would spin in
#: HDF5 for ever. Linux's PR_SET_PDEATHSIG sends it SIGKILL when its parent dies (checked
#: after the call, in case the parent died first); everywhere, RLIMIT_CPU stops it once it has
#: used its time (SIGXCPU, without a core file).
_PROBE_START = """
import os, sys
parent, cpu_limit = int(sys.argv[1]), int(sys.argv[2])
engine, path = sys.argv[3:5]
if sys.platform.startswith("linux"):
    import ctypes, signal
    ctypes.CDLL(None).prctl(1, int(signal.SIGKILL))  # PR_SET_PDEATHSIG
if os.getppid() != parent:
    sys.exit("the caller has gone")
try:
    import resource
    resource.setrlimit(resource.RLIMIT_CORE, (0, 0))
    resource.setrlimit(resource.RLIMIT_CPU, (cpu_limit, cpu_limit + 1))
except (ImportError, ValueError, OSError):
    pass
"""

#: Reads every variable and attribute of the netCDF file ``path`` with ``engine``.
_PROBE_BODY = """
if engine == "h5netcdf":
    import h5netcdf
    def walk(g):
        dict(g.attrs)
        for v in g.variables.values():
            v[...]
            dict(v.attrs)
        for sub in g.groups.values():
            walk(sub)
    with h5netcdf.File(path, "r") as f:
        walk(f)
else:
    import netCDF4
    def walk(g):
        g.__dict__
        for v in g.variables.values():
            v.set_auto_maskandscale(False)
            v[...]
            v.__dict__
        for sub in g.groups.values():
            walk(sub)
    with netCDF4.Dataset(path) as f:
        walk(f)
"""


def probe_command(engine: str, path: str | os.PathLike, limit: float) -> list[str]:
    """The command of the probe child that reads ``path`` with ``engine`` within ``limit``
    seconds (of CPU time: the caller kills it after as many seconds of wall time)."""
    cpu = str(math.ceil(limit) + 1)
    code = _PROBE_START + _PROBE_BODY
    return [sys.executable, "-c", code, str(os.getpid()), cpu, engine, os.fspath(path)]


def probe_netcdf(path: str | os.PathLike, engine: str) -> None:
    """ValueError naming ``path`` unless the netCDF library reads all of it in a subprocess.

    The HDF5 library under both engines (netCDF4 and h5netcdf/h5py) trusts the bytes of a
    file: a damaged one can make it loop for ever in C, deaf to Ctrl-C (512 zeroed bytes in
    the global heap of a motion map do, in netCDF4 1.7 / HDF5 1.14), or crash the process.
    No check of the file's signature or size finds such damage, and a thread cannot be
    stopped, so the file is first read whole in a child process with a time limit; only a
    file it reads is then opened here. The child dies with its caller (see
    :data:`_PROBE_START`). Costs about 0.3 s per file.
    """
    limit = PROBE_SECONDS + os.path.getsize(path) / PROBE_BYTES_PER_SECOND
    try:
        proc = subprocess.run(
            probe_command(engine, path, limit),
            stdin=subprocess.DEVNULL,
            capture_output=True,
            text=True,
            errors="replace",
            timeout=limit,
            check=False,
        )
    except subprocess.TimeoutExpired:  # run() has killed it
        raise file_error(
            path, f"is not a readable netcdf map: the netCDF library hangs on it ({limit:.0f} s)"
        ) from None
    if proc.returncode < 0:
        crash = f"the netCDF library crashed on it (signal {-proc.returncode})"
        raise file_error(path, f"is not a readable netcdf map: {crash}")
    if proc.returncode:
        lines = proc.stderr.replace(os.fspath(path), "").strip().splitlines() or ["?"]
        if "ModuleNotFoundError" in lines[-1]:  # the engine is not importable from a child
            raise ImportError(lines[-1])
        raise file_error(path, f"is not a readable netcdf map: {lines[-1]}")


def _read(path: str | os.PathLike, fmt: str) -> tuple[Layout, xr.Dataset | None]:
    """The layout of the map file at ``path`` (unchecked) and, for .nc and .zarr, its
    dataset (loaded into memory); ValueError naming ``path`` for whatever the reader of the
    format cannot read (its errors are of many types: zipfile's, zarr's, zstd's, HDF5's)."""
    _check_source(path, fmt)
    try:
        if fmt == "npz":
            lay = load_npz(path)
            upgrade_attrs(lay["attrs"])
            return lay, None
        xr = require("xarray")
        if fmt == "netcdf":
            engine = netcdf_engine()
            probe_netcdf(path, engine)  # reads it all: the checksums are checked there
            with xr.open_dataset(path, engine=engine) as ds:
                ds = ds.load()
            check_netcdf(path, ds)
        else:
            ds = _read_zarr(xr, path)
        upgrade_attrs(ds.attrs)
        return layout_from_xarray(ds), ds
    except (ImportError, MemoryError):
        raise
    except Invalid as err:
        raise file_error(path, str(err)) from None
    except OSError as err:
        if err.errno in _ACCESS_ERRNOS:
            raise
        raise file_error(path, f"is not a readable {fmt} map: {_detail(err)}") from err
    except ValueError as err:
        if str(err).startswith(shown(path)):  # already names the file (probe_netcdf)
            raise
        raise file_error(path, f"is not a readable {fmt} map: {_detail(err)}") from err
    except Exception as err:
        raise file_error(path, f"is not a readable {fmt} map: {_detail(err)}") from err


def _read_zarr(xr: Any, path: str | os.PathLike) -> xr.Dataset:
    """The zarr map at ``path``, loaded, after its integrity check (:mod:`eccjump.maps.integrity`);
    each array's own metadata is read, not the consolidated copy, which a damaged store may
    not match."""
    zarr = require("zarr")
    check_metadata_size(path)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")  # zarr's about metadata: errors say enough
        group = zarr.open_group(path, mode="r", use_consolidated=False)
    check_zarr(path, group)
    with warnings.catch_warnings():
        warnings.simplefilter("ignore")
        with xr.open_zarr(path, consolidated=False) as ds:
            return ds.load()


def _detail(err: BaseException) -> str:
    """An exception of a reader in a few words (without the file's path, named already)."""
    text = str(err).replace(str(getattr(err, "filename", None) or "\0"), "")
    if "checksum do not match" in text:  # zarr's crc32c codec: the bytes of no use
        return "a chunk's checksum does not match: the map is damaged"
    return f"{type(err).__name__}: {text}"[:100]


def read_layout(path: str | os.PathLike) -> tuple[Layout, MapKind]:
    """The layout and kind of the map file at ``path``: every loader reads through here, so
    each refuses the same files in the same words. ValueError naming ``path`` for anything
    that is no valid map (unreadable, damaged, foreign, codes out of their tables, NaN
    coordinates, wrong shapes: see :mod:`eccjump.maps.check`); FileNotFoundError if missing,
    PermissionError if not readable."""
    path = check_path("path", path)
    lay, _ = _read(path, format_of(path))
    return lay, check_layout(lay, path)


def load_layout(path: str | os.PathLike) -> Layout:
    """The layout of a map file, checked as by :func:`read_layout`."""
    return read_layout(path)[0]


def open_dataset(path: str | os.PathLike) -> xr.Dataset:
    """A map file as an ``xarray.Dataset``, loaded into memory and checked.

    Parameters
    ----------
    path : str or os.PathLike
        A ``.nc``, ``.zarr`` or ``.npz`` map file, of either kind, swept or not.

    Returns
    -------
    xarray.Dataset

    Raises
    ------
    ValueError
        For a file that is no valid map (naming it and what is wrong).
    FileNotFoundError
        If there is no file at ``path``.
    ImportError
        Without xarray.
    """
    path = check_path("path", path)
    lay, ds = _read(path, format_of(path))
    check_layout(lay, path)
    return layout_to_xarray(lay) if ds is None else ds


# load, which made a Region here before the map layer knew no kind, for one release.
if not TYPE_CHECKING:  # (a module __getattr__ would let mypy pass any typo)

    def __getattr__(name: str):
        return _compat.moved_name(__name__, name)


class _quiet_consolidation(warnings.catch_warnings):
    """Consolidated metadata is not yet in the zarr v3 spec; zarr warns, xarray reads it."""

    def __enter__(self) -> None:
        super().__enter__()
        warnings.filterwarnings("ignore", message="Consolidated metadata", category=UserWarning)


def _json_attrs(attrs: Mapping[str, Any]) -> dict[str, Any]:
    return json.loads(attrs_json(attrs))


class ZarrMap:
    """A map in a zarr store written chunk by chunk along α (``chunk`` slices each).

    The store is a regular xarray-readable dataset (``xr.open_zarr``) with the variable
    ``alpha_done`` and the attribute ``complete``.
    """

    def __init__(self, path: str | os.PathLike) -> None:
        """Open the map at ``path`` for writing; ValueError naming ``path`` if it is not one
        (FileNotFoundError if it does not exist). The metadata of each array is read from
        the array itself, not from the consolidated copy, which a damaged store may not
        match."""
        zarr = require("zarr")
        self.path = Path(path)
        _check_source(self.path, "zarr")
        try:
            check_metadata_size(self.path)
            self.group = zarr.open_group(self.path, mode="r+", use_consolidated=False)
            self.attrs: dict[str, Any] = dict(self.group.attrs)
            self.kind = kind_of(self.attrs)
            self._check_arrays()
            self.alpha, self.chi, self.km_frac = (
                np.asarray(self.group[k][:], dtype=np.float64) for k in ("alpha", "chi", "km_frac")
            )
            self.chunk = int(self.group["alpha_done"].chunks[0])
        except (ImportError, MemoryError):
            raise
        except Invalid as err:
            raise file_error(self.path, str(err)) from None
        except OSError as err:
            if err.errno in _ACCESS_ERRNOS:
                raise
            raise file_error(self.path, f"is not a zarr map: {_detail(err)}") from err
        except Exception as err:  # zarr's errors are of many types
            raise file_error(self.path, f"is not a zarr map: {_detail(err)}") from err

    def _check_arrays(self) -> None:
        """:class:`Invalid` if an array or an attribute of the kind is missing."""
        arrays = ("alpha", "chi", "km_frac", *self.kind.fields, "alpha_done")
        missing = [k for k in arrays if k not in self.group]
        missing_attrs = [k for k in self.kind.required_attrs if k not in self.attrs]
        if missing or missing_attrs:
            what = [f"arrays {', '.join(missing)}"] if missing else []
            what += [f"attributes {', '.join(missing_attrs)}"] if missing_attrs else []
            raise Invalid("is not an eccjump zarr map: missing " + "; ".join(what))

    @classmethod
    def create(
        cls,
        path: str | os.PathLike,
        alpha: NDArray[np.float64],
        chi: NDArray[np.float64],
        km_frac: NDArray[np.float64],
        attrs: Mapping[str, Any],
        chunk: int,
    ) -> ZarrMap:
        """An empty map (every point at its fill value, ``alpha_done`` all False) at
        ``path``, which must not exist (write it under :func:`temp_sibling` and
        :func:`install` it)."""
        zarr = require("zarr")
        check_parent(path)
        if os.path.lexists(path):
            raise FileExistsError(errno.EEXIST, "exists", str(path))
        try:
            cls._build(zarr, path, alpha, chi, km_frac, attrs, chunk)
        except BaseException:  # no half-built store left behind
            remove(path)
            raise
        _step("created")
        return cls(path)

    @staticmethod
    def _build(
        zarr: Any,
        path: str | os.PathLike,
        alpha: NDArray[np.float64],
        chi: NDArray[np.float64],
        km_frac: NDArray[np.float64],
        attrs: Mapping[str, Any],
        chunk: int,
    ) -> None:
        shape = (alpha.size, chi.size, km_frac.size)
        chunks = (max(1, min(chunk, alpha.size)), max(chi.size, 1), max(km_frac.size, 1))
        group = zarr.create_group(
            store=str(path),
            overwrite=False,
            attributes=_json_attrs({**attrs, "complete": 0, "chunk": chunks[0]}),
        )
        for name, (dims, values, vattrs) in grid_coords(alpha, chi, km_frac).items():
            arr = group.create_array(
                name,
                shape=values.shape,
                dtype=values.dtype,
                chunks=values.shape if values.size else None,
                compressors=zarr_codecs(),
                fill_value=np.nan,
                dimension_names=dims,
                attributes=_json_attrs(vattrs),
            )
            arr[...] = values
        _step("create")
        kind = kind_of(attrs)
        for name in kind.fields:
            group.create_array(
                name,
                shape=shape,
                dtype=kind.dtypes[name],
                chunks=chunks,
                compressors=zarr_codecs(),
                fill_value=kind.fill[name],
                dimension_names=DIMS,
                attributes=_json_attrs({**kind.var_attrs(name), "coordinates": "alpha_deg km"}),
            )
        done = group.create_array(
            "alpha_done",
            shape=(alpha.size,),
            dtype=np.bool_,
            chunks=(chunks[0],),
            compressors=zarr_codecs(),
            fill_value=False,
            dimension_names=("alpha",),
            attributes=_json_attrs({**COORD_ATTRS["alpha_done"], "coordinates": "alpha_deg"}),
        )
        with zarr.config.set({"array.write_empty_chunks": True}):  # each chunk is there
            done[...] = np.zeros(alpha.size, dtype=bool)
        with _quiet_consolidation():
            zarr.consolidate_metadata(str(path))

    @property
    def n_chunks(self) -> int:
        return -(-self.alpha.size // self.chunk)

    def bounds(self, i: int) -> tuple[int, int]:
        """The α index range [i0, i1) of chunk ``i``."""
        return i * self.chunk, min((i + 1) * self.chunk, self.alpha.size)

    def alpha_done(self) -> NDArray[np.bool_]:
        return np.asarray(self.group["alpha_done"][:], dtype=bool)

    def _done(self, i: int) -> bool:
        """Whether chunk ``i`` is marked done (False if the mark cannot be read)."""
        try:
            return bool(np.asarray(self.group["alpha_done"][slice(*self.bounds(i))]).all())
        except (MemoryError, ValueError, OSError, RuntimeError, TypeError):
            return False

    def missing(self) -> list[int]:
        """Chunks not finished, in order."""
        return [i for i in range(self.n_chunks) if not self._done(i)]

    def write(self, i: int, fields: Mapping[str, NDArray]) -> None:
        """Write chunk ``i`` (every field, shape (i1 - i0, nchi, nkm)), then mark it done.
        Every chunk is stored, even one of fill values, so that a chunk file missing from
        a store says it was lost (:meth:`damage`)."""
        zarr = require("zarr")
        i0, i1 = self.bounds(i)
        with zarr.config.set({"array.write_empty_chunks": True}):
            for name in self.kind.fields:
                self.group[name][i0:i1] = np.asarray(fields[name], dtype=self.kind.dtypes[name])
            _step("chunk-data")
            self.group["alpha_done"][i0:i1] = True
        _step("chunk-done")

    def damage(self, i: int) -> str | None:
        """What is wrong with chunk ``i``, marked done, in a few words (None: it reads back
        whole and valid): a field's chunk file is missing (lost: each is written), cannot
        be read (its checksum fails), or holds codes out of their tables."""
        i0, i1 = self.bounds(i)
        try:
            for name in self.kind.fields:
                key = self.group[name].metadata.encode_chunk_key((i, 0, 0))
                if not (self.path / name / key).is_file():
                    return f"{name}: chunk file missing"
            values = self.read(i)
        except MemoryError:
            raise
        except Exception as err:  # zarr's and the codecs' errors are of many types
            return f"unreadable: {_detail(err)}"
        shape = (i1 - i0, self.chi.size, self.km_frac.size)
        wrong = [k for k, v in values.items() if v.shape != shape]
        if wrong:
            return f"{wrong[0]}: shape {values[wrong[0]].shape}"
        mark = self.kind.computed_mark
        if mark is not None and (values[mark] == self.kind.fill[mark]).any():
            return f"{mark} {self.kind.fill[mark]} (not computed)"
        return self.kind.bad_codes(values) or self.kind.bad_values(values)

    def rewrite_coords(self) -> None:
        """Write the coordinates derived from α, χ and km_frac again (``alpha_deg``,
        ``km``): a resume repairs them rather than trust them."""
        for name, (_, values, _) in grid_coords(self.alpha, self.chi, self.km_frac).items():
            if name not in ("alpha", "chi", "km_frac"):
                self.group[name][...] = values

    def read(self, i: int, names: tuple[str, ...] | None = None) -> dict[str, NDArray]:
        """Fields ``names`` (default: all) of chunk ``i``."""
        i0, i1 = self.bounds(i)
        names = self.kind.fields if names is None else names
        return {k: np.asarray(self.group[k][i0:i1]) for k in names}

    def finish(self, **attrs: Any) -> None:
        """Record ``complete`` (and other attributes) and consolidate the metadata."""
        zarr = require("zarr")
        complete = int(bool(self.alpha_done().all()))
        self.group.attrs.update(_json_attrs({**attrs, "complete": complete}))
        self.attrs = dict(self.group.attrs)
        _step("finish")
        with _quiet_consolidation():
            zarr.consolidate_metadata(str(self.path))
        _step("finished")

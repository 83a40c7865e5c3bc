"""JARM maps on disk, the format chosen by the suffix: ``.nc`` (netCDF4, engine h5netcdf or
netCDF4), ``.zarr`` (zarr v3 directory store) or ``.npz`` (numpy; needs neither xarray nor
zarr).

:func:`save` and :func:`load`/:func:`open_dataset` handle whole maps. :class:`ZarrMap`
writes a map chunk by chunk along alpha, recording finished alpha slices in the data
variable ``alpha_done`` (written after the data of its chunk), so that an interrupted map
keeps what was finished and can be resumed; the attribute ``complete`` (0/1) says whether
every slice is there. Points not computed hold the fill values: NaN, ``is_jarm`` False,
``n`` 0 and ``reason`` 255 (not a :class:`~eccjump.Reason`).

A map is never half there. Every new file or store is written under a temporary sibling name
(``.<name>.tmp-<pid>``, same directory) and renamed into place by :func:`install`; a map it
replaces is removed only after that (a directory is swapped in with one atomic
``renameat2(RENAME_EXCHANGE)`` on Linux, elsewhere the old one is renamed aside to
``.<name>.old-<pid>`` first). :func:`recover` removes what a killed process left behind and
puts back a map left aside. A missing parent directory is an error, never created.
"""

from __future__ import annotations

import ctypes
import errno
import json
import os
import re
import shutil
import signal
import sys
import warnings
import zipfile
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump._checks import mapping
from eccjump._checks import path as check_path
from eccjump.classification import Region
from eccjump.labelled import (
    COORD_ATTRS,
    DIMS,
    Layout,
    attrs_json,
    grid_coords,
    layout_from_xarray,
    layout_to_xarray,
    region_layout,
    require,
    to_region,
)
from eccjump.map_kinds import MapKind, kind_of

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

FORMATS = {".nc": "netcdf", ".zarr": "zarr", ".npz": "npz"}


def format_of(path: str | os.PathLike) -> str:
    """``"netcdf"``, ``"zarr"`` or ``"npz"`` from the suffix of ``path``."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(
            f"path {str(path)[-80:]!r}: unknown output format {suffix[:20]!r}; "
            "use .nc, .zarr or .npz"
        )
    return FORMATS[suffix]


def netcdf_engine() -> str:
    """h5netcdf if it and h5py are installed, else netCDF4."""
    for modules, engine in ((("h5netcdf", "h5py"), "h5netcdf"), (("netCDF4",), "netcdf4")):
        try:
            for module in modules:
                __import__(module)
            return engine
        except ImportError:
            continue
    require("h5netcdf")  # raises with the install hint
    raise AssertionError  # pragma: no cover


def _as_layout(obj: Region | Layout | xr.Dataset) -> Layout:
    if isinstance(obj, Region):
        return region_layout(obj.compute())
    if isinstance(obj, dict):
        return obj
    return layout_from_xarray(obj)


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
    """Clean up after a process killed while writing ``path``: remove its temporary
    ``.<name>.tmp-<pid>``, and put back a map it had set aside (``.<name>.old-<pid>``) if
    ``path`` is missing, else remove that too. Only names of processes no longer running are
    touched (POSIX; elsewhere nothing is done). Returns notes of what was put back."""
    path = Path(path)
    pattern = re.compile(rf"\.{re.escape(path.name)}\.(tmp|old)-(\d+)")
    notes = []
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


def install(tmp: str | os.PathLike, path: str | os.PathLike) -> None:
    """Rename the finished ``tmp`` to ``path``; a map already at ``path`` is removed only once
    the new one is in place. A file replaces a file atomically (``os.replace``); a directory
    is swapped in atomically on Linux, elsewhere the old one is renamed aside first (a crash
    in between leaves it as ``.<name>.old-<pid>``, put back by :func:`recover`)."""
    tmp, path = Path(tmp), Path(path)
    if not os.path.lexists(path):
        if not _renameat2(tmp, path, _RENAME_NOREPLACE):
            if os.path.lexists(path):
                raise FileExistsError(errno.EEXIST, "appeared while writing", str(path))
            os.rename(tmp, path)
        return
    if not tmp.is_dir() and not path.is_dir():
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
    obj: Region | Layout | xr.Dataset,
    path: str | os.PathLike,
    *,
    attrs: Mapping[str, Any] | None = None,
) -> Path:
    """Write a map (a :class:`Region`, a dataset or a layout) to ``path``, replacing it.

    Every format is written under a temporary name next to ``path`` and renamed into place
    (:func:`install`), so a map at ``path`` is always whole and the one it replaces is kept
    until then; on failure nothing is left behind. The directory of ``path`` must exist.
    ``.npz`` needs numpy only.
    """
    path = Path(check_path("path", path))
    mapping("attrs", attrs)
    if not isinstance(obj, Region | dict) and not hasattr(obj, "data_vars"):
        raise TypeError(f"obj must be a Region, an xarray.Dataset or a layout, not {type(obj)}")
    fmt = format_of(path)
    check_parent(path)
    lay = _as_layout(obj)
    if attrs:
        lay = {**lay, "attrs": {**lay["attrs"], **attrs}}
    tmp = temp_sibling(path)
    try:
        if fmt == "npz":
            save_npz(lay, tmp)
            _fsync(tmp)
        elif fmt == "netcdf":
            try:
                layout_to_xarray(lay).to_netcdf(tmp, engine=netcdf_engine())
            except RuntimeError as err:  # netCDF4 reports a failed write as "HDF error"
                raise OSError(errno.EIO, f"netCDF write failed ({err})", str(tmp)) from err
            _fsync(tmp)
        else:
            ds = layout_to_xarray(lay)
            require("zarr")
            with _quiet_consolidation():
                ds.to_zarr(tmp, mode="w-", consolidated=True)
        _step("written")
        install(tmp, path)
    except BaseException:
        remove(tmp)
        raise
    return path


def save_npz(layout: Layout, path: str | os.PathLike) -> None:
    """A layout as ``.npz``: one array per variable, dims and attributes as JSON."""
    arrays: dict[str, NDArray] = {}
    meta: dict[str, Any] = {"attrs": json.loads(attrs_json(layout["attrs"]))}
    for part in ("coords", "data_vars"):
        meta[part] = {}
        for name, (dims, values, attrs) in layout[part].items():
            arrays[f"{part}/{name}"] = np.asarray(values)
            meta[part][name] = {"dims": list(dims), "attrs": json.loads(attrs_json(attrs))}
    arrays["__layout__"] = np.array(json.dumps(meta))
    with open(path, "wb") as fh:
        np.savez(fh, **arrays)


def load_npz(path: str | os.PathLike) -> Layout:
    with np.load(path, allow_pickle=False) as z:
        if not isinstance(z, np.lib.npyio.NpzFile):
            raise ValueError(f"{path} is a .npy array, not an .npz archive")
        if "__layout__" not in z.files:
            raise ValueError(f"{path} is not an eccjump map: no __layout__ array in the archive")
        meta = json.loads(str(z["__layout__"]))
        lay: Layout = {"attrs": meta["attrs"]}
        for part in ("coords", "data_vars"):
            lay[part] = {
                name: (tuple(m["dims"]), z[f"{part}/{name}"], m["attrs"])
                for name, m in meta[part].items()
            }
    return lay


def open_dataset(path: str | os.PathLike) -> xr.Dataset:
    """A map file as an ``xarray.Dataset`` (loaded into memory)."""
    fmt = format_of(path)
    if fmt == "npz":
        return layout_to_xarray(load_npz(path))
    xr = require("xarray")
    if fmt == "netcdf":
        with xr.open_dataset(path, engine=netcdf_engine()) as ds:
            return ds.load()
    require("zarr")
    with xr.open_zarr(path, consolidated=None) as ds:
        return ds.load()


#: What a map file holds (coordinates, data variables, attributes), checked by :func:`load`.
def required(kind: MapKind) -> tuple[tuple[str, tuple[str, ...]], ...]:
    """What a map file of ``kind`` holds: coordinates, data variables, attributes."""
    return (
        ("coordinates", ("alpha", "chi", "km_frac")),
        ("variables", kind.fields),
        ("attributes", kind.required_attrs),
    )


#: OSError numbers that are about reaching the file, not about what is in it.
_ACCESS_ERRNOS = (errno.EACCES, errno.EPERM)


def load_layout(path: str | os.PathLike) -> Layout:
    """The layout of a map file; ValueError naming ``path`` if it is no readable map (a
    missing or unreadable path raises the OSError)."""
    fmt = format_of(path)
    if not os.path.exists(path):
        raise FileNotFoundError(errno.ENOENT, "no such map", str(path))
    try:
        if fmt == "npz":
            return load_npz(path)
        return layout_from_xarray(open_dataset(path))
    except ImportError:
        raise
    except (ValueError, KeyError, EOFError, zipfile.BadZipFile, OSError) as err:
        if isinstance(err, OSError) and err.errno in (errno.EACCES, errno.EPERM):
            raise
        if str(err).startswith(f"{path} "):  # already names the path (load_npz)
            raise
        raise ValueError(f"{path} is not a readable {fmt} map: {err}") from err


def check_layout(lay: Layout, path: str | os.PathLike) -> MapKind:
    """The kind of the map in ``lay``; ValueError naming ``path`` if something is missing."""
    try:
        kind = kind_of(lay.get("attrs", {}))
    except ValueError as err:
        raise ValueError(f"{path} is not an eccjump map: {err}") from None
    have = {
        "coordinates": set(lay.get("coords", {})) | set(lay.get("data_vars", {})),
        "variables": set(lay.get("data_vars", {})),
        "attributes": set(lay.get("attrs", {})),
    }
    missing = [
        f"{what} {', '.join(n for n in names if n not in have[what])}"
        for what, names in required(kind)
        if not set(names) <= have[what]
    ]
    if missing:
        raise ValueError(f"{path} is not an eccjump {kind.name} map: missing " + "; ".join(missing))
    return kind


def load(path: str | os.PathLike) -> Region:
    """A map file (of one map, no swept dimensions) as a :class:`Region`. ``.npz`` needs
    numpy only. The file's ``complete`` and ``alpha_done`` go to ``Region.attrs``. A file
    that is not such a map raises ValueError naming it and what is missing."""
    lay = load_layout(check_path("path", path))
    if check_layout(lay, path).name != "jarm":
        raise ValueError(f"{path} is a motion map: load it with eccjump.motion_maps.load")
    reg = to_region(lay)
    if "alpha_done" in lay["data_vars"]:
        reg.attrs["alpha_done"] = np.asarray(lay["data_vars"]["alpha_done"][1], dtype=bool)
    return reg


class _quiet_consolidation(warnings.catch_warnings):
    """Consolidated metadata is not yet in the zarr v3 spec; zarr warns, xarray reads it."""

    def __enter__(self) -> None:
        super().__enter__()
        warnings.filterwarnings("ignore", message="Consolidated metadata", category=UserWarning)


def _json_attrs(attrs: Mapping[str, Any]) -> dict[str, Any]:
    return json.loads(attrs_json(attrs))


class ZarrMap:
    """A map in a zarr store written chunk by chunk along alpha (``chunk`` slices each).

    The store is a regular xarray-readable dataset (``xr.open_zarr``) with the variable
    ``alpha_done`` and the attribute ``complete``.
    """

    def __init__(self, path: str | os.PathLike) -> None:
        """Open the map at ``path`` for writing; ValueError naming ``path`` if it is not one
        (FileNotFoundError if it does not exist)."""
        zarr = require("zarr")
        self.path = Path(path)
        if not self.path.exists():
            raise FileNotFoundError(errno.ENOENT, "no such zarr map", str(self.path))
        try:
            self.group = zarr.open_group(self.path, mode="r+")
        except (ValueError, KeyError) as err:  # zarr's errors are ValueErrors
            raise ValueError(f"{self.path} is not a zarr map: {err}") from err
        except OSError as err:
            if err.errno in _ACCESS_ERRNOS:
                raise
            raise ValueError(f"{self.path} is not a zarr map: {err}") from err
        self.attrs: dict[str, Any] = dict(self.group.attrs)
        try:
            self.kind = kind_of(self.attrs)
        except ValueError as err:
            raise ValueError(f"{self.path} is not an eccjump zarr map: {err}") from None
        arrays = ("alpha", "chi", "km_frac", *self.kind.fields, "alpha_done")
        missing = [k for k in arrays if k not in self.group]
        missing_attrs = [k for k in self.kind.required_attrs if k not in self.attrs]
        if missing or missing_attrs:
            what = [f"arrays {', '.join(missing)}"] if missing else []
            what += [f"attributes {', '.join(missing_attrs)}"] if missing_attrs else []
            raise ValueError(f"{self.path} is not an eccjump zarr map: missing " + "; ".join(what))
        self.alpha = np.asarray(self.group["alpha"][:], dtype=np.float64)
        self.chi = np.asarray(self.group["chi"][:], dtype=np.float64)
        self.km_frac = np.asarray(self.group["km_frac"][:], dtype=np.float64)
        self.chunk = int(self.group["alpha_done"].chunks[0])

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
                fill_value=kind.fill[name],
                dimension_names=DIMS,
                attributes=_json_attrs({**kind.var_attrs(name), "coordinates": "alpha_deg km"}),
            )
        done = group.create_array(
            "alpha_done",
            shape=(alpha.size,),
            dtype=np.bool_,
            chunks=(chunks[0],),
            fill_value=False,
            dimension_names=("alpha",),
            attributes=_json_attrs({**COORD_ATTRS["alpha_done"], "coordinates": "alpha_deg"}),
        )
        done[...] = np.zeros(alpha.size, dtype=bool)
        with _quiet_consolidation():
            zarr.consolidate_metadata(str(path))

    @property
    def n_chunks(self) -> int:
        return -(-self.alpha.size // self.chunk)

    def bounds(self, i: int) -> tuple[int, int]:
        """The alpha index range [i0, i1) of chunk ``i``."""
        return i * self.chunk, min((i + 1) * self.chunk, self.alpha.size)

    def alpha_done(self) -> NDArray[np.bool_]:
        return np.asarray(self.group["alpha_done"][:], dtype=bool)

    def missing(self) -> list[int]:
        """Chunks not finished, in order."""
        done = self.alpha_done()
        return [i for i in range(self.n_chunks) if not done[slice(*self.bounds(i))].all()]

    def write(self, i: int, fields: Mapping[str, NDArray]) -> None:
        """Write chunk ``i`` (every field, shape (i1 - i0, nchi, nkm)), then mark it done."""
        i0, i1 = self.bounds(i)
        for name in self.kind.fields:
            self.group[name][i0:i1] = np.asarray(fields[name], dtype=self.kind.dtypes[name])
        _step("chunk-data")
        self.group["alpha_done"][i0:i1] = True
        _step("chunk-done")

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

"""Results of every kind on disk: the registry of result classes, their one file format, and
:func:`load`, which reads any result of eccjump back as its type.

A result class names its type when it is defined, ``class RollResult(Result, kind="roll")``,
as a map class names its kind (:class:`~eccjump.maps.map.Map`): this layer then reads a file
of that type back as that class without knowing it.

File format (the suffix chooses):

- ``.nc`` (netCDF, needs xarray): the result's ``to_xarray()`` dataset (labelled, units in
  the attributes), plus any field array it does not hold as it is; the attributes
  ``eccjump_type`` (the registered type) and ``eccjump_fields`` (the fields as JSON, arrays
  by variable name: :mod:`eccjump._base.records`). Arrays are stored in their own dtype, so
  the result read back is the one saved, bit for bit.
- ``.json`` (no extra dependency): the same fields, each array as its dtype, shape and
  base64 bytes. For the small results (a design) or where netCDF is not installed.

What is not saved: a dense solution (``sol``; read back as None).
"""

from __future__ import annotations

import base64
import errno
import json
import os
import stat
from collections.abc import Callable, Mapping, Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, TypeVar

import numpy as np

from eccjump._base import records
from eccjump._base.checks import file_error, flag, shown
from eccjump._base.checks import path as path_arg
from eccjump._base.overwrite import check_overwrite, never
from eccjump._base.userfiles import MAX_BYTES, read_text
from eccjump._core import VERSION
from eccjump.maps import store
from eccjump.maps.integrity import netcdf_encoding
from eccjump.maps.layout import require
from eccjump.maps.map import Map

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

T = TypeVar("T")

#: The attribute (of a dataset, a key of a JSON file) that names a result's registered type.
TYPE_ATTR = "eccjump_type"
#: The attribute that holds the fields of a saved result as JSON.
FIELDS_ATTR = "eccjump_fields"
#: The suffixes :meth:`Result.save` writes.
SUFFIXES = (".nc", ".json")
#: The suffixes of map files (:func:`eccjump.maps.load`).
MAP_SUFFIXES = (".npz", ".zarr")


class Result:
    """What every result of eccjump that is not a map has: :meth:`to_xarray`, :meth:`save`,
    and a registered type that :func:`load` reads back.

    ``class RollResult(Result, kind="roll")`` registers the class; ``suffixes=(".csv",)``
    gives it files of its own format too, read by its ``_read`` (an uncertainty study)."""

    #: The registered type: the ``eccjump_type`` attribute of the class's files.
    kind: ClassVar[str]
    #: Fields not saved (read back as None): a dense solution.
    _unsaved: ClassVar[tuple[str, ...]] = ()
    _classes: ClassVar[dict[str, type[Result]]] = {}
    _suffix_owners: ClassVar[dict[str, type[Result]]] = {}

    def __init_subclass__(
        cls, kind: str | None = None, suffixes: tuple[str, ...] = (), **kwargs: Any
    ) -> None:
        super().__init_subclass__(**kwargs)
        if kind is None:
            return
        if Result._classes.setdefault(kind, cls) is not cls:
            raise TypeError(f"the results of type {kind!r} have a class already")
        cls.kind = kind
        for suffix in suffixes:
            Result._suffix_owners[suffix] = cls

    def to_xarray(self) -> xr.Dataset:
        """The result as a labelled ``xarray.Dataset`` (needs xarray)."""
        raise NotImplementedError

    def save(self, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
        """Write the result to ``path`` (``.nc`` or ``.json``): :func:`eccjump.load` reads it
        back, equal field by field (a dense solution ``sol`` is not saved). The file appears
        whole or not at all; a file already at ``path`` is replaced only with
        ``overwrite=True`` (else ValueError). Returns the path written."""
        return save(self, path, overwrite=overwrite)

    @classmethod
    def _read(cls, path: Path, suffix: str) -> Result:
        """The result in the file at ``path``, written by :meth:`save`."""
        fields, arrays = _read_json(path) if suffix == ".json" else _read_netcdf(path)
        obj = records.decode(fields, arrays)
        if type(obj) is not cls:
            raise ValueError(f"holds a {type(obj).__name__}, not a {cls.__name__}")
        return obj


def type_attrs(obj: Result) -> dict[str, str]:
    """The attributes every result's dataset carries: its type and who wrote it."""
    return {TYPE_ATTR: obj.kind, "created_by": f"eccjump {VERSION}"}


def _suffix(path: str | os.PathLike, allowed: tuple[str, ...]) -> str:
    suffix = Path(path).suffix.lower()
    if suffix not in allowed:
        raise ValueError(f"path: the suffix must be one of {', '.join(allowed)}, not {suffix!r}")
    return suffix


def save(obj: Result, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
    """Write ``obj`` to ``path`` (see :meth:`Result.save`), under a temporary name first."""
    target = Path(path_arg("path", path))
    suffix = _suffix(target, SUFFIXES)
    # ours=never: a saved result is a file of the user's too, replaced only when asked.
    check_overwrite(
        target, overwrite=flag("overwrite", overwrite), option="overwrite=True", ours=never,
        what="a file eccjump replaces unasked", name="path",
    )  # fmt: skip
    store.check_parent(target)
    store.check_name(target)
    tmp = store.temp_sibling(target)
    try:
        _write(obj, tmp, suffix)
        store.install(tmp, target)
    except RuntimeError as err:  # netCDF4 reports a failed write as "NetCDF: HDF error"
        raise OSError(errno.EIO, f"netCDF write failed ({err})", str(target)) from err
    except OSError as err:  # the user's path, not the temporary one
        raise OSError(err.errno, err.strerror or str(err), str(target)) from err
    finally:
        store.remove(tmp)
    return target


def _write(obj: Result, tmp: Path, suffix: str) -> None:
    arrays: dict[str, np.ndarray] = {}
    fields = records.encode(obj, arrays, "", obj._unsaved)
    if suffix == ".json":
        packed = {k: _pack(a) for k, a in arrays.items()}
        doc = {**type_attrs(obj), "fields": fields, "arrays": packed}
        tmp.write_bytes(_json_bytes(doc))
    else:
        ds = _with_arrays(obj.to_xarray(), arrays)
        ds.attrs.update({**type_attrs(obj), FIELDS_ATTR: json.dumps(fields, ensure_ascii=False)})
        ds.to_netcdf(tmp, engine=store.netcdf_engine(), encoding=_encoding(ds))
    with open(tmp, "rb") as fh:
        os.fsync(fh.fileno())


def _json_bytes(doc: dict[str, Any]) -> bytes:
    """``doc`` as UTF-8 JSON; ValueError if :func:`load` would refuse it as too large."""
    data = json.dumps(doc, ensure_ascii=False).encode("utf-8")
    if len(data) > MAX_BYTES:
        raise ValueError(
            f"path: the result is {len(data) / 2**20:.0f} MiB as JSON, more than the "
            f"{MAX_BYTES // 2**20} MiB a file is read back with; save it as .nc"
        )
    return data


def _pack(a: np.ndarray) -> dict[str, Any]:
    data = base64.b64encode(np.ascontiguousarray(a).tobytes()).decode("ascii")
    return {"dtype": a.dtype.str, "shape": list(a.shape), "data": data}


def _unpack(d: dict[str, Any]) -> np.ndarray:
    dtype = np.dtype(d["dtype"])
    if dtype.kind not in "biuf":
        raise ValueError(f"an array of dtype {dtype} is no result's")
    raw = base64.b64decode(d["data"], validate=True)
    return np.frombuffer(raw, dtype=dtype).reshape(tuple(d["shape"])).copy()


def _with_arrays(ds: xr.Dataset, arrays: dict[str, np.ndarray]) -> xr.Dataset:
    """``ds`` with every field array it does not hold bit for bit under the field's path
    (``_saved`` appended where the dataset uses the name for something else)."""
    names = {}
    for key, a in arrays.items():
        if key in ds.variables and _same_bits(ds.variables[key].values, a):
            names[key] = key
            continue
        name = key if key not in ds.variables else f"{key}_saved"
        ds[name] = ([f"{name}_{k}" for k in range(a.ndim)], a)
        names[key] = name
    ds.attrs["eccjump_arrays"] = json.dumps(names)
    return ds


def _same_bits(x: Any, a: np.ndarray) -> bool:
    x = np.asarray(x)
    return x.dtype == a.dtype and x.shape == a.shape and x.tobytes() == a.tobytes()


def _encoding(ds: xr.Dataset) -> dict[str, dict[str, Any]]:
    """Checksums (as a map's: damage is found on reading) and no fill value (every value,
    NaN or not, is read back as written) on every numeric variable."""
    checked = netcdf_encoding(ds.variables.items())
    return {str(k): {**e, "_FillValue": None} for k, e in checked.items()}


def _read_json(path: Path) -> tuple[Any, dict[str, np.ndarray]]:
    doc = json.loads(read_text("path", path))
    return doc["fields"], {k: _unpack(v) for k, v in dict(doc["arrays"]).items()}


def _read_netcdf(path: Path) -> tuple[Any, dict[str, np.ndarray]]:
    with _open_netcdf(path) as ds:
        names = json.loads(ds.attrs["eccjump_arrays"])
        arrays = {k: ds.variables[v].values for k, v in names.items()}
        return json.loads(ds.attrs[FIELDS_ATTR]), arrays


def _open_netcdf(path: Path) -> xr.Dataset:
    """The netCDF file at ``path``, loaded, once the library has read it whole in a child
    process with a time limit (a damaged file can hang it: the maps' guard)."""
    xr = require("xarray")
    engine = store.netcdf_engine()
    store.probe_netcdf(path, engine)
    return xr.open_dataset(path, engine=engine, mask_and_scale=False, decode_times=False).load()


def _result_type(path: Path, suffix: str) -> str:
    """The ``eccjump_type`` of a file; ``"map"`` for a map of eccjump (a netCDF file with
    ``eccjump_version`` but no type); ValueError for a file with neither."""
    if suffix == ".json":
        head = json.loads(read_text("path", path))
        kind = head.get(TYPE_ATTR) if isinstance(head, dict) else None
    else:
        with _open_netcdf(path) as ds:
            is_map = "eccjump_version" in ds.attrs
            kind = ds.attrs.get(TYPE_ATTR, "map" if is_map else None)
    if kind is None:
        raise ValueError(f"has no {TYPE_ATTR}")
    return str(kind)


def load(path: str | os.PathLike) -> Any:
    """Any result of eccjump saved to a file, read back as its type.

    A result's ``save(path)`` writes the file (``.nc`` or ``.json``; a map also ``.npz``
    or ``.zarr``; an uncertainty study also ``.csv``); the type recorded in it
    (``eccjump_type``; a map's kind) chooses the class. What is read back equals what was
    saved, field by field and bit for bit, except a dense solution ``sol`` (None).

    Parameters
    ----------
    path : str or os.PathLike
        A file written by a result's ``save`` (:class:`RollResult`, :class:`MotionResult`,
        :class:`JarmResult`, :class:`MotionPoints`, :class:`Design`, :class:`Analysis`,
        :class:`Uncertainty`), a map's (:class:`Region`, :class:`MotionMap`, or
        :func:`eccjump.maps.save`) or ``eccjump map -o``.

    Returns
    -------
    RollResult, MotionResult, JarmResult, MotionPoints, Design, Analysis, Uncertainty,
    Region or MotionMap
        The result, as the class that saved it.

    Raises
    ------
    ValueError
        Naming ``path``: for a file that is no saved result (no type recorded, an unknown
        type, damaged or foreign content) or an unknown suffix.
    FileNotFoundError
        If there is no file at ``path``.
    ImportError
        For ``.nc`` or ``.zarr`` without xarray (``pip install "eccjump[xarray]"``).

    Examples
    --------
    >>> import math, os, tempfile
    >>> import eccjump
    >>> run = eccjump.roll(eccjump.Cylinder(chi=0.15, km=0.02), math.radians(40), mu_s=1.0)
    >>> path = run.save(os.path.join(tempfile.mkdtemp(), "run.json"))
    >>> back = eccjump.load(path)
    >>> type(back).__name__, back == run
    ('RollResult', True)
    """
    source = Path(path_arg("path", path))
    suffix = _suffix(source, (*SUFFIXES, *MAP_SUFFIXES, *Result._suffix_owners))
    if suffix in Result._suffix_owners:
        return Result._suffix_owners[suffix]._read(source, suffix)
    if suffix in MAP_SUFFIXES:
        return store_load(source)
    _check_file(source)
    kind = _guarded(source, lambda: _result_type(source, suffix))
    if kind == "map":
        return store_load(source)
    if kind not in Result._classes:
        raise file_error(source, f"holds an unknown {TYPE_ATTR} {kind[:30]!r}", name="path")
    return _guarded(source, lambda: Result._classes[kind]._read(source, suffix))


def _guarded(source: Path, read: Callable[[], T]) -> T:
    """``read()``, its failures on a file that is no saved result a ValueError naming it."""
    try:
        return read()
    except (KeyError, TypeError, ValueError, IndexError, AttributeError) as err:
        if str(err).startswith(("path: ", shown(source))):  # names the file (too large, ...)
            raise
        what = f"is no saved result of eccjump ({_detail(err)})"
        raise file_error(source, what, name="path") from err
    except OSError as err:
        raise file_error(source, f"cannot be read ({_detail(err)})", name="path") from None


def _check_file(path: Path) -> None:
    """FileNotFoundError if missing, ValueError naming ``path`` if it is no regular file."""
    mode = os.stat(path).st_mode
    if not stat.S_ISREG(mode):
        raise file_error(path, "is not a regular file", name="path")


def _detail(err: BaseException) -> str:
    return f"{type(err).__name__}: {err}"[:80]


def store_load(path: Path) -> Map:
    """A map file as its class (as :func:`eccjump.maps.load`)."""
    lay, kind = store.read_layout(path)
    return Map.of_kind(kind).from_layout(lay, path)


def clean_attrs(attrs: Mapping[str, Any]) -> dict[str, Any]:
    """Attributes a netCDF file takes: None left out, booleans as 0/1."""
    return {k: int(v) if isinstance(v, bool) else v for k, v in attrs.items() if v is not None}


def dataset(
    obj: Result,
    data_vars: Mapping[str, Any],
    coords: Mapping[str, Any] | None = None,
    attrs: Mapping[str, Any] | None = None,
) -> xr.Dataset:
    """The dataset of a result: its variables, and its scalar facts and type as attributes."""
    xr = require("xarray")
    every = {**clean_attrs(attrs or {}), **type_attrs(obj)}
    return xr.Dataset(data_vars, coords=coords, attrs=every)


def series(
    dim: str, values: Mapping[str, Any], attrs_of: Callable[[str], dict[str, Any]]
) -> dict[str, tuple[tuple[str, ...], Any, dict[str, Any]]]:
    """Variables along ``dim``, each with the attributes ``attrs_of(name)``."""
    return {k: ((dim,), np.asarray(v), attrs_of(k)) for k, v in values.items()}


def records_of(
    dim: str,
    rows: Sequence[tuple],
    names: Sequence[str],
    attrs_of: Callable[[str], dict[str, Any]] = lambda _: {},
) -> dict[str, Any]:
    """A table of records (tuples) along its own dimension ``dim``: one variable per column,
    named ``<dim>_<column>`` (an event's ``t`` is ``event_t``, apart from the series' ``t``;
    a column named as ``dim`` keeps its name), with the attributes ``attrs_of(column)``."""
    return {
        (dim if k == dim else f"{dim}_{k}"): ((dim,), _column(rows, i), attrs_of(k))
        for i, k in enumerate(names)
    }


def _column(rows: Sequence[tuple], i: int) -> np.ndarray:
    """Column ``i`` of ``rows`` (None, the first transition's mode before, as "")."""
    values = ["" if r[i] is None else r[i] for r in rows]
    return np.array(values) if values else np.zeros(0)


def point_dims(shape: tuple[int, ...]) -> tuple[str, ...]:
    """The dimensions of a result over points of ``shape``: ``point`` for a 1-D array,
    ``point_0``, ``point_1``, ... for more, none for one point."""
    return ("point",) if len(shape) == 1 else tuple(f"point_{i}" for i in range(len(shape)))


def points(
    obj: Result, values: Mapping[str, Any], attrs_of: Callable[[str], dict[str, Any]]
) -> xr.Dataset:
    """The dataset of a result over points (every field of the points' shape, or that shape
    and a trailing ``wrt``): one variable per field with ``attrs_of(name)``."""
    shape = np.shape(next(iter(values.values())))
    dims = point_dims(shape)
    data = {
        k: ((*dims, "wrt")[: np.ndim(v)], np.asarray(v), attrs_of(k)) for k, v in values.items()
    }
    return dataset(obj, data)


def to_frame(ds: xr.Dataset, dims: tuple[str, ...]) -> Any:
    """The variables of ``ds`` over exactly ``dims`` as a ``pandas.DataFrame`` indexed by
    them, the units of its columns in ``attrs["units"]``, the dataset's attributes too."""
    names = [k for k, v in ds.data_vars.items() if v.dims == dims]
    sub = ds[names]
    frame = sub.to_dataframe() if dims else sub.expand_dims("point").to_dataframe()
    units = {k: str(v.attrs.get("units", "")) for k, v in sub.variables.items()}
    frame.attrs = {**ds.attrs, "units": units}
    return frame

"""JARM maps on disk, the format chosen by the suffix: ``.nc`` (netCDF4, engine h5netcdf or
netCDF4), ``.zarr`` (zarr v3 directory store) or ``.npz`` (numpy; needs neither xarray nor
zarr).

:func:`save` and :func:`load`/:func:`open_dataset` handle whole maps. :class:`ZarrMap`
writes a map chunk by chunk along alpha, recording finished alpha slices in the data
variable ``alpha_done`` (written after the data of its chunk), so that an interrupted map
keeps what was finished and can be resumed; the attribute ``complete`` (0/1) says whether
every slice is there. Points not computed hold the fill values: NaN, ``is_jarm`` False,
``n`` 0 and ``reason`` 255 (not a :class:`~eccjump.Reason`).
"""

from __future__ import annotations

import json
import os
import warnings
from collections.abc import Mapping
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump.classification import Region
from eccjump.fields import DTYPES, FIELDS, FILL
from eccjump.labelled import (
    COORD_ATTRS,
    DIMS,
    Layout,
    attrs_json,
    field_var,
    grid_coords,
    layout_from_xarray,
    layout_to_xarray,
    region_layout,
    require,
    to_region,
)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

FORMATS = {".nc": "netcdf", ".zarr": "zarr", ".npz": "npz"}


def format_of(path: str | os.PathLike) -> str:
    """``"netcdf"``, ``"zarr"`` or ``"npz"`` from the suffix of ``path``."""
    suffix = Path(path).suffix.lower()
    if suffix not in FORMATS:
        raise ValueError(f"unknown output format {suffix!r} of {path}; use .nc, .zarr or .npz")
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


def _replace(tmp: Path, path: Path) -> None:
    os.replace(tmp, path)


def save(
    obj: Region | Layout | xr.Dataset,
    path: str | os.PathLike,
    *,
    attrs: Mapping[str, Any] | None = None,
) -> Path:
    """Write a map (a :class:`Region`, a dataset or a layout) to ``path``, replacing it.

    ``.nc`` and ``.npz`` are written to a temporary file first and renamed, so a file at
    ``path`` is always whole. ``.npz`` needs numpy only.
    """
    path = Path(path)
    fmt = format_of(path)
    lay = _as_layout(obj)
    if attrs:
        lay = {**lay, "attrs": {**lay["attrs"], **attrs}}
    if fmt == "npz":
        tmp = path.with_name(path.name + ".tmp")
        save_npz(lay, tmp)
        _replace(tmp, path)
        return path
    ds = layout_to_xarray(lay)
    if fmt == "netcdf":
        tmp = path.with_name(path.name + ".tmp")
        ds.to_netcdf(tmp, engine=netcdf_engine())
        _replace(tmp, path)
    else:
        require("zarr")
        with _quiet_consolidation():
            ds.to_zarr(path, mode="w", consolidated=True)
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


def load_layout(path: str | os.PathLike) -> Layout:
    if format_of(path) == "npz":
        return load_npz(path)
    return layout_from_xarray(open_dataset(path))


def load(path: str | os.PathLike) -> Region:
    """A map file (of one map, no swept dimensions) as a :class:`Region`. ``.npz`` needs
    numpy only. The file's ``complete`` and ``alpha_done`` go to ``Region.attrs``."""
    lay = load_layout(path)
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
        zarr = require("zarr")
        self.path = Path(path)
        self.group = zarr.open_group(self.path, mode="r+")
        self.attrs: dict[str, Any] = dict(self.group.attrs)
        self.alpha = np.asarray(self.group["alpha"][:], dtype=np.float64)
        self.chi = np.asarray(self.group["chi"][:], dtype=np.float64)
        self.km_frac = np.asarray(self.group["km_frac"][:], dtype=np.float64)
        self.chunk = int(self.group["is_jarm"].chunks[0])

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
        """An empty map (every point at its fill value, ``alpha_done`` all False)."""
        zarr = require("zarr")
        shape = (alpha.size, chi.size, km_frac.size)
        chunks = (max(1, min(chunk, alpha.size)), max(chi.size, 1), max(km_frac.size, 1))
        group = zarr.create_group(
            store=str(path),
            overwrite=True,
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
        for name in FIELDS:
            dtype = DTYPES[name]
            group.create_array(
                name,
                shape=shape,
                dtype=dtype,
                chunks=chunks,
                fill_value=FILL[name],
                dimension_names=DIMS,
                attributes=_json_attrs({**field_var(name), "coordinates": "alpha_deg km"}),
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
        return cls(path)

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
        for name in FIELDS:
            self.group[name][i0:i1] = np.asarray(fields[name], dtype=DTYPES[name])
        self.group["alpha_done"][i0:i1] = True

    def read(self, i: int, names: tuple[str, ...] = FIELDS) -> dict[str, NDArray]:
        i0, i1 = self.bounds(i)
        return {k: np.asarray(self.group[k][i0:i1]) for k in names}

    def finish(self, **attrs: Any) -> None:
        """Record ``complete`` (and other attributes) and consolidate the metadata."""
        zarr = require("zarr")
        complete = int(bool(self.alpha_done().all()))
        self.group.attrs.update(_json_attrs({**attrs, "complete": complete}))
        self.attrs = dict(self.group.attrs)
        with _quiet_consolidation():
            zarr.consolidate_metadata(str(self.path))

"""JARM maps in and out of files and datasets: a JARM map file as a :class:`~eccjump.Region`
(:func:`load`), a dataset or layout of one map as a Region (:func:`to_region`).

The map layer reads and writes layouts of any kind (:mod:`eccjump.maps.store`); making a
Region of one is the classification's (:meth:`Region.from_layout
<eccjump.Region.from_layout>`), so that the map layer knows no kind. :func:`eccjump.maps.load`
reads a map file of either kind as its class.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from eccjump.classification.classify import Region
from eccjump.classification.fields import JARM
from eccjump.maps.check import file_error
from eccjump.maps.layout import DIMS, Layout, layout_from_xarray
from eccjump.maps.store import read_layout

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


def load(path: str | os.PathLike) -> Region:
    """A JARM map file (of one map, no swept dimensions) as a :class:`Region`.

    ``.npz`` needs numpy only. The file's ``complete`` and ``alpha_done`` go to
    ``Region.attrs``. :func:`eccjump.maps.load` reads either kind.

    Parameters
    ----------
    path : str or os.PathLike
        A ``.nc``, ``.zarr`` or ``.npz`` JARM map file.

    Returns
    -------
    Region

    Raises
    ------
    ValueError
        For a file that is not such a map (a motion map, swept maps, damaged), naming it and
        what is wrong.
    FileNotFoundError
        If there is no file at ``path``.
    """
    lay, kind = read_layout(path)
    if kind is not JARM:
        raise file_error(path, f"is a {kind.words()}: load it with eccjump.maps.load")
    return Region.from_layout(lay, path)


def to_region(ds: xr.Dataset | Layout) -> Region:
    """A :class:`Region` back from a dataset or layout of one JARM map (no swept dimensions;
    unchecked: a file is read checked by :func:`load`)."""
    lay = ds if isinstance(ds, dict) else layout_from_xarray(ds)
    dims = tuple(lay["data_vars"]["is_jarm"][0])
    if dims != DIMS:
        raise ValueError(
            f"a Region has dims {DIMS}; this map has {dims} "
            "(select one value of each swept parameter first)"
        )
    return Region.from_layout(lay, "ds")


__all__ = ["load", "to_region"]

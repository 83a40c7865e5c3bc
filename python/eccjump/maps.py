"""Maps: a result at every point of a parameter grid, JARM maps and motion maps alike.

Both kinds are a :class:`Map` -- :class:`~eccjump.Region` from :func:`~eccjump.region` and
:class:`~eccjump.MotionMap` from :func:`~eccjump.motion_map` -- with the same ``coords``,
``fields``, ``shape``, ``fraction()`` and ``to_xarray()``. :func:`save` writes a map of either
kind to a file (``.nc``, ``.zarr`` or ``.npz``) and :func:`load` reads it back as its type.
"""

from __future__ import annotations

import os

from eccjump import store
from eccjump._map import Map
from eccjump.classification import Region, region
from eccjump.motion_maps import MotionMap, from_layout, motion_map
from eccjump.store import save


def load(path: str | os.PathLike) -> Map:
    """The map file at ``path`` (``.nc``, ``.zarr`` or ``.npz``) as a :class:`Region` or a
    :class:`MotionMap`, by the kind recorded in it. A file that is no valid map raises
    ValueError naming it and what is wrong (a JARM file of swept maps, written with
    ``region(..., output="xarray")``: open it with :func:`eccjump.store.open_dataset`)."""
    lay, kind = store.read_layout(path)
    if kind.name == "motion":
        return from_layout(lay, kind, path)
    return store.region_of(lay, path)


__all__ = ["Map", "MotionMap", "Region", "load", "motion_map", "region", "save"]

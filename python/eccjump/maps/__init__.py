"""Maps: a result at every point of a parameter grid, JARM maps, motion maps and maps of
P(JARM) under tolerances alike.

Every kind is a :class:`Map` -- :class:`~eccjump.Region` from :func:`~eccjump.region`,
:class:`~eccjump.MotionMap` from :func:`~eccjump.motion_map` and
:class:`~eccjump.UncertaintyMap` from :func:`~eccjump.uncertainty_map` -- with the same
``coords``, ``fields``, ``shape``, ``fraction()`` and ``to_xarray()``. :func:`save` writes a
map of any kind to a file (``.nc``, ``.zarr`` or ``.npz``) and :func:`load` reads it back as
its type.

The map layer knows no kind of map: each kind (:mod:`eccjump.maps.kinds`) and its result
class (:class:`Map`) register themselves, and this layer finds them by the kind in a file.
"""

from __future__ import annotations

import os
from typing import TYPE_CHECKING

from eccjump import _compat
from eccjump.maps import store
from eccjump.maps.map import Map
from eccjump.maps.store import save


def load(path: str | os.PathLike) -> Map:
    """The map file at ``path`` as a :class:`Region` or a :class:`MotionMap`, by the kind
    recorded in it.

    Parameters
    ----------
    path : str or os.PathLike
        A map file written by :func:`save` or ``eccjump map``: ``.nc`` (netCDF, needs
        xarray), ``.zarr`` (needs zarr) or ``.npz`` (numpy only).

    Returns
    -------
    Map
        A :class:`Region` (JARM map) or a :class:`MotionMap`: the result class of the file's
        kind.

    Raises
    ------
    ValueError
        For a file that is no valid map, naming it and what is wrong (a JARM file of swept
        maps, written from :func:`eccjump.region_dataset`: open it with
        :func:`eccjump.store.open_dataset`) or an unknown suffix.
    FileNotFoundError
        If there is no file at ``path``.

    Examples
    --------
    >>> import os, tempfile
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.region(np.radians([35, 40, 45]), [0.1, 0.15], [0.0, 0.1], 1.0)
    >>> path = os.path.join(tempfile.mkdtemp(), "region.npz")
    >>> _ = eccjump.maps.save(m, path)
    >>> back = eccjump.load_map(path)
    >>> type(back).__name__, back == m
    ('Region', True)
    """
    lay, kind = store.read_layout(path)
    return Map.of_kind(kind).from_layout(lay, path)


# Region, region, MotionMap and motion_map, re-exported here before the map layer knew no
# kind, for one release: eccjump.Region and the others are their names.
if not TYPE_CHECKING:  # (a module __getattr__ would let mypy pass any typo)

    def __getattr__(name: str):
        return _compat.moved_name(__name__, name)


__all__ = ["Map", "load", "save"]

"""Labelled maps: a map of any kind as an ``xarray.Dataset``, and back.

The layout (names, dimensions, units, attributes) is built with numpy alone by each map's
``to_layout()`` (the names and attributes of the fields from its kind,
:class:`~eccjump.maps.kinds.MapKind`), so that plain ``.npz`` files work without xarray;
xarray, zarr and netCDF are optional (``pip install eccjump[xarray]``) and imported only when
needed. The layout code itself is in the private ``eccjump.maps.layout``.

Dataset layout
--------------
One dimension per swept axis (a JARM map: ``alpha`` [rad], ``chi``, ``km_frac`` (= k_m/(1 -
χ)); a motion map: those of its eight axes that are swept), one data variable per field
of the kind with its units (``units``, ``long_name``) and the codes of a coded field as CF
``flag_values``/``flag_meanings``; the dataset attributes record the kind (``kind``; none: a
JARM map), how the map was made and ``eccjump_version``. A map on α × χ × km_frac also
has the coordinates ``alpha_deg`` (on ``alpha``) and the 2-D ``km`` (on ``chi`` x
``km_frac``). The JARM layout, and sweeps of ``mu_s``, ``theta0``, ``omega0`` as extra
dimensions: :func:`eccjump.region_dataset`.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

from eccjump import _compat
from eccjump.maps.layout import (
    COORD_ATTRS,
    DIMS,
    Layout,
    attrs_json,
    grid_coords,
    layout_from_xarray,
    layout_to_xarray,
    make_layout,
    require,
)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

    from eccjump.maps.map import Map


def to_xarray(m: Map) -> xr.Dataset:
    """The map ``m`` as an ``xarray.Dataset`` (lazy if ``m`` is)."""
    return m.to_xarray()


# The JARM names this module had before the map layer knew no kind, for one release.
if not TYPE_CHECKING:  # (a module __getattr__ would let mypy pass any typo)

    def __getattr__(name: str):
        return _compat.moved_name(__name__, name)


__all__ = [
    "COORD_ATTRS",
    "DIMS",
    "Layout",
    "attrs_json",
    "grid_coords",
    "layout_from_xarray",
    "layout_to_xarray",
    "make_layout",
    "require",
    "to_xarray",
]

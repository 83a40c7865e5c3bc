"""Labelled JARM maps: :class:`~eccjump.Region` as an ``xarray.Dataset``, and sweeps of
``mu_s``, ``theta0``, ``omega0`` as extra dimensions.

The layout (names, dimensions, units, attributes) is built with numpy alone by
:func:`region_layout`, so that plain ``.npz`` files work without xarray; xarray, zarr and
netCDF are optional (``pip install eccjump[xarray]``) and imported only when needed. The
units and meanings of the fields come from :mod:`eccjump.classification.fields`; the layout
code itself is in the private ``eccjump.maps.layout`` (below :mod:`eccjump.classification`,
which uses it for :meth:`Region.to_xarray <eccjump.Region.to_xarray>` and
``region(..., output="xarray")``).

Dataset layout
--------------
dims ``alpha`` [rad], ``chi``, ``km_frac`` (= k_m/(1 - chi)), preceded by ``mu_s``,
``theta0``, ``omega0`` for the ones swept; coordinates ``alpha_deg`` (on ``alpha``) and the
2-D ``km`` (on ``chi`` x ``km_frac``); one data variable per field of
:class:`~eccjump.JarmResult`. ``reason`` carries the CF ``flag_values``/``flag_meanings``;
the dataset attributes record how the map was made (``mu_s``, ``n`` with 0 meaning "the
first jump whatever its turn", ``rule``, ``method``, ``theta0``, ``omega0``, tolerances, the
``integrator``, ``eccjump_version``) and the Reason code table.
"""

from __future__ import annotations

from typing import TYPE_CHECKING

import numpy as np

from eccjump.classification.classify import (
    JarmResult,
    Region,
    region_attrs,
    region_dataset,
    region_layout,
)
from eccjump.classification.fields import BY_NAME, DERIVATIVES, DTYPES, FIELDS, FILL, reason_table
from eccjump.maps.layout import (
    COORD_ATTRS,
    DIMS,
    EXTRA,
    MAP_INFO,
    SWEEPABLE,
    Layout,
    attrs_json,
    field_var,
    grid_coords,
    layout_from_xarray,
    layout_to_xarray,
    make_layout,
    map_attrs,
    require,
)

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

#: Units and meaning of every field (CF-style ``units`` and ``long_name``).
FIELD_ATTRS: dict[str, dict[str, str]] = {
    k: {"units": f.units, "long_name": f.description} for k, f in BY_NAME.items()
}


def to_xarray(region: Region) -> xr.Dataset:
    """``region`` as an ``xarray.Dataset`` (lazy if ``region`` is)."""
    return region.to_xarray()


def to_region(ds: xr.Dataset | Layout) -> Region:
    """A :class:`Region` back from a dataset or layout of one map (no swept dimensions)."""
    lay = ds if isinstance(ds, dict) else layout_from_xarray(ds)
    dv, co, at = lay["data_vars"], lay["coords"], dict(lay["attrs"])
    if tuple(dv["is_jarm"][0]) != DIMS:
        raise ValueError(
            f"a Region has dims {DIMS}; this map has {tuple(dv['is_jarm'][0])} "
            "(select one value of each swept parameter first)"
        )
    names = FIELDS + (DERIVATIVES if "d_theta_J" in dv else ())
    res = JarmResult(**{k: np.asarray(dv[k][1], dtype=DTYPES[k]) for k in names})
    made = ("mu_s", "n", "rule", "method", "theta0", "omega0")
    n = int(at["n"])
    return Region(
        alpha=np.asarray(co["alpha"][1], dtype=np.float64),
        chi=np.asarray(co["chi"][1], dtype=np.float64),
        km_frac=np.asarray(co["km_frac"][1], dtype=np.float64),
        result=res,
        mu_s=float(at["mu_s"]),
        n=None if n == 0 else n,
        rule=str(at["rule"]),
        method=str(at["method"]),
        theta0=float(at["theta0"]),
        omega0=float(at["omega0"]),
        attrs={
            k: (v.item() if isinstance(v, np.generic) else v)
            for k, v in at.items()
            if k not in MAP_INFO and k not in made
        },
    )


__all__ = [
    "COORD_ATTRS",
    "DIMS",
    "DTYPES",
    "EXTRA",
    "FIELD_ATTRS",
    "FILL",
    "SWEEPABLE",
    "Layout",
    "attrs_json",
    "field_var",
    "grid_coords",
    "layout_from_xarray",
    "layout_to_xarray",
    "make_layout",
    "map_attrs",
    "reason_table",
    "region_attrs",
    "region_dataset",
    "region_layout",
    "require",
    "to_region",
    "to_xarray",
]

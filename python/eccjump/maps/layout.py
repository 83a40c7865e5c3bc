"""The layout of a labelled map of any kind (names, dimensions, units, attributes), built with
numpy alone from coordinate and field arrays; the conversion to and from ``xarray.Dataset``.

A layout is what every map file holds and every map result gives (``Map.to_layout()``): the
names, dtypes and attributes of its fields come from its kind
(:class:`~eccjump.maps.kinds.MapKind`), the coordinates' from :data:`COORD_ATTRS`. The
public face is :mod:`eccjump.maps.xarray`.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base import optional
from eccjump.maps.kinds import MapKind

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

#: The dimensions of a map on the grid alpha x chi x km_frac, in order: a JARM map's, and
#: those of a map of either kind written in chunks along alpha (``eccjump map``,
#: :class:`~eccjump.maps.store.ZarrMap`).
DIMS = ("alpha", "chi", "km_frac")

COORD_ATTRS: dict[str, dict[str, str]] = {
    "alpha": {"units": "rad", "long_name": "ramp angle"},
    "alpha_deg": {"units": "degree", "long_name": "ramp angle"},
    "chi": {"units": "1", "long_name": "centre-of-mass offset d/R"},
    "km_frac": {"units": "1", "long_name": "shell mass fraction as k_m/(1 - chi)"},
    "km": {"units": "1", "long_name": "shell mass fraction k_m = km_frac (1 - chi)"},
    "mu_s": {"units": "1", "long_name": "static friction coefficient"},
    "mu_k": {"units": "1", "long_name": "kinetic friction coefficient"},
    "restitution": {"units": "1", "long_name": "energetic coefficient of restitution e"},
    "theta0": {"units": "rad", "long_name": "initial angle"},
    "omega0": {"units": "sqrt(g/R) rad", "long_name": "initial angular velocity"},
    "alpha_done": {"units": "1", "long_name": "alpha slice computed (False: missing, fill)"},
}

#: A layout: {"coords": {name: (dims, array, attrs)}, "data_vars": {...}, "attrs": {...}}.
Layout = dict[str, Any]


def require(module: str) -> ModuleType:
    """Import an optional dependency of the labelled results, or fail with the pip command
    that installs it."""
    return optional.require(
        module, purpose="labelled results, netCDF and zarr files", extra="xarray"
    )


def grid_coords(
    alpha: NDArray[np.float64], chi: NDArray[np.float64], km_frac: NDArray[np.float64]
) -> dict[str, tuple[tuple[str, ...], NDArray, dict[str, str]]]:
    km = km_frac[None, :] * (1.0 - chi[:, None])
    return {
        "alpha": (("alpha",), alpha, COORD_ATTRS["alpha"]),
        "alpha_deg": (("alpha",), np.degrees(alpha), COORD_ATTRS["alpha_deg"]),
        "chi": (("chi",), chi, COORD_ATTRS["chi"]),
        "km_frac": (("km_frac",), km_frac, COORD_ATTRS["km_frac"]),
        "km": (("chi", "km_frac"), km, COORD_ATTRS["km"]),
    }


def make_layout(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    fields: Mapping[str, Any],
    attrs: Mapping[str, Any],
    alpha_done: NDArray[np.bool_] | None,
    kind: MapKind,
) -> Layout:
    """The layout of a map of ``kind`` on α × χ × km_frac (numpy only), with the
    variable ``alpha_done`` unless it is None."""
    data_vars: dict[str, tuple[tuple[str, ...], Any, dict[str, Any]]] = {
        k: (DIMS, fields[k], kind.var_attrs(k)) for k in kind.fields
    }
    if alpha_done is not None:
        data_vars["alpha_done"] = (("alpha",), alpha_done, COORD_ATTRS["alpha_done"])
    return {
        "coords": grid_coords(alpha, chi, km_frac),
        "data_vars": data_vars,
        "attrs": dict(attrs),
    }


def layout_to_xarray(layout: Layout) -> xr.Dataset:
    xr = require("xarray")

    def variable(dims: tuple[str, ...], values: Any, attrs: dict[str, Any]) -> Any:
        # Names (the coordinate wrt) as Python strings: zarr v3 has no fixed-width unicode
        # (it warns), while .npz needs them fixed-width (no pickles), so only here.
        if getattr(values, "dtype", None) is not None and values.dtype.kind == "U":
            values = values.astype(object)
        return xr.Variable(dims, values, attrs)

    return xr.Dataset(
        data_vars={k: variable(*v) for k, v in layout["data_vars"].items()},
        coords={k: variable(*v) for k, v in layout["coords"].items()},
        attrs=dict(layout["attrs"]),
    )


def layout_from_xarray(ds: xr.Dataset) -> Layout:
    def values(v: xr.Variable) -> Any:
        # Strings back to fixed-width unicode (see layout_to_xarray).
        return np.array(v.values.tolist(), dtype=str) if v.dtype.kind in "OT" else v.values

    def part(variables: Mapping) -> dict:
        return {k: (tuple(v.dims), values(v), dict(v.attrs)) for k, v in variables.items()}

    return {"coords": part(ds.coords), "data_vars": part(ds.data_vars), "attrs": dict(ds.attrs)}


def attrs_json(attrs: Mapping[str, Any]) -> str:
    """Attributes as JSON (numpy scalars and arrays converted)."""

    def conv(v: Any) -> Any:
        if isinstance(v, np.ndarray):
            return v.tolist()
        if isinstance(v, np.generic):
            return v.item()
        return v

    return json.dumps({k: conv(v) for k, v in attrs.items()})

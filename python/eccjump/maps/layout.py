"""The layout of a labelled JARM map (names, dimensions, units, attributes), built with numpy
alone from coordinate and field arrays; the conversion to and from ``xarray.Dataset``.

Knows nothing of :class:`~eccjump.Region` (so that :mod:`eccjump.classification` can use it);
the public face is :mod:`eccjump.maps.xarray`, which documents the dataset layout. The units and
meanings of the fields come from :mod:`eccjump.classification.fields`.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._base import optional
from eccjump.classification.fields import BY_NAME, FIELDS, WRT, cf_attrs, reason_table

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

EXTRA = "pip install eccjump[xarray]"

#: Dimensions of a map, in order.
DIMS = ("alpha", "chi", "km_frac")
#: Parameters that :func:`eccjump.region_dataset` can sweep, in the order of their dimensions.
SWEEPABLE = ("mu_s", "theta0", "omega0")

COORD_ATTRS: dict[str, dict[str, str]] = {
    "alpha": {"units": "rad", "long_name": "ramp angle"},
    "alpha_deg": {"units": "degree", "long_name": "ramp angle"},
    "chi": {"units": "1", "long_name": "centre-of-mass offset d/R"},
    "km_frac": {"units": "1", "long_name": "shell mass fraction as k_m/(1 - chi)"},
    "km": {"units": "1", "long_name": "shell mass fraction k_m = km_frac (1 - chi)"},
    "mu_s": {"units": "1", "long_name": "static friction coefficient"},
    "theta0": {"units": "rad", "long_name": "initial angle"},
    "omega0": {"units": "sqrt(g/R) rad", "long_name": "initial angular velocity"},
    "alpha_done": {"units": "1", "long_name": "alpha slice computed (False: missing, fill)"},
    "wrt": {"long_name": "parameter of the derivative: alpha [rad], chi or km (k_m itself)"},
}

#: A layout: {"coords": {name: (dims, array, attrs)}, "data_vars": {...}, "attrs": {...}}.
Layout = dict[str, Any]


def require(module: str) -> ModuleType:
    """Import an optional dependency of the labelled results, or fail with the pip command
    that installs it."""
    return optional.require(
        module, purpose="labelled results, netCDF and zarr files", extra="xarray"
    )


def map_attrs(
    mu_s: float,
    n: int | None,
    rule: str,
    method: str,
    theta0: float,
    omega0: float,
    **extra: Any,
) -> dict[str, Any]:
    """Attributes of a map: how it was made (netCDF-safe scalars and strings only)."""
    return {
        "title": "JARM map of an eccentric cylinder on a ramp (eccjump)",
        "eccjump_version": _core.VERSION,
        "mu_s": float(mu_s),
        "n": 0 if n is None else int(n),
        "n_meaning": "requested turn of the jump; 0: the first jump whatever its turn",
        "rule": str(rule),
        "method": str(method),
        "theta0": float(theta0),
        "omega0": float(omega0),
        **{k: (int(v) if isinstance(v, bool) else v) for k, v in extra.items()},
        "reason_codes": reason_table(),
        "units": "g = R = M = 1: angles in rad, forces in M g, omega in sqrt(g/R) rad",
    }


#: Attributes written by :func:`map_attrs` that are not options of the map.
MAP_INFO = ("title", "eccjump_version", "n_meaning", "reason_codes", "units")


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


def field_var(name: str) -> dict[str, Any]:
    """Attributes of a field variable (with the flag table on ``reason``)."""
    return cf_attrs(name)


def make_layout(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    fields: Mapping[str, Any],
    attrs: Mapping[str, Any],
    alpha_done: NDArray[np.bool_] | None = None,
    kind: Any = None,
) -> Layout:
    """The layout of a map of ``kind`` (an :class:`eccjump.maps.kinds.MapKind`, above this
    module; default: a JARM map) on alpha x chi x km_frac (numpy only)."""
    names, var_attrs = (FIELDS, field_var) if kind is None else (kind.fields, kind.var_attrs)
    data_vars: dict[str, tuple[tuple[str, ...], Any, dict[str, Any]]] = {
        k: (DIMS, fields[k], var_attrs(k)) for k in names
    }
    if alpha_done is not None:
        data_vars["alpha_done"] = (("alpha",), alpha_done, COORD_ATTRS["alpha_done"])
    return {
        "coords": grid_coords(alpha, chi, km_frac),
        "data_vars": data_vars,
        "attrs": dict(attrs),
    }


def with_derivatives(layout: Layout, derivatives: Mapping[str, Any]) -> Layout:
    """``layout`` with the derivative fields ``derivatives`` (of
    :data:`eccjump.classification.fields.DERIVATIVES`; none: ``layout`` itself) as variables,
    the float ones with the trailing dimension ``wrt`` and its coordinate of parameter names."""
    if not derivatives:
        return layout
    data_vars = dict(layout["data_vars"])
    for k, v in derivatives.items():
        dims = (*DIMS, "wrt") if BY_NAME[k].dtype.kind == "f" else DIMS
        data_vars[k] = (dims, v, field_var(k))
    wrt = (("wrt",), np.array(WRT), COORD_ATTRS["wrt"])
    return {**layout, "coords": {**layout["coords"], "wrt": wrt}, "data_vars": data_vars}


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

"""Labelled JARM maps: :class:`~eccjump.Region` as an ``xarray.Dataset``, and sweeps of
``mu_s``, ``theta0``, ``omega0`` as extra dimensions.

The layout (names, dimensions, units, attributes) is built with numpy alone by
:func:`region_layout`, so that plain ``.npz`` files work without xarray; xarray, zarr and
netCDF are optional (``pip install eccjump[xarray]``) and imported only when needed.

Dataset layout
--------------
dims ``alpha`` [rad], ``chi``, ``km_frac`` (= k_m/(1 - chi)), preceded by ``mu_s``,
``theta0``, ``omega0`` for the ones swept; coordinates ``alpha_deg`` (on ``alpha``) and the
2-D ``km`` (on ``chi`` x ``km_frac``); one data variable per field of
:class:`~eccjump.JarmResult`. ``reason`` carries the CF ``flag_values``/``flag_meanings``;
the dataset attributes record how the map was made (``mu_s``, ``n`` with 0 meaning "the
first jump whatever its turn", ``rule``, ``method``, ``theta0``, ``omega0``, tolerances,
``eccjump_version``) and the Reason code table.
"""

from __future__ import annotations

import json
from collections.abc import Mapping
from types import ModuleType
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump.classification import FIELDS, JarmResult, Region

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr

EXTRA = "pip install eccjump[xarray]"

#: Dimensions of a map, in order.
DIMS = ("alpha", "chi", "km_frac")
#: Parameters that :func:`region_dataset` can sweep, in the order of their dimensions.
SWEEPABLE = ("mu_s", "theta0", "omega0")

#: Units and meaning of every field (CF-style ``units`` and ``long_name``).
FIELD_ATTRS: dict[str, dict[str, str]] = {
    "is_jarm": {"units": "1", "long_name": "jump straight out of pure rolling (JARM)"},
    "reason": {"units": "1", "long_name": "why the point is or is not a JARM (Reason code)"},
    "n": {
        "units": "1",
        "long_name": "turn of the jump, earlier lift-off or deciding event; 0 none",
    },
    "theta_J": {
        "units": "rad",
        "long_name": "lift-off angle (JARM, LIFTOFF_EARLIER, SLIP_AT_JUMP)",
    },
    "theta_event": {"units": "rad", "long_name": "angle of the deciding failure (NaN for a JARM)"},
    "Fx_J": {"units": "M g", "long_name": "friction force at the jump (JARM only)"},
    "Fy_J": {"units": "M g", "long_name": "normal force at the jump (JARM only)"},
    "max_ratio": {"units": "1", "long_name": "largest |Fx|/Fy on the rolling path"},
    "theta_max_ratio": {"units": "rad", "long_name": "angle of the largest |Fx|/Fy"},
    "min_Fy": {"units": "M g", "long_name": "smallest normal force on the rolling path"},
    "theta_min_Fy": {"units": "rad", "long_name": "angle of the smallest normal force"},
}

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
}

#: Values of the fields where a point was not computed (an interrupted map).
FILL: dict[str, Any] = {"is_jarm": False, "reason": 255, "n": 0}
DTYPES: dict[str, np.dtype] = {
    "is_jarm": np.dtype(np.bool_),
    "reason": np.dtype(np.uint8),
    "n": np.dtype(np.uint32),
    **{k: np.dtype(np.float64) for k in FIELDS[3:]},
}


def require(module: str) -> ModuleType:
    """Import an optional dependency, or fail with the pip command that installs it."""
    import importlib

    try:
        return importlib.import_module(module)
    except ImportError as err:
        raise ImportError(
            f"{module} is needed for labelled results, netCDF and zarr files: {EXTRA}"
        ) from err


def reason_table() -> str:
    """The Reason codes as ``"0: jarm, 1: no_root, ..."``."""
    return ", ".join(f"{code}: {name}" for code, name in _core.reason_codes())


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


def region_attrs(region: Region) -> dict[str, Any]:
    """:func:`map_attrs` of a :class:`Region`."""
    return map_attrs(
        region.mu_s,
        region.n,
        region.rule,
        region.method,
        region.theta0,
        region.omega0,
        **region.attrs,
    )


#: A layout: {"coords": {name: (dims, array, attrs)}, "data_vars": {...}, "attrs": {...}}.
Layout = dict[str, Any]


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
    attrs: dict[str, Any] = dict(FIELD_ATTRS[name])
    if name == "reason":
        codes = _core.reason_codes()
        attrs["flag_values"] = np.array([c for c, _ in codes], dtype=np.uint8)
        attrs["flag_meanings"] = " ".join(n for _, n in codes)
    return attrs


def make_layout(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km_frac: NDArray[np.float64],
    fields: Mapping[str, Any],
    attrs: Mapping[str, Any],
    alpha_done: NDArray[np.bool_] | None = None,
) -> Layout:
    """The layout of a map on alpha x chi x km_frac (numpy only)."""
    data_vars = {k: (DIMS, fields[k], field_var(k)) for k in FIELDS}
    if alpha_done is not None:
        data_vars["alpha_done"] = (("alpha",), alpha_done, COORD_ATTRS["alpha_done"])
    return {
        "coords": grid_coords(alpha, chi, km_frac),
        "data_vars": data_vars,
        "attrs": dict(attrs),
    }


def region_layout(region: Region) -> Layout:
    """The layout of a :class:`Region` (numpy only)."""
    fields = {k: getattr(region.result, k) for k in FIELDS}
    return make_layout(region.alpha, region.chi, region.km_frac, fields, region_attrs(region))


def layout_to_xarray(layout: Layout) -> xr.Dataset:
    xr = require("xarray")
    return xr.Dataset(
        data_vars={k: xr.Variable(*v) for k, v in layout["data_vars"].items()},
        coords={k: xr.Variable(*v) for k, v in layout["coords"].items()},
        attrs=dict(layout["attrs"]),
    )


def layout_from_xarray(ds: xr.Dataset) -> Layout:
    def part(variables: Mapping) -> dict:
        return {k: (tuple(v.dims), v.values, dict(v.attrs)) for k, v in variables.items()}

    return {"coords": part(ds.coords), "data_vars": part(ds.data_vars), "attrs": dict(ds.attrs)}


def to_xarray(region: Region) -> xr.Dataset:
    """``region`` as an ``xarray.Dataset`` (lazy if ``region`` is)."""
    return layout_to_xarray(region_layout(region))


def to_region(ds: xr.Dataset | Layout) -> Region:
    """A :class:`Region` back from a dataset or layout of one map (no swept dimensions)."""
    lay = ds if isinstance(ds, dict) else layout_from_xarray(ds)
    dv, co, at = lay["data_vars"], lay["coords"], dict(lay["attrs"])
    if tuple(dv["is_jarm"][0]) != DIMS:
        raise ValueError(
            f"a Region has dims {DIMS}; this map has {tuple(dv['is_jarm'][0])} "
            "(select one value of each swept parameter first)"
        )
    res = JarmResult(**{k: np.asarray(dv[k][1], dtype=DTYPES[k]) for k in FIELDS})
    known = {"title", "eccjump_version", "n_meaning", "reason_codes", "units"}
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
            if k not in known and k not in made
        },
    )


def region_dataset(
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    **kwargs: Any,
) -> xr.Dataset:
    """Map the JARM region as an ``xarray.Dataset``, sweeping ``mu_s``, ``theta0`` and
    ``omega0`` when they are 1-D sequences (one Rust grid call per combination; the swept
    parameters become leading dimensions, in that order). Other arguments as
    :func:`eccjump.region` (``chunks=`` gives a dask-backed, lazily computed dataset).
    """
    from eccjump.classification import region

    require("xarray")
    kwargs.pop("output", None)
    given = {"mu_s": mu_s, "theta0": theta0, "omega0": omega0}
    scalars: dict[str, float] = {}
    swept: dict[str, NDArray[np.float64]] = {}
    for name in SWEEPABLE:
        arr = np.asarray(given[name], dtype=np.float64)
        if arr.ndim == 0:
            scalars[name] = float(arr)
        elif arr.ndim == 1 and arr.size:
            swept[name] = arr
        else:
            raise ValueError(f"{name} must be a number or a non-empty 1-D sequence")
    grid = {"alpha": alpha, "chi": chi, "km": km}

    def one(values: Mapping[str, float]) -> xr.Dataset:
        reg = region(n=n, **grid, **scalars, **values, **kwargs)  # type: ignore[arg-type]
        return reg.to_xarray()

    if not swept:
        return one({})
    xr = require("xarray")
    names = list(swept)

    def build(level: int, fixed: dict[str, float]) -> xr.Dataset:
        name = names[level]
        parts = []
        for v in swept[name]:
            here = {**fixed, name: float(v)}
            if level + 1 < len(names):
                ds = build(level + 1, here)
            else:
                ds = one(here)
                for k in names:  # swept values live in coordinates, not attributes
                    ds.attrs.pop(k, None)
                ds = ds.assign_coords({k: xr.Variable((), here[k]) for k in names})
            parts.append(ds)
        return xr.concat(
            parts,
            dim=name,
            data_vars="all",
            coords="minimal",
            compat="override",
            join="exact",
            combine_attrs="override",
        )

    out = build(0, {})
    for k in names:
        out[k].attrs.update(COORD_ATTRS[k])
    out.attrs["swept"] = " ".join(names)
    return out


def attrs_json(attrs: Mapping[str, Any]) -> str:
    """Attributes as JSON (numpy scalars and arrays converted)."""

    def conv(v: Any) -> Any:
        if isinstance(v, np.ndarray):
            return v.tolist()
        if isinstance(v, np.generic):
            return v.item()
        return v

    return json.dumps({k: conv(v) for k, v in attrs.items()})


__all__ = [
    "COORD_ATTRS",
    "DIMS",
    "FIELD_ATTRS",
    "SWEEPABLE",
    "make_layout",
    "region_dataset",
    "region_layout",
    "require",
    "to_region",
    "to_xarray",
]

"""JARM maps as datasets and files: the map as an ``xarray.Dataset`` sweeping ``mu_s``,
``theta0``, ``omega0`` as extra dimensions (:func:`region_dataset`), a JARM map file as a
:class:`~eccjump.Region` (:func:`load`), a dataset or layout of one map as a Region
(:func:`to_region`).

The map layer reads and writes layouts of any kind (:mod:`eccjump.maps.store`); making a
Region of one is the classification's (:meth:`Region.from_layout
<eccjump.Region.from_layout>`), so that the map layer knows no kind. :func:`eccjump.maps.load`
reads a map file of either kind as its class.

Dataset layout
--------------
dims ``alpha`` [rad], ``chi``, ``km_frac`` (= k_m/(1 - χ)), preceded by ``mu_s``,
``theta0``, ``omega0`` for the ones swept; coordinates ``alpha_deg`` (on ``alpha``) and the
2-D ``km`` (on ``chi`` x ``km_frac``); one data variable per field of
:class:`~eccjump.JarmResult`. ``reason`` carries the CF ``flag_values``/``flag_meanings``;
the dataset attributes record how the map was made (``mu_s``, ``n`` with 0 meaning "the
first jump whatever its turn", ``rule``, ``method``, ``theta0``, ``omega0``, tolerances, the
``integrator``, ``eccjump_version``) and the Reason code table.
"""

from __future__ import annotations

import os
from collections.abc import Mapping
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump._base.arrays import fraction_axis, refuses_km
from eccjump._base.checks import file_error, real_array
from eccjump._base.docs import fill
from eccjump.classification.classify import Region, region
from eccjump.classification.fields import JARM
from eccjump.maps.layout import COORD_ATTRS, DIMS, Layout, layout_from_xarray, require
from eccjump.maps.store import read_layout

if TYPE_CHECKING:  # pragma: no cover
    import xarray as xr


#: Parameters that :func:`region_dataset` can sweep, in the order of their dimensions.
SWEEPABLE = ("mu_s", "theta0", "omega0")


@refuses_km
@fill
def region_dataset(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: float | ArrayLike,
    n: int | None = None,
    *,
    km: None = None,
    theta0: float | ArrayLike = 0.0,
    omega0: float | ArrayLike = 0.0,
    **kwargs: Any,
) -> xr.Dataset:
    """Map the JARM region as an ``xarray.Dataset``, sweeping ``mu_s``, ``theta0`` and
    ``omega0`` when they are 1-D sequences.

    One Rust grid call per combination of the swept values; the swept parameters become
    leading dimensions, in the order μ_s, theta0, omega0. Needs xarray
    (``pip install "eccjump[xarray]"``).

    Parameters
    ----------
    alpha : array_like of float, 1-D
        Ramp angles [rad], each in [0, π/2].
    chi : array_like of float, 1-D
        The bodies' d/R, each in [0, 1].
    km_frac : array_like of float, 1-D
        k_m/(1 - χ), each in [0, 1].
    mu_s : float or array_like of float
        Static friction coefficient(s), each in [0, inf); a 1-D sequence is swept.
    n : int or None, default None
        The turn on which the jump must happen (≥ 1), or None for the first jump.
    km : None
        Not accepted (the axis is ``km_frac``): passing it is a TypeError.
    theta0 : float or array_like of float, default 0.0
        Initial angle(s) [rad], |theta0| ≤ 2π 1e6; a 1-D sequence is swept.
    omega0 : float or array_like of float, default 0.0
        Initial angular velocity(ies) [√(g/R) rad], in [0, 1e6]; a 1-D sequence is swept.
    **kwargs
        The options of :func:`region`: ``method``, ``rule``, ``rtol``, ``atol``,
        ``max_turns``, ``refine_extrema``, ``stop_at_slip``, ``n_threads``, ``integrator``,
        ``derivatives`` (the ``d_*`` variables, with a trailing dimension ``wrt``) and
        ``chunks`` (a dask-backed, lazily computed dataset).

    Returns
    -------
    xarray.Dataset
        Dimensions (swept parameters..., α, χ, km_frac), one variable per result
        field with its units, the reasons as CF flags, the options as attributes.

    Raises
    ------
    ValueError
        For a swept value that is not a number or a non-empty 1-D sequence, or any bad
        argument of :func:`region`.
    %(type_error_km)s
    ImportError
        Without xarray.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> ds = eccjump.region_dataset(np.radians([35, 40, 45]), [0.1, 0.15], [0.0, 0.1],
    ...                             mu_s=[0.7, 1.0])
    >>> dict(ds.sizes)
    {'mu_s': 2, 'alpha': 3, 'chi': 2, 'km_frac': 2}
    """
    xarray = require("xarray")
    kwargs.pop("output", None)
    given = {"mu_s": mu_s, "theta0": theta0, "omega0": omega0}
    scalars: dict[str, float] = {}
    swept: dict[str, NDArray[np.float64]] = {}
    for name in SWEEPABLE:
        arr = real_array(name, given[name])
        if arr.ndim == 0:
            scalars[name] = float(arr)
        elif arr.ndim == 1 and arr.size:
            swept[name] = arr
        else:
            raise ValueError(f"{name} must be a number or a non-empty 1-D sequence")
    grid = {"alpha": alpha, "chi": chi, "km_frac": fraction_axis(km_frac)}
    options: dict[str, Any] = {**grid, **scalars, **kwargs}

    def one(values: Mapping[str, float]) -> xr.Dataset:
        return region(n=n, **{**options, **values}).to_xarray()

    if not swept:
        return one({})
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
                ds = ds.assign_coords({k: xarray.Variable((), here[k]) for k in names})
            parts.append(ds)
        return xarray.concat(
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


__all__ = ["SWEEPABLE", "load", "region_dataset", "to_region"]

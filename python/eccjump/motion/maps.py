"""Maps of the full motion: what the cylinder does at every point of a parameter grid.

:func:`motion_map` runs :func:`eccjump.simulate` to the first landing at every point of the
product of up to eight axes -- (α, χ, km fraction, μ_s, μ_k, restitution, theta0,
omega0) -- in parallel in the Rust core with the GIL released, and keeps a fixed-size
summary per point (:data:`FIELDS`). Each summary is exactly what ``simulate`` gives at that
point; maps are bit-identical for any thread count or dask chunking.

The sequence of modes is a compact code (2 bits per mode, the start's mode first, at most
:data:`SEQUENCE_LEN` modes): :func:`sequence_name` names any code, and
:meth:`MotionMap.sequences` tabulates those in a map with their counts.
"""

from __future__ import annotations

import dataclasses
import os
from collections.abc import Mapping
from dataclasses import dataclass, field
from pathlib import Path
from typing import TYPE_CHECKING, Any, ClassVar, Literal

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.arrays import fields_equal, fraction_axis, refuses_km
from eccjump._base.canvas import Plottable
from eccjump._base.checks import U64_MAX, Integrator, file_error, integer, real_array, short, text
from eccjump._base.docs import fill
from eccjump._base.html import best_slice, card, deg, jarm_slice, span
from eccjump._base.progress import Progress, checked, cut, grid_in_parts, reporting
from eccjump._base.sizes import check_fits, result_bytes
from eccjump._base.units import ramp_angles
from eccjump.maps import store
from eccjump.maps.dask import lazy_fields
from eccjump.maps.kinds import MapKind, upgrade_attrs
from eccjump.maps.layout import COORD_ATTRS, Layout
from eccjump.maps.map import Map
from eccjump.motion.fields import (
    DTYPES,
    FIELDS,
    INVALID,
    LANDINGS,
    MOTION,
    STATUS_NAMES,
    TABLE,
    cf_attrs,
    sequence_code,
    sequence_name,
)
from eccjump.motion.options import MotionOptions
from eccjump.motion.simulation import Rule

if TYPE_CHECKING:
    import xarray as xr

#: The axes of a map, in the order of the grid (C order: alpha slowest); ``km_frac`` is the
#: fraction k_m/(1 - chi), as in JARM maps.
AXES = tuple(a for a, _ in MOTION.axes)
#: Dimension name of each axis.
DIM_OF = dict(MOTION.axes)


@dataclass(frozen=True, eq=False)
class MotionMap(Map, Plottable, kind=MOTION):
    """A motion map: one array per summary field, with one dimension per swept axis.

    Made by :func:`motion_map`. Each field is also an attribute (``m.apex``, ``m.sequence``,
    ...). As every :class:`~eccjump.Map`: ``shape``, ``fraction()`` (the share of points
    that are a JARM) and ``to_xarray()``; :func:`eccjump.maps.save` writes it.

    Attributes
    ----------
    coords : dict of str to numpy.ndarray
        The swept axes (1-D, angles in rad), in the order ``alpha``, ``chi``,
        ``km_frac``, ``mu_s``, ``mu_k``, ``restitution``, ``theta0``, ``omega0``.
    scalars : dict of str to float or None
        The axes given as one value (``mu_k`` None: μ_k = μ_s).
    fields : dict of str to numpy.ndarray
        The summaries of the runs, each of the map's shape: ``status``, ``sequence`` (the
        first modes as a code, named by ``sequence_name``), ``n_modes``, ``jarm``,
        ``slipped_first``, ``slip_t`` [√(R/g)], ``slip_theta`` [rad],
        ``liftoff_reason``, ``liftoff_t`` [√(R/g)], ``liftoff_theta`` [rad],
        ``flight_time`` [√(R/g)], ``apex`` [R], ``distance`` [R], ``landing`` and
        ``energy_lost`` [M g R]; NaN or a fill code where a run never got there.
    options : dict of str to object
        The options shared by every point (rule, t_max, max_transitions, rtol, atol,
        max_steps, integrator).

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> m = eccjump.motion_map(np.radians([30, 40]), [0.15, 0.5], [0.02 / 0.85, 0.8], 1.0)
    >>> m.shape, list(m.coords)
    ((2, 2, 2), ['alpha', 'chi', 'km_frac'])
    >>> print(f"{np.degrees(m.liftoff_theta[1, 0, 0]):.6f} deg, apex {m.apex[1, 0, 0]:.6f} R")
    334.343838 deg, apex 0.006696 R
    """

    jarm_field: ClassVar[str] = "jarm"

    coords: dict[str, NDArray[np.float64]]
    scalars: dict[str, float | None]
    fields: dict[str, NDArray]
    options: dict[str, Any] = field(default_factory=dict)

    #: Field by field: coords, scalars, fields (by shape, dtype and values, NaN equal to NaN)
    #: and options; a map loaded from a file equals the map saved.
    __eq__ = fields_equal
    __hash__ = None  # type: ignore[assignment]

    def __getattr__(self, name: str) -> NDArray:
        fields = self.__dict__.get("fields", {})
        if name in fields:
            return fields[name]
        raise AttributeError(f"MotionMap has no attribute {name!r}")

    def sequences(self) -> dict[int, tuple[str, int]]:
        """Every sequence of modes in the map, most frequent first.

        Returns
        -------
        dict of int to tuple of (str, int)
            For each sequence code, its name (e.g. ``"ROLL→SLIP→FLIGHT→ROLL"``) and the
            number of points with it.

        Examples
        --------
        >>> import numpy as np
        >>> import eccjump
        >>> m = eccjump.motion_map(np.radians([30, 40]), [0.15, 0.5], [0.02 / 0.85, 0.8], 1.0)
        >>> [name for name, count in m.sequences().values()][:2]
        ['ROLL→SLIP→ROLL→SLIP→FLIGHT→SLIP', 'ROLL→SLIP→FLIGHT→ROLL']
        """
        codes, counts = np.unique(self.fields["sequence"], return_counts=True)
        order = np.argsort(-counts, kind="stable")
        return {int(codes[i]): (sequence_name(codes[i]), int(counts[i])) for i in order}

    def save(self, path: str | os.PathLike, *, overwrite: bool = False) -> Path:
        """Write the map to ``path`` (``.nc``, ``.zarr`` or ``.npz``) by :func:`eccjump.maps.save`,
        whose rules for what may be replaced hold; :func:`eccjump.load` reads it back."""
        return store.save(self, path, overwrite=overwrite)

    def to_layout(self) -> Layout:
        """The map as a layout (numpy only; dask arrays if lazy): one variable per field with
        CF attributes and flag tables (a lazy map's ``sequence`` codes are known once
        computed: ``sequence_name`` names them), the options as attributes."""
        dims = tuple(DIM_OF[k] for k in self.coords)
        seq = self.fields["sequence"]
        codes = np.unique(seq) if isinstance(seq, np.ndarray) else None
        return {
            "coords": {
                DIM_OF[k]: ((DIM_OF[k],), v, COORD_ATTRS[DIM_OF[k]]) for k, v in self.coords.items()
            },
            "data_vars": {f: (dims, self.fields[f], cf_attrs(f, codes)) for f in FIELDS},
            "attrs": self.attrs(),
        }

    @classmethod
    def from_layout(cls, lay: Layout, source: object) -> MotionMap:
        """The MotionMap of the layout ``lay`` of a valid motion map (``source``, the path it
        was read from, is not needed: every valid motion map is one)."""
        dims, attrs = lay["data_vars"][FIELDS[0]][0], lay["attrs"]
        axis_of = {d: a for a, d in DIM_OF.items()}
        coords = {axis_of[d]: np.asarray(lay["coords"][d][1], dtype=np.float64) for d in dims}
        scalars: dict[str, float | None] = {}
        for k in AXES:
            if k not in coords:
                # mu_k = mu_s (not given) is recorded as mu_s's value, or as "mu_s" if swept
                scalars[k] = None if attrs.get(k, "mu_s") == "mu_s" else float(attrs[k])
        fields = {k: np.asarray(lay["data_vars"][k][1], dtype=DTYPES[k]) for k in FIELDS}
        opts = {k: attrs[k] for k in OPTIONS if k in attrs}
        return cls(coords, scalars, fields, opts)

    def attrs(self) -> dict[str, Any]:
        """How the map was made, as netCDF-safe file attributes (``mu_k`` the text "μ_s"
        where it was not given: μ_k = μ_s, and ``scalars['mu_k']`` None once loaded)."""
        given: dict[str, Any] = {k: float(v) for k, v in self.scalars.items() if v is not None}
        if "mu_k" in self.scalars and self.scalars["mu_k"] is None:
            given["mu_k"] = "mu_s"
        return {
            "title": "motion map of an eccentric cylinder on a ramp (eccjump)",
            "kind": "motion",
            "eccjump_version": _core.VERSION,
            "units": "g = R = M = 1: angles in rad, times in sqrt(R/g), lengths in R",
            **given,
            **self.options,
        }

    def __repr__(self) -> str:
        dims = ", ".join(f"{k}: {v.size}" for k, v in self.coords.items()) or "one point"
        top = list(self.sequences().values())[:3]
        seq = ", ".join(f"{n or '-'} ({c})" for n, c in top)
        return f"MotionMap({dims}; {int(np.prod(self.shape))} points; {seq})"

    def _repr_html_(self) -> str:
        rows = [(k, span(v, " deg" if k == "alpha" else "")) for k, v in self.coords.items()]
        given = {k: v for k, v in self.scalars.items() if v is not None}
        rows += [(k, deg(v) if k == "alpha" else f"{v:g}") for k, v in given.items()]
        if isinstance(self.fields["sequence"], np.ndarray):
            rows.append(("JARM fraction", f"{self.fraction():.4g}"))
            for name, count in list(self.sequences().values())[:4]:
                rows.append((f"{count} points", name or "-"))
        picture = ""
        if tuple(self.coords)[:2] == ("alpha", "chi") and len(self.coords) <= 3:
            jarm = np.asarray(self.fields["jarm"], dtype=bool).reshape(*self.shape[:2], -1)
            _, cut = best_slice(jarm)
            picture = jarm_slice(cut, "JARM (green) over chi (across) and alpha (up)")
        return card(f"MotionMap ({int(np.prod(self.shape))} points)", rows, picture)

    _plot_doc = """The map in the (χ, α) plane, coloured by the sequence of modes, a few
    k_m slices (``eccjump.plot.sequence_map``). ``ax=``: only one slice (``km_frac=``),
    drawn into this matplotlib Axes and returned (``eccjump.plot.sequence_panel``), to
    compose figures; ``fig=``: the full figure in this empty Figure or SubFigure.
    ``kwargs`` go to the function drawn. Needs ``pip install eccjump[plot]``."""


#: The options shared by every point, recorded with a map.
OPTIONS = tuple(f.name for f in dataclasses.fields(MotionOptions))


def _axes(values: Mapping[str, object]) -> tuple[dict[str, NDArray], dict[str, float | None]]:
    coords: dict[str, NDArray] = {}
    scalars: dict[str, float | None] = {}
    for name in AXES:
        v = values[name]
        if name == "mu_k" and v is None:
            scalars[name] = None
            continue
        a = real_array(name, v)
        if a.ndim == 0:
            scalars[name] = float(a)
        elif a.ndim == 1 and a.size > 0:
            coords[name] = a
        else:
            raise ValueError(
                f"{name} must be a number or a non-empty 1-D array, got shape {a.shape}"
            )
    return coords, scalars


def _axis(coords: Mapping[str, NDArray], scalars: Mapping[str, float | None], name: str) -> NDArray:
    if name in coords:
        return coords[name]
    v = scalars[name]
    return np.empty(0) if v is None else np.array([v])


def _block(
    alpha: NDArray[np.float64], rest: tuple[NDArray, ...], opts: MotionOptions, n_threads: int
) -> dict[str, NDArray]:
    """One grid call of the core: the flat fields of α × the other axes."""
    a = np.array(alpha, dtype=np.float64, order="C").ravel()
    others = [np.array(x, dtype=np.float64, order="C").ravel() for x in rest]
    return _core.motion_grid(a, *others, options=opts.to_core(n_threads))


@refuses_km
@fill
def motion_map(
    alpha: ArrayLike,
    chi: ArrayLike,
    km_frac: ArrayLike,
    mu_s: ArrayLike,
    *,
    mu_k: ArrayLike | None = None,
    restitution: ArrayLike = 0.0,
    theta0: ArrayLike = 0.0,
    omega0: ArrayLike = 0.0,
    rule: Rule = "paper",
    t_max: float = 100.0,
    max_transitions: int = 100,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_steps: int = 1_000_000,
    n_threads: int = 0,
    integrator: Integrator = "RK45",
    chunks: int | None = None,
    output: Literal["map", "xarray"] = "map",
    km: None = None,
    progress: bool | Progress | None = None,
) -> MotionMap | xr.Dataset:
    """Map the full motion, to the first landing, over the product of the given axes.

    At every point of the grid, :func:`eccjump.simulate` runs to its first landing (status
    ``"landed"``, once the mode after it is chosen) or to ``t_max``/``max_transitions``, in
    parallel in the Rust core with the GIL released, and a fixed-size summary is kept. Each
    summary is exactly what ``simulate`` gives there; maps are bit-identical for any thread
    count or chunking. The grid first, then ``mu_s``, as :func:`region`, then keyword-only
    options. Each of the eight axes (``alpha``, ``chi``, ``km_frac``, ``mu_s``, ``mu_k``,
    ``restitution``, ``theta0``, ``omega0``) is one number or a 1-D array (an axis of the
    map). A point whose own values are invalid (μ_k > μ_s, km_frac 0, χ = 1, a value
    out of range) has status ``"invalid"`` and the fill values: the map goes on.

    Parameters
    ----------
    alpha : float or array_like of float
        Ramp angle(s) [rad], in [0, π/2] (``np.radians`` for degrees): one number out of
        it is a ValueError; values in (π/2, 90] (degrees?) give one UserWarning.
    chi : float or array_like of float
        The bodies' d/R, in [0, 1].
    km_frac : float or array_like of float
        The shell mass fraction as the share k_m/(1 - χ) of its largest value, in [0, 1]
        (> 0 for a valid run: ``simulate`` needs km > 0).
    mu_s : float or array_like of float
        Static friction coefficient(s), in [0, inf).
    mu_k : float, array_like of float or None, default None
        Kinetic friction coefficient(s), in [0, μ_s]; None: μ_k = μ_s.
    restitution : float or array_like of float, default 0.0
        Stronge's energetic coefficient of restitution, in [0, 1].
    theta0 : float or array_like of float, default 0.0
        Initial angle(s) [rad], |theta0| ≤ 2π 1e6.
    omega0 : float or array_like of float, default 0.0
        Initial angular velocity(ies) [√(g/R) rad], |omega0| ≤ 1e6.
    %(rule_rolling)s
    t_max : float, default 100.0
        End time of each run [√(R/g)], in (0, 1e6].
    max_transitions : int, default 100
        Transitions of each run after the start, 1 ... 10**6.
    rtol : float, default 1e-10
        Relative tolerance, in [1e-15, 1e-6] (recorded with the map).
    atol : float, default 1e-12
        Absolute tolerance, in [1e-300, 1e-6] (recorded with the map).
    max_steps : int, default 1_000_000
        Accepted steps of each run, 1 ... 10**7.
    %(n_threads)s
    integrator : {"RK45", "DOP853", "Vern9"}, default "RK45"
        The Runge–Kutta pair (recorded with the map). For speed pick ``"Vern9"`` (at the
        default rtol 1.5–1.9× faster than RK45 and about 15× more accurate); keep
        ``"RK45"`` for step-for-step parity with scipy.
    chunks : int or None, default None
        Alpha values per block (≥ 1): the map as a lazily computed, dask-backed
        ``xarray.Dataset``, one core call per block (``pip install "eccjump[dask]"``).
    output : {"map", "xarray"}, default "map"
        ``"map"``: a :class:`MotionMap`; ``"xarray"``: a labelled ``xarray.Dataset``.
    km : None
        Not accepted: ``km`` is the body's k_m elsewhere; the axis is ``km_frac``. Passing
        it is a TypeError.
    %(progress)s
        Not with ``chunks`` (a ValueError).

    Returns
    -------
    MotionMap or xarray.Dataset
        The summaries, one array per field over the swept axes.

    Raises
    ------
    ValueError
        For a bad shared option or a malformed axis, or an axis given as one number that
        makes every point invalid; the message names the parameter and its range.
    %(type_error_km)s
    MemoryError
        If the map does not fit in memory.
    KeyboardInterrupt
        On Ctrl-C (the work stops within a second).

    See Also
    --------
    simulate : one run, recorded in full.
    region : maps of the JARM classification alone (faster, by the closed forms).

    Examples
    --------
    The paper's JARM point (α = 40 deg, χ = 0.15, k_m = 0.02) and three others:

    >>> import numpy as np
    >>> import eccjump
    >>> from eccjump.motion.maps import sequence_name
    >>> m = eccjump.motion_map(np.radians([30, 40]), [0.15, 0.5], [0.02 / 0.85, 0.8], 1.0)
    >>> [sequence_name(c) for c in m.sequence[:, 0, 0]]
    ['ROLL→SLIP→FLIGHT→ROLL', 'ROLL→FLIGHT→SLIP']
    >>> bool(m.jarm[1, 0, 0]), m.fraction()
    (True, 0.125)
    """
    coords, scalars = _axes(
        {
            "alpha": ramp_angles("alpha", alpha),
            "chi": chi,
            "km_frac": fraction_axis(km_frac),
            "mu_s": mu_s,
            "mu_k": mu_k,
            "restitution": restitution,
            "theta0": theta0,
            "omega0": omega0,
        }
    )
    out = text("output", output)
    if out not in ("map", "xarray"):
        raise ValueError(f"output must be 'map' or 'xarray', got {out!r}")
    opts = MotionOptions(
        rule=rule,
        t_max=t_max,
        max_transitions=max_transitions,
        rtol=rtol,
        atol=atol,
        max_steps=max_steps,
        integrator=integrator,
    )
    opts.to_core(n_threads)  # the shared options checked first: a bad one is an error, not a map
    axis = {name: _axis(coords, scalars, name) for name in AXES}
    shape = tuple(c.size for c in coords.values())
    _check_scalars(scalars, opts, n_threads)
    if chunks is not None:
        if checked(progress):
            raise ValueError("progress needs chunks=None (dask reports a lazy map's progress)")
        return _lazy(axis, coords, scalars, opts, n_threads, shape, chunks)
    points = int(np.prod(shape, dtype=object))
    check_fits("motion_map", points, result_bytes(points, MOTION.bytes_per_point()), "the axes")
    grid = [axis[name] for name in AXES]  # mu_k empty for mu_k = mu_s: one value in the grid

    def part(ax: int, values: slice) -> dict[str, NDArray]:
        a, *others = cut(grid, ax, values)
        return _block(a, tuple(others), opts, n_threads)

    with reporting(progress) as report:
        flat = grid_in_parts(part, [max(a.size, 1) for a in grid], report)
    fields = {k: flat[k].reshape(shape) for k in FIELDS}
    m = MotionMap(coords, scalars, fields, opts.keywords())
    return m.to_xarray() if out == "xarray" else m


#: A point where every axis has a valid value, where each axis given as one number is tried.
_PROBE: dict[str, float | None] = {
    "alpha": 0.5,
    "chi": 0.3,
    "km_frac": 0.5,
    "mu_s": 1.0,
    "mu_k": None,
    "restitution": 0.0,
    "theta0": 0.0,
    "omega0": 0.0,
}


def _check_scalars(
    scalars: Mapping[str, float | None], opts: MotionOptions, n_threads: int
) -> None:
    """ValueError naming an axis given as one number that makes every point of the map
    invalid (NaN, out of range): as in :func:`eccjump.region`, a bad parameter is an error,
    not a map of invalid points. Each is tried alone at :data:`_PROBE` (a swept μ_s taken at
    least as large as μ_k), then all together (μ_k > μ_s). Bad values on a swept axis only
    mark their points invalid. The core alone knows the ranges, so it is asked."""
    given = {k: v for k, v in scalars.items() if v is not None}
    quick = dataclasses.replace(opts, t_max=min(opts.t_max, 1e-3))  # known at the start
    for name, value in given.items():
        if not _valid_point({name: value}, quick, n_threads):
            raise ValueError(
                f"{name} = {short(value)} is not allowed: every point of the map would be invalid"
            )
    if len(given) > 1 and not _valid_point(given, quick, n_threads):
        raise ValueError(
            f"{', '.join(given)}: these values make every point of the map invalid (mu_k > mu_s?)"
        )


def _valid_point(values: Mapping[str, float], opts: MotionOptions, n_threads: int) -> bool:
    """Whether the core runs the point of :data:`_PROBE` with ``values`` (not invalid)."""
    point = {**_PROBE, **values}
    mu_k = values.get("mu_k")
    if "mu_s" not in values and mu_k is not None and np.isfinite(mu_k):
        point["mu_s"] = max(1.0, mu_k)
    rest = tuple(np.empty(0) if point[k] is None else np.array([point[k]]) for k in AXES[1:])
    status = _block(np.array([point["alpha"]]), rest, opts, n_threads)["status"]
    return int(status[0]) != INVALID


def _lazy(
    axis: dict[str, NDArray],
    coords: dict[str, NDArray],
    scalars: dict[str, float | None],
    opts: MotionOptions,
    n_threads: int,
    shape: tuple[int, ...],
    chunks: object,
) -> xr.Dataset:
    """A dask-backed Dataset: one core call per block of ``chunks`` α values."""
    c = integer("chunks", chunks, 1, U64_MAX)
    same_mu = scalars.get("mu_k", 0.0) is None  # mu_k = mu_s: the core's empty mu_k axis
    axes = [np.zeros(1) if name == "mu_k" and same_mu else axis[name] for name in AXES]
    blocks = [
        min(c, a.size) if name == "alpha" else a.size for name, a in zip(AXES, axes, strict=True)
    ]
    lazy = lazy_fields(MOTION, _grid_block, axes, blocks, (opts, n_threads, same_mu))
    fields = {k: v.reshape(shape) for k, v in lazy.items()}
    return MotionMap(coords, scalars, fields, opts.keywords()).to_xarray()


def _grid_block(*args: Any) -> dict[str, NDArray]:
    """The grid call of :func:`_block` as :func:`eccjump.maps.dask.lazy_fields` makes it: the
    eight axes, the options, the threads and whether μ_k is μ_s (its axis then a placeholder)."""
    *axes, opts, n_threads, same_mu = args
    rest = tuple(
        np.empty(0) if same_mu and name == "mu_k" else a for name, a in zip(AXES, axes, strict=True)
    )
    return _block(axes[0], rest[1:], opts, n_threads)


def from_dataset(ds: xr.Dataset) -> MotionMap:
    """A :class:`MotionMap` from its Dataset (:meth:`MotionMap.to_xarray`, or a file of
    ``eccjump map --kind motion`` opened with :func:`eccjump.store.open_dataset`);
    ValueError naming ``ds`` if it is no valid motion map."""
    if not hasattr(type(ds), "data_vars"):
        raise TypeError(f"ds must be an xarray.Dataset, not {type(ds).__name__}")
    lay = store.layout_from_xarray(ds)
    upgrade_attrs(lay["attrs"])
    return _motion_map_of(lay, store.check_layout(lay, "ds"), "ds")


def _motion_map_of(lay: Layout, kind: MapKind, source: object) -> MotionMap:
    """The :class:`MotionMap` of a layout checked to be a map of ``kind``; ValueError naming
    ``source`` if it is a map of another kind."""
    if kind is not MOTION:
        raise file_error(
            source, f"is a {kind.words()}, not a motion map: load it with eccjump.maps.load"
        )
    return MotionMap.from_layout(lay, source)


def load(path: str | os.PathLike) -> MotionMap:
    """A motion map file (.nc, .zarr, .npz; .npz needs numpy only) as a :class:`MotionMap`.

    ValueError naming the path for a file that is no valid motion map (a JARM map:
    ``eccjump.maps.load``), as every loader of :mod:`eccjump.store`.
    """
    lay, kind = store.read_layout(path)
    return _motion_map_of(lay, kind, path)


__all__ = [
    "AXES",
    "FIELDS",
    "INVALID",
    "LANDINGS",
    "STATUS_NAMES",
    "TABLE",
    "MotionMap",
    "from_dataset",
    "motion_map",
    "sequence_code",
    "sequence_name",
]

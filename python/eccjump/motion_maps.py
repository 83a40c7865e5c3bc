"""Maps of the full motion: what the cylinder does at every point of a parameter grid.

:func:`motion_map` runs :func:`eccjump.simulate` to the first landing at every point of the
product of up to eight axes -- (alpha, chi, km fraction, mu_s, mu_k, restitution, theta0,
omega0) -- in parallel in the Rust core with the GIL released, and keeps a fixed-size
summary per point (:data:`FIELDS`). Each summary is exactly what ``simulate`` gives at that
point; maps are bit-identical for any thread count or dask chunking.

The sequence of modes is a compact code (2 bits per mode, the start's mode first, at most
:data:`SEQUENCE_LEN` modes): :func:`sequence_name` names any code, and
:meth:`MotionMap.sequences` tabulates those in a map with their counts.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from dataclasses import dataclass, field
from typing import TYPE_CHECKING, Any, Literal, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._checks import U64_MAX, integer, real_array, text
from eccjump.motion import MODES, REASONS, STATUSES, Rule

if TYPE_CHECKING:
    import xarray as xr

#: The axes of a map, in the order of the grid (C order: alpha slowest).
AXES = ("alpha", "chi", "km", "mu_s", "mu_k", "restitution", "theta0", "omega0")
#: Modes kept in the sequence code.
SEQUENCE_LEN = 8
#: ``status`` of a point with invalid parameters (mu_k > mu_s, a value out of range).
INVALID = 255
#: How the first landing ended, by code.
LANDINGS: tuple[str, ...] = tuple(name for _, name in sorted(_core.landing_codes()))
#: ``status`` names by code (:data:`INVALID` is "invalid").
STATUS_NAMES: dict[int, str] = {**dict(enumerate(STATUSES)), INVALID: "invalid"}


class Field(NamedTuple):
    """One summary field: name, numpy dtype, units, meaning, value where not computed."""

    name: str
    dtype: np.dtype
    units: str
    description: str
    fill: Any


_B, _U8, _U16, _F = (np.dtype(t) for t in (np.bool_, np.uint8, np.uint16, np.float64))
_T = "sqrt(R/g)"
#: Every summary field, in the order of the bridge.
TABLE: tuple[Field, ...] = (
    Field("status", _U8, "1", "how the run ended (STATUS_NAMES; landed: at its first landing)", 0),
    Field("sequence", _U16, "1", "the first modes as a code (sequence_name)", 0),
    Field("n_modes", _U16, "1", "modes in the run, the start's included", 0),
    Field("jarm", _B, "1", "lift-off straight out of pure rolling from the start", False),
    Field("slipped_first", _B, "1", "a slip came before the first flight", False),
    Field("slip_t", _F, _T, "time of the first slip onset (NaN: none)", math.nan),
    Field("slip_theta", _F, "rad", "angle of the first slip onset (NaN: none)", math.nan),
    Field("liftoff_reason", _U8, "1", "why the first flight began (REASONS; 255: none)", 255),
    Field("liftoff_t", _F, _T, "time of the first lift-off (NaN: none)", math.nan),
    Field("liftoff_theta", _F, "rad", "angle of the first lift-off (NaN: none)", math.nan),
    Field("flight_time", _F, _T, "duration of the first flight (NaN: did not land)", math.nan),
    Field("apex", _F, "R", "largest height of the first flight above contact", math.nan),
    Field("distance", _F, "R", "distance down the ramp covered by the first flight", math.nan),
    Field("landing", _U8, "1", "how the first landing ended (LANDINGS)", 0),
    Field("energy_lost", _F, "M g R", "energy dissipated by sliding and impacts", math.nan),
)
#: Field names, in the order of the bridge.
FIELDS: tuple[str, ...] = tuple(f.name for f in TABLE)


def sequence_name(code: int) -> str:
    """The modes of a sequence code, e.g. ``"ROLL→SLIP→FLIGHT"`` ("" for 0)."""
    names = []
    code = int(code)
    while code:
        names.append(MODES[(code & 3) - 1])
        code >>= 2
    return "→".join(names)


def sequence_code(modes: list[str] | tuple[str, ...]) -> int:
    """The code of the first :data:`SEQUENCE_LEN` of ``modes`` (names from :data:`MODES`)."""
    return sum((MODES.index(m) + 1) << (2 * i) for i, m in enumerate(modes[:SEQUENCE_LEN]))


@dataclass(frozen=True, eq=False)
class MotionMap:
    """A motion map: one array per summary field, with one dimension per swept axis.

    ``coords`` holds the swept axes (1-D, in :data:`AXES` order; ``km`` as the fraction
    k_m/(1 - chi)), ``scalars`` the axes given as one value (``mu_k`` None: mu_k = mu_s),
    ``fields`` the summaries (see :data:`TABLE`), ``options`` the shared options.
    """

    coords: dict[str, NDArray[np.float64]]
    scalars: dict[str, float | None]
    fields: dict[str, NDArray]
    options: dict[str, Any] = field(default_factory=dict)

    def __getattr__(self, name: str) -> NDArray:
        fields = self.__dict__.get("fields", {})
        if name in fields:
            return fields[name]
        raise AttributeError(f"MotionMap has no attribute {name!r}")

    @property
    def shape(self) -> tuple[int, ...]:
        return tuple(c.size for c in self.coords.values())

    def sequences(self) -> dict[int, tuple[str, int]]:
        """Every sequence code in the map: (name, number of points), most frequent first."""
        codes, counts = np.unique(self.fields["sequence"], return_counts=True)
        order = np.argsort(-counts, kind="stable")
        return {int(codes[i]): (sequence_name(codes[i]), int(counts[i])) for i in order}

    def to_xarray(self) -> xr.Dataset:
        """The map as a labelled xarray Dataset (CF attributes, flag tables)."""
        import xarray as xr

        dims = tuple(self.coords)
        data = {}
        for f in TABLE:
            attrs: dict[str, Any] = {"units": f.units, "long_name": f.description}
            if f.name == "sequence" and isinstance(self.fields[f.name], np.ndarray):
                # (a lazy map's codes are known once computed: sequence_name names them)
                table = self.sequences()
                attrs["flag_values"] = np.array(list(table), dtype=f.dtype)
                attrs["flag_meanings"] = " ".join(
                    name.replace("→", "_") or "none" for name, _ in table.values()
                )
            elif f.name == "status":
                attrs["flag_values"] = np.array(list(STATUS_NAMES), dtype=f.dtype)
                attrs["flag_meanings"] = " ".join(STATUS_NAMES.values())
            elif f.name == "landing":
                attrs["flag_values"] = np.arange(len(LANDINGS), dtype=f.dtype)
                attrs["flag_meanings"] = " ".join(LANDINGS)
            elif f.name == "liftoff_reason":
                attrs["flag_values"] = np.arange(len(REASONS), dtype=f.dtype)
                attrs["flag_meanings"] = " ".join(REASONS)
            data[f.name] = (dims, self.fields[f.name], attrs)
        coords = {k: (k, v) for k, v in self.coords.items()}
        attrs = {
            "title": "motion map of an eccentric cylinder on a ramp (eccjump)",
            "eccjump_version": _core.VERSION,
            "km_meaning": "km is the fraction k_m/(1 - chi)",
            "units": "g = R = M = 1: angles in rad, times in sqrt(R/g), lengths in R",
            **{k: ("mu_s" if v is None else float(v)) for k, v in self.scalars.items()},
            **{k: v for k, v in self.options.items()},
        }
        return xr.Dataset(data, coords=coords, attrs=attrs)

    def __repr__(self) -> str:
        dims = ", ".join(f"{k}: {v.size}" for k, v in self.coords.items()) or "one point"
        top = list(self.sequences().values())[:3]
        seq = ", ".join(f"{n or '-'} ({c})" for n, c in top)
        return f"MotionMap({dims}; {int(np.prod(self.shape))} points; {seq})"


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
    alpha: NDArray[np.float64], rest: tuple[NDArray, ...], opts: dict[str, Any]
) -> dict[str, NDArray]:
    """One grid call of the core: the flat fields of alpha × the other axes."""
    a = np.array(alpha, dtype=np.float64, order="C").ravel()
    others = [np.array(x, dtype=np.float64, order="C").ravel() for x in rest]
    return _core.motion_grid(a, *others, **opts)


def motion_map(
    *,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    mu_s: ArrayLike,
    mu_k: ArrayLike | None = None,
    restitution: ArrayLike = 0.0,
    theta0: ArrayLike = 0.0,
    omega0: ArrayLike = 0.0,
    rule: Rule = "paper",
    t_max: float = 100.0,
    max_transitions: int = 50,
    rtol: float = 1e-10,
    atol: float = 1e-12,
    max_steps: int = 1_000_000,
    n_threads: int = 0,
    chunks: int | None = None,
    output: Literal["map", "xarray"] = "map",
) -> MotionMap | xr.Dataset:
    """Map the full motion, to the first landing, over the product of the given axes.

    Each of ``alpha`` [rad], ``chi``, ``km`` (the fraction k_m/(1 - chi) in [0, 1], so every
    grid point is a valid body), ``mu_s``, ``mu_k`` (None: mu_k = mu_s), ``restitution``,
    ``theta0`` and ``omega0`` is one number or a 1-D array (an axis of the map). The other
    options are those of :func:`eccjump.simulate`; a run ends at its first landing (status
    "landed") once the mode after it is chosen, or at ``t_max``/``max_transitions``. A
    point with invalid values (mu_k > mu_s, km fraction 0, ...) has status "invalid".

    ``chunks`` (needs dask): the map as a lazily computed, dask-backed xarray Dataset, one
    core call per block of ``chunks`` alpha values. ``output="xarray"``: a labelled Dataset.

    Raises ValueError naming the parameter for a bad shared option or a malformed axis;
    Ctrl-C raises KeyboardInterrupt (the work stops within a second).
    """
    coords, scalars = _axes(
        {
            "alpha": alpha,
            "chi": chi,
            "km": km,
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
    opts = {
        "rule": text("rule", rule),
        "t_max": float(real_array("t_max", t_max)),
        "max_transitions": integer("max_transitions", max_transitions, 1, U64_MAX),
        "rtol": float(real_array("rtol", rtol)),
        "atol": float(real_array("atol", atol)),
        "max_steps": integer("max_steps", max_steps, 1, U64_MAX),
        "n_threads": integer("n_threads", n_threads, 0, 256),
    }
    axis = {name: _axis(coords, scalars, name) for name in AXES}
    rest = tuple(axis[name] for name in AXES[1:])
    shape = tuple(c.size for c in coords.values())
    info = {k: v for k, v in opts.items() if k != "n_threads"}
    # The shared options checked on one point first: a bad one is an error, not a map.
    _block(axis["alpha"][:1], tuple(a[:1] for a in rest), opts)
    if chunks is not None:
        return _lazy(axis, rest, coords, scalars, info, opts, shape, chunks)
    flat = _block(axis["alpha"], rest, opts)
    fields = {k: flat[k].reshape(shape) for k in FIELDS}
    m = MotionMap(coords, scalars, fields, info)
    return m.to_xarray() if out == "xarray" else m


def _lazy(
    axis: dict[str, NDArray],
    rest: tuple[NDArray, ...],
    coords: dict[str, NDArray],
    scalars: dict[str, float | None],
    info: dict[str, Any],
    opts: dict[str, Any],
    shape: tuple[int, ...],
    chunks: object,
) -> xr.Dataset:
    """A dask-backed Dataset: one core call per block of alpha values."""
    from eccjump.scale import require_dask

    da = require_dask()
    import dask

    c = integer("chunks", chunks, 1, U64_MAX)
    alpha = axis["alpha"]
    inner = tuple(s for name, s in zip(AXES, shape_of(axis), strict=True) if name != "alpha")
    pieces: dict[str, list[Any]] = {k: [] for k in FIELDS}
    for i0 in range(0, alpha.size, c):
        part = dask.delayed(_block)(alpha[i0 : i0 + c], rest, opts)
        n = min(c, alpha.size - i0)
        for f in TABLE:
            arr = da.from_delayed(part[f.name], shape=(n * int(np.prod(inner)),), dtype=f.dtype)
            pieces[f.name].append(arr.reshape((n, *inner)))
    fields = {k: da.concatenate(v, axis=0).reshape(shape) for k, v in pieces.items()}
    return MotionMap(coords, scalars, fields, info).to_xarray()


def shape_of(axis: Mapping[str, NDArray]) -> tuple[int, ...]:
    """Lengths of the eight grid axes (mu_k empty counts 1)."""
    return tuple(max(axis[name].size, 1) for name in AXES)


def from_dataset(ds: xr.Dataset) -> MotionMap:
    """A computed :class:`MotionMap` from a Dataset of :meth:`MotionMap.to_xarray` (or a
    lazy one, computed here)."""
    coords = {k: np.asarray(ds[k].values) for k in ds.dims}
    scalars = {
        k: (None if ds.attrs.get(k) == "mu_s" else ds.attrs.get(k)) for k in AXES if k not in coords
    }
    fields = {k: np.asarray(ds[k].values) for k in FIELDS}
    opts = {
        k: ds.attrs[k]
        for k in ("rule", "t_max", "max_transitions", "rtol", "atol", "max_steps")
        if k in ds.attrs
    }
    return MotionMap(coords, scalars, fields, opts)


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

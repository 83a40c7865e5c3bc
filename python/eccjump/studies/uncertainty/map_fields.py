"""The one description of the fields of an uncertainty map (:func:`eccjump.uncertainty_map`):
P(JARM) with its Wilson interval, the valid samples, and the share of each other outcome
(a :class:`~eccjump.Reason` of the closed form), per grid point. The map kind
:data:`UNCERTAINTY` (:class:`~eccjump.maps.kinds.MapKind`) is how the files of
:mod:`eccjump.maps.store`, their checks and ``eccjump map --kind uncertainty`` know it.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump.classification.fields import Field, Reason
from eccjump.maps.kinds import MapKind, register
from eccjump.studies.uncertainty.delta import Status

#: The outcomes other than a JARM whose shares a map holds: every verdict the closed form
#: gives without ``stop_at_slip`` (INVALID_PARAMS is no outcome: such a sample counts in no
#: share; SOLVER_FAILED and SLIP need the integrator or ``stop_at_slip``).
OUTCOMES: tuple[Reason, ...] = (
    Reason.NO_ROOT,
    Reason.LIFTOFF_EARLIER,
    Reason.NORMAL_FORCE_LOST,
    Reason.SLIP_BEFORE,
    Reason.SLIP_AT_JUMP,
    Reason.ROCKS_BACK,
    Reason.TURN_LIMIT,
)

_F64, _U32, _U8 = np.dtype(np.float64), np.dtype(np.uint32), np.dtype(np.uint8)
_SHARE = (0.0, 1.0)

#: Every field, in order. A point not computed, or without a valid sample, has n_valid 0 and
#: NaN shares.
TABLE: tuple[Field, ...] = (
    Field("p_jarm", _F64, "1", "probability of a JARM under the tolerances", math.nan, _SHARE),
    Field("p_jarm_low", _F64, "1", "lower end of its Wilson interval", math.nan, _SHARE),
    Field("p_jarm_high", _F64, "1", "upper end of its Wilson interval", math.nan, _SHARE),
    Field("n_valid", _U32, "1", "samples in the physical range (the shares' denominator)", 0),
    *(
        Field(f"p_{r.name.lower()}", _F64, "1", f"share of outcome {r.name}", math.nan, _SHARE)
        for r in OUTCOMES
    ),
)
FIELDS: tuple[str, ...] = tuple(f.name for f in TABLE)
BY_NAME: dict[str, Field] = {f.name: f for f in TABLE}
DTYPES: dict[str, np.dtype] = {f.name: f.dtype for f in TABLE}
FILL: dict[str, Any] = {f.name: f.fill for f in TABLE}
VALID: dict[str, tuple[float, float]] = {f.name: f.valid for f in TABLE if f.dtype.kind == "f"}
#: The contours drawn on P(JARM) (``.plot()`` and the explorer): an even chance and the 95 %
#: design target.
PROBABILITY_LEVELS = (0.5, 0.95)
#: The share field of each outcome.
SHARE_OF: dict[Reason, str] = {r: f"p_{r.name.lower()}" for r in OUTCOMES}


def cf_attrs(name: str) -> dict[str, Any]:
    """CF attributes of field ``name``."""
    f = BY_NAME[name]
    return {"units": f.units, "long_name": f.description}


def _interval_holds(values: Mapping[str, NDArray]) -> str | None:
    """What is wrong beyond the tables: P(JARM) must lie in its interval."""
    p, lo, hi = (np.asarray(values[k], dtype=np.float64) for k in FIELDS[:3])
    with np.errstate(invalid="ignore"):
        bad = (lo > p) | (p > hi)
    if bad.any():
        return "p_jarm lies outside [p_jarm_low, p_jarm_high]"
    return None


def _grid_kind(
    name: str, fields: Any, dtypes: Any, fill: Any, cf_attrs: Any, codes: Any, **kwargs: Any
) -> MapKind:
    """A registered map kind over the region grid (``alpha``, ``chi``, ``km_frac``) that
    keeps the uncertainty maps' settings (μ_s, n, seed, confidence, rule); the rest as
    :class:`~eccjump.maps.kinds.MapKind` takes it."""
    return register(
        MapKind(
            name,
            fields,
            dtypes,
            fill,
            cf_attrs,
            ("mu_s", "n", "seed", "confidence", "rule"),
            (("mu_s", "mu_s"), ("alpha", "alpha"), ("chi", "chi"), ("km_frac", "km_frac")),
            ("alpha", "chi", "km_frac"),
            codes,
            **kwargs,
        )
    )


#: The uncertainty map (:func:`eccjump.uncertainty_map`, ``eccjump map --kind uncertainty``)
#: as a kind of map file, on alpha x chi x km_frac.
UNCERTAINTY = _grid_kind(
    "uncertainty",
    FIELDS,
    DTYPES,
    FILL,
    cf_attrs,
    {},
    valid=VALID,
    invalid=("n_valid", frozenset([0])),
    agree=tuple(("n_valid", k, True) for k in FIELDS if k != "n_valid"),
    validator=_interval_holds,
    title="uncertainty",
)


#: The first flight's quantities a motion map summarises per grid point (of
#: ``Uncertainty.distributions``, with their units), each by its median and its 2.5 % and
#: 97.5 % quantiles among the valid samples that have it: the lift-off's time, the flight's
#: duration and the distance down the ramp it covers.
MOTION_QUANTITIES: dict[str, str] = {
    "liftoff_t": "sqrt(R/g)",
    "flight_time": "sqrt(R/g)",
    "distance": "R",
}
#: The unit and physical range of each (times: as a motion map's; a distance: any finite).
_QUANTITY_RANGES = {
    q: (u, (0.0, 1e6) if u == "sqrt(R/g)" else (-sys.float_info.max, sys.float_info.max))
    for q, u in MOTION_QUANTITIES.items()
}
#: The quantiles of each quantity, as fields ``<quantity>_<statistic>`` (names of
#: :class:`.results.Summary`).
MOTION_STATISTICS = ("median", "q025", "q975")

#: The fields of a map of the full motion (``uncertainty_map(question="motion")``): P(JARM)
#: of the full motion (a lift-off straight out of pure rolling), its interval, the valid
#: samples, the shares that fly and that slip before their first flight, and the quantiles
#: of :data:`MOTION_QUANTITIES` (NaN where no valid sample has the quantity).
MOTION_TABLE: tuple[Field, ...] = (
    *TABLE[:4],
    Field("p_flies", _F64, "1", "share of samples that lift off", math.nan, _SHARE),
    Field(
        "p_slipped_first", _F64, "1", "share that slip before the first flight", math.nan, _SHARE
    ),
    *(
        Field(f"{q}_{s}", _F64, unit, f"{s} of {q} of the first flight", math.nan, valid)
        for q, (unit, valid) in _QUANTITY_RANGES.items()
        for s in MOTION_STATISTICS
    ),
)
MOTION_FIELDS: tuple[str, ...] = tuple(f.name for f in MOTION_TABLE)
_MOTION_BY_NAME: dict[str, Field] = {f.name: f for f in MOTION_TABLE}


def _motion_cf_attrs(name: str) -> dict[str, Any]:
    f = _MOTION_BY_NAME[name]
    return {"units": f.units, "long_name": f.description}


#: P(JARM) and the first flight under tolerances (``uncertainty_map(question="motion")``)
#: as a kind of map file: the shares are NaN exactly where no sample is valid; a quantile may
#: be NaN anywhere (no valid sample flew there).
UNCERTAINTY_MOTION = _grid_kind(
    "uncertainty_motion",
    MOTION_FIELDS,
    {f.name: f.dtype for f in MOTION_TABLE},
    {f.name: f.fill for f in MOTION_TABLE},
    _motion_cf_attrs,
    {},
    valid={f.name: f.valid for f in MOTION_TABLE if f.dtype.kind == "f"},
    invalid=("n_valid", frozenset([0])),
    agree=tuple(("n_valid", k, True) for k in MOTION_FIELDS[:6] if k != "n_valid"),
    validator=_interval_holds,
    title="uncertainty (full motion)",
)

#: The fields of a first-order map (``uncertainty_map(..., method="delta")``): P(JARM) and the
#: spread of θ_J from the derivatives at each nominal point, NaN where the linearisation
#: fails there, and why (:class:`.delta.Status`; a number only where it is ESTIMATE, or
#: REACHES: given, but the tolerances reach another verdict).
DELTA_TABLE: tuple[Field, ...] = (
    Field("p_jarm", _F64, "1", "first-order P(JARM) (NaN: see delta_status)", math.nan, _SHARE),
    Field(
        "theta_J_sd",
        _F64,
        "rad",
        "first-order standard deviation of the lift-off angle",
        math.nan,
        (0.0, sys.float_info.max),
    ),
    Field("delta_status", _U8, "1", "0 an estimate, 6 a doubtful one, else why none", 5),
)
DELTA_FIELDS: tuple[str, ...] = tuple(f.name for f in DELTA_TABLE)
#: The statuses with a first-order P(JARM).
GIVEN = (int(Status.ESTIMATE), int(Status.REACHES))
_DELTA_BY_NAME: dict[str, Field] = {f.name: f for f in DELTA_TABLE}


def _delta_cf_attrs(name: str) -> dict[str, Any]:
    f = _DELTA_BY_NAME[name]
    return {"units": f.units, "long_name": f.description}


def _estimate_agrees(values: Mapping[str, NDArray]) -> str | None:
    """P(JARM) is a number exactly where the status says ESTIMATE or REACHES."""
    has = np.isin(np.asarray(values["delta_status"]), GIVEN)
    if (has != ~np.isnan(np.asarray(values["p_jarm"], dtype=np.float64))).any():
        return "p_jarm disagrees with delta_status (a number exactly where it is 0 or 6)"
    return None


#: The first-order P(JARM) over a grid as a kind of map file.
UNCERTAINTY_DELTA = _grid_kind(
    "uncertainty_delta",
    DELTA_FIELDS,
    {f.name: f.dtype for f in DELTA_TABLE},
    {f.name: f.fill for f in DELTA_TABLE},
    _delta_cf_attrs,
    {"delta_status": frozenset(int(s) for s in Status)},
    valid={f.name: f.valid for f in DELTA_TABLE if f.dtype.kind == "f"},
    invalid=("delta_status", frozenset([int(Status.INVALID)])),
    validator=_estimate_agrees,
    title="first-order uncertainty",
)

__all__ = [
    "BY_NAME",
    "DELTA_FIELDS",
    "DELTA_TABLE",
    "DTYPES",
    "FIELDS",
    "FILL",
    "MOTION_FIELDS",
    "MOTION_QUANTITIES",
    "MOTION_STATISTICS",
    "MOTION_TABLE",
    "OUTCOMES",
    "SHARE_OF",
    "TABLE",
    "UNCERTAINTY",
    "UNCERTAINTY_DELTA",
    "UNCERTAINTY_MOTION",
]

"""The one description of the fields of an uncertainty map (:func:`eccjump.uncertainty_map`):
P(JARM) with its Wilson interval, the valid samples, and the share of each other outcome
(a :class:`~eccjump.Reason` of the closed form), per grid point. The map kind
:data:`UNCERTAINTY` (:class:`~eccjump.maps.kinds.MapKind`) is how the files of
:mod:`eccjump.maps.store`, their checks and ``eccjump map --kind uncertainty`` know it.
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump.classification.fields import Field, Reason
from eccjump.maps.kinds import MapKind, register

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

_F64, _U32 = np.dtype(np.float64), np.dtype(np.uint32)
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


#: The uncertainty map (:func:`eccjump.uncertainty_map`, ``eccjump map --kind uncertainty``)
#: as a kind of map file, on alpha x chi x km_frac.
UNCERTAINTY = register(
    MapKind(
        "uncertainty",
        FIELDS,
        DTYPES,
        FILL,
        cf_attrs,
        ("mu_s", "n", "seed", "confidence", "rule"),
        (("mu_s", "mu_s"), ("alpha", "alpha"), ("chi", "chi"), ("km_frac", "km_frac")),
        ("alpha", "chi", "km_frac"),
        {},
        valid=VALID,
        invalid=("n_valid", frozenset([0])),
        agree=tuple(("n_valid", k, True) for k in FIELDS if k != "n_valid"),
        validator=_interval_holds,
        title="uncertainty",
    )
)

__all__ = ["BY_NAME", "DTYPES", "FIELDS", "FILL", "OUTCOMES", "SHARE_OF", "TABLE", "UNCERTAINTY"]

"""The one description of the fields of a motion map (:func:`eccjump.motion_map`).

Each field of a point's summary is described ONCE here -- name, numpy dtype, units, meaning,
fill value of a point not computed -- and the :class:`~eccjump.MotionMap`, its xarray and CF
attributes, the files of :mod:`eccjump.store` and ``eccjump map --kind motion`` derive from
this table, through the map kind :data:`MOTION` (:class:`~eccjump.maps.kinds.MapKind`). Also
the codes of the sequence of modes, the statuses and the landing outcomes, read from the core's
tables.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._base.checks import integer
from eccjump.classification.fields import ROUNDING, Field
from eccjump.maps.kinds import MapKind, register


def _names(codes: list[tuple[int, str]]) -> tuple[str, ...]:
    """The names of one of the core's code tables, by code (0, 1, ...)."""
    return tuple(name for _, name in sorted(codes))


#: Mode names by code (the core's; :data:`eccjump.motion.MODES` names them too).
MODES = _names(_core.mode_codes())
#: Why a mode began, by code: the ``liftoff_reason`` codes (the core's).
REASONS = _names(_core.transition_reason_codes())
#: How a run ended, by code (the core's).
STATUSES = _names(_core.status_codes())

#: Modes kept in the sequence code (the core's).
SEQUENCE_LEN: int = _core.SEQUENCE_LEN
#: ``status`` of a point with invalid parameters (mu_k > mu_s, a value out of range): the
#: core's.
INVALID: int = _core.INVALID
#: How the first landing ended, by code.
LANDINGS: tuple[str, ...] = _names(_core.landing_codes())
#: ``status`` names by code (:data:`INVALID` is "invalid").
STATUS_NAMES: dict[int, str] = {**dict(enumerate(STATUSES)), INVALID: "invalid"}


_B, _U8, _U16, _F = (np.dtype(t) for t in (np.bool_, np.uint8, np.uint16, np.float64))
_T = "sqrt(R/g)"
#: Times of a run: t_max is at most 10^6.
_TIMES = (0.0, 1e6)
#: Energy dissipated: never negative, less the rounding of the energy balance of fast runs.
_LOST = (-1e-3, sys.float_info.max)
#: Every summary field, in the order of the bridge. A point not computed has status
#: :data:`INVALID` and the fill values.
TABLE: tuple[Field, ...] = (
    Field("status", _U8, "1", "how the run ended (landed: at its first landing)", INVALID),
    Field("sequence", _U16, "1", "the first modes as a code (sequence_name)", 0),
    Field("n_modes", _U16, "1", "modes in the run, the start's included", 0),
    Field("jarm", _B, "1", "lift-off straight out of pure rolling from the start", False),
    Field("slipped_first", _B, "1", "a slip came before the first flight", False),
    Field("slip_t", _F, _T, "time of the first slip onset (NaN: none)", math.nan, _TIMES),
    Field("slip_theta", _F, "rad", "angle of the first slip onset (NaN: none)", math.nan),
    Field("liftoff_reason", _U8, "1", "why the first flight began (255: none)", 255),
    Field("liftoff_t", _F, _T, "time of the first lift-off (NaN: none)", math.nan, _TIMES),
    Field("liftoff_theta", _F, "rad", "angle of the first lift-off (NaN: none)", math.nan),
    Field(
        "flight_time",
        _F,
        _T,
        "duration of the first flight (NaN: did not land)",
        math.nan,
        _TIMES,
    ),
    Field(
        "apex",
        _F,
        "R",
        "largest height of the first flight above contact",
        math.nan,
        (-ROUNDING, sys.float_info.max),
    ),
    Field("distance", _F, "R", "distance down the ramp covered by the first flight", math.nan),
    Field("landing", _U8, "1", "how the first landing ended", 0),
    Field("energy_lost", _F, "M g R", "energy dissipated by sliding and impacts", math.nan, _LOST),
)
#: Field names, in the order of the bridge.
FIELDS: tuple[str, ...] = tuple(f.name for f in TABLE)
#: Field by name.
BY_NAME: dict[str, Field] = {f.name: f for f in TABLE}
#: numpy dtype of each field.
DTYPES: dict[str, np.dtype] = {f.name: f.dtype for f in TABLE}
#: Value of each field where a point was not computed.
FILL: dict[str, Any] = {f.name: f.fill for f in TABLE}
#: The physical range of each float field, NaN aside.
VALID: dict[str, tuple[float, float]] = {f.name: f.valid for f in TABLE if f.dtype.kind == "f"}


#: The largest sequence code: :data:`SEQUENCE_LEN` modes of 2 bits (the field's uint16).
SEQUENCE_MAX = 4**SEQUENCE_LEN - 1


def sequence_name(code: int) -> str:
    """The modes of a sequence code, e.g. ``"ROLL→SLIP→FLIGHT"`` ("" for 0). ``code``: an int
    (or numpy integer) in [0, :data:`SEQUENCE_MAX`] made by :func:`sequence_code`; anything
    else is a TypeError or ValueError naming ``code``."""
    rest = integer("code", code, 0, SEQUENCE_MAX)
    names = []
    while rest:
        mode = rest & 3
        if mode == 0:  # a gap before a later mode: no sequence_code gives this
            raise ValueError(f"code = {code} is not a sequence code (a mode of 2 bits is 0)")
        names.append(MODES[mode - 1])
        rest >>= 2
    return "→".join(names)


def sequence_code(modes: list[str] | tuple[str, ...]) -> int:
    """The code of the first :data:`SEQUENCE_LEN` of ``modes`` (names from :data:`MODES`):
    Σ (mode_i + 1)·4^i, so ROLL→FLIGHT is 13. ValueError naming a mode not in MODES.

    The core computes it (its own formula, so this is the code a motion map stores); MODES
    is read from the core's table, so a mode's index in it is its code in the core."""
    if isinstance(modes, str) or not isinstance(modes, list | tuple):
        raise TypeError(f"modes must be a list or tuple of mode names, not {type(modes).__name__}")
    for m in modes:
        if m not in MODES:
            shown = repr(m) if len(repr(m)) <= 40 else repr(m)[:37] + "..."
            raise ValueError(f"modes: {shown} is not a mode; use {', '.join(MODES)}")
    return _core.sequence_code([MODES.index(m) for m in modes[:SEQUENCE_LEN]])


def _reads_the_cores_codes() -> bool:
    """Whether :func:`sequence_name` reads back the code the core gives every mode."""
    modes = [*MODES, MODES[0]]
    try:
        return sequence_name(sequence_code(modes)) == "→".join(modes)
    except ValueError:  # a code of another packing
        return False


# A build that packs the codes otherwise is refused at import: a map's sequences would all
# be misnamed.
if not _reads_the_cores_codes():
    raise ImportError("eccjump.motion.fields: sequence_name cannot read the core's codes: rebuild")


def _flags(values: Any, names: Any) -> dict[str, Any]:
    return {"flag_values": np.asarray(values), "flag_meanings": " ".join(names)}


def cf_attrs(name: str, sequences: Any = None) -> dict[str, Any]:
    """CF attributes of field ``name``: units, long_name and the flag tables of the coded
    fields (for ``sequence``, of the codes in ``sequences`` when given)."""
    f = BY_NAME[name]
    attrs: dict[str, Any] = {"units": f.units, "long_name": f.description}
    if name == "status":
        attrs |= _flags(np.array(list(STATUS_NAMES), dtype=f.dtype), STATUS_NAMES.values())
    elif name == "landing":
        attrs |= _flags(np.arange(len(LANDINGS), dtype=f.dtype), LANDINGS)
    elif name == "liftoff_reason":
        attrs |= _flags(np.arange(len(REASONS), dtype=f.dtype), REASONS)
    elif name == "sequence" and sequences is not None:
        codes = np.asarray(sorted(int(c) for c in sequences), dtype=f.dtype)
        attrs |= _flags(codes, (sequence_name(c).replace("→", "_") or "none" for c in codes))
    return attrs


def valid_sequences(codes: NDArray[np.int64]) -> NDArray[np.bool_]:
    """Which codes are sequence codes (:func:`sequence_code`): at most SEQUENCE_LEN modes of
    2 bits, none 0 below a later one."""
    ok = (codes >= 0) & (codes <= SEQUENCE_MAX)
    for i in range(SEQUENCE_LEN):
        gap = ((codes >> (2 * i)) & 3) == 0
        ok &= ~(gap & ((codes >> (2 * i + 2)) != 0))
    return ok


def _sequences_valid(values: Mapping[str, NDArray]) -> str | None:
    """What is wrong with a motion map's codes beyond their tables: each ``sequence`` must be
    a sequence code."""
    seq = np.asarray(values["sequence"]).astype(np.int64)
    ok = valid_sequences(seq)
    if not ok.all():
        return f"sequence holds code {int(seq[~ok].flat[0])}, not a sequence code"
    return None


#: The motion map (:func:`eccjump.motion_map`, ``eccjump map --kind motion``) as a kind of map
#: file: any of its eight axes may be swept.
MOTION = register(
    MapKind(
        "motion",
        FIELDS,
        DTYPES,
        FILL,
        cf_attrs,
        ("mu_s", "mu_k", "restitution", "rule", "theta0", "omega0", "t_max", "max_transitions"),
        (
            ("alpha", "alpha"),
            ("chi", "chi"),
            ("km_frac", "km_frac"),
            ("mu_s", "mu_s"),
            ("mu_k", "mu_k"),
            ("restitution", "restitution"),
            ("theta0", "theta0"),
            ("omega0", "omega0"),
        ),
        (),
        {
            "status": frozenset(STATUS_NAMES),
            "landing": frozenset(range(len(LANDINGS))),
            "liftoff_reason": frozenset([*range(len(REASONS)), FILL["liftoff_reason"]]),
        },
        valid=VALID,
        invalid=("status", frozenset([INVALID])),
        agree=(
            ("status", "energy_lost", True),
            ("slipped_first", "slip_t", True),
            ("slipped_first", "slip_theta", True),
            ("liftoff_reason", "liftoff_t", True),
            ("liftoff_reason", "liftoff_theta", True),
            ("liftoff_reason", "apex", True),
        ),
        validator=_sequences_valid,
        # 0.1 recorded a motion map's scalar fraction axis as km, today the body's k_m
        renamed={"km": "km_frac"},
        title="motion",
    )
)


__all__ = [
    "BY_NAME",
    "DTYPES",
    "FIELDS",
    "FILL",
    "INVALID",
    "LANDINGS",
    "MODES",
    "MOTION",
    "REASONS",
    "SEQUENCE_LEN",
    "SEQUENCE_MAX",
    "STATUSES",
    "STATUS_NAMES",
    "TABLE",
    "VALID",
    "Field",
    "cf_attrs",
    "sequence_code",
    "sequence_name",
    "valid_sequences",
]

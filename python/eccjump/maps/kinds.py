"""The kinds of map a file can hold -- the JARM region
(:mod:`eccjump.classification.fields`) and the full motion (:mod:`eccjump.motion.fields`)
-- described by their field tables, so that the files of :mod:`eccjump.store` and
``eccjump map`` handle both with the same code. A file records its kind in the attribute
``kind`` (a file without it is a JARM map).

Each kind also says what a valid map of it holds (checked by :mod:`eccjump.maps.check` when
a map is read or written): its axes (each a dimension of the map or one value in the
attributes) and the allowed values of its coded fields (:meth:`MapKind.bad_codes`)."""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump.classification import fields
from eccjump.motion import fields as motion_fields
from eccjump.motion.simulation import REASONS


class MapKind(NamedTuple):
    """What one kind of map holds per point."""

    #: The value of the file attribute ``kind``.
    name: str
    #: Field names, in the order of the bridge.
    fields: tuple[str, ...]
    #: numpy dtype of each field.
    dtypes: Mapping[str, np.dtype]
    #: Value of each field where a point was not computed.
    fill: Mapping[str, Any]
    #: CF attributes of a field's variable.
    var_attrs: Callable[[str], dict[str, Any]]
    #: File attributes every map of the kind has (how it was made), less the axes swept.
    required_attrs: tuple[str, ...]
    #: The axes of the map as (parameter, dimension), in the order of the dimensions: each
    #: is a dimension (with a 1-D coordinate) or, if not swept, the attribute ``parameter``.
    axes: tuple[tuple[str, str], ...]
    #: The dimensions every map of the kind has.
    fixed_dims: tuple[str, ...]
    #: The allowed values of each coded field, the fill value included.
    codes: Mapping[str, frozenset[int]]
    #: A field whose fill value no computed point has (None: the fill can be a result).
    computed_mark: str | None = None
    #: The physical range of each float field, NaN aside
    #: (:attr:`eccjump.classification.fields.Field.valid`).
    valid: Mapping[str, tuple[float, float]] = MappingProxyType({})
    #: The field and codes that mark a point invalid (or not computed): the only points a map
    #: may hold at a coordinate outside its range (:data:`AXIS_RANGES`).
    invalid: tuple[str, frozenset[int]] = ("", frozenset())
    #: Rules (flag, float field, both ways): where a point has the flag (a bool, or a code
    #: other than the flag's fill), the float field is a number (not NaN); both ways: only
    #: there.
    agree: tuple[tuple[str, str, bool], ...] = ()

    def bytes_per_point(self) -> int:
        return sum(np.dtype(self.dtypes[k]).itemsize for k in self.fields)

    def bad_codes(self, values: Mapping[str, NDArray]) -> str | None:
        """What is wrong with the coded fields in ``values`` (None: nothing): a code not in
        its table, or (JARM) ``is_jarm`` not saying ``reason`` is JARM."""
        for name, allowed in self.codes.items():
            a = np.asarray(values[name])
            bad = ~np.isin(a, list(allowed))
            if a.size and bad.any():
                return f"{name} holds code {a[bad].flat[0].item()!r}, not in its table"
        if self.name == "motion":
            seq = np.asarray(values["sequence"]).astype(np.int64)
            ok = valid_sequences(seq)
            if not ok.all():
                return f"sequence holds code {int(seq[~ok].flat[0])}, not a sequence code"
        if self.name == "jarm":
            is_jarm = np.asarray(values["is_jarm"], dtype=bool)
            if not np.array_equal(is_jarm, np.asarray(values["reason"]) == fields.Reason.JARM):
                return "is_jarm contradicts reason"
        return None

    def bad_values(self, values: Mapping[str, NDArray]) -> str | None:
        """What is wrong with the values in ``values`` (None: nothing): a float field outside
        its physical range (:attr:`valid`), or two fields that disagree (:attr:`agree`)."""
        for name, (lo, hi) in self.valid.items():
            if name not in values:
                continue
            a = np.asarray(values[name], dtype=np.float64)
            with np.errstate(invalid="ignore"):
                bad = ~((a >= lo) & (a <= hi)) & ~np.isnan(a)
            if bad.any():
                return f"{name} holds {outside(a[bad].flat[0], lo, hi)}"
        for flag, name, both in self.agree:
            f = np.asarray(values[flag])
            has = f if f.dtype.kind == "b" else f != self.fill[flag]
            number = ~np.isnan(np.asarray(values[name], dtype=np.float64))
            if (has & ~number).any():
                return f"{name} is NaN where {flag} says it is set"
            if both and (number & ~has).any():
                return f"{name} is set where {flag} says it is not"
        return None


def valid_sequences(codes: NDArray[np.int64]) -> NDArray[np.bool_]:
    """Which codes are sequence codes (:func:`eccjump.motion.fields.sequence_code`): at most
    SEQUENCE_LEN modes of 2 bits, none 0 below a later one."""
    ok = (codes >= 0) & (codes <= motion_fields.SEQUENCE_MAX)
    for i in range(motion_fields.SEQUENCE_LEN):
        gap = ((codes >> (2 * i)) & 3) == 0
        ok &= ~(gap & ((codes >> (2 * i + 2)) != 0))
    return ok


JARM = MapKind(
    "jarm",
    fields.FIELDS,
    fields.DTYPES,
    fields.FILL,
    fields.cf_attrs,
    ("mu_s", "n", "rule", "method", "theta0", "omega0"),
    (
        ("mu_s", "mu_s"),
        ("theta0", "theta0"),
        ("omega0", "omega0"),
        ("alpha", "alpha"),
        ("chi", "chi"),
        ("km_frac", "km_frac"),
    ),
    ("alpha", "chi", "km_frac"),
    {"reason": frozenset([*(int(r) for r in fields.Reason), fields.FILL["reason"]])},
    "reason",
    fields.VALID,
    ("reason", frozenset([int(fields.Reason.INVALID_PARAMS), fields.FILL["reason"]])),
    (("is_jarm", "Fx_J", True), ("is_jarm", "Fy_J", True), ("is_jarm", "theta_J", False)),
)
MOTION = MapKind(
    "motion",
    motion_fields.FIELDS,
    motion_fields.DTYPES,
    motion_fields.FILL,
    motion_fields.cf_attrs,
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
        "status": frozenset(motion_fields.STATUS_NAMES),
        "landing": frozenset(range(len(motion_fields.LANDINGS))),
        "liftoff_reason": frozenset([*range(len(REASONS)), motion_fields.FILL["liftoff_reason"]]),
    },
    None,
    motion_fields.VALID,
    ("status", frozenset([motion_fields.INVALID])),
    (
        ("status", "energy_lost", True),
        ("slipped_first", "slip_t", True),
        ("slipped_first", "slip_theta", True),
        ("liftoff_reason", "liftoff_t", True),
        ("liftoff_reason", "liftoff_theta", True),
        ("liftoff_reason", "apex", True),
    ),
)
#: The physical range of each axis of a map, a coordinate or (not swept) an attribute; a map
#: may hold points outside it only as invalid points (:attr:`MapKind.invalid`): the
#: computation marks them so and goes on.
AXIS_RANGES: dict[str, tuple[float, float]] = {
    "alpha": (0.0, math.pi / 2),
    "chi": (0.0, 1.0),
    "km_frac": (0.0, 1.0),
    "mu_s": (0.0, sys.float_info.max),
    "mu_k": (0.0, sys.float_info.max),
    "restitution": (0.0, 1.0),
    "theta0": (-2 * math.pi * 1e6, 2 * math.pi * 1e6),
    "omega0": (-1e6, 1e6),
}


def outside(value: float, lo: float, hi: float) -> str:
    """How ``value`` leaves the range [lo, hi], in words: ``"-5 (below -0.001)"``."""
    return f"{value:g} ({f'below {lo:g}' if value < lo else f'above {hi:g}'})"


#: Every kind by name.
KINDS: dict[str, MapKind] = {k.name: k for k in (JARM, MOTION)}


def kind_of(attrs: Mapping[str, Any]) -> MapKind:
    """The kind of a map from its attributes; ValueError for an unknown ``kind``."""
    name = attrs.get("kind", "jarm")
    if not isinstance(name, str) or name not in KINDS:
        raise ValueError(f"unknown map kind {str(name)[:20]!r}; known: {', '.join(KINDS)}")
    return KINDS[name]


def upgrade_attrs(attrs: dict[str, Any]) -> None:
    """The attributes of a map file written before 0.2, in today's names, in place: a motion
    map's scalar fraction axis was recorded as ``km`` (the parameter's name then); it is
    ``km_frac`` now, and ``km`` always the body's k_m."""
    if attrs.get("kind") == "motion" and "km" in attrs and "km_frac" not in attrs:
        attrs["km_frac"] = attrs.pop("km")


__all__ = [
    "AXIS_RANGES",
    "JARM",
    "KINDS",
    "MOTION",
    "MapKind",
    "kind_of",
    "upgrade_attrs",
    "valid_sequences",
]

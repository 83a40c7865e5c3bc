"""The kinds of map a file can hold -- the JARM region (:mod:`eccjump.fields`) and the full
motion (:mod:`eccjump.motion_fields`) -- described by their field tables, so that the files
of :mod:`eccjump.store` and ``eccjump map`` handle both with the same code. A file records
its kind in the attribute ``kind`` (a file without it is a JARM map).

Each kind also says what a valid map of it holds (checked by :mod:`eccjump._mapcheck` when
a map is read or written): its axes (each a dimension of the map or one value in the
attributes) and the allowed values of its coded fields (:meth:`MapKind.bad_codes`)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump import fields, motion_fields
from eccjump.motion import REASONS


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


def valid_sequences(codes: NDArray[np.int64]) -> NDArray[np.bool_]:
    """Which codes are sequence codes (:func:`eccjump.motion_fields.sequence_code`): at most
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
)
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


__all__ = ["JARM", "KINDS", "MOTION", "MapKind", "kind_of", "upgrade_attrs", "valid_sequences"]

"""The kinds of map a file can hold -- the JARM region (:mod:`eccjump.fields`) and the full
motion (:mod:`eccjump.motion_fields`) -- described by their field tables, so that the files
of :mod:`eccjump.store` and ``eccjump map`` handle both with the same code. A file records
its kind in the attribute ``kind`` (a file without it is a JARM map)."""

from __future__ import annotations

from collections.abc import Callable, Mapping
from typing import Any, NamedTuple

import numpy as np

from eccjump import fields, motion_fields


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
    #: File attributes every map of the kind has (how it was made).
    required_attrs: tuple[str, ...]

    def bytes_per_point(self) -> int:
        return sum(np.dtype(self.dtypes[k]).itemsize for k in self.fields)


JARM = MapKind(
    "jarm",
    fields.FIELDS,
    fields.DTYPES,
    fields.FILL,
    fields.cf_attrs,
    ("mu_s", "n", "rule", "method", "theta0", "omega0"),
)
MOTION = MapKind(
    "motion",
    motion_fields.FIELDS,
    motion_fields.DTYPES,
    motion_fields.FILL,
    motion_fields.cf_attrs,
    ("mu_s", "mu_k", "restitution", "rule", "theta0", "omega0", "t_max", "max_transitions"),
)
#: Every kind by name.
KINDS: dict[str, MapKind] = {k.name: k for k in (JARM, MOTION)}


def kind_of(attrs: Mapping[str, Any]) -> MapKind:
    """The kind of a map from its attributes; ValueError for an unknown ``kind``."""
    name = attrs.get("kind", "jarm")
    if name not in KINDS:
        raise ValueError(f"unknown map kind {name!r}; known: {', '.join(KINDS)}")
    return KINDS[str(name)]


__all__ = ["JARM", "KINDS", "MOTION", "MapKind", "kind_of"]

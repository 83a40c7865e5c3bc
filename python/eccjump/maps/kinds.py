"""The kinds of map a file can hold, and the registry that the files of :mod:`eccjump.maps.store`
and ``eccjump map`` read them by: a :class:`MapKind` describes what one kind of map holds per
point (its fields, dtypes, fill values, axes, attributes and codes) and what a valid map of it
holds (checked by :mod:`eccjump.maps.check` when a map is read or written). A file records
its kind in the attribute ``kind`` (a file without it is a JARM map, from before kinds were
recorded).

The map layer knows no kind by itself: each kind is defined next to its field table and joins
:data:`KINDS` with :func:`register` -- the JARM region (``JARM`` in
:mod:`eccjump.classification.fields`), the full motion (``MOTION`` in
:mod:`eccjump.motion.fields`) and P(JARM) under tolerances (``UNCERTAINTY`` in
:mod:`eccjump.studies.uncertainty.map_fields`). ``import eccjump`` imports all three.

Where to add a third map kind:

1. a fields module above the map layer (as :mod:`eccjump.motion.fields`): its :class:`Field`
   table (:class:`eccjump.classification.fields.Field`) and ``register(MapKind(...))``, with a
   ``validator`` for what its codes must satisfy beyond their tables;
2. a result class, ``class MyMap(Map, kind=MY_KIND)`` (:class:`eccjump.maps.map.Map`), with
   ``coords``, ``fields``, ``to_layout()`` and the classmethod ``from_layout()``: then
   :func:`eccjump.maps.save` writes it, :func:`eccjump.maps.load` reads it back as ``MyMap``
   and ``to_xarray()`` labels it, with no change to the map layer;
3. for ``eccjump map``: a job class in :mod:`eccjump.cli.map_jobs`.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Mapping
from types import MappingProxyType
from typing import TYPE_CHECKING, Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump import _compat


def _nothing_wrong(values: Mapping[str, NDArray]) -> str | None:
    return None


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
    #: The kind's own rule for its coded fields beyond their tables: what is wrong with the
    #: fields ``values`` by name (None: nothing), e.g. two fields that contradict each other.
    validator: Callable[[Mapping[str, NDArray]], str | None] = _nothing_wrong
    #: File attributes renamed since they were first written: old name -> today's
    #: (:func:`upgrade_attrs`).
    renamed: Mapping[str, str] = MappingProxyType({})
    #: The kind in messages, "a JARM map" (empty: its :attr:`name`).
    title: str = ""

    def words(self) -> str:
        """The kind in messages: ``"JARM map"``."""
        return f"{self.title or self.name} map"

    def bytes_per_point(self) -> int:
        return sum(np.dtype(self.dtypes[k]).itemsize for k in self.fields)

    def record(self) -> np.dtype:
        """One record per point holding every field (the dtype of a map's dask blocks)."""
        return np.dtype([(k, self.dtypes[k]) for k in self.fields])

    def bad_codes(self, values: Mapping[str, NDArray]) -> str | None:
        """What is wrong with the coded fields in ``values`` (None: nothing): a code not in
        its table, or what the kind's :attr:`validator` finds."""
        for name, allowed in self.codes.items():
            a = np.asarray(values[name])
            bad = ~np.isin(a, list(allowed))
            if a.size and bad.any():
                return f"{name} holds code {a[bad].flat[0].item()!r}, not in its table"
        return self.validator(values)

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


#: Every kind by name, each registered by its fields module (:func:`register`).
KINDS: dict[str, MapKind] = {}
#: The kind of a file without the attribute ``kind`` (written before kinds were recorded).
DEFAULT_KIND = "jarm"


def register(kind: MapKind) -> MapKind:
    """``kind``, made known to the files by its name (once: a second kind of that name is a
    ValueError)."""
    if KINDS.setdefault(kind.name, kind) is not kind:
        raise ValueError(f"a map kind named {kind.name!r} is registered already")
    return kind


def kind_of(attrs: Mapping[str, Any]) -> MapKind:
    """The kind of a map from its attributes; ValueError for an unknown ``kind``."""
    name = attrs.get("kind", DEFAULT_KIND)
    if not isinstance(name, str) or name not in KINDS:
        raise ValueError(f"unknown map kind {str(name)[:20]!r}; known: {', '.join(KINDS)}")
    return KINDS[name]


def upgrade_attrs(attrs: dict[str, Any]) -> None:
    """The attributes of a map file written before 0.2, in today's names, in place (the
    kind's :attr:`MapKind.renamed`; an unknown kind is left to :func:`kind_of`)."""
    name = attrs.get("kind", DEFAULT_KIND)
    kind = KINDS.get(name) if isinstance(name, str) else None
    for old, new in kind.renamed.items() if kind is not None else ():
        if old in attrs and new not in attrs:
            attrs[new] = attrs.pop(old)


# JARM, MOTION and valid_sequences, defined here before the kinds joined a registry, for one
# release.
if not TYPE_CHECKING:  # (a module __getattr__ would let mypy pass any typo)

    def __getattr__(name: str):
        return _compat.moved_name(__name__, name)


__all__ = [
    "AXIS_RANGES",
    "DEFAULT_KIND",
    "KINDS",
    "MapKind",
    "kind_of",
    "register",
    "upgrade_attrs",
]

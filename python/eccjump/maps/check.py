"""What a valid map holds, checked wherever a map is read or written (:mod:`eccjump.store`,
:mod:`eccjump.motion.maps`, ``eccjump map --resume``), so that every loader refuses the same
things in the same words and no writer writes what a loader refuses. numpy only.

A map (a layout, see :mod:`eccjump.maps.xarray`) is valid when it has the variables and
attributes of its kind (:mod:`eccjump.maps.kinds`); every field has the same dimensions, a
sub-sequence of the kind's axes with its fixed ones, each with a finite 1-D coordinate of the
field's length; every axis that is not a dimension is a finite number in the attributes; the
dtypes fit; the coded fields hold codes of their tables; every float field is within its
physical range (:attr:`eccjump.classification.fields.Field.valid`) and the fields that must agree do
(:attr:`eccjump.maps.kinds.MapKind.agree`); every axis is within
:data:`eccjump.maps.kinds.AXIS_RANGES` (a swept coordinate outside it only where every point
is invalid); the derived coordinates ``alpha_deg`` and ``km`` are what their sources give;
and (JARM) no slice marked done holds the fill value ``reason`` 255 of a point not computed.

Errors are ValueErrors naming the file (:func:`~eccjump._base.checks.shown`: at most
:data:`~eccjump._base.checks.SHOWN` characters of its path) in at most
:data:`~eccjump._base.checks.MAX_MESSAGE` characters.
"""

from __future__ import annotations

import numbers
from collections.abc import Mapping
from typing import Any

import numpy as np

# file_error and shown (the one form of a message naming a file, in _base for the overwrite
# policy below the maps), re-exported from here where they were before
from eccjump._base.checks import MAX_MESSAGE as MAX_MESSAGE
from eccjump._base.checks import SHOWN as SHOWN
from eccjump._base.checks import file_error
from eccjump._base.checks import shown as shown
from eccjump.maps.kinds import AXIS_RANGES, MapKind, kind_of, outside

#: Attributes that are text, and integer counts (the other attributes checked are numbers).
TEXT_ATTRS = ("rule", "method")
COUNT_ATTRS = ("n", "max_transitions")


class Invalid(ValueError):
    """What is wrong with a map (without the file's name)."""


def check_layout(lay: object, path: object) -> MapKind:
    """The kind of the map ``lay`` read from ``path``; ValueError naming ``path`` and the first
    thing wrong with it."""
    try:
        return check(lay)
    except Invalid as err:
        raise file_error(path, str(err)) from None


def check(lay: object) -> MapKind:
    """The kind of the valid map ``lay``; :class:`Invalid` saying what is wrong."""
    coords, data_vars, attrs = _parts(lay)
    try:
        kind = kind_of(attrs)
    except ValueError as err:
        raise Invalid(f"is not an eccjump map: {err}") from None
    variables = {**coords, **data_vars}
    dims = _field_dims(kind, variables, data_vars, attrs)
    shape = tuple(_coordinate(variables, d) for d in dims)
    for name in kind.fields:
        _field(kind, name, data_vars[name], dims, shape)
    _axis_attrs(kind, dims, attrs)
    done = _done(variables, attrs, dims, shape)
    values = {k: np.asarray(data_vars[k][1]) for k in kind.fields}
    _derived_coords(variables, dims)
    _axis_ranges(kind, variables, dims, values)
    extra = {k: np.asarray(v[1]) for k, v in data_vars.items() if k in kind.valid}
    problem = kind.bad_codes(values) or kind.bad_values({**extra, **values})
    if problem is None and kind.computed_mark is not None and done is not None:
        name, fill = kind.computed_mark, kind.fill[kind.computed_mark]
        if (values[name].compress(done, axis=dims.index("alpha")) == fill).any():
            problem = f"a slice marked done has {name} {fill} (not computed)"
    if problem:
        raise Invalid(f"is a damaged {kind.name} map: {problem}")
    return kind


def _parts(lay: object) -> tuple[dict, dict, dict]:
    """``coords``, ``data_vars``, ``attrs`` of a layout whose variables are (dims, array,
    attrs) triples."""
    if not isinstance(lay, Mapping) or not all(
        isinstance(lay.get(k), Mapping) for k in ("coords", "data_vars", "attrs")
    ):
        raise Invalid("is not an eccjump map: no coords, data_vars and attrs")
    for part in ("coords", "data_vars"):
        for name, var in lay[part].items():
            if not (
                isinstance(var, tuple | list)
                and len(var) == 3
                and isinstance(var[0], tuple | list)
                and all(isinstance(d, str) for d in var[0])
            ):
                raise Invalid(f"is not an eccjump map: malformed variable {str(name)[:30]!r}")
    return dict(lay["coords"]), dict(lay["data_vars"]), dict(lay["attrs"])


def _field_dims(kind: MapKind, variables: dict, data_vars: dict, attrs: dict) -> tuple[str, ...]:
    """The dimensions of the fields (after checking that nothing required is missing)."""
    first = data_vars.get(kind.fields[0])
    dims = tuple(first[0]) if first is not None else kind.fixed_dims
    swept = {p for p, d in kind.axes if d in dims}
    need = (
        ("coordinates", kind.fixed_dims, set(variables)),
        ("variables", kind.fields, set(data_vars)),
        ("attributes", tuple(a for a in kind.required_attrs if a not in swept), set(attrs)),
    )
    missing = [
        f"{what} {', '.join(n for n in names if n not in have)}"
        for what, names, have in need
        if not set(names) <= have
    ]
    if missing:
        raise Invalid(f"is not an eccjump {kind.name} map: missing " + "; ".join(missing))
    order = [d for _, d in kind.axes]
    if len(set(dims)) != len(dims) or [d for d in order if d in dims] != list(dims):
        raise Invalid(f"is not an eccjump {kind.name} map: dimensions {_names(dims)}")
    return dims


def _names(names: tuple[str, ...]) -> str:
    return ", ".join(n[:20] for n in names[:8])[:80]


def _coordinate(variables: dict, dim: str) -> int:
    """The length of dimension ``dim``, whose coordinate must be finite, 1-D and not empty."""
    var = variables.get(dim)
    if var is None:
        raise Invalid(f"has no coordinate {dim}")
    values = np.asarray(var[1])
    if tuple(var[0]) != (dim,) or values.ndim != 1 or values.size == 0:
        raise Invalid(f"has a malformed coordinate {dim} of shape {values.shape}")
    if values.dtype.kind not in "iuf" or not np.isfinite(values).all():
        raise Invalid(f"has a coordinate {dim} that is not all finite numbers")
    return values.size


def _axis_ranges(kind: MapKind, variables: dict, dims: tuple[str, ...], values: dict) -> None:
    """A swept coordinate may leave its physical range (:data:`AXIS_RANGES`) only where every
    point of the map is invalid: the computation marks such points so and goes on (a kind
    without an invalid mark has no such points)."""
    mark, codes = kind.invalid
    for axis, dim in kind.axes:
        if dim not in dims or axis not in AXIS_RANGES:
            continue
        lo, hi = AXIS_RANGES[axis]
        coord = np.asarray(variables[dim][1], dtype=np.float64)
        out = ~((coord >= lo) & (coord <= hi))
        if not out.any():
            continue
        at = np.asarray(values[mark]).compress(out, axis=dims.index(dim)) if mark else None
        if at is None or not np.isin(at, list(codes)).all():
            raise Invalid(
                f"has a coordinate {dim} = {outside(coord[out][0], lo, hi)} with valid points"
            )


#: The coordinates derived from others (:func:`eccjump.maps.xarray.grid_coords`), by their
#: dimensions and how: each must be what its sources give, bit for bit.
_DERIVED = {
    "alpha_deg": (("alpha",), lambda v: np.degrees(v["alpha"])),
    "km": (("chi", "km_frac"), lambda v: v["km_frac"][None, :] * (1.0 - v["chi"][:, None])),
}


def _derived_coords(variables: dict, dims: tuple[str, ...]) -> None:
    for name, (sources, derive) in _DERIVED.items():
        if name not in variables or not set(sources) <= set(dims):
            continue
        have = np.asarray(variables[name][1])
        want = derive({d: np.asarray(variables[d][1], dtype=np.float64) for d in sources})
        if tuple(variables[name][0]) != sources or not np.array_equal(have, want):
            raise Invalid(f"has a coordinate {name} that is not what {', '.join(sources)} give")


def _field(
    kind: MapKind, name: str, var: Any, dims: tuple[str, ...], shape: tuple[int, ...]
) -> None:
    values = np.asarray(var[1])
    if tuple(var[0]) != dims or values.shape != shape:
        raise Invalid(f"has a field {name} of shape {values.shape}, not {shape}")
    want = np.dtype(kind.dtypes[name])
    if not _fits(values, want):
        raise Invalid(f"has a field {name} of dtype {values.dtype}, not {want}")


def _fits(values: np.ndarray, want: np.dtype) -> bool:
    """Whether ``values`` convert to ``want`` without loss of meaning."""
    have = values.dtype.kind
    if want.kind == "f":
        return have in "iuf"
    if have not in "iub":
        return False
    if want.kind == "b" or have == "b":
        return have == "b" or not values.size or bool(np.isin(values, (0, 1)).all())
    info = np.iinfo(want)
    return not values.size or bool(values.min() >= info.min and values.max() <= info.max)


def _axis_attrs(kind: MapKind, dims: tuple[str, ...], attrs: dict) -> None:
    """Every axis not swept, and every number of ``required_attrs``, is a finite number."""
    numbers_ = [p for p, d in kind.axes if d not in dims and p in attrs]
    numbers_ += [a for a in kind.required_attrs if a in attrs and a not in TEXT_ATTRS]
    for name in dict.fromkeys(numbers_):
        value = attrs[name]
        if name == "mu_k" and value == "mu_s":  # mu_k = mu_s, swept (MotionMap.attrs)
            continue
        if not _finite(value) or (name in COUNT_ATTRS and not _count(value)):
            raise Invalid(f"has a bad attribute {name} = {str(value)[:20]!r}")
        lo, hi = AXIS_RANGES.get(name, (-np.inf, np.inf))
        if not lo <= float(value) <= hi:
            raise Invalid(f"has an attribute {name} = {outside(float(value), lo, hi)}")
    for name in TEXT_ATTRS:
        if name in attrs and not isinstance(attrs[name], str):
            raise Invalid(f"has a bad attribute {name} (not text)")


def attr_problem(attrs: Mapping[str, Any], name: str) -> str | None:
    """What makes ``attrs`` (called ``name``) no attributes every format stores alike (None:
    nothing): each is text, a number (not a bool: netCDF has none) or a 1-D list or array of
    numbers or of texts, under a text key."""
    for key, value in attrs.items():
        if not isinstance(key, str):
            return f"{name} has a key {str(key)[:20]!r} that is not text"
        if not _attr_value(value):
            what = getattr(value, "dtype", None) or type(value).__name__
            return (
                f"{name}[{key[:20]!r}] is of type {str(what)[:20]}, not text, a number or "
                "a 1-D list of numbers or of texts"
            )
    return None


def _attr_value(value: object) -> bool:
    if isinstance(value, str):
        return True
    if isinstance(value, list | tuple):
        return all(isinstance(v, str) for v in value) or all(map(_number, value))
    if isinstance(value, np.ndarray):
        return value.ndim <= 1 and value.dtype.kind in "iufU"
    return _number(value)


def _number(value: object) -> bool:
    return isinstance(value, numbers.Real) and not isinstance(value, bool | np.bool_)


def _finite(value: object) -> bool:
    value = value.item() if isinstance(value, np.generic) else value
    return (
        isinstance(value, numbers.Real)
        and not isinstance(value, bool)
        and bool(np.isfinite(float(value)))
    )


def _count(value: object) -> bool:
    """Whether ``value`` (a finite number) is a whole number ≥ 0."""
    number = float(value.item() if isinstance(value, np.generic) else value)  # type: ignore[arg-type]
    return number.is_integer() and number >= 0


def _done(
    variables: dict, attrs: dict, dims: tuple[str, ...], shape: tuple[int, ...]
) -> np.ndarray | None:
    """Which α slices are marked done (``alpha_done``; without it all of a map not
    marked incomplete); None where the map has no α dimension."""
    if "alpha" not in dims:
        return None
    n = shape[dims.index("alpha")]
    complete = attrs.get("complete", 1)
    if complete not in (0, 1):
        raise Invalid(f"has a bad attribute complete = {str(complete)[:20]!r}")
    var = variables.get("alpha_done")
    if var is None:
        return np.full(n, bool(complete))
    done = np.asarray(var[1])
    if tuple(var[0]) != ("alpha",) or done.shape != (n,) or not _fits(done, np.dtype(bool)):
        raise Invalid(f"has a malformed alpha_done of shape {done.shape}")
    done = done.astype(bool)
    if complete and not done.all():
        raise Invalid("is marked complete with slices not done")
    return done

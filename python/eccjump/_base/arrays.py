"""Helpers that turn user input into the contiguous float64 arrays the Rust bridge takes."""

from __future__ import annotations

import dataclasses
import functools
import operator
from collections.abc import Callable, Mapping
from typing import Any, NamedTuple, ParamSpec, TypeVar

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump._base.checks import U32_MAX, int_array, integer, real_array

T = TypeVar("T")
P = ParamSpec("P")
R = TypeVar("R", bound=NamedTuple)


def broadcast_flat(
    **arrays: object,
) -> tuple[tuple[int, ...], list[NDArray[np.float64]]]:
    """Broadcast the named inputs together; return the common shape and contiguous 1-D float64
    copies. Raises TypeError naming the input that is not real numbers (see
    :func:`eccjump._base.checks.real_array`) and ValueError naming the inputs when the shapes do
    not broadcast."""
    converted = [real_array(k, v) for k, v in arrays.items()]
    try:
        b = np.broadcast_arrays(*converted)
    except ValueError as err:
        shapes = ", ".join(f"{k}{np.shape(v)}" for k, v in zip(arrays, converted, strict=True))
        raise ValueError(f"shapes do not broadcast: {shapes}"[:200]) from err
    shape = b[0].shape if b else ()
    return shape, [_c_aligned(x.ravel()) for x in b]


def _c_aligned(a: ArrayLike) -> NDArray[np.float64]:
    """C-contiguous, aligned float64 (unpickled arrays can be misaligned; Rust needs both)."""
    return np.require(a, dtype=np.float64, requirements=["C", "A"])


def axis(name: str, values: object) -> NDArray[np.float64]:
    """A 1-D coordinate axis as a contiguous float64 array."""
    a = real_array(name, values)
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of coordinates, got shape {a.shape}")
    return a


def km_on_a_map() -> TypeError:
    """The error of ``km=`` given to a map. ``km`` is the body's k_m in every function of the
    package; a map does not take it as an axis (it would not be rectangular), and before 0.2
    a map's ``km`` meant the fraction: an error that says so, never a silent reading of one
    for the other."""
    return TypeError(
        "km is the body's k_m; a map's axis is km_frac = k_m / (1 - chi), the fraction in "
        "[0, 1] (a map's km meant it before 0.2)"
    )


def refuses_km(fn: Callable[P, T]) -> Callable[P, T]:
    """Decorator of the maps over (α, χ, ``km_frac``): ``km=`` in any call form (alone,
    with ``km_frac``, after positional axes) raises :func:`km_on_a_map`, before Python
    would report a missing ``km_frac`` instead."""

    @functools.wraps(fn)
    def call(*args: P.args, **kwargs: P.kwargs) -> T:
        if kwargs.get("km") is not None:
            raise km_on_a_map()
        return fn(*args, **kwargs)

    return call


def fraction_axis(km_frac: object) -> object:
    """The grid axis of the shell mass fraction of a map: ``km_frac``, the share
    k_m/(1 − χ) of its largest value (``km`` is refused by :func:`refuses_km`)."""
    if km_frac is None:
        raise TypeError("km_frac is required: the axis of the fraction k_m/(1 - chi) in [0, 1]")
    return km_frac


#: The largest turn number (the core counts turns in 32 bits).
MAX_TURN = U32_MAX


def turn(n: object, name: str = "n") -> int | None:
    """Validate a turn number: None (automatic) or an integer ≥ 1 (TypeError for what is not
    an integer, bools and floats included)."""
    if n is None:
        return None
    return integer(name, n, 1, MAX_TURN)


def turns(n: object) -> int | NDArray[np.int64] | None:
    """Validate a turn argument that may vary per point: None (automatic; only as a scalar),
    an integer ≥ 1, or an array-like of integers ≥ 1 (returned as an int64 array)."""
    if n is None or isinstance(n, int | np.integer):  # bool included: integer() rejects it
        return turn(n)
    if isinstance(n, np.ndarray) and n.ndim == 0 and not isinstance(n, np.ma.MaskedArray):
        return turn(n)
    return int_array("n", n, 1, MAX_TURN)


def same_values(x: object, y: object) -> bool:
    """Equality of result fields: arrays (numpy, or dask computed on the way) by shape, dtype
    and values with NaN equal to NaN; tuples, lists and dicts item by item; anything else by
    ``==`` (floats with NaN equal to NaN)."""
    if hasattr(x, "__array__") and not isinstance(x, np.generic):
        if not hasattr(y, "__array__") or isinstance(y, np.generic):
            return False
        a, b = np.asarray(x), np.asarray(y)
        if a.shape != b.shape or a.dtype != b.dtype:
            return False
        if a.dtype.kind in "fc":
            return bool(np.array_equal(a, b, equal_nan=True))
        return bool(np.array_equal(a, b))
    if isinstance(x, tuple | list) and not hasattr(x, "_fields"):
        return (
            type(x) is type(y)
            and len(x) == len(y)
            and all(same_values(p, q) for p, q in zip(x, y, strict=True))
        )
    if isinstance(x, tuple):  # named tuples (Event): same type, then item by item
        return type(x) is type(y) and same_values(tuple(x), tuple(y))
    if isinstance(x, dict):
        return (
            isinstance(y, dict) and x.keys() == y.keys() and all(same_values(x[k], y[k]) for k in x)
        )
    if isinstance(x, float) and isinstance(y, float) and x != x and y != y:
        return True
    return bool(x == y)


def fields_equal(self: Any, other: Any) -> bool:
    """``__eq__`` of the result dataclasses: field by field, arrays by shape, dtype and values
    (NaN equal to NaN; a lazy result is computed to compare)."""
    if type(other) is not type(self):
        return NotImplemented
    return all(
        same_values(getattr(self, f.name), getattr(other, f.name)) for f in dataclasses.fields(self)
    )


def frozen_result(cls: type[T], fields: dict[str, Any]) -> T:
    """The frozen dataclass ``cls`` holding ``fields`` (every field, by name):
    the object ``cls(**fields)`` makes, without the ``object.__setattr__`` its ``__init__``
    calls per field (for ``RollResult``'s 19 fields, a tenth of a short ``roll``). The tests
    compare the two (``tests/test_roll.py``, ``tests/test_motion.py``)."""
    result = object.__new__(cls)
    object.__setattr__(result, "__dict__", fields)  # the frozen class's own refuses
    return result


def records(cls: type[R], columns: Mapping[str, Any]) -> tuple[R, ...]:
    """The named tuples ``cls`` (of two fields or more) of a run's records from the bridge's
    columns, one list per field by name (``rust/eccjump-py/src/columns.rs``, ``Records``):
    the order of the fields is ``cls``'s, written there only. The columns have one length by
    construction."""
    # zip without strict=: its keyword alone costs a fifth of a one-event roll's records.
    return tuple(map(cls._make, zip(*_columns_of(cls)(columns))))  # noqa: B905


@functools.cache
def _columns_of(cls: type[tuple]) -> Callable[[Mapping[str, Any]], tuple[Any, ...]]:
    """The getter of ``cls``'s columns in the order of its fields, made once per class: a
    record of a short run costs little more than its tuple."""
    return operator.itemgetter(*cls._fields)  # type: ignore[attr-defined]

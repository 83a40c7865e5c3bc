"""Type checks of user input, shared by every public entry point.

Only types are checked here (and whether an integer fits the bridge's integer type): the
ranges are checked once, by the Rust core. What is not a real number raises ``TypeError``
naming the parameter: ``None``, strings, bytes, bools (``True`` is not a number here),
complex numbers, times (``np.timedelta64`` and ``np.datetime64``: numpy makes a timedelta an
integer), masked arrays, object arrays of non-numbers and ragged lists; :func:`real` refuses
an array of shape (1,) as well (a scalar is due). Python ints and floats, numpy integer and
floating scalars and arrays of real dtype are accepted; arrays are returned as native,
contiguous, aligned float64 (big-endian, strided, read-only, 0-d and empty arrays all work).
Messages are short (≤ :data:`MAX_MESSAGE` characters): numbers are shown with :func:`short`,
paths with :func:`shown`, and :func:`file_error` is the one form of a message naming a file.
"""

from __future__ import annotations

import numbers
import os
import sys
from collections.abc import Mapping
from types import FrameType
from typing import Any, Literal, cast

import numpy as np
from numpy.typing import NDArray

#: The lift-off rules (``docs/motion.md``).
Rule = Literal["paper", "normal_force"]
#: The Runge–Kutta pair of an integration: scipy's "RK45" and "DOP853", or Verner's "Vern9".
Integrator = Literal["RK45", "DOP853", "Vern9"]

#: The largest value of the bridge's unsigned integer types.
U32_MAX = 2**32 - 1
U64_MAX = 2**64 - 1

#: Longest error message, the prefix ``eccjump: error: `` of the command line included.
MAX_MESSAGE = 200
#: Characters of a path shown in a message (its end, where the file's name is).
SHOWN = 80


def short(value: object) -> str:
    """``value`` for an error message: floats as ``:g``, huge integers as ``~1e+400``,
    anything else by its repr cut to 40 characters."""
    if isinstance(value, bool | np.bool_):
        return repr(bool(value))
    if isinstance(value, numbers.Integral):
        text = str(int(value))
        if len(text) <= 20:
            return text
        sign = "-" if text.startswith("-") else ""
        return f"{sign}~1e+{len(text.lstrip('-')) - 1}"
    if isinstance(value, numbers.Real):
        try:
            return f"{float(value):g}"
        except (OverflowError, ValueError):
            pass
    text = repr(value)
    return text if len(text) <= 40 else text[:37] + "..."


def shown(path: object) -> str:
    """``path`` for a message: its last :data:`SHOWN` characters."""
    text = os.fspath(path) if isinstance(path, str | os.PathLike) else repr(path)
    text = text if isinstance(text, str) else repr(text)
    return text if len(text) <= SHOWN else "..." + text[3 - SHOWN :]


def file_error(
    path: object, what: str, cls: type[Exception] = ValueError, name: str | None = None
) -> Exception:
    """``cls("<path> <what>")`` (``"<name>: <path> <what>"`` with the parameter or option
    ``name`` that gave the path), cut to fit an ``eccjump: error:`` line of MAX_MESSAGE."""
    text = " ".join(f"{shown(path)} {what}".split())  # one line
    text = text if name is None else f"{name}: {text}"
    limit = MAX_MESSAGE - len("eccjump: error: ")
    return cls(text if len(text) <= limit else text[: limit - 3] + "...")


def _kind(value: object) -> str:
    """The type of ``value`` for a message (with the dtype of an array)."""
    if isinstance(value, np.ndarray):
        return f"{type(value).__name__} of dtype {value.dtype}"
    return type(value).__name__


def _not_real(value: object) -> bool:
    """True for what is never a real number here: bools, complex, masked arrays, text, times
    (``np.timedelta64`` subclasses ``np.signedinteger``: without this it passes as an int)."""
    return (
        value is None
        or isinstance(value, bool | np.bool_ | str | bytes | np.ma.MaskedArray)
        or isinstance(value, complex | np.complexfloating)
        or isinstance(value, np.timedelta64 | np.datetime64)
    )


def real(name: str, value: object) -> float:
    """A real scalar as a Python float (NaN and infinities pass: the core checks ranges).
    Accepts ints, floats, numpy integer/floating scalars and 0-d arrays of real dtype."""
    if type(value) is float:  # the common case first: a few ns instead of the ABC checks
        return value
    if isinstance(value, np.ndarray) and not isinstance(value, np.ma.MaskedArray):
        if value.ndim != 0:
            raise TypeError(f"{name} must be a real number, not an array of shape {value.shape}")
        if value.dtype.kind not in "iuf":
            raise TypeError(f"{name} must be a real number, not an array of dtype {value.dtype}")
        value = value[()]
    if _not_real(value) or not isinstance(value, numbers.Real):
        raise TypeError(f"{name} must be a real number, not {_kind(value)}")
    try:
        return float(value)
    except OverflowError:
        raise ValueError(
            f"{name} = {short(value)} is outside the allowed range of float64 numbers"
        ) from None


def optional_real(name: str, value: object) -> float | None:
    """None, or a real scalar as :func:`real`."""
    return None if value is None else real(name, value)


def integer(name: str, value: object, lo: int = 0, hi: int = U64_MAX) -> int:
    """An integer (int, numpy integer or 0-d integer array; not a bool, not a float) as a
    Python int within [lo, hi] (the range the bridge can carry; ValueError outside)."""
    if type(value) is int and lo <= value <= hi:  # the common case first
        return value
    if isinstance(value, np.ndarray) and not isinstance(value, np.ma.MaskedArray):
        if value.ndim == 0 and value.dtype.kind in "iu":
            value = value[()]
    if _not_real(value) or not isinstance(value, numbers.Integral):
        raise TypeError(f"{name} must be an integer, not {_kind(value)}")
    v = int(value)
    if not lo <= v <= hi:
        raise ValueError(f"{name} = {short(v)} is outside the allowed range [{lo}, {hi}]")
    return v


def flag(name: str, value: object) -> bool:
    """A boolean option: True/False (or a numpy bool), nothing else."""
    if type(value) is bool:  # the common case first
        return value
    if not isinstance(value, np.bool_):
        raise TypeError(f"{name} must be True or False, not {_kind(value)}")
    return bool(value)


def text(name: str, value: object) -> str:
    """A string option (its allowed values are checked by the core)."""
    if not isinstance(value, str):
        raise TypeError(f"{name} must be a string, not {_kind(value)}")
    return value


def rule_name(value: object) -> Rule:
    """The lift-off rule's name (a string; the core checks which)."""
    return cast("Rule", text("rule", value))


def path(name: str, value: object) -> str | os.PathLike:
    """A file path: a str or an ``os.PathLike`` (not bytes)."""
    if not isinstance(value, str | os.PathLike) or isinstance(value, bytes):
        raise TypeError(f"{name} must be a str or os.PathLike path, not {_kind(value)}")
    if isinstance(os.fspath(value), bytes):
        raise TypeError(f"{name} must be a str path, not bytes")
    return value


def mapping(name: str, value: object) -> Mapping[str, Any] | None:
    """None or a mapping."""
    if value is not None and not isinstance(value, Mapping):
        raise TypeError(f"{name} must be a mapping or None, not {_kind(value)}")
    return value


def _object_values(name: str, a: NDArray[np.object_]) -> NDArray[np.float64]:
    """An object array whose every entry is a real number, as float64."""
    for x in a.flat:
        if _not_real(x) or not isinstance(x, numbers.Real):
            raise TypeError(f"{name} must hold real numbers, not {_kind(x)}")
    try:
        return a.astype(np.float64)
    except OverflowError:
        raise ValueError(f"{name} holds a number outside the range of float64 numbers") from None


def real_array(name: str, value: object) -> NDArray[np.float64]:
    """A real number or array-like as a native, C-contiguous, aligned float64 array of its
    own shape (0-d for a scalar)."""
    if _not_real(value):
        if isinstance(value, np.ma.MaskedArray):
            raise TypeError(f"{name} must be a real number or array, not a masked array")
        raise TypeError(f"{name} must be a real number or array, not {_kind(value)}")
    if isinstance(value, numbers.Real) and not isinstance(value, np.generic):
        return np.array(real(name, value))
    try:
        a = np.asarray(value)
    except (TypeError, ValueError, OverflowError) as err:  # ragged, or no array at all
        raise TypeError(
            f"{name} must be a real number or a rectangular array: {err}"[:200]
        ) from None
    if isinstance(a, np.ma.MaskedArray):
        raise TypeError(f"{name} must be a real number or array, not a masked array")
    kind = a.dtype.kind
    if kind == "O":
        a = _object_values(name, a)
    elif kind not in "iuf":
        raise TypeError(f"{name} must hold real numbers, not {a.dtype} values")
    with np.errstate(over="ignore"):  # a longdouble beyond float64 becomes inf: range-checked
        return np.require(a, dtype=np.float64, requirements=["C", "A"])


def int_array(name: str, value: object, lo: int, hi: int) -> NDArray[np.int64]:
    """An integer array-like (int dtype, no bools or floats) with entries in [lo, hi]."""
    if _not_real(value):
        raise TypeError(f"{name} must be integers, not {_kind(value)}")
    try:
        a = np.asarray(value)
    except (TypeError, ValueError, OverflowError) as err:
        raise TypeError(f"{name} must be integers in a rectangular array: {err}"[:200]) from None
    if isinstance(a, np.ma.MaskedArray):
        raise TypeError(f"{name} must be integers, not a masked array")
    if a.dtype.kind == "O":  # Python ints beyond int64, or mixed objects
        for x in a.flat:
            integer(name, x, lo, hi)
        a = a.astype(np.int64)
    if a.dtype.kind not in "iu":
        raise TypeError(f"{name} must hold integers, not {a.dtype} values")
    out = (a < lo) | (a > hi)
    if a.size and out.any():
        i = int(np.flatnonzero(out.ravel())[0])
        raise ValueError(
            f"{name}[{i}] = {short(a.ravel()[i])} is outside the allowed range [{lo}, {hi}]"
        )
    return a.astype(np.int64)


def stacklevel_outside() -> int:
    """The ``stacklevel`` for ``warnings.warn`` in the function that calls this one: the first
    frame outside eccjump (the user's call), however deep in the package the warning is
    raised and whatever decorators wrap the entry point."""
    frame: FrameType | None = sys._getframe(1)
    level = 1
    while frame is not None and frame.f_globals.get("__name__", "").startswith("eccjump"):
        frame, level = frame.f_back, level + 1
    return level

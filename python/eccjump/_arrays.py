"""Helpers that turn user input into the contiguous float64 arrays the Rust bridge takes."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray


def broadcast_flat(
    **arrays: ArrayLike,
) -> tuple[tuple[int, ...], list[NDArray[np.float64]]]:
    """Broadcast the named inputs together; return the common shape and contiguous 1-D float64
    copies. Raises ValueError naming the inputs when the shapes do not broadcast, and TypeError
    for non-numeric input."""
    try:
        converted = [np.asarray(v, dtype=np.float64) for v in arrays.values()]
    except (TypeError, ValueError) as err:
        raise TypeError(
            f"inputs {', '.join(arrays)} must be real numbers or arrays: {err}"
        ) from err
    try:
        b = np.broadcast_arrays(*converted)
    except ValueError as err:
        shapes = ", ".join(f"{k}{np.shape(v)}" for k, v in zip(arrays, converted, strict=True))
        raise ValueError(f"shapes do not broadcast: {shapes}") from err
    shape = b[0].shape if b else ()
    return shape, [_c_aligned(x.ravel()) for x in b]


def _c_aligned(a: ArrayLike) -> NDArray[np.float64]:
    """C-contiguous, aligned float64 (unpickled arrays can be misaligned; Rust needs both)."""
    return np.require(a, dtype=np.float64, requirements=["C", "A"])


def axis(name: str, values: ArrayLike) -> NDArray[np.float64]:
    """A 1-D coordinate axis as a contiguous float64 array."""
    a = _c_aligned(np.asarray(values, dtype=np.float64))
    if a.ndim == 0:
        a = a.reshape(1)
    if a.ndim != 1:
        raise ValueError(f"{name} must be a 1-D array of coordinates, got shape {a.shape}")
    return a


def turn(n: int | None) -> int | None:
    """Validate a turn number: None (automatic) or an integer >= 1."""
    if n is None:
        return None
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or n < 1:
        raise ValueError(f"n = {n!r} is outside the allowed range [1, inf) (None: automatic)")
    return int(n)


def turns_array(n: ArrayLike | None, shape: tuple[int, ...]) -> NDArray[np.uint32]:
    """The turn n of :func:`eccjump.jarm` as the bridge takes it: a flat uint32 array of the
    broadcast ``shape`` (or of length 1), 0 for None (the first jump). Every entry must be an
    integer >= 1."""
    if n is None:
        return np.zeros(1, dtype=np.uint32)
    if isinstance(n, bool):
        raise TypeError(f"n = {n!r} must be an integer >= 1 or None")
    try:
        a = np.asarray(n)
    except (TypeError, ValueError, OverflowError) as err:
        raise TypeError(f"n must be an integer >= 1 (or an array of them) or None: {err}") from err
    if a.dtype == object and a.ndim == 0 and isinstance(n, int):
        raise ValueError(f"n = {n} is outside the allowed range [1, 4294967295]")
    if not np.issubdtype(a.dtype, np.integer):
        raise TypeError(f"n must be an integer >= 1 (or an array of them) or None, not {a.dtype}")
    try:
        flat = np.broadcast_to(a, shape).ravel()
    except ValueError as err:
        raise ValueError(f"n of shape {a.shape} does not broadcast to {shape}") from err
    bad = np.flatnonzero((flat < 1) | (flat > 2**32 - 1))
    if bad.size:
        i = int(bad[0])
        raise ValueError(f"n[{i}] = {flat[i]} is outside the allowed range [1, 4294967295]")
    return np.ascontiguousarray(flat, dtype=np.uint32)

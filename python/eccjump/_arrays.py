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


#: The largest turn number (the core counts turns in 32 bits).
MAX_TURN = 2**32 - 1


def turn(n: int | None) -> int | None:
    """Validate a turn number: None (automatic) or an integer >= 1."""
    if n is None:
        return None
    if isinstance(n, bool) or not isinstance(n, int | np.integer) or not 1 <= n <= MAX_TURN:
        raise ValueError(
            f"n = {n!r} is outside the allowed range [1, {MAX_TURN}] (None: automatic)"
        )
    return int(n)


def turns(n: object) -> int | NDArray[np.int64] | None:
    """Validate a turn argument that may vary per point: None (automatic; only as a scalar),
    an integer >= 1, or an array-like of integers >= 1 (returned as an int64 array)."""
    if n is None or isinstance(n, int | np.integer):  # bool included: turn() rejects it
        return turn(n)  # type: ignore[arg-type]
    try:
        a = np.asarray(n)
    except (TypeError, ValueError) as err:  # ragged input
        raise ValueError(
            f"n must be None, an integer or an array of integers in the allowed range "
            f"[1, {MAX_TURN}]: {err}"
        ) from err
    if a.ndim == 0:
        return turn(a.item() if a.dtype.kind in "iu" else n)  # type: ignore[arg-type]
    if a.dtype.kind not in "iu":
        raise ValueError(
            f"n holds {a.dtype} values; its entries must be integers in the allowed range "
            f"[1, {MAX_TURN}] (None, the first jump, only as a scalar)"
        )
    out = (a < 1) | (a > MAX_TURN)
    if a.size and out.any():
        i = int(np.flatnonzero(out.ravel())[0])
        raise ValueError(
            f"n[{i}] = {a.ravel()[i]} is outside the allowed range [1, {MAX_TURN}] "
            "(None, the first jump, only as a scalar)"
        )
    return a.astype(np.int64)

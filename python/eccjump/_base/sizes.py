"""How much memory a call will hold, checked before any work (the user guide's "Limits",
section "Memory").

One estimate for every result of points -- JARM points and maps, full-motion points and maps
(:func:`result_bytes`), uncertainty studies (:func:`uncertainty_bytes`) -- counts every field
the call returns (the derivative fields included) and the working columns it builds on the
way, at the bytes per point its caller prices from the result's field table
(:meth:`eccjump.maps.kinds.MapKind.bytes_per_point`, :func:`field_bytes`): this module knows
no field. :func:`check_fits` compares the estimate with the memory this process can have
and raises a ``MemoryError`` that says how much was asked for and which parameter to shrink.
The core's own allocations stay fallible (a second line of defence), but they come after the
work: a result whose derivative fields do not fit was refused only after the classification
had run for minutes.
"""

from __future__ import annotations

import math
import os
from collections.abc import Iterable

import numpy as np

#: Bytes of one float64 column entry.
F64 = 8


def field_bytes(dtypes: Iterable[np.dtype], wrt: int = 1) -> int:
    """Bytes per point of fields of ``dtypes``, each float field of ``wrt`` values."""
    return sum(np.dtype(d).itemsize * (wrt if d == np.float64 else 1) for d in dtypes)


def result_bytes(points: int, per_point: int, inputs: int = 0) -> int:
    """The memory of a result of ``points`` points of ``per_point`` bytes each (its fields and
    the working columns of each point) with ``inputs`` flat float64 input columns."""
    return points * (per_point + inputs * F64)


def uncertainty_bytes(n: int, varied: int, per_sample: int) -> int:
    """The memory of an uncertainty study of ``n`` samples: the unit cube (``varied``
    columns), the eight parameter columns, the scipy quantile function's four working
    columns, the outcome fields of a sample (``per_sample`` bytes) and two columns for each
    summary."""
    return n * ((varied + 8 + 4 + 2) * F64 + 1 + per_sample)


def memory_limit() -> int | None:
    """The bytes this process may still allocate: the memory the system has available
    (Linux's MemAvailable; elsewhere the physical memory), capped by an
    address-space limit (``ulimit -v``); None where neither can be told."""
    limits = [x for x in (_available(), _address_space()) if x is not None]
    return min(limits) if limits else None


def _available() -> int | None:
    try:
        with open("/proc/meminfo", encoding="ascii") as fh:
            for line in fh:
                if line.startswith("MemAvailable:"):
                    return int(line.split()[1]) * 1024
    except (OSError, ValueError, IndexError):
        pass
    try:
        return os.sysconf("SC_PHYS_PAGES") * os.sysconf("SC_PAGE_SIZE")
    except (AttributeError, ValueError, OSError):
        return None


def _address_space() -> int | None:
    try:
        import resource
    except ImportError:  # pragma: no cover - not POSIX
        return None
    soft, _ = resource.getrlimit(resource.RLIMIT_AS)
    return None if soft == resource.RLIM_INFINITY else int(soft)


def gib(nbytes: int) -> str:
    """``nbytes`` in GiB for a message (``1.2e+08`` beyond a million GiB)."""
    x = nbytes / 2**30
    return f"{x:,.1f} GiB" if x < 1e6 else f"{x:.2g} GiB"


def check_fits(what: str, points: int, nbytes: int, shrink: str, unit: str = "points") -> None:
    """MemoryError, before any work, if ``nbytes`` (the estimate for ``what`` of ``points``
    points or samples, ``unit``) exceeds :func:`memory_limit`; the message says how much was
    asked for and which parameter to shrink (``shrink``)."""
    have = memory_limit()
    if have is None or nbytes <= have:
        return
    count = f"{points:,}" if points < 10**15 else f"{points:.3g}"
    per = math.ceil(nbytes / max(points, 1))
    raise MemoryError(
        f"{what}: the result for {count} {unit} ({per} bytes each) needs {gib(nbytes)}, more "
        f"than the {gib(have)} of memory available; shrink {shrink}"
    )


__all__ = [
    "F64",
    "check_fits",
    "field_bytes",
    "gib",
    "memory_limit",
    "result_bytes",
    "uncertainty_bytes",
]

"""How much memory a call will hold, checked before any work (the user guide's "Limits",
section "Memory").

One estimate per kind of result -- JARM points and maps (:func:`jarm_bytes`), full-motion
points and maps (:func:`motion_bytes`), uncertainty studies (:func:`uncertainty_bytes`) --
counts every field the call returns (the derivative fields included) and the working columns
it builds on the way; :func:`check_fits` compares it with the memory this process can have
and raises a ``MemoryError`` that says how much was asked for and which parameter to shrink.
The core's own allocations stay fallible (a second line of defence), but they come after the
work: a result whose derivative fields do not fit was refused only after the classification
had run for minutes.
"""

from __future__ import annotations

import math
import os

import numpy as np

from eccjump.classification import fields
from eccjump.motion import fields as motion_fields

#: Bytes of one float64 column entry.
_F64 = 8


def _field_bytes(table: tuple[fields.Field, ...], wrt: int = 1) -> int:
    """Bytes per point of the fields of ``table``, each float field ``wrt`` values."""
    return sum(np.dtype(f.dtype).itemsize * (wrt if f.dtype == np.float64 else 1) for f in table)


#: Per point: the classification's fields.
JARM_POINT = _field_bytes(fields.TABLE)
#: Per point: the derivative fields (each float one of 3 values,
#: :data:`eccjump.classification.fields.WRT`) and the six float64 columns the derivative pass
#: builds (the grid's points, k_m, mu_s).
JARM_DERIVATIVES = _field_bytes(fields.DERIVATIVE_TABLE, len(fields.WRT)) + 6 * _F64
#: Per point: the summary fields of a run to its first landing.
MOTION_POINT = _field_bytes(motion_fields.TABLE)


def jarm_bytes(points: int, derivatives: bool, inputs: int = 0) -> int:
    """The memory of a JARM result of ``points`` points (:func:`eccjump.jarm`,
    :func:`eccjump.region`) with ``inputs`` flat float64 input columns."""
    per = JARM_POINT + (JARM_DERIVATIVES if derivatives else 0) + inputs * _F64
    return points * per


def motion_bytes(points: int, inputs: int = 0) -> int:
    """The memory of a full-motion result of ``points`` points (:func:`eccjump.motion_map`,
    :func:`eccjump.motion_points`) with ``inputs`` flat float64 input columns."""
    return points * (MOTION_POINT + inputs * _F64)


def uncertainty_bytes(n: int, question: str, varied: int) -> int:
    """The memory of an uncertainty study of ``n`` samples: the unit cube (``varied``
    columns), the eight parameter columns, the scipy quantile function's four working
    columns, the outcome fields of ``question`` and two columns for each summary."""
    outcomes = JARM_POINT if question == "jarm" else MOTION_POINT
    return n * ((varied + 8 + 4 + 2) * _F64 + 1 + outcomes)


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
    "check_fits",
    "gib",
    "jarm_bytes",
    "memory_limit",
    "motion_bytes",
    "uncertainty_bytes",
]

"""Dask scale-out of a map of any kind: its fields as lazily computed dask arrays, one call of
the kind's grid function per block.

:func:`lazy_fields` splits the product of a map's 1-D axes into blocks (chunk sizes per axis,
:func:`normalize_chunks`) and builds, with :func:`dask.array.map_blocks`, one array of the
kind's records per block, each made by ONE call of a grid function on that block's coordinate
slices (the JARM classification's :func:`eccjump._base.bridge.jarm_grid`, the motion's grid
call in :mod:`eccjump.motion.maps`), which releases the GIL and runs on ``n_threads`` threads.
Every point is computed exactly as in a single-process call, so a map is bit-identical
whatever the chunks, the scheduler or the cluster.

``region(..., chunks=(ca, cc, ck))`` (or a dict ``{"alpha": ca, ...}``, or one int for every
axis; -1 or None = the whole axis) chunks along (α, χ, km_frac);
``motion_map(..., chunks=c)`` along α.

Threads: on a ``dask.distributed`` cluster set ``n_threads`` = threads per worker divided
by the tasks a worker runs at once -- in practice ``n_threads=1`` with
``threads_per_worker`` = cores per worker, or ``threads_per_worker=1`` with ``n_threads`` =
cores per worker. The default ``n_threads=0`` (one thread per core in every call)
oversubscribes the cores when several blocks run at once on one machine.

The block function and its arguments are plain module-level functions, numpy arrays and
options of plain values, so the graph pickles to any cluster whose workers can import
``eccjump``. This module builds the dask arrays only; :func:`eccjump.region` wraps them into a
lazy :class:`~eccjump.Region` and :meth:`~eccjump.Region.compute` computes them.
"""

from __future__ import annotations

from collections.abc import Callable, Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer
from eccjump._base.optional import require
from eccjump.maps.kinds import MapKind
from eccjump.maps.layout import DIMS

Chunks = int | None | Sequence[int | None] | Mapping[str, int | None]
#: The grid function of a kind: the fields of the product of the (flat) axes given first,
#: each flat in C order, from the axes and the block's fixed arguments.
GridFunction = Callable[..., Mapping[str, NDArray]]


def require_dask() -> Any:
    return require("dask.array", purpose="chunks=", extra="dask")


def normalize_chunks(
    chunks: Chunks, shape: tuple[int, ...], dims: tuple[str, ...] = DIMS
) -> tuple[int, ...]:
    """Chunk sizes along the axes ``dims`` of ``shape``, each in [1, size] (a dict may name
    the axis km_frac ``km``, as before 0.2: a chunk size cannot be mistaken for a body)."""
    if isinstance(chunks, Mapping):
        unknown = set(chunks) - {*dims, "km"}
        if unknown:
            raise ValueError(f"chunks has unknown axes {sorted(unknown)}; use {dims}")
        seq = [chunks.get(k, chunks.get("km") if k == "km_frac" else None) for k in dims]
    elif chunks is None or isinstance(chunks, int | np.integer):
        seq = [chunks] * len(dims)
    elif not isinstance(chunks, Sequence):
        raise ValueError(f"chunks must be an int, a {len(dims)}-sequence or a dict, got {chunks!r}")
    else:
        seq = list(chunks)
        if len(seq) != len(dims):
            raise ValueError(f"chunks needs {len(dims)} sizes ({', '.join(dims)}), got {chunks!r}")
    out = []
    for c, size in zip(seq, shape, strict=True):
        # The checks of every integer argument: a numpy timedelta64 is a numpy integer
        # too, and must not pass as a chunk size.
        n = -1 if c is None else integer("chunks", c, -1)
        if n == 0:
            raise ValueError("chunks = 0: a chunk size is an integer >= 1 (or -1/None)")
        out.append(max(size, 1) if n == -1 else min(n, max(size, 1)))
    return tuple(out)


def records_block(
    *axes: NDArray[np.float64],
    grid: GridFunction,
    fixed: tuple[Any, ...],
    record: np.dtype,
) -> NDArray[np.void]:
    """One block: ``grid`` on the block's (broadcast-shaped) coordinate slices and the
    arguments ``fixed``, as records."""
    # fresh copies: arrays unpickled on a worker may be misaligned, which the bridge refuses
    flat = [np.array(x, dtype=np.float64, order="C").ravel() for x in axes]
    out = np.empty(tuple(x.size for x in flat), dtype=record)
    if out.size == 0:
        return out
    raw = grid(*flat, *fixed)
    for k in record.names or ():
        out[k] = raw[k].reshape(out.shape)
    return out


def field_of(block: NDArray[np.void], name: str) -> NDArray:
    """One field of a block of records (a contiguous copy)."""
    return np.ascontiguousarray(block[name])


def lazy_fields(
    kind: MapKind,
    grid: GridFunction,
    axes: Sequence[NDArray[np.float64]],
    chunks: Sequence[int],
    fixed: tuple[Any, ...] = (),
) -> dict[str, Any]:
    """Every field of ``kind`` on the product of the 1-D ``axes`` as a dask array, in blocks
    of ``chunks`` (one size per axis, each in [1, size]), one call ``grid(*slices, *fixed)``
    per block. The fields are views of the same blocks of records: computing them together
    with ``dask.compute`` computes each block once."""
    da = require_dask()
    record = kind.record()
    n = len(axes)
    parts = []
    for i, (values, size) in enumerate(zip(axes, chunks, strict=True)):
        along = [1] * n
        along[i] = -1
        block = tuple(size if j == i else 1 for j in range(n))
        parts.append(da.from_array(values.reshape(along), chunks=block))
    records = da.map_blocks(
        records_block,
        *parts,
        grid=grid,
        fixed=tuple(fixed),
        record=record,
        chunks=tuple(p.chunks[i] for i, p in enumerate(parts)),
        dtype=record,
        meta=np.empty((0,) * n, dtype=record),
        token=f"eccjump-{kind.name}-grid",
    )
    return {
        k: records.map_blocks(
            field_of, k, dtype=record[k], meta=np.empty((0,) * n, dtype=record[k])
        )
        for k in kind.fields
    }

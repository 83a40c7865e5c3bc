"""Dask scale-out of :func:`eccjump.region`: a lazily computed map, one Rust grid call per block.

``region(..., chunks=(ca, cc, ck))`` (or a dict ``{"alpha": ca, ...}``, or one int for every
axis; -1 or None = the whole axis) builds the map with :func:`dask.array.map_blocks`. Each
block is ONE call of the grid bridge (:func:`eccjump._base.bridge.jarm_grid`) on that block's
coordinate slices, which releases the GIL and runs on ``n_threads`` threads. Every point is
computed exactly as in a single-process call, so the result is bit-identical whatever the
chunks, the scheduler or the cluster.

Threads: on a ``dask.distributed`` cluster set ``n_threads`` = threads per worker divided
by the tasks a worker runs at once -- in practice ``n_threads=1`` with
``threads_per_worker`` = cores per worker, or ``threads_per_worker=1`` with ``n_threads`` =
cores per worker. The default ``n_threads=0`` (one thread per core in every call)
oversubscribes the cores when several blocks run at once on one machine.

The block function and its arguments are plain module-level functions, numpy arrays and a
frozen dataclass of options, so the graph pickles to any cluster whose workers can import
``eccjump``. This module builds the dask arrays only (:func:`lazy_records`,
:func:`lazy_fields`); :func:`eccjump.region` wraps them into a lazy :class:`~eccjump.Region`
and :meth:`~eccjump.Region.compute` computes them.
"""

from __future__ import annotations

from collections.abc import Mapping, Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.bridge import CallOptions, jarm_grid
from eccjump._base.checks import integer
from eccjump.classification.fields import FIELDS, RECORD

AXES = ("alpha", "chi", "km_frac")

Chunks = int | None | Sequence[int | None] | Mapping[str, int | None]


def require_dask() -> Any:
    try:
        import dask.array as da
    except ImportError as err:
        raise ImportError(
            "chunks= needs dask: pip install eccjump[dask] (or eccjump[all])"
        ) from err
    return da


def normalize_chunks(chunks: Chunks, shape: tuple[int, int, int]) -> tuple[int, int, int]:
    """Chunk sizes along (alpha, chi, km_frac), each in [1, size] (a dict may name the last
    axis ``km``, as before 0.2: a chunk size cannot be mistaken for a body)."""
    if isinstance(chunks, Mapping):
        unknown = set(chunks) - {*AXES, "km"}
        if unknown:
            raise ValueError(f"chunks has unknown axes {sorted(unknown)}; use {AXES}")
        seq = [chunks.get(k, chunks.get("km") if k == "km_frac" else None) for k in AXES]
    elif chunks is None or isinstance(chunks, int | np.integer):
        seq = [chunks] * 3
    elif not isinstance(chunks, Sequence):
        raise ValueError(f"chunks must be an int, a 3-sequence or a dict, got {chunks!r}")
    else:
        seq = list(chunks)
        if len(seq) != 3:
            raise ValueError(f"chunks needs 3 sizes (alpha, chi, km_frac), got {chunks!r}")
    out = []
    for c, size in zip(seq, shape, strict=True):
        # The checks of every integer argument: a numpy timedelta64 is a numpy integer
        # too, and must not pass as a chunk size.
        n = -1 if c is None else integer("chunks", c, -1)
        if n == 0:
            raise ValueError("chunks = 0: a chunk size is an integer >= 1 (or -1/None)")
        out.append(max(size, 1) if n == -1 else min(n, max(size, 1)))
    return out[0], out[1], out[2]


def grid_block(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    frac: NDArray[np.float64],
    mu_s: float,
    opts: CallOptions,
) -> NDArray[np.void]:
    """One block: the grid of the (broadcast-shaped) coordinate slices, as records."""
    # fresh copies: arrays unpickled on a worker may be misaligned, which the bridge refuses
    a, c, f = (np.array(x, dtype=np.float64, order="C").ravel() for x in (alpha, chi, frac))
    out = np.empty((a.size, c.size, f.size), dtype=RECORD)
    if out.size == 0:
        return out
    raw = jarm_grid(a, c, f, mu_s, opts)
    for k in FIELDS:
        out[k] = raw[k].reshape(out.shape)
    return out


def field_of(block: NDArray[np.void], name: str) -> NDArray:
    """One field of a block of records (a contiguous copy)."""
    return np.ascontiguousarray(block[name])


def lazy_records(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    frac: NDArray[np.float64],
    mu_s: float,
    opts: CallOptions,
    chunks: Chunks,
) -> Any:
    """The map as a dask array of :data:`RECORD`, one Rust call per block."""
    da = require_dask()
    shape = (alpha.size, chi.size, frac.size)
    ca, cc, ck = normalize_chunks(chunks, shape)
    A = da.from_array(alpha.reshape(-1, 1, 1), chunks=(ca, 1, 1))
    C = da.from_array(chi.reshape(1, -1, 1), chunks=(1, cc, 1))
    F = da.from_array(frac.reshape(1, 1, -1), chunks=(1, 1, ck))
    out_chunks = (A.chunks[0], C.chunks[1], F.chunks[2])
    return da.map_blocks(
        grid_block,
        A,
        C,
        F,
        mu_s=float(mu_s),
        opts=opts,
        chunks=out_chunks,
        dtype=RECORD,
        meta=np.empty((0, 0, 0), dtype=RECORD),
        token="eccjump-jarm-grid",
    )


def lazy_fields(records: Any) -> dict[str, Any]:
    """Every field as a dask array, all views of the same blocks of records (computing them
    together with ``dask.compute`` computes each block once)."""
    return {
        k: records.map_blocks(
            field_of, k, dtype=RECORD[k], meta=np.empty((0, 0, 0), dtype=RECORD[k])
        )
        for k in FIELDS
    }

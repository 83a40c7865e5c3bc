"""``uncertainty(..., chunks=)``: the samples' answers computed in chunks scheduled by Dask --
the threads of this machine, its processes, or a ``dask.distributed`` cluster when a
``Client`` is active. Each chunk is :func:`.questions.evaluate` on its own samples, and a
sample's answer depends on its own values alone, so the outcomes (and the study) are the
same bits for any chunk size, scheduler or number of workers.

The tasks are a plain module-level function of numpy arrays and options of plain values, so
they pickle to any cluster whose workers can import ``eccjump``."""

from __future__ import annotations

from collections.abc import Mapping
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer
from eccjump._base.optional import require
from eccjump.studies.uncertainty.questions import evaluate
from eccjump.studies.uncertainty.sampling import N_MAX


def chunk_size(chunks: object) -> int:
    """Samples per chunk, 1 ... 10**8 (TypeError or ValueError naming ``chunks``)."""
    return integer("chunks", chunks, 1, N_MAX)


def evaluate_scheduled(
    question: str,
    cols: Mapping[str, NDArray[np.float64]],
    valid: NDArray[np.bool_],
    opts: Mapping[str, Any],
    size: int,
) -> dict[str, NDArray[Any]]:
    """:func:`.questions.evaluate` of every sample, in chunks of ``size`` samples, one dask
    task each, computed by the current scheduler and joined in order."""
    dask = require("dask", purpose="chunks=", extra="dask")
    task = dask.delayed(evaluate, pure=True)
    parts = [
        task(question, {k: v[i0 : i0 + size] for k, v in cols.items()}, valid[i0 : i0 + size], opts)
        for i0 in range(0, valid.size, size)
    ]
    done = dask.compute(*parts)
    return {k: np.concatenate([part[k] for part in done]) for k in done[0]}


__all__ = ["chunk_size", "evaluate_scheduled"]

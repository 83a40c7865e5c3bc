"""Progress of long calls: the ``progress=`` keyword of the Python API and the bars of the
command line, one mechanism for both.

``progress`` is None or False (the default: nothing is reported), True (a tqdm bar on
stderr; tqdm is a dependency of eccjump) or a callable, called as ``progress(done, total)``
with two ints, ``done`` growing to ``total``. Reporting never changes a result: the work is
split into parts whose points are computed exactly as in one call (every point is computed
from its own values alone), so the results are bit-identical with and without progress.
"""

from __future__ import annotations

import math
import sys
from collections.abc import Callable, Iterator, Mapping, Sequence
from contextlib import contextmanager
from typing import Any

import numpy as np
from numpy.typing import NDArray

#: What a caller's progress is called with: (done, total).
Progress = Callable[[int, int], object]

#: Parts a computation reporting progress is split into (about), and the least points of a
#: part (a core call of fewer points would spend its time starting its threads).
PARTS = 100
MIN_PART_POINTS = 2_000


def checked(progress: object) -> bool | Progress:
    """``progress`` as False (off), True (a bar) or the callable; TypeError naming
    ``progress`` for anything else (checked before any work)."""
    if progress is None:
        return False
    if isinstance(progress, bool | np.bool_):
        return bool(progress)
    if callable(progress):
        return progress
    raise TypeError(
        f"progress must be None, True/False or a callable progress(done, total), "
        f"not {type(progress).__name__}"
    )


@contextmanager
def reporting(
    progress: object, unit: str = "pt", *, unit_scale: bool = True, leave: bool = True
) -> Iterator[Progress | None]:
    """The reporter of ``progress`` (:func:`checked`) for the duration of a call: None when
    off, the caller's callable, or for True a function that draws a tqdm bar on stderr
    (made at its first call, its ``total`` following the one reported; ``unit_scale``: 1.2k
    for counts in thousands) and closes it at the end."""
    how = checked(progress)
    if how is False:
        yield None
        return
    if how is not True:
        yield how
        return
    from tqdm import tqdm

    bar: Any = None

    def report(done: int, total: int) -> None:
        nonlocal bar
        if bar is None:
            bar = tqdm(total=total, unit=unit, unit_scale=unit_scale, file=sys.stderr, leave=leave)
        elif bar.total != total:
            bar.total = total
        bar.update(done - bar.n)

    try:
        yield report
    finally:
        if bar is not None:
            bar.close()


def parts(size: int, points_per_item: int, report: Progress | None) -> list[tuple[int, int]]:
    """The [start, stop) ranges of ``size`` items (of ``points_per_item`` points each) that
    a computation runs in: one range without a reporter, else about :data:`PARTS` of them,
    each of at least :data:`MIN_PART_POINTS` points where there are that many."""
    if report is None or size <= 1:
        return [(0, size)]
    per_part = max(-(-size // PARTS), -(-MIN_PART_POINTS // max(points_per_item, 1)))
    return [(i, min(i + per_part, size)) for i in range(0, size, per_part)]


def run_in_parts(
    compute: Callable[[int, int], Mapping[str, NDArray]],
    size: int,
    points_per_item: int,
    report: Progress | None,
) -> list[Mapping[str, NDArray]]:
    """``compute(start, stop)`` over the :func:`parts` of ``size`` items, with
    ``report(points done, points in all)`` at the start and after each part."""
    total = size * points_per_item
    if report is not None:
        report(0, total)
    out = []
    for i0, i1 in parts(size, points_per_item, report):
        out.append(compute(i0, i1))
        if report is not None:
            report(i1 * points_per_item, total)
    return out


def points_in_parts(
    compute: Callable[[int, int], Mapping[str, NDArray]], size: int, report: Progress | None
) -> dict[str, NDArray]:
    """The fields of ``size`` independent points, ``compute(start, stop)`` giving those of
    the points [start, stop) (each field's first axis the point)."""
    pieces = run_in_parts(compute, size, 1, report)
    if len(pieces) == 1:
        return dict(pieces[0])
    return {k: np.concatenate([p[k] for p in pieces]) for k in pieces[0]}


def cut(axes: Sequence[NDArray], ax: int, part: slice) -> list[NDArray]:
    """``axes`` with the axis ``ax`` cut to ``part`` (for :func:`grid_in_parts`)."""
    return [np.ascontiguousarray(a[part]) if i == ax else a for i, a in enumerate(axes)]


def grid_in_parts(
    compute: Callable[[int, slice], Mapping[str, NDArray]],
    sizes: Sequence[int],
    report: Progress | None,
) -> dict[str, NDArray]:
    """The flat fields (C order) of a grid of axes of ``sizes``; ``compute(axis, cut)``
    gives those of the grid with the axis ``axis`` cut to ``cut``. The grid is split along
    its first axis longer than one (its points are independent: the fields are the ones a
    single call gives)."""
    total = math.prod(sizes)
    ax = next((i for i, n in enumerate(sizes) if n > 1), 0)
    if report is None or total == 0:
        pieces = [compute(ax, slice(None))]
    else:
        size = sizes[ax]
        pieces = run_in_parts(
            lambda i0, i1: compute(ax, slice(i0, i1)), size, total // size, report
        )
    if len(pieces) == 1:
        return dict(pieces[0])
    out = {}
    for k, first in pieces[0].items():
        tail = np.shape(first)[1:]  # a field's own trailing axes
        blocks = [np.reshape(p[k], (*sizes[:ax], -1, *sizes[ax + 1 :], *tail)) for p in pieces]
        out[k] = np.concatenate(blocks, axis=ax).reshape(total, *tail)
    return out


__all__ = [
    "Progress",
    "checked",
    "cut",
    "grid_in_parts",
    "parts",
    "points_in_parts",
    "reporting",
    "run_in_parts",
]

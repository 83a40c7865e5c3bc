"""The notebook views of the results (``_repr_html_``): a compact table of the key numbers
and, where a picture says more, a small inline SVG -- the mode timeline of a motion, a slice
of a map. Plain HTML strings made with numpy alone (no matplotlib), read from the results'
documented attributes, so every result module can use them without importing another.
"""

from __future__ import annotations

import html
import math
from collections.abc import Sequence
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.palette import JARM_COLOR, MODE_COLORS, OTHER_COLOR

#: The most cells a map slice shows along a side (its SVG stays under ~250 kB).
MAX_CELLS = 60

#: One row of a table: a label and its value, already formatted (with its unit).
Row = tuple[str, str]


def num(x: float, digits: int = 6) -> str:
    """``x`` to ``digits`` significant digits ("-" for NaN)."""
    return "-" if math.isnan(x) else f"{x:.{digits}g}"


def deg(x: float) -> str:
    """An angle in rad shown in degrees."""
    return "-" if math.isnan(x) else f"{math.degrees(x):.6g} deg"


def span(values: NDArray[np.float64], unit: str = "") -> str:
    """A 1-D axis as "[first, last] unit (n values)"."""
    if values.size == 0:
        return "empty"
    if values.size == 1:
        return f"{num(float(values[0]))}{unit}"
    return f"[{num(float(values[0]))}, {num(float(values[-1]))}]{unit} ({values.size} values)"


def card(title: str, rows: Sequence[Row], picture: str = "") -> str:
    """The view of one result: its title, a two-column table, and a picture if any."""
    cells = "".join(
        f"<tr><th style='text-align:left;padding-right:1em'>{html.escape(k)}</th>"
        f"<td style='text-align:left'>{html.escape(v)}</td></tr>"
        for k, v in rows
    )
    return (
        "<div class='eccjump-result'>"
        f"<strong>{html.escape(title)}</strong>"
        f"<table style='margin:0.3em 0'>{cells}</table>{picture}</div>"
    )


def timeline(t: NDArray[np.float64], mode: NDArray[Any], modes: Sequence[str]) -> str:
    """The modes of a run as coloured bars over time, with a legend (SVG, 400 × 36)."""
    if t.size < 2 or not t[-1] > t[0]:
        return ""
    width, scale = 400.0, 400.0 / float(t[-1] - t[0])
    change = np.flatnonzero(np.diff(mode)) + 1
    starts, ends = np.r_[0, change], np.r_[change, t.size - 1]
    bars = "".join(
        f"<rect x='{(t[i] - t[0]) * scale:.2f}' y='0' "
        f"width='{max((t[j] - t[i]) * scale, 0.5):.2f}' height='14' "
        f"fill='{MODE_COLORS.get(modes[int(mode[i])], '#999')}'/>"
        for i, j in zip(starts, ends, strict=True)
    )
    legend = "".join(
        f"<rect x='{80 * k}' y='20' width='10' height='10' fill='{c}'/>"
        f"<text x='{80 * k + 14}' y='29' font-size='11'>{m}</text>"
        for k, (m, c) in enumerate(MODE_COLORS.items())
    )
    end = f"<text x='{width}' y='29' font-size='11' text-anchor='end'>t = {num(t[-1], 4)}</text>"
    return (
        f"<svg width='{width:.0f}' height='36' role='img' aria-label='mode timeline'>"
        f"{bars}{legend}{end}</svg>"
    )


def jarm_slice(is_jarm: NDArray[np.bool_], caption: str) -> str:
    """A 2-D boolean slice (rows: α, bottom to top; columns: χ) as an SVG of cells,
    at most :data:`MAX_CELLS` a side (a larger slice is shown at every k-th point)."""
    step = max(1, math.ceil(max(is_jarm.shape) / MAX_CELLS))
    is_jarm = is_jarm[::step, ::step]
    rows, cols = is_jarm.shape
    if rows == 0 or cols == 0:
        return ""
    cell = max(2.0, min(12.0, 240.0 / max(rows, cols)))
    rects = "".join(
        f"<rect x='{j * cell:.1f}' y='{(rows - 1 - i) * cell:.1f}' width='{cell:.1f}' "
        f"height='{cell:.1f}' fill='{JARM_COLOR if is_jarm[i, j] else OTHER_COLOR}'/>"
        for i in range(rows)
        for j in range(cols)
    )
    w, h = cols * cell, rows * cell
    return (
        f"<div><svg width='{w:.0f}' height='{h:.0f}' role='img' aria-label='{html.escape(caption)}'"
        f">{rects}</svg><br><small>{html.escape(caption)}</small></div>"
    )


def best_slice(is_jarm: NDArray[np.bool_]) -> tuple[int, NDArray[np.bool_]]:
    """The index along the last axis with the most JARM points of an (α, χ, k) map, and
    that (α, χ) slice."""
    k = int(np.argmax(is_jarm.sum(axis=(0, 1)))) if is_jarm.size else 0
    return k, is_jarm[:, :, k]


__all__ = [
    "MAX_CELLS",
    "MODE_COLORS",
    "Row",
    "best_slice",
    "card",
    "deg",
    "jarm_slice",
    "num",
    "span",
    "timeline",
]

"""A tracked experiment: the frame times and the lab positions of the axle C and of a marker
M fixed on the body, read from a CSV file or from Tracker's exported data table.

Lab frame: x to the right, y up, in metres (pixel tracks are divided by ``scale`` [px/m];
image rows that grow downwards must be flipped before, as Tracker does). Checks: every value
finite, times strictly increasing, at least :data:`MIN_FRAMES` frames; each failure is a
``ValueError`` naming the column or parameter.
"""

from __future__ import annotations

import io
import math
import os
from dataclasses import dataclass
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from eccjump._checks import real, real_array

#: The CSV columns, in this order of meaning (the header may list them in any order).
COLUMNS = ("t", "xc", "yc", "xm", "ym")
#: The fewest frames that can be analysed (the smoothing window and a few frames of each
#: phase need them).
MIN_FRAMES = 12


@dataclass(frozen=True, eq=False)
class Track:
    """Frame times ``t`` [s] and the lab positions ``c`` (axle) and ``m`` (marker), each of
    shape (n, 2) [m]; ``source`` says where they came from."""

    t: NDArray[np.float64]
    c: NDArray[np.float64]
    m: NDArray[np.float64]
    source: str = "arrays"

    @property
    def n(self) -> int:
        return int(self.t.size)

    @property
    def dt(self) -> float:
        """The median frame interval [s]."""
        return float(np.median(np.diff(self.t)))

    def __repr__(self) -> str:
        return (
            f"Track({self.n} frames, t = {self.t[0]:.4g} ... {self.t[-1]:.4g} s, "
            f"{1 / self.dt:.4g} fps, from {self.source})"
        )


def track_from_arrays(
    t: object,
    xc: object,
    yc: object,
    xm: object,
    ym: object,
    *,
    scale: float | None = None,
    source: str = "arrays",
) -> Track:
    """A :class:`Track` from five 1-D arrays of equal length (positions in metres, or in
    pixels with ``scale`` [px/m])."""
    cols = {name: real_array(name, v) for name, v in zip(COLUMNS, (t, xc, yc, xm, ym), strict=True)}
    for name, v in cols.items():
        if v.ndim != 1:
            raise ValueError(f"{name}: a track column must be 1-D, got shape {v.shape}")
    n = {v.size for v in cols.values()}
    if len(n) != 1:
        sizes = ", ".join(f"{k} {v.size}" for k, v in cols.items())
        raise ValueError(f"track columns differ in length: {sizes}")
    if cols["t"].size < MIN_FRAMES:
        raise ValueError(
            f"t: a track needs at least {MIN_FRAMES} frames, got {cols['t'].size} (too few frames)"
        )
    for name, v in cols.items():
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ValueError(
                f"{name}: value {v[bad[0]]} at frame {bad[0]} ({bad.size} non-finite in all)"
            )
    steps = np.diff(cols["t"])
    if (steps <= 0).any():
        k = int(np.flatnonzero(steps <= 0)[0])
        what = "repeated" if steps[k] == 0 else "unsorted"
        raise ValueError(
            f"t: times must increase strictly; {what} at frame {k + 1} "
            f"(t = {cols['t'][k]:.6g}, then {cols['t'][k + 1]:.6g} s)"
        )
    factor = 1.0
    if scale is not None:
        s = real("scale", scale)
        if not (math.isfinite(s) and s > 0):
            raise ValueError(f"scale must be a finite number of pixels per metre > 0, got {s:g}")
        factor = 1.0 / s
    c = np.column_stack([cols["xc"], cols["yc"]]) * factor
    m = np.column_stack([cols["xm"], cols["ym"]]) * factor
    return Track(t=cols["t"], c=c, m=m, source=source)


def read_track(
    source: str | os.PathLike[str], *, scale: float | None = None, fmt: str = "auto"
) -> Track:
    """Read a track file: ``fmt="csv"`` (a header naming ``t,xc,yc,xm,ym`` in any order,
    comma-separated; extra columns are ignored), ``"tracker"`` (Tracker's exported data
    table, see :func:`parse_tracker`) or ``"auto"`` (Tracker's if the text holds a tab)."""
    if not isinstance(source, str | os.PathLike):
        raise TypeError(f"source must be a path, not {type(source).__name__}")
    if fmt not in ("auto", "csv", "tracker"):
        raise ValueError(f"fmt must be 'auto', 'csv' or 'tracker', got {fmt!r}")
    path = Path(source)
    try:
        text = path.read_text(encoding="utf-8-sig")
    except OSError as err:
        raise ValueError(f"source: cannot read {str(path)[:80]}: {err.strerror}") from None
    except UnicodeDecodeError:
        raise ValueError(f"source: {str(path)[:80]} is not a text file") from None
    if fmt == "tracker" or (fmt == "auto" and "\t" in text):
        cols = parse_tracker(text)
    else:
        cols = parse_csv(text)
    return track_from_arrays(*(cols[k] for k in COLUMNS), scale=scale, source=path.name)


def parse_csv(text: str) -> dict[str, NDArray[np.float64]]:
    """The five columns of a comma-separated table whose first line names them."""
    lines = [ln for ln in text.splitlines() if ln.strip() and not ln.lstrip().startswith("#")]
    if not lines:
        raise ValueError("track file is empty: a header t,xc,yc,xm,ym and rows are due")
    header = [h.strip().lower() for h in lines[0].split(",")]
    missing = [k for k in COLUMNS if k not in header]
    if missing:
        raise ValueError(
            f"missing column(s) {', '.join(missing)}: the header must name t,xc,yc,xm,ym "
            f"(found {','.join(header)[:60]})"
        )
    return _columns(lines[1:], header, ",")


def parse_tracker(text: str) -> dict[str, NDArray[np.float64]]:
    """Tracker's exported data table (File | Export | Data, tab-delimited) of two point
    tracks, the axle first and then the marker::

        #multi:
        <tab>axle<tab><tab>marker<tab>
        t<tab>x<tab>y<tab>x<tab>y
        0.0<tab>0.1021<tab>0.4410<tab>0.1230<tab>0.4583
        ...

    A single-track export (the name line, then ``t x y``) is refused: both points are due.
    Rows where Tracker left a position empty (frames not marked) at the start or the end are
    dropped; an empty cell inside the track is an error naming its column. Times and
    positions in Tracker's world units (set the scale to metres, the x axis horizontal)."""
    lines = [ln.rstrip("\r\n") for ln in text.splitlines() if ln.strip()]
    if lines and lines[0].strip().lower().startswith("#multi"):
        lines = lines[1:]
    head = next((i for i, ln in enumerate(lines) if ln.split("\t")[0].strip() == "t"), None)
    if head is None:
        raise ValueError("missing column t: no header line starting with 't' in the Tracker table")
    names = [c.strip().lower() for c in lines[head].split("\t")]
    positions = [i for i, c in enumerate(names) if c in ("x", "y")]
    if len(positions) < 4 or names[positions[0]] != "x" or names[positions[1]] != "y":
        raise ValueError(
            "missing columns xm, ym: the Tracker table needs x and y of two tracks "
            "(the axle, then the marker)"
        )
    rows = []
    for ln in lines[head + 1 :]:
        cells = ln.split("\t")
        rows.append([_cell(cells, i) for i in (0, *positions[:4])])
    data = np.array(rows, dtype=np.float64).reshape(-1, 5)
    full = np.isfinite(data).all(axis=1)
    if full.any():  # frames not marked before the first and after the last full row
        first, last = np.flatnonzero(full)[[0, -1]]
        data = data[first : last + 1]
    return {k: data[:, j] for j, k in enumerate(COLUMNS)}


def _cell(cells: list[str], i: int) -> float:
    text = cells[i].strip() if i < len(cells) else ""
    if not text:
        return math.nan
    try:
        return float(text)
    except ValueError:
        raise ValueError(f"track: {text[:20]!r} is not a number (column {i + 1})") from None


def _columns(rows: list[str], header: list[str], sep: str) -> dict[str, NDArray[np.float64]]:
    index = {k: header.index(k) for k in COLUMNS}
    out = {k: np.empty(len(rows)) for k in COLUMNS}
    for r, ln in enumerate(rows):
        cells = ln.split(sep)
        for k, i in index.items():
            text = cells[i].strip() if i < len(cells) else ""
            try:
                out[k][r] = float(text) if text else math.nan
            except ValueError:
                raise ValueError(f"{k}: {text[:20]!r} at row {r + 1} is not a number") from None
    return out


def write_csv(track: Track, target: io.TextIOBase | None = None, *, scale: float = 1.0) -> str:
    """The track as CSV text (positions times ``scale``: pixels if ``scale`` is px/m); written
    to ``target`` too if given."""
    lines = ["t,xc,yc,xm,ym"]
    digits = 2 if scale > 100 else 7
    for i in range(track.n):
        xs = (*track.c[i] * scale, *track.m[i] * scale)
        lines.append(f"{track.t[i]:.6f}," + ",".join(f"{x:.{digits}f}" for x in xs))
    text = "\n".join(lines) + "\n"
    if target is not None:
        target.write(text)
    return text

"""A tracked experiment: the frame times and the lab positions of the axle C and of a marker
M fixed on the body, read from a CSV file or from Tracker's exported data table.

Lab frame: x to the right, y up, in metres (pixel tracks are divided by ``scale`` [px/m];
image rows that grow downwards must be flipped before, as Tracker does). Checks: every value
finite, times strictly increasing, at least :data:`MIN_FRAMES` frames; each failure is a
``ValueError`` naming the column or parameter.
"""

from __future__ import annotations

import csv
import io
import math
import os
from collections.abc import Iterator
from dataclasses import dataclass, fields, replace
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import real_array, short
from eccjump._base.userfiles import read_text
from eccjump.studies.experiment.inputs import (
    MAX_POSITION,
    MAX_SECONDS,
    MIN_FRAME_INTERVAL,
    in_range,
)

#: The CSV columns, in this order of meaning (the header may list them in any order).
COLUMNS = ("t", "xc", "yc", "xm", "ym")
#: The fewest frames that can be analysed (the smoothing window and a few frames of each
#: phase need them).
MIN_FRAMES = 12
#: The most frames a track may hold (docs/limits.md): analyze took 8 s (14 s with the mu_k
#: profile) for 10^4 frames, 74 s (135 s) for 2 x 10^4: the lift-off timing in events.py
#: grows with the square of a flight's frames.
MAX_FRAMES = 10_000
#: The most lines of a track file (rows, blank and comment lines): skipping a million blank
#: lines would take seconds.
MAX_LINES = 100_000
#: The longest line of a track file [characters]: a row of Tracker's widest exports fits many
#: times; a longer one is refused before it is split into cells.
MAX_LINE = 2**16
#: The cell delimiters of a CSV track: whichever splits its header into the five names.
DELIMITERS = (",", ";", "\t")


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


def first_frames(track: Track, n: int) -> Track:
    """The first ``n`` frames of ``track`` (of any Track subclass: every per-frame array is
    cut, the rest kept)."""
    return _frames(track, slice(None, n))


def frames_from(track: Track, k: int) -> Track:
    """``track`` from its frame ``k`` on (as :func:`first_frames`)."""
    return _frames(track, slice(k, None))


def _frames(track: Track, frames: slice) -> Track:
    cut = {
        f.name: getattr(track, f.name)[frames]
        for f in fields(track)
        if isinstance(getattr(track, f.name), np.ndarray)
        and getattr(track, f.name).shape[:1] == (track.n,)
    }
    return replace(track, **cut)


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
    pixels with ``scale`` [px/m]). The bounds (``eccjump.studies.experiment.inputs``): ``scale`` in
    [1, 1e9] px/m, every coordinate within 10^6 m, the duration at most 1000 s, the median
    frame interval at least 1e-7 s."""
    cols = {name: real_array(name, v) for name, v in zip(COLUMNS, (t, xc, yc, xm, ym), strict=True)}
    for name, v in cols.items():
        if v.ndim != 1:
            raise ValueError(f"{name}: a track column must be 1-D, got shape {v.shape}")
    n = {v.size for v in cols.values()}
    if len(n) != 1:
        sizes = ", ".join(f"{k} {v.size}" for k, v in cols.items())
        raise ValueError(f"track columns differ in length: {sizes}")
    if not MIN_FRAMES <= cols["t"].size <= MAX_FRAMES:
        raise ValueError(
            f"t: a track needs {MIN_FRAMES} to {MAX_FRAMES:,} frames, got {cols['t'].size:,}"
        )
    for name, v in cols.items():
        bad = np.flatnonzero(~np.isfinite(v))
        if bad.size:
            raise ValueError(
                f"{name}: value {v[bad[0]]} at frame {bad[0]} ({bad.size} non-finite in all)"
            )
    _check_times(cols["t"])
    factor = 1.0 if scale is None else 1.0 / in_range("scale", scale)
    for name in COLUMNS[1:]:
        cols[name] = cols[name] * factor
        far = np.flatnonzero(np.abs(cols[name]) > MAX_POSITION)
        if far.size:
            raise ValueError(
                f"{name}: {short(cols[name][far[0]])} m at frame {far[0]} is beyond the "
                f"{MAX_POSITION:g} m a lab track spans (a track in pixels needs scale)"
            )
    c = np.column_stack([cols["xc"], cols["yc"]])
    m = np.column_stack([cols["xm"], cols["ym"]])
    return Track(t=cols["t"], c=c, m=m, source=source)


def _check_times(t: NDArray[np.float64]) -> None:
    """Strictly increasing times, a median frame interval of at least MIN_FRAME_INTERVAL
    and a duration of at most MAX_SECONDS (errors naming t)."""
    steps = np.diff(t)
    if (steps <= 0).any():
        k = int(np.flatnonzero(steps <= 0)[0])
        what = "repeated" if steps[k] == 0 else "unsorted"
        raise ValueError(
            f"t: times must increase strictly; {what} at frame {k + 1} "
            f"(t = {t[k]:.6g}, then {t[k + 1]:.6g} s)"
        )
    if t[-1] - t[0] > MAX_SECONDS:
        raise ValueError(
            f"t: the track lasts {short(t[-1] - t[0])} s, more than the {MAX_SECONDS:g} s "
            "allowed (times in seconds?)"
        )
    dt = float(np.median(steps))
    if dt < MIN_FRAME_INTERVAL:
        raise ValueError(
            f"t: a median frame interval of {dt:.3g} s, less than {MIN_FRAME_INTERVAL:g} s "
            "(10 million fps; times in seconds?)"
        )


def read_track(
    source: str | os.PathLike[str], *, scale: float | None = None, fmt: str = "auto"
) -> Track:
    """Read a track file (``"-"``: the standard input): ``fmt="csv"`` (a header naming
    ``t,xc,yc,xm,ym`` in any order, see :func:`parse_csv`), ``"tracker"`` (Tracker's
    exported data table, see :func:`parse_tracker`) or ``"auto"`` (a CSV if a line names
    the five columns, else Tracker's if the text holds a tab). The file passes the guard of
    every user's file (``eccjump._base.userfiles``: a regular file of at most 64 MiB)."""
    return load_track(source, scale=scale, fmt=fmt, name="source")


def load_track(source: object, *, scale: float | None, fmt: str, name: str) -> Track:
    """:func:`read_track`, whose messages name the caller's parameter ``name``."""
    if not isinstance(source, str | os.PathLike) or isinstance(os.fspath(source), bytes):
        raise TypeError(f"{name} must be a path, not {type(source).__name__}")
    if fmt not in ("auto", "csv", "tracker"):
        raise ValueError(f"fmt must be 'auto', 'csv' or 'tracker', got {fmt!r}")
    text = read_text(name, source, stdin=True)
    if fmt == "csv" or (fmt == "auto" and _csv_header(text, name) is not None):
        cols = parse_csv(text, name=name)
    elif fmt == "tracker" or "\t" in text:
        cols = parse_tracker(text, name=name)
    else:
        cols = parse_csv(text, name=name)
    label = "standard input" if source == "-" else Path(source).name
    return track_from_arrays(*(cols[k] for k in COLUMNS), scale=scale, source=label)


def parse_csv(text: str, *, name: str = "track") -> dict[str, NDArray[np.float64]]:
    """The five columns of a table whose first line (after blank and ``#`` lines) names
    them: cells separated by commas, semicolons or tabs (the one that splits that header
    into the five names), optionally quoted (``"``). With semicolons or tabs a comma in a
    number is its decimal separator (``0,25``). Every row must have as many cells as the
    header; at most :data:`MAX_FRAMES` rows, each at most :data:`MAX_LINE` characters."""
    found = _csv_header(text, name)
    if found is None:
        first = next((ln for _, ln in _lines(text, name) if not _skipped(ln)), None)
        if first is None:
            raise ValueError(f"{name}: the file is empty: a header t,xc,yc,xm,ym and rows are due")
        names = max(
            (_split(first, d) for d in DELIMITERS), key=lambda n: len(set(n) & set(COLUMNS))
        )
        missing = ", ".join(k for k in COLUMNS if k not in names)
        raise ValueError(
            f"missing column(s) {missing}: the header must name t,xc,yc,xm,ym, separated by "
            f"commas, semicolons or tabs (found {' '.join(first.split())[:40]!r})"
        )
    line_no, delimiter, header = found
    rows = _rows(text, line_no, delimiter, len(header), name)
    return _columns(rows, [header.index(k) for k in COLUMNS], delimiter)


def parse_tracker(text: str, *, name: str = "track") -> dict[str, NDArray[np.float64]]:
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
    positions in Tracker's world units (set the scale to metres, the x axis horizontal).
    The rows are read as :func:`parse_csv` reads them (tab-delimited: a comma in a number is
    its decimal separator)."""
    head = next(
        ((i, cells) for i, ln in _lines(text, name) if (cells := _split(ln, "\t"))[0] == "t"),
        None,
    )
    if head is None:
        raise ValueError("missing column t: no header line starting with 't' in the Tracker table")
    line_no, names = head
    positions = [i for i, c in enumerate(names) if c in ("x", "y")]
    if len(positions) < 4 or names[positions[0]] != "x" or names[positions[1]] != "y":
        raise ValueError(
            "missing columns xm, ym: the Tracker table needs x and y of two tracks "
            "(the axle, then the marker)"
        )
    cols = _columns(_rows(text, line_no, "\t", len(names), name), [0, *positions[:4]], "\t")
    data = np.column_stack([cols[k] for k in COLUMNS])
    full = np.isfinite(data).all(axis=1)
    if full.any():  # frames not marked before the first and after the last full row
        first, last = np.flatnonzero(full)[[0, -1]]
        data = data[first : last + 1]
    return {k: data[:, j] for j, k in enumerate(COLUMNS)}


def _lines(text: str, name: str) -> Iterator[tuple[int, str]]:
    """(line number, line) of ``text``, lazily (no list of a million empty lines); more
    than MAX_LINES lines, or a line longer than MAX_LINE characters, is an error naming
    ``name`` (and the line)."""
    sep = "\n" if "\n" in text or "\r" not in text else "\r"  # "\r" alone: old Mac files
    if text.count(sep) > MAX_LINES:
        raise ValueError(
            f"{name}: {text.count(sep):,} lines, more than the {MAX_LINES:,} a track file may have"
        )
    pos, number = 0, 0
    while pos < len(text):
        end = text.find(sep, pos)
        end = len(text) if end < 0 else end
        number += 1
        if end - pos > MAX_LINE:
            raise ValueError(
                f"{name}: line {number} has {end - pos:,} characters, more than the "
                f"{MAX_LINE:,} a row of a track may have"
            )
        yield number, text[pos:end].rstrip("\r")
        pos = end + 1


def _skipped(line: str) -> bool:
    """A blank or a comment (``#``) line."""
    stripped = line.strip()
    return not stripped or stripped.startswith("#")


def _split(line: str, delimiter: str) -> list[str]:
    """The cells of one line (the csv module: quotes, spaces after the delimiter), stripped
    and in lower case."""
    cells = next(csv.reader([line], delimiter=delimiter, skipinitialspace=True), [])
    return [c.strip().lower() for c in cells] or [""]


def _csv_header(text: str, name: str) -> tuple[int, str, list[str]] | None:
    """(line number, delimiter, names) of the header: the first line that is not blank or
    a comment, if one of the delimiters splits it into cells naming every column."""
    for number, line in _lines(text, name):
        if _skipped(line):
            continue
        for delimiter in DELIMITERS:
            names = _split(line, delimiter)
            if all(k in names for k in COLUMNS):
                return number, delimiter, names
        return None
    return None


def _rows(
    text: str, header: int, delimiter: str, width: int, name: str
) -> Iterator[tuple[int, list[str]]]:
    """(line number, cells) of every row after the header line: exactly ``width`` cells
    each, at most MAX_FRAMES rows (errors naming ``name`` and the line)."""
    frames = 0
    for number, line in _lines(text, name):
        if number <= header or _skipped(line):
            continue
        frames += 1
        if frames > MAX_FRAMES:
            raise ValueError(
                f"{name}: more than {MAX_FRAMES:,} frames (rows); analyse a shorter span "
                f"or every n-th frame"
            )
        cells = next(csv.reader([line], delimiter=delimiter, skipinitialspace=True))
        if len(cells) != width:
            raise ValueError(
                f"{name}: line {number} has {len(cells)} cells, the header {width}: every "
                f"row must have the header's"
            )
        yield number, cells


def _columns(
    rows: Iterator[tuple[int, list[str]]], index: list[int], delimiter: str
) -> dict[str, NDArray[np.float64]]:
    """The columns at ``index`` (in the order of COLUMNS) as floats; an empty cell is NaN
    (refused by :func:`track_from_arrays` unless Tracker's ends drop it)."""
    decimal_comma = delimiter != ","
    out: dict[str, list[float]] = {k: [] for k in COLUMNS}
    for number, cells in rows:
        for k, i in zip(COLUMNS, index, strict=True):
            text = cells[i].strip()
            if decimal_comma:
                text = text.replace(",", ".")
            try:
                out[k].append(float(text) if text else math.nan)
            except ValueError:
                raise ValueError(f"{k}: {text[:20]!r} on line {number} is not a number") from None
    return {k: np.array(v, dtype=np.float64) for k, v in out.items()}


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

"""The resumable runner of ``eccjump map``: a map of any kind over (α, χ, km_frac),
computed in chunks along α and written to ``.nc``, ``.zarr`` or ``.npz`` (by suffix).

What it computes comes from the caller, a :class:`Job` (its :class:`~eccjump.maps.kinds.MapKind`,
file attributes and ``compute`` of one chunk; ``eccjump.cli.map_jobs`` has one per kind), so
this layer knows no kind's physics. Its messages name the options of ``eccjump map``.

Ctrl-C stops after the chunk in progress (one Rust call; a second Ctrl-C aborts at once):
a ``.zarr`` map already holds every finished chunk (``alpha_done`` records them) and a
resumed run computes only the missing ones; ``.nc``/``.npz`` are written with what is
finished and the attribute ``complete = 0``; interrupted before any chunk is finished,
nothing is written.

A map is never lost (see :mod:`eccjump.maps.store`): a new ``.zarr`` store is built under a
temporary name next to the output and renamed into place after its first chunk (so that a
resumed run always finds a whole store); a map replacing another replaces it only when it
is finished (or stopped by Ctrl-C), so a failure or a crash keeps the old map. ``.nc``/``.npz``
are written to a temporary file and renamed. A failure leaves no temporary files behind;
those of a killed run are removed by the next run on the same output.
"""

from __future__ import annotations

import os
import signal
import time
from collections.abc import Callable, Mapping
from dataclasses import dataclass
from pathlib import Path
from typing import Any, Protocol

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import MAX_MESSAGE, shown
from eccjump._base.progress import reporting
from eccjump._base.sizes import gib, memory_limit
from eccjump.maps import store
from eccjump.maps.kinds import MapKind
from eccjump.maps.store import ZarrMap, format_of, save
from eccjump.maps.xarray import make_layout

#: Default points per chunk when none is given (a few seconds on a laptop core).
POINTS_PER_CHUNK = 100_000

Axes = tuple[NDArray, NDArray, NDArray]  # alpha [rad], chi, km_frac
#: Where the runner's notes go, one whole line each (``eccjump map``: stderr).
Note = Callable[[str], None]


class Job(Protocol):
    """What a map is made of: its kind, its file attributes (those named in ``matched`` must
    equal a store's to resume it; ``unrecorded``: the value of an option that a store written
    before the option was recorded was made with), one chunk's fields, and the count of
    finished points (``count`` of the fields ``counted``, read back from a resumed store
    too). Optional: ``cost``, the work of a point in JARM classifications (default 1), which
    sizes the default chunk."""

    # Read-only, so that a job may narrow them (``counted = ("is_jarm", "n")``).
    @property
    def kind(self) -> MapKind: ...
    @property
    def attrs(self) -> Mapping[str, Any]: ...
    @property
    def matched(self) -> tuple[str, ...]: ...
    @property
    def unrecorded(self) -> Mapping[str, Any]: ...
    @property
    def counted(self) -> tuple[str, ...]: ...

    def compute(
        self, alpha: NDArray, chi: NDArray, km: NDArray, threads: int
    ) -> dict[str, NDArray]: ...

    def count(self, part: dict[str, NDArray]) -> None: ...


@dataclass(frozen=True)
class Options:
    """How to run: ``chunk`` α slices per chunk (None: about :data:`POINTS_PER_CHUNK`
    points), ``resume`` a ``.zarr`` map, ``overwrite`` an existing output, a progress bar
    on stderr, and ``stop_after`` (a testing aid: behave as if interrupted after that many
    chunks)."""

    threads: int = 0
    chunk: int | None = None
    resume: bool = False
    overwrite: bool = False
    progress: bool = True
    stop_after: int | None = None


@dataclass(frozen=True)
class Outcome:
    """What a run did: ``written`` False when it was interrupted before a chunk was finished
    (nothing written; ``replacing``: an existing output was kept); ``done`` α slices
    finished of ``shape[0]``."""

    path: Path
    fmt: str
    shape: tuple[int, int, int]
    computed: int
    seconds: float
    complete: bool
    interrupted: bool
    done: int
    written: bool = True
    replacing: bool = False


class Failed(Exception):
    """The map could not be written or read (I/O error, out of memory): exit status 1."""


def one_line(text: str) -> str:
    """``text`` as one line that fits an ``eccjump: error:`` line of MAX_MESSAGE."""
    text = " ".join(text.split())
    limit = MAX_MESSAGE - len("eccjump: error: ")
    return text if len(text) <= limit else text[: limit - 3] + "..."


def why(err: BaseException) -> str:
    """An OSError or MemoryError as a short reason."""
    if isinstance(err, MemoryError):
        return f"out of memory ({err})" if str(err) else "out of memory"
    if isinstance(err, OSError) and err.strerror:
        name = err.filename2 or err.filename
        return f"{err.strerror}: {shown(name)}" if name else err.strerror
    return str(err) or type(err).__name__


class Interrupt:
    """SIGINT sets a flag checked between chunks; a second SIGINT raises at once."""

    def __init__(self, note: Note) -> None:
        self.requested = False
        self._note = note
        self._old: Any = None

    def _handler(self, signum: int, frame: Any) -> None:
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True
        self._note("\neccjump: interrupt: finishing the chunk in progress (Ctrl-C again to abort)")

    def __enter__(self) -> Interrupt:
        try:
            self._old = signal.signal(signal.SIGINT, self._handler)
        except ValueError:  # not the main thread: no handler, KeyboardInterrupt as usual
            self._old = None
        return self

    def __exit__(self, *exc: object) -> None:
        if self._old is not None:
            signal.signal(signal.SIGINT, self._old)


def check_memory(points: int, fmt: str, total: int, kind: MapKind) -> None:
    """Fail early (exit 1) if the fields of ``points`` points cannot fit in the memory this
    process can have, rather than have numpy fill it and the system kill the process."""
    need = points * kind.bytes_per_point()
    have = memory_limit()  # the library's limit (eccjump._base.sizes), the same for every call
    if have is not None and need > have:
        how = "a smaller --chunk or grid" if fmt == "zarr" else ".zarr (written chunk by chunk)"
        held = "a chunk of" if fmt == "zarr" else "the whole map,"
        raise Failed(
            f"out of memory: {held} {points} points needs {gib(need)}, the machine has "
            f"{gib(have)} available; use {how} (grid of {total} points)"
        )


def run(path: Path, axes: Axes, job: Job, options: Options, note: Note) -> Outcome:
    """Compute the map of ``job`` on the grid ``axes`` into ``path``, chunk by chunk.

    Bad input (the core's check of every option on one point, the output's directory and
    name, a store that cannot be resumed, an existing output) is a ValueError before anything
    is written; a map that cannot be written is :class:`Failed`; a second Ctrl-C is
    KeyboardInterrupt (a ``.zarr`` map keeps its finished chunks)."""
    fmt = format_of(path)
    alpha, chi, km = axes
    # Let the core check every option on one point before anything is written (an invalid
    # mu_s, theta0, tolerance or thread count is a one-line error, not a map of INVALID).
    job.compute(alpha[:1], chi[:1], km[:1], options.threads)
    # A job may say what a point costs, in JARM classifications (P(JARM) under tolerances:
    # its samples per point), so that the default chunk holds about the same work.
    per_slice = max(1, chi.size * km.size * int(getattr(job, "cost", 1)))
    chunk = options.chunk or max(1, round(POINTS_PER_CHUNK / per_slice))
    chunk = min(chunk, alpha.size)
    held = shape_points = alpha.size * chi.size * km.size
    if fmt == "zarr":  # one chunk in memory at a time
        held = chunk * chi.size * km.size
    check_memory(held, fmt, shape_points, job.kind)
    _check_output(path, fmt, options, note)
    # The handler goes first: a Ctrl-C while the store is created stops before the first chunk.
    with Interrupt(note) as stop:
        try:
            return _write(path, fmt, axes, job, chunk, options, stop, note)
        except (OSError, MemoryError) as err:
            raise Failed(f"cannot write {path}: {why(err)}") from err


def _check_output(path: Path, fmt: str, options: Options, note: Note) -> None:
    """The output can be written (or resumed), and what a killed run left there is gone."""
    try:
        store.check_parent(path)
        store.check_name(path)
    except OSError as err:
        raise ValueError(one_line(f"cannot write {path}: {why(err)}")) from err
    except ValueError as err:
        raise ValueError(f"-o {err}") from None
    try:
        for text in store.recover(path):
            note(f"eccjump: {text}")
    except OSError as err:
        raise Failed(f"cannot clean up after an interrupted write of {path}: {why(err)}") from err
    if options.resume:
        if fmt != "zarr":
            raise ValueError("--resume needs a .zarr map (.nc and .npz are written once)")
        if not path.exists():
            raise ValueError(
                f"--resume: {path} does not exist (a run stopped before its first chunk "
                "leaves nothing to resume; run without --resume)"
            )
    elif os.path.lexists(path):
        try:  # the overwrite policy of every writer (eccjump._base.overwrite)
            store.check_replaceable(
                path, fmt == "zarr", overwrite=options.overwrite, option="--overwrite"
            )
        except ValueError as err:
            raise ValueError(f"-o {err}") from None
        if not options.overwrite:  # even a map: it may be the one to --resume
            hint = " or --resume" if fmt == "zarr" else ""
            raise ValueError(one_line(f"{path} exists; use --overwrite{hint}"))


def _mismatch(store_attrs: dict[str, Any], job: Job, old: Axes, new: Axes) -> list[str]:
    """What differs between a store's options and grid and the job's: one entry each."""
    stored = {k: store_attrs.get(k, job.unrecorded.get(k)) for k in job.matched}
    diffs = [
        f"{k}: store {stored[k]!r}, now {job.attrs[k]!r}"
        for k in job.matched
        if stored[k] != job.attrs[k]
    ]
    for name, a, b in zip(("alpha", "chi", "km_frac"), old, new, strict=True):
        if a.shape != b.shape or a.tobytes() != b.tobytes():
            lo, hi = (
                f"[{x[0]:.6g}, {x[-1]:.6g}] x {x.size}" if x.size else "empty" for x in (a, b)
            )
            diffs.append(f"{name} grid: store {lo}, now {hi}")
    return diffs


def _reopen(path: Path, job: Job, axes: Axes) -> ZarrMap:
    """The store at ``path`` to resume, once it is known to be a map of the same kind, the
    same options and the same grid (ValueError saying what differs); its derived coordinates
    are written again. Whatever else its damage raises is a ValueError naming it."""
    try:
        zmap = ZarrMap(path)
        if zmap.kind != job.kind:
            raise ValueError(
                f"{shown(path)} holds a {zmap.kind.name} map, not a {job.kind.name} map (--kind)"
            )
        stored = (zmap.alpha, zmap.chi, zmap.km_frac)
        diffs = _mismatch(zmap.attrs, job, stored, axes)
        if diffs:
            raise ValueError(f"the options differ from those of {shown(path)}: " + "; ".join(diffs))
        zmap.rewrite_coords()
        return zmap
    except ValueError as err:
        raise ValueError(one_line(f"--resume: {err}")) from None
    except (OSError, MemoryError):
        raise
    except Exception as err:  # zarr's errors on a damaged store are of many types
        what = f"{type(err).__name__}: {err}"
        raise ValueError(one_line(f"--resume: {shown(path)} is damaged ({what})")) from err


def _resume_todo(zmap: ZarrMap, job: Job, path: Path, note: Note) -> list[int]:
    """The chunks to compute: those not marked done, and those marked done that do not read
    back whole and valid (:meth:`ZarrMap.damage`, said in a note). The others are counted."""
    todo = zmap.missing()
    for i in sorted(set(range(zmap.n_chunks)) - set(todo)):
        problem = zmap.damage(i)
        if problem is None:
            job.count(zmap.read(i, job.counted))
            continue
        note(
            one_line(
                f"eccjump: {shown(path)}: chunk {i} is damaged ({problem}); computing it again"
            )
        )
        todo.append(i)
    return sorted(todo)


class _Target:
    """Where the map goes while it is computed, and how it gets to ``path``.

    A new .zarr store is built under a temporary name; a new map is renamed into place once
    its first chunk is done (from then on a crash leaves a resumable store), a map replacing
    an existing one (--overwrite) only at the end, so that a failure keeps the old map.
    .nc/.npz maps are held in memory and written at the end by :func:`store.save` (temporary
    file, then rename). On any failure the temporary store is removed.
    """

    def __init__(self, path: Path, fmt: str, resume: bool) -> None:
        self.path = path
        self.fmt = fmt
        self.tmp = store.temp_sibling(path)
        self.replacing = path.exists() and not resume
        self.zmap: ZarrMap | None = None
        self.in_place = resume

    def publish(self) -> None:
        """Rename the temporary store to ``path`` (replacing the old map if any)."""
        assert self.zmap is not None
        if self.replacing:
            store._step("written")
        store.install(self.tmp, self.path)
        self.in_place = True
        self.zmap = ZarrMap(self.path)
        store._step("published")

    def discard(self) -> None:
        if not self.in_place:
            store.remove(self.tmp)


def _write(
    path: Path,
    fmt: str,
    axes: Axes,
    job: Job,
    chunk: int,
    options: Options,
    stop: Interrupt,
    note: Note,
) -> Outcome:
    alpha, chi, km = axes
    kind, attrs = job.kind, job.attrs
    shape = (alpha.size, chi.size, km.size)
    target = _Target(path, fmt, options.resume)
    fields: dict[str, NDArray] = {}
    done = np.zeros(alpha.size, dtype=bool)
    try:
        if options.resume:
            target.zmap = _reopen(path, job, axes)
            todo = _resume_todo(target.zmap, job, path, note)
            if options.chunk and options.chunk != target.zmap.chunk:
                note(f"eccjump: resuming with the store's chunk of {target.zmap.chunk}")
        elif fmt == "zarr":
            target.zmap = ZarrMap.create(target.tmp, alpha, chi, km, attrs, chunk)
            todo = list(range(target.zmap.n_chunks))
        else:
            fields = {k: np.full(shape, kind.fill[k], dtype=kind.dtypes[k]) for k in kind.fields}
            todo = list(range(-(-alpha.size // chunk)))
        if target.zmap is not None:
            chunk = target.zmap.chunk
        result = _compute(options, target, fields, done, job, axes, chunk, todo, stop)
        computed, seconds, interrupted = result
        if computed == 0 and interrupted and not target.in_place:
            target.discard()
            return Outcome(
                path,
                fmt,
                shape,
                0,
                seconds,
                complete=False,
                interrupted=True,
                done=0,
                written=False,
                replacing=target.replacing,
            )
        if target.zmap is not None:
            target.zmap.finish()
            complete = bool(target.zmap.attrs["complete"])
            n_done = int(target.zmap.alpha_done().sum())
            if not target.in_place:
                target.publish()
        else:
            complete = bool(done.all())
            n_done = int(done.sum())
            lay = make_layout(
                alpha, chi, km, fields, {**attrs, "complete": int(complete)}, done, kind
            )
            save(lay, path)
    except (OSError, MemoryError) as err:
        target.discard()
        kept = ""
        if target.in_place and fmt == "zarr":
            kept = "; its finished chunks are kept, --resume continues it"
        raise Failed(f"cannot write {path}: {why(err)}{kept}") from err
    except BaseException:
        target.discard()
        raise
    return Outcome(
        path, fmt, shape, computed, seconds, complete=complete, interrupted=interrupted, done=n_done
    )


def _compute(
    options: Options,
    target: _Target,
    fields: dict[str, NDArray],
    done: NDArray[np.bool_],
    job: Job,
    axes: Axes,
    chunk: int,
    todo: list[int],
    stop: Interrupt,
) -> tuple[int, float, bool]:
    """Compute the chunks ``todo`` into the target: (points computed, seconds, interrupted)."""
    alpha, chi, km = axes
    todo_points = sum(
        (min((i + 1) * chunk, alpha.size) - i * chunk) * chi.size * km.size for i in todo
    )
    computed = 0
    interrupted = False
    t0 = time.perf_counter()
    with reporting(options.progress) as report:
        if report is not None:
            report(0, todo_points)
        for k, i in enumerate(todo):
            if stop.requested or (options.stop_after is not None and k >= options.stop_after):
                interrupted = True
                break
            i0, i1 = i * chunk, min((i + 1) * chunk, alpha.size)
            part = job.compute(alpha[i0:i1], chi, km, options.threads)
            if target.zmap is not None:
                target.zmap.write(i, part)
                if not target.in_place and not target.replacing:
                    target.publish()  # a new map: resumable from its first chunk on
            else:
                for f in job.kind.fields:
                    fields[f][i0:i1] = part[f]
                done[i0:i1] = True
            job.count(part)
            size = part[job.kind.fields[0]].size
            computed += size
            if report is not None:
                report(computed, todo_points)
    return computed, time.perf_counter() - t0, interrupted

"""``eccjump map``: the JARM region over (alpha, chi, k_m), computed in chunks along alpha and
written to ``.nc``, ``.zarr`` or ``.npz`` (by suffix).

Ctrl-C stops after the chunk in progress (one Rust call; a second Ctrl-C aborts at once):
a ``.zarr`` map already holds every finished chunk (``alpha_done`` records them) and
``--resume`` computes only the missing ones; ``.nc``/``.npz`` are written with what is
finished and the attribute ``complete = 0``; interrupted before any chunk is finished,
nothing is written. Exit status 0 when complete, 130 when interrupted, 2 on bad input
(including an output whose directory does not exist, or a --resume of a store that is not
an eccjump map), 1 when the map cannot be written (I/O error, disk full, out of memory):
one ``eccjump: error:`` line on stderr.

A map is never lost (see :mod:`eccjump.store`): a new ``.zarr`` store is built under a
temporary name next to the output and renamed into place after its first chunk (so that
``--resume`` always finds a whole store); with ``--overwrite`` the new map replaces the old
one only when it is finished (or stopped by Ctrl-C), so a failure or a crash keeps the old
map. ``.nc``/``.npz`` are written to a temporary file and renamed. A failure leaves no
temporary files behind; those of a killed run are removed by the next run on the same output.
"""

from __future__ import annotations

import argparse
import math
import os
import signal
import sys
import time
from pathlib import Path
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import U32_MAX, short
from eccjump._base.sizes import gib, memory_limit
from eccjump.cli import map_jobs
from eccjump.cli._args import add_integrator, int_at_least, int_in
from eccjump.cli._output import check_output, figure_suffixes
from eccjump.cli.map_jobs import Job
from eccjump.maps import store
from eccjump.maps.check import MAX_MESSAGE, shown
from eccjump.maps.kinds import MapKind
from eccjump.maps.store import ZarrMap, format_of, save
from eccjump.maps.xarray import make_layout

#: Default points per chunk when --chunk is not given (a few seconds on a laptop core).
POINTS_PER_CHUNK = 100_000
#: Most points along one axis of the grid (--grid, --n-alpha, --n-chi, --n-km-frac).
MAX_AXIS_POINTS = 1_000_000


def _axis_points(text: str) -> int:
    """The type of the grid options: an integer in [1, MAX_AXIS_POINTS] (a larger one would
    only fill the memory before anything is computed)."""
    value = int(text)
    if not 1 <= value <= MAX_AXIS_POINTS:
        raise argparse.ArgumentTypeError(
            f"{short(value)} is outside the allowed range [1, {MAX_AXIS_POINTS}]"
        )
    return value


_axis_points.__name__ = "integer"


def _line(text: str) -> str:
    """``text`` as one line that fits an ``eccjump: error:`` line of MAX_MESSAGE."""
    text = " ".join(text.split())
    limit = MAX_MESSAGE - len("eccjump: error: ")
    return text if len(text) <= limit else text[: limit - 3] + "..."


def _range(lo: float, hi: float, name: str, lo_ok: float, hi_ok: float) -> None:
    if not (lo_ok <= lo <= hi <= hi_ok):
        raise ValueError(
            f"{name} range [{lo:g}, {hi:g}] must satisfy {lo_ok:g} <= min <= max <= {hi_ok:g}"
        )


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "map",
        help="map the JARM region (or the full motion) over (alpha, chi, km) to .nc, .zarr or .npz",
        description="Classify every point of the grid alpha x chi x km_frac (km = km_frac "
        "(1 - chi)) as JARM or not (--kind jarm), or follow its full motion to the first "
        "landing (--kind motion), in chunks along alpha, and write all result fields. "
        "Ctrl-C keeps the finished chunks; a .zarr map can be resumed with --resume.",
    )
    p.add_argument(
        "--kind",
        choices=("jarm", "motion"),
        default="jarm",
        help="jarm: the JARM classification (default); motion: the full motion to the first "
        "landing (sequence of modes, lift-off, flight, landing)",
    )
    p.add_argument("--mu-s", type=float, required=True, help="static friction coefficient")
    p.add_argument(
        "--n",
        type=int_in(1, U32_MAX),
        default=None,
        help="turn of the jump (default: the first jump; --kind jarm)",
    )
    p.add_argument("-o", "--output", required=True, help="output file: .nc, .zarr or .npz")
    p.add_argument(
        "--figure", default=None, help="also draw the map to this image (needs eccjump[plot])"
    )
    g = p.add_argument_group("grid (end points included)")
    g.add_argument("--grid", type=_axis_points, default=50, help="points per axis (default 50)")
    g.add_argument("--n-alpha", type=_axis_points, help="points along alpha (default --grid)")
    g.add_argument("--n-chi", type=_axis_points, help="points along chi (default --grid)")
    g.add_argument("--n-km-frac", type=_axis_points, help="points along km_frac (default --grid)")
    g.add_argument("--alpha-min", type=float, default=0.0, help="[deg] (default 0)")
    g.add_argument("--alpha-max", type=float, default=90.0, help="[deg] (default 90)")
    g.add_argument("--chi-min", type=float, default=0.0, help="(default 0)")
    g.add_argument(
        "--chi-max", type=float, default=None, help="(default 1; 0.99 for --kind motion)"
    )
    g.add_argument(
        "--km-frac-min",
        type=float,
        default=None,
        help="the fraction km/(1-chi) (default 0; 0.01 for --kind motion; --km is the body's "
        "k_m elsewhere)",
    )
    g.add_argument("--km-frac-max", type=float, default=1.0, help="km/(1-chi) (default 1)")
    m = p.add_argument_group("model")
    # The options of one kind default to None here: map_jobs.kind_options tells given from
    # not given, refuses those of the other kind and puts in the defaults.
    m.add_argument(
        "--route",
        choices=("closed-form", "ode"),
        default=None,
        help="closed forms with a rigorous scan (default) or the integrator (--kind jarm)",
    )
    m.add_argument(
        "--rule", choices=("paper", "normal_force"), default="paper", help="lift-off rule"
    )
    m.add_argument("--theta0", type=float, default=0.0, help="initial angle [deg]")
    m.add_argument(
        "--omega0", type=float, default=0.0, help="initial angular velocity [sqrt(g/R) rad]"
    )
    m.add_argument("--rtol", type=float, default=1e-10, help="integrator rtol (--route ode)")
    m.add_argument("--atol", type=float, default=1e-12, help="integrator atol (--route ode)")
    add_integrator(m, " (--route ode, --kind motion)")
    m.add_argument(
        "--max-turns",
        type=int_in(1, map_jobs.MAX_TURNS),
        default=None,
        help=f"cap of the search, 1 ... {map_jobs.MAX_TURNS} turns (default 10000; --kind jarm)",
    )
    m.add_argument(
        "--stop-at-slip",
        action="store_true",
        default=None,
        help="paper rule: stop at the first slip (reason slip), not telling slip_before from "
        "slip_at_jump; same is_jarm, faster (--kind jarm)",
    )
    k = p.add_argument_group("full motion (--kind motion)")
    k.add_argument("--mu-k", type=float, default=None, help="kinetic friction (default mu_s)")
    k.add_argument(
        "--restitution", type=float, default=None, help="Stronge's coefficient e (default 0)"
    )
    k.add_argument("--t-max", type=float, default=None, help="end time of each run (default 100)")
    k.add_argument(
        "--max-transitions",
        type=int_at_least(1),
        default=None,
        help="transitions before the first landing (default 100, as simulate)",
    )
    r = p.add_argument_group("run")
    r.add_argument("--threads", type=int, default=0, help="threads (0 = one per core)")
    r.add_argument(
        "--chunk",
        type=int_at_least(1),
        default=None,
        help=f"alpha slices per chunk (default: about {POINTS_PER_CHUNK} points)",
    )
    r.add_argument(
        "--resume", action="store_true", help="continue an interrupted .zarr map (same options)"
    )
    r.add_argument("--overwrite", action="store_true", help="replace an existing output")
    r.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    # Testing aid: behave as if interrupted after K chunks.
    r.add_argument("--stop-after", type=int, default=None, help=argparse.SUPPRESS)
    p.set_defaults(func=_cmd_map)


class _Interrupt:
    """SIGINT sets a flag checked between chunks; a second SIGINT raises at once."""

    def __init__(self) -> None:
        self.requested = False
        self._old: Any = None

    def _handler(self, signum: int, frame: Any) -> None:
        if self.requested:
            raise KeyboardInterrupt
        self.requested = True
        print(
            "\neccjump: interrupt: finishing the chunk in progress (Ctrl-C again to abort)",
            file=sys.stderr,
        )

    def __enter__(self) -> _Interrupt:
        try:
            self._old = signal.signal(signal.SIGINT, self._handler)
        except ValueError:  # not the main thread: no handler, KeyboardInterrupt as usual
            self._old = None
        return self

    def __exit__(self, *exc: object) -> None:
        if self._old is not None:
            signal.signal(signal.SIGINT, self._old)


#: The default ends of the chi and km_frac axes that differ by kind: the full motion needs
#: k_m > 0 (simulate), so its default grid leaves out k_m = 0 (chi = 1 and km_frac = 0), which
#: would be invalid points (4.9 % of a 40^3 map).
DEFAULT_ENDS = {"jarm": (1.0, 0.0), "motion": (0.99, 0.01)}


def _axes(args: argparse.Namespace) -> tuple[NDArray, NDArray, NDArray]:
    chi_max, km_frac_min = DEFAULT_ENDS[args.kind]
    if args.chi_max is not None:
        chi_max = args.chi_max
    if args.km_frac_min is not None:
        km_frac_min = args.km_frac_min
    args.chi_max, args.km_frac_min = chi_max, km_frac_min
    _range(args.alpha_min, args.alpha_max, "alpha [deg]", 0.0, 90.0)
    _range(args.chi_min, args.chi_max, "chi", 0.0, 1.0)
    _range(args.km_frac_min, args.km_frac_max, "km_frac", 0.0, 1.0)
    na = args.n_alpha or args.grid
    nc = args.n_chi or args.grid
    nk = args.n_km_frac or args.grid
    alpha = np.radians(np.linspace(args.alpha_min, args.alpha_max, na))
    chi = np.linspace(args.chi_min, args.chi_max, nc)
    km = np.linspace(args.km_frac_min, args.km_frac_max, nk)
    return alpha, chi, km


def _mismatch(
    store_attrs: dict[str, Any],
    attrs: dict[str, Any],
    matched: tuple[str, ...],
    old: tuple,
    new: tuple,
) -> list[str]:
    stored = {k: store_attrs.get(k, map_jobs.UNRECORDED.get(k)) for k in matched}
    diffs = [
        f"{k}: store {stored[k]!r}, now {attrs[k]!r}" for k in matched if stored[k] != attrs[k]
    ]
    for name, a, b in zip(("alpha", "chi", "km_frac"), old, new, strict=True):
        if a.shape != b.shape or a.tobytes() != b.tobytes():
            lo, hi = (
                f"[{x[0]:.6g}, {x[-1]:.6g}] x {x.size}" if x.size else "empty" for x in (a, b)
            )
            diffs.append(f"{name} grid: store {lo}, now {hi}")
    return diffs


def _summary(
    job: Job,
    total: int,
    shape: tuple[int, int, int],
    computed: int,
    seconds: float,
    path: Path,
    fmt: str,
    complete: bool,
) -> str:
    rate = computed / seconds if seconds > 0 else math.inf
    lines = [
        f"grid          {shape[0]} x {shape[1]} x {shape[2]} = {total} points "
        "(alpha x chi x km_frac)",
        f"computed      {computed} points this run, {job.points} of {total} finished",
        f"time          {seconds:.2f} s, {rate:.0f} points/s",
        *job.lines(),
    ]
    state = "complete" if complete else "INCOMPLETE (interrupted)"
    lines.append(f"output        {path} ({fmt}, {state})")
    return "\n".join(lines)


class _Failed(Exception):
    """The map could not be written or read (I/O error, out of memory): exit status 1."""


def _why(err: BaseException) -> str:
    """An OSError or MemoryError as a short reason."""
    if isinstance(err, MemoryError):
        return f"out of memory ({err})" if str(err) else "out of memory"
    if isinstance(err, OSError) and err.strerror:
        name = err.filename2 or err.filename
        return f"{err.strerror}: {shown(name)}" if name else err.strerror
    return str(err) or type(err).__name__


def _check_memory(points: int, fmt: str, total: int, kind: MapKind) -> None:
    """Fail early (exit 1) if the fields of ``points`` points cannot fit in the memory this
    process can have, rather than have numpy fill it and the system kill the process."""
    need = points * kind.bytes_per_point()
    have = memory_limit()  # the library's limit (eccjump._base.sizes), the same for every call
    if have is not None and need > have:
        how = "a smaller --chunk or grid" if fmt == "zarr" else ".zarr (written chunk by chunk)"
        held = "a chunk of" if fmt == "zarr" else "the whole map,"
        raise _Failed(
            f"out of memory: {held} {points} points needs {gib(need)}, the machine has "
            f"{gib(have)} available; use {how} (grid of {total} points)"
        )


def _cmd_map(args: argparse.Namespace) -> int:
    try:
        return _run(args)
    except ImportError as err:  # an optional extra is missing: say which, no traceback
        raise ValueError(str(err)) from err
    except KeyboardInterrupt:  # a second Ctrl-C: .zarr keeps its finished chunks
        print("eccjump: aborted", file=sys.stderr)
        return 130
    except _Failed as err:
        print(f"eccjump: error: {_line(str(err))}", file=sys.stderr)
        return 1


def _run(args: argparse.Namespace) -> int:
    path = Path(args.output)
    fmt = format_of(path)
    # The figure's path is checked before the work, as every figure of the command line.
    if args.figure:
        args.figure = check_output("--figure", args.figure, figure_suffixes())
    alpha, chi, km = _axes(args)
    job = map_jobs.job(args)
    if args.threads < 0:
        raise ValueError(f"--threads {args.threads} is outside the allowed range [0, 256]")
    # Let the core check every option on one point before anything is written (an invalid
    # mu_s, theta0, tolerance or thread count is a one-line error, not a map of INVALID).
    job.compute(alpha[:1], chi[:1], km[:1], args.threads)
    chunk = args.chunk or max(1, round(POINTS_PER_CHUNK / max(1, chi.size * km.size)))
    chunk = min(chunk, alpha.size)
    held = shape_points = alpha.size * chi.size * km.size
    if fmt == "zarr":  # one chunk in memory at a time
        held = chunk * chi.size * km.size
    _check_memory(held, fmt, shape_points, job.kind)
    try:
        store.check_parent(path)
        store.check_name(path)
    except OSError as err:
        raise ValueError(_line(f"cannot write {path}: {_why(err)}")) from err
    except ValueError as err:
        raise ValueError(f"-o {err}") from None
    try:
        for note in store.recover(path):
            print(f"eccjump: {note}", file=sys.stderr)
    except OSError as err:
        raise _Failed(f"cannot clean up after an interrupted write of {path}: {_why(err)}") from err
    if args.resume:
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
                path, fmt == "zarr", overwrite=args.overwrite, option="--overwrite"
            )
        except ValueError as err:
            raise ValueError(f"-o {err}") from None
        if not args.overwrite:  # even a map: it may be the one to --resume
            hint = " or --resume" if fmt == "zarr" else ""
            raise ValueError(_line(f"{path} exists; use --overwrite{hint}"))
    # The handler goes first: a Ctrl-C while the store is created stops before the first chunk.
    with _Interrupt() as stop:
        try:
            return _write(args, path, fmt, (alpha, chi, km), job, chunk, stop)
        except (OSError, MemoryError) as err:
            raise _Failed(f"cannot write {path}: {_why(err)}") from err


def _reopen(path: Path, job: Job, axes: tuple[NDArray, NDArray, NDArray]) -> ZarrMap:
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
        diffs = _mismatch(zmap.attrs, job.attrs, job.matched, stored, axes)
        if diffs:
            raise ValueError(f"the options differ from those of {shown(path)}: " + "; ".join(diffs))
        zmap.rewrite_coords()
        return zmap
    except ValueError as err:
        raise ValueError(_line(f"--resume: {err}")) from None
    except (OSError, MemoryError):
        raise
    except Exception as err:  # zarr's errors on a damaged store are of many types
        why = f"{type(err).__name__}: {err}"
        raise ValueError(_line(f"--resume: {shown(path)} is damaged ({why})")) from err


def _resume_todo(zmap: ZarrMap, job: Job, path: Path) -> list[int]:
    """The chunks to compute: those not marked done, and those marked done that do not read
    back whole and valid (:meth:`ZarrMap.damage`, said on stderr). The others are counted."""
    todo = zmap.missing()
    for i in sorted(set(range(zmap.n_chunks)) - set(todo)):
        problem = zmap.damage(i)
        if problem is None:
            job.count(zmap.read(i, job.counted))
            continue
        print(
            _line(f"eccjump: {shown(path)}: chunk {i} is damaged ({problem}); computing it again"),
            file=sys.stderr,
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
    args: argparse.Namespace,
    path: Path,
    fmt: str,
    axes: tuple[NDArray, NDArray, NDArray],
    job: Job,
    chunk: int,
    stop: _Interrupt,
) -> int:
    alpha, chi, km = axes
    kind, attrs = job.kind, job.attrs
    shape = (alpha.size, chi.size, km.size)
    total = int(np.prod(shape))
    target = _Target(path, fmt, args.resume)
    fields: dict[str, NDArray] = {}
    done = np.zeros(alpha.size, dtype=bool)
    try:
        if args.resume:
            target.zmap = _reopen(path, job, axes)
            todo = _resume_todo(target.zmap, job, path)
            if args.chunk and args.chunk != target.zmap.chunk:
                print(
                    f"eccjump: resuming with the store's chunk of {target.zmap.chunk}",
                    file=sys.stderr,
                )
        elif fmt == "zarr":
            target.zmap = ZarrMap.create(target.tmp, alpha, chi, km, attrs, chunk)
            todo = list(range(target.zmap.n_chunks))
        else:
            fields = {k: np.full(shape, kind.fill[k], dtype=kind.dtypes[k]) for k in kind.fields}
            todo = list(range(-(-alpha.size // chunk)))
        if target.zmap is not None:
            chunk = target.zmap.chunk
        result = _compute(args, target, fields, done, job, axes, chunk, todo, stop)
        computed, seconds, interrupted = result
        if computed == 0 and interrupted and not target.in_place:
            target.discard()
            print(
                f"eccjump: interrupted before a chunk was finished: nothing written "
                f"({path} {'unchanged' if target.replacing else 'not created'})",
                file=sys.stderr,
            )
            return 130
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
        raise _Failed(f"cannot write {path}: {_why(err)}{kept}") from err
    except BaseException:
        target.discard()
        raise
    print(_summary(job, total, shape, computed, seconds, path, fmt, complete))
    if interrupted or not complete:
        if fmt == "zarr":
            how = f"resume with the same options and --resume -o {path}"
        else:
            how = "the unfinished points hold fill values; use .zarr for resumable maps"
        print(
            f"eccjump: interrupted: {n_done} of {alpha.size} alpha slices written to {path} "
            f"with complete = 0; {how}",
            file=sys.stderr,
        )
        return 130
    if args.figure:
        job.draw(str(path), args.figure)
        print(f"figure: {args.figure}")
    return 0


def _compute(
    args: argparse.Namespace,
    target: _Target,
    fields: dict[str, NDArray],
    done: NDArray[np.bool_],
    job: Job,
    axes: tuple[NDArray, NDArray, NDArray],
    chunk: int,
    todo: list[int],
    stop: _Interrupt,
) -> tuple[int, float, bool]:
    """Compute the chunks ``todo`` into the target: (points computed, seconds, interrupted)."""
    from tqdm import tqdm

    alpha, chi, km = axes
    todo_points = sum(
        (min((i + 1) * chunk, alpha.size) - i * chunk) * chi.size * km.size for i in todo
    )
    quiet = args.quiet or not sys.stderr.isatty()
    computed = 0
    interrupted = False
    t0 = time.perf_counter()
    with tqdm(total=todo_points, unit="pt", unit_scale=True, disable=quiet, file=sys.stderr) as bar:
        for k, i in enumerate(todo):
            if stop.requested or (args.stop_after is not None and k >= args.stop_after):
                interrupted = True
                break
            i0, i1 = i * chunk, min((i + 1) * chunk, alpha.size)
            part = job.compute(alpha[i0:i1], chi, km, args.threads)
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
            bar.update(size)
    return computed, time.perf_counter() - t0, interrupted

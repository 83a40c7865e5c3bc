"""``eccjump map``: the JARM region over (α, χ, k_m), computed in chunks along α and
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

This module is the options and the printing; the chunks, the resume and the files are
:mod:`eccjump.maps.runner`'s, and what a chunk computes is a job of :mod:`eccjump.cli.map_jobs`.
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import U32_MAX, short
from eccjump.cli import map_jobs
from eccjump.cli._args import (
    RAMP_RADIANS,
    Degrees,
    add_integrator,
    int_at_least,
    int_in,
    shows_progress,
)
from eccjump.cli._output import check_output, figure_suffixes
from eccjump.cli.map_jobs import Job
from eccjump.maps import runner
from eccjump.maps.runner import POINTS_PER_CHUNK
from eccjump.maps.store import format_of
from eccjump.studies.uncertainty.sampling import N_MAX

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
        choices=("jarm", "motion", "uncertainty"),
        default="jarm",
        help="jarm: the JARM classification (default); motion: the full motion to the first "
        "landing (sequence of modes, lift-off, flight, landing); uncertainty: P(JARM) under "
        "the tolerances --sd",
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
    ramp = {"action": Degrees, "radians_up_to": RAMP_RADIANS, "type": float}  # range: _axes
    g.add_argument("--alpha-min", **ramp, default=0.0, help="[deg] (default 0)")
    g.add_argument("--alpha-max", **ramp, default=90.0, help="[deg] (default 90)")
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
    m.add_argument("--theta0", action=Degrees, default=0.0, help="initial angle [deg]")
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
    u = p.add_argument_group("P(JARM) under tolerances (--kind uncertainty)")
    u.add_argument(
        "--sd",
        action="append",
        default=None,
        metavar="NAME=SD[,...]",
        help="normal tolerances around each grid point, e.g. alpha=0.25,chi=0.002 (NAME: "
        "chi, km, alpha, mu_s; alpha in degrees; repeatable)",
    )
    u.add_argument(
        "--samples", type=int_in(1, N_MAX), default=None, help="samples per point (default 2000)"
    )
    u.add_argument("--seed", type=int_in(0, 2**63), default=None, help="seed (default 0)")
    u.add_argument("--sampling", choices=("random", "sobol"), default=None, help="default random")
    u.add_argument("--confidence", type=float, default=None, help="interval level (0.95)")
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


#: The default ends of the chi and km_frac axes that differ by kind: the full motion needs
#: k_m > 0 (simulate), so its default grid leaves out k_m = 0 (chi = 1 and km_frac = 0), which
#: would be invalid points (4.9 % of a 40^3 map).
DEFAULT_ENDS = {"jarm": (1.0, 0.0), "motion": (0.99, 0.01), "uncertainty": (1.0, 0.0)}


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


def _summary(job: Job, out: runner.Outcome) -> str:
    total = int(np.prod(out.shape))
    rate = out.computed / out.seconds if out.seconds > 0 else math.inf
    lines = [
        f"grid          {out.shape[0]} x {out.shape[1]} x {out.shape[2]} = {total} points "
        "(alpha x chi x km_frac)",
        f"computed      {out.computed} points this run, {job.points} of {total} finished",
        f"time          {out.seconds:.2f} s, {rate:.0f} points/s",
        *job.lines(),
    ]
    state = "complete" if out.complete else "INCOMPLETE (interrupted)"
    lines.append(f"output        {out.path} ({out.fmt}, {state})")
    return "\n".join(lines)


def _note(line: str) -> None:
    print(line, file=sys.stderr)


def _cmd_map(args: argparse.Namespace) -> int:
    try:
        return _run(args)
    except ImportError as err:  # an optional extra is missing: say which, no traceback
        raise ValueError(str(err)) from err
    except KeyboardInterrupt:  # a second Ctrl-C: .zarr keeps its finished chunks
        print("eccjump: aborted", file=sys.stderr)
        return 130
    except runner.Failed as err:
        print(f"eccjump: error: {runner.one_line(str(err))}", file=sys.stderr)
        return 1


def _run(args: argparse.Namespace) -> int:
    path = Path(args.output)
    format_of(path)  # the output's suffix is the first thing checked
    # The figure's path is checked before the work, as every figure of the command line.
    if args.figure:
        args.figure = check_output("--figure", args.figure, figure_suffixes())
    axes = _axes(args)
    job = map_jobs.job(args)
    if args.threads < 0:
        raise ValueError(f"--threads {args.threads} is outside the allowed range [0, 256]")
    options = runner.Options(
        threads=args.threads,
        chunk=args.chunk,
        resume=args.resume,
        overwrite=args.overwrite,
        progress=shows_progress(args),
        stop_after=args.stop_after,
    )
    return _report(runner.run(path, axes, job, options, _note), job, args.figure)


def _report(out: runner.Outcome, job: Job, figure: Path | None) -> int:
    """Say what the run did; draw the figure of a complete map. The exit status."""
    if not out.written:
        print(
            f"eccjump: interrupted before a chunk was finished: nothing written "
            f"({out.path} {'unchanged' if out.replacing else 'not created'})",
            file=sys.stderr,
        )
        return 130
    print(_summary(job, out))
    if out.interrupted or not out.complete:
        if out.fmt == "zarr":
            how = f"resume with the same options and --resume -o {out.path}"
        else:
            how = "the unfinished points hold fill values; use .zarr for resumable maps"
        print(
            f"eccjump: interrupted: {out.done} of {out.shape[0]} alpha slices written to "
            f"{out.path} with complete = 0; {how}",
            file=sys.stderr,
        )
        return 130
    if figure:
        job.draw(str(out.path), figure)
        print(f"figure: {figure}")
    return 0

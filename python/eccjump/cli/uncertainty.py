"""``eccjump uncertainty``: the probability of a JARM (and of each outcome) and the spread of
the lift-off and the first flight when the body, the ramp, the friction and the start are
known within tolerances (:func:`eccjump.uncertainty`), with a progress bar, a figure and
the samples as CSV or netCDF."""

from __future__ import annotations

import argparse
import json
import math
from pathlib import Path
from typing import Any

from eccjump import plot
from eccjump._base.body import Cylinder
from eccjump._base.overwrite import check_overwrite, never
from eccjump.cli._args import (
    RAMP_RADIANS,
    TURN_RADIANS,
    Degrees,
    add_integrator,
    int_in,
    radians_hint,
    shows_progress,
)
from eccjump.cli._output import (
    DPI_RANGE,
    bounded,
    check_output,
    figure_suffixes,
    save_figure,
    writing,
)
from eccjump.studies.uncertainty import Uncertainty, uncertainty
from eccjump.studies.uncertainty.indices import SobolIndex
from eccjump.studies.uncertainty.results import QUANTITIES, _first_order
from eccjump.studies.uncertainty.sampling import N_MAX, PARAMETERS

#: Parameters given in degrees on the command line (radians in Python).
ANGLES = ("alpha", "theta0")
#: What ``-o`` writes.
DATA_SUFFIXES = frozenset({".csv", ".nc"})


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "uncertainty",
        help="probability of a JARM and spread of the lift-off under tolerances",
        description="Draw samples around a nominal body and ramp (normal tolerances with "
        "--sd, uniform ranges with --bounds; angles in degrees), classify each (JARM, closed "
        "form) or run it to its first landing (--question motion), and print P(JARM) with "
        "its Wilson interval, the share of each outcome and the distributions of the "
        "lift-off angle, time, apex and distance.",
    )
    p.add_argument("--chi", type=float, required=True, help="nominal d/R, in [0, 1]")
    p.add_argument("--km", type=float, required=True, help="nominal shell mass fraction k_m")
    p.add_argument(
        "--alpha",
        action=Degrees,
        lo=0.0,
        hi=90.0,
        radians_up_to=RAMP_RADIANS,
        required=True,
        help="nominal ramp angle [deg]",
    )
    p.add_argument("--mu-s", type=float, required=True, help="nominal static friction")
    p.add_argument("--mu-k", type=float, default=None, help="nominal kinetic friction (mu_s)")
    p.add_argument("--restitution", type=float, default=0.0, help="nominal e (default 0)")
    p.add_argument("--theta0", action=Degrees, default=0.0, help="nominal start angle [deg]")
    p.add_argument("--omega0", type=float, default=0.0, help="nominal start rate [sqrt(g/R)]")
    p.add_argument(
        "--sd",
        nargs=2,
        action="append",
        default=[],
        metavar=("NAME", "SD"),
        help=f"a normal tolerance (repeatable); NAME one of {', '.join(PARAMETERS)}; "
        "alpha and theta0 in degrees",
    )
    p.add_argument(
        "--bounds",
        nargs=3,
        action="append",
        default=[],
        metavar=("NAME", "LO", "HI"),
        help="a uniform range (repeatable), absolute values; alpha and theta0 in degrees",
    )
    p.add_argument(
        "-n", "--samples", type=int_in(1, N_MAX), default=10_000, help="samples (default 10000)"
    )
    p.add_argument("--seed", type=int_in(0, 2**63), default=0, help="seed (default 0)")
    p.add_argument(
        "--sampling",
        choices=("random", "sobol"),
        default="random",
        help="pseudo-random or scrambled Sobol' points (best for n a power of 2)",
    )
    p.add_argument(
        "--question",
        choices=("jarm", "motion"),
        default="jarm",
        help="jarm: the closed-form classification (chi, km, alpha, mu_s may vary); motion: "
        "the full motion to the first landing (every parameter)",
    )
    p.add_argument(
        "--invalid",
        choices=("truncate", "count"),
        default="truncate",
        help="samples outside the physical range: truncate the distributions (default) or "
        "count them as invalid",
    )
    p.add_argument("--confidence", type=float, default=0.95, help="interval level (0.95)")
    p.add_argument(
        "--indices",
        action="store_true",
        help="also the first-order and total Sobol' indices of P(JARM) per varied parameter "
        "(which tolerance matters; n (d + 2) runs for d varied parameters)",
    )
    p.add_argument(
        "--rule", choices=("paper", "normal_force"), default="paper", help="lift-off rule"
    )
    p.add_argument("--t-max", type=float, default=100.0, help="end time of a motion run")
    p.add_argument(
        "--max-transitions", type=int_in(1), default=100, help="transitions of a motion run"
    )
    add_integrator(p, " of --question motion")
    p.add_argument(
        "--threads", type=int_in(0, 256), default=0, help="threads, 0 ... 256 (0: one per core)"
    )
    p.add_argument("-o", "--output", default=None, help="write the samples (.csv or .nc)")
    p.add_argument(
        "--overwrite", action="store_true", help="replace the file at --output if there is one"
    )
    p.add_argument("--figure", default=None, help="draw the study (needs eccjump[plot])")
    p.add_argument(
        "--dpi",
        type=int_in(*DPI_RANGE),
        default=100,
        help=f"resolution of the figure, {DPI_RANGE[0]} ... {DPI_RANGE[1]} (default 100)",
    )
    p.add_argument("--json", action="store_true", help="print machine-readable JSON")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")
    p.set_defaults(func=_cmd_uncertainty)


def _value(name: str, text: str) -> float:
    """A number of --sd/--bounds in the API's unit (degrees to radians for the angles)."""
    try:
        x = float(text)
    except ValueError:
        raise ValueError(f"{name}: {text[:40]!r} is not a number") from None
    return math.radians(x) if name in ANGLES else x


def _spreads(args: argparse.Namespace) -> tuple[dict[str, float], dict[str, tuple[float, float]]]:
    """--sd and --bounds as the API's dicts (a name given twice: ValueError)."""
    sd: dict[str, float] = {}
    bounds: dict[str, tuple[float, float]] = {}
    for name, value in args.sd:
        if name in sd:
            raise ValueError(f"--sd {name[:40]}: given twice")
        sd[name] = _value(name, value)
    for name, lo, hi in args.bounds:
        if name in bounds:
            raise ValueError(f"--bounds {name[:40]}: given twice")
        bounds[name] = (_value(name, lo), _value(name, hi))
        if name in ANGLES:  # a range of angles can look like radians; a spread cannot
            up_to = RAMP_RADIANS if name == "alpha" else TURN_RADIANS
            radians_hint(f"--bounds {name}", [float(lo), float(hi)], up_to)
    return sd, bounds


def _cmd_uncertainty(args: argparse.Namespace) -> int:
    # Both paths checked before the work: a bad one costs nothing.
    output = figure = None
    if args.output is not None:
        output = check_output("--output", args.output, DATA_SUFFIXES)
        check_overwrite(
            output,
            overwrite=args.overwrite,
            option="--overwrite",
            ours=never,
            what="an uncertainty result",
            name="--output",
        )
    if args.figure is not None:
        figure = check_output("--figure", args.figure, figure_suffixes())
    sd, bounds = _spreads(args)
    result = _run(args, sd, bounds)
    if output is not None:
        with writing("--output", output):  # save writes a temporary file and renames it
            result.save(output, overwrite=args.overwrite)
    if figure is not None:
        import matplotlib

        matplotlib.use("Agg")
        save_figure("--figure", plot.uncertainty(result), figure, args.dpi)
    written = {"output": output, "figure": figure}
    if args.json:
        out: dict[str, Any] = result.to_dict()
        out.update({k: str(v) for k, v in written.items() if v is not None})
        print(json.dumps(out, indent=2))
    else:
        _print(result, written)
    return 0


def _run(
    args: argparse.Namespace, sd: dict[str, float], bounds: dict[str, tuple[float, float]]
) -> Uncertainty:
    return uncertainty(
        Cylinder(args.chi, args.km),
        math.radians(args.alpha),
        args.mu_s,
        mu_k=args.mu_k,
        restitution=args.restitution,
        theta0=math.radians(args.theta0),
        omega0=args.omega0,
        sd=sd,
        bounds=bounds,
        n=args.samples,
        seed=args.seed,
        sampling=args.sampling,
        question=args.question,
        invalid=args.invalid,
        confidence=args.confidence,
        indices=args.indices,
        rule=args.rule,
        t_max=args.t_max,
        max_transitions=args.max_transitions,
        integrator=args.integrator,
        n_threads=args.threads,
        progress=shows_progress(args),
    )


def _shown(name: str, x: float) -> str:
    """A distribution's value in the command line's unit (angles in degrees)."""
    if name == "liftoff_theta":
        return bounded(math.degrees(x), "10.4f")
    return bounded(x, "10.5g")


def _print(r: Uncertainty, written: dict[str, Path | None]) -> None:
    lo, hi = r.p_jarm_ci
    level = f"{100 * r.confidence:g} %"
    print(f"question      {r.question}, {r.n} samples ({r.sampling}, seed {r.seed})")
    print(f"valid         {r.n_valid} ({bounded(100 * (1 - r.p_invalid), '.4g')} %, {r.invalid})")
    print(f"P(JARM)       {r.p_jarm:.5f}  [{lo:.5f}, {hi:.5f}] ({level} Wilson)")
    for name, count in list(r.counts.items())[:10]:
        a, b = r.interval(name)
        p = count / max(r.n_valid, 1)
        print(f"  {name:<36} {p:.5f}  [{a:.5f}, {b:.5f}]")
    if r.distributions:
        print(f"{'':<14}{'n':>8} {'median':>10} {'2.5 %':>10} {'97.5 %':>10}  unit")
    for name, s in r.distributions.items():
        unit = "deg" if name == "liftoff_theta" else QUANTITIES[name]
        cells = " ".join(_shown(name, v) for v in (s.median, s.q025, s.q975))
        print(f"{name:<14}{s.n:>8} {cells}  {unit}")
    if r.delta is not None:
        print(f"first order   {_first_order(r.delta)}")
    if r.indices is not None:
        _print_indices(r)
    for what, path in written.items():
        if path is not None:
            print(f"{what}: {path}")


def _print_indices(r: Uncertainty) -> None:
    """The Sobol' indices as tables, one varied parameter a row: of P(JARM), and for the
    full motion of the first lift-off's time."""
    level = f"{100 * r.confidence:g} % bootstrap"
    runs = r.n * (len(r.samples) + 2)
    _index_table(f"Sobol' indices of P(JARM) ({level}; n (d + 2) = {runs} runs)", r.indices)
    if r.liftoff_indices is not None:
        _index_table("Sobol' indices of the lift-off time", r.liftoff_indices)


def _index_table(title: str, indices: dict[str, SobolIndex] | None) -> None:
    print(title)
    print(f"  {'parameter':<12}{'first':>8} {'interval':<18}{'total':>8} interval")
    for name, ix in (indices or {}).items():
        f, t = ix.first, ix.total
        print(
            f"  {name:<12}{f.value:8.3f} [{f.low:6.3f}, {f.high:6.3f}]  "
            f"{t.value:8.3f} [{t.low:6.3f}, {t.high:6.3f}]"
        )
    if not indices:
        print("  (no parameter varies)")

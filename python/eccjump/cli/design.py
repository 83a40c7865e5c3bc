"""``eccjump design``: the body and ramp angle whose JARM (or, with ``--target slip``, whose
slip before lift-off) is most robust, printed as a lab sheet (or JSON). See the user guide's
"Experiment design" page."""

from __future__ import annotations

import argparse
import json
import math

from eccjump._base.body import Cylinder
from eccjump.cli._args import RAMP_RADIANS, Degrees, int_at_least
from eccjump.cli.map_jobs import tolerances
from eccjump.studies.design import GRID_RANGE, design


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "design",
        help="design a lab experiment: the most robust JARM (or a sure slip, for a control)",
        description="Find the body (shell plus rod) and ramp angle whose verdict holds with the "
        "largest relative margins to the exact region boundaries in alpha, mu_s and the rod "
        "position, under both lift-off rules and the whole mu_s uncertainty; print a lab sheet.",
    )
    p.add_argument(
        "--alpha-range",
        nargs=2,
        action=Degrees,
        lo=0.0,
        hi=90.0,
        radians_up_to=RAMP_RADIANS,
        required=True,
        metavar=("LO", "HI"),
        help="ramp angles the lab can set [deg], within [0, 90]",
    )
    p.add_argument("--mu-s", type=float, required=True, help="static friction coefficient")
    p.add_argument("--mu-s-err", type=float, default=0.0, help="uncertainty of mu_s (default 0)")
    p.add_argument(
        "--target",
        choices=("jarm", "slip"),
        default="jarm",
        help="jarm (default) or slip: a body that certainly slips first (control run)",
    )
    p.add_argument(
        "--km-range",
        nargs=2,
        type=float,
        default=(0.01, 0.9),
        metavar=("LO", "HI"),
        help="shell mass fractions to choose from, within [0, 1) (default 0.01 0.9)",
    )
    p.add_argument(
        "--rod-range",
        nargs=2,
        type=float,
        default=(0.05, 0.95),
        metavar=("LO", "HI"),
        help="rod positions r/R to choose from, within [0, 1] (default 0.05 0.95)",
    )
    p.add_argument("--chi", type=float, default=None, help="a fixed body: d/R (with --km)")
    p.add_argument("--km", type=float, default=None, help="a fixed body: shell mass fraction")
    p.add_argument("--radius", type=float, default=None, help="R [m] (with --mass: SI sheet)")
    p.add_argument("--mass", type=float, default=None, help="M [kg] (with --radius)")
    p.add_argument("--g", type=float, default=9.81, help="gravity [m/s^2] (default 9.81)")
    p.add_argument(
        "--max-turns",
        type=int_at_least(1),
        default=10,
        help="turns the ramp allows before the event (default 10, at most 1000)",
    )
    p.add_argument(
        "--error",
        type=float,
        default=0.05,
        help="fractional input error of the sensitivity table, in (0, 0.5] (default 0.05)",
    )
    p.add_argument(
        "--grid",
        type=int_at_least(GRID_RANGE[0]),
        default=24,
        help=f"coarse grid points per axis, {GRID_RANGE[0]} ... {GRID_RANGE[1]} (default 24)",
    )
    p.add_argument(
        "--min-apex",
        type=float,
        default=0.0,
        help="least apex of the first flight [R, or m with --radius] for a jump you can see "
        "(default 0: none; try 0.15 on a 40-70 deg ramp)",
    )
    p.add_argument(
        "--sd",
        nargs="+",
        action="append",
        default=[],
        metavar="NAME=SD[,NAME=SD...]",
        help="lab tolerances (repeatable; as eccjump map --kind uncertainty, or NAME SD): the "
        "normal standard deviation of chi, km, alpha (in degrees) or mu_s; the sheet then "
        "gives P(success), the probability of the verdict",
    )
    p.add_argument(
        "--p-target",
        type=float,
        default=None,
        help="with --sd: the P(JARM) the design must reach, in (0, 1), by its 95 %% Wilson "
        "lower bound (the lower of the two rules'); an error with the best found if none does",
    )
    p.add_argument(
        "--maximise",
        choices=("margin", "probability"),
        default="margin",
        help="maximise the smallest relative margin (default) or, with --sd, P(success)",
    )
    p.add_argument(
        "--samples", type=int, default=10_000, help="samples per probability (default 10000)"
    )
    p.add_argument("--json", action="store_true", help="print machine-readable JSON")
    p.set_defaults(func=_cmd_design)


def _tolerances(given: list[list[str]]) -> dict[str, float] | None:
    """--sd as the API's tolerances, by the parser of ``eccjump map --kind uncertainty``
    (α from degrees; a name given twice: ValueError). ``--sd NAME SD``, the older form, is
    read as ``--sd NAME=SD``."""
    items = [
        f"{words[0]}={words[1]}" if len(words) == 2 and "=" not in words[0] else ",".join(words)
        for words in given
    ]
    return tolerances(items) or None


def _cmd_design(args: argparse.Namespace) -> int:
    if (args.chi is None) != (args.km is None):
        raise ValueError("--chi and --km: give both (a fixed body) or neither")
    body = None if args.chi is None else Cylinder(args.chi, args.km)
    d = design(
        tuple(math.radians(a) for a in args.alpha_range),
        args.mu_s,
        args.mu_s_err,
        target=args.target,
        body=body,
        km_range=tuple(args.km_range),
        rod_range=tuple(args.rod_range),
        radius=args.radius,
        mass=args.mass,
        g=args.g,
        max_turns=args.max_turns,
        error=args.error,
        grid=args.grid,
        min_apex=args.min_apex,
        tolerances=_tolerances(args.sd),
        maximise=args.maximise,
        samples=args.samples,
        p_target=args.p_target,
    )
    if args.json:
        print(json.dumps(d.to_dict(), indent=2))
    else:
        print(d.sheet())
    return 0

"""``eccjump analyze``: a tracked experiment (CSV ``t,xc,yc,xm,ym`` or Tracker's export) in,
the verdict -- jarm, slip_first or undetermined -- with its evidence out, as text or JSON, and
optionally a figure of data and model (the site's page "Analysing an experiment")."""

from __future__ import annotations

import argparse
import json
import math

from eccjump.cli._args import degrees_in, radians_hint
from eccjump.cli._output import check_output, figure_suffixes, save_figure
from eccjump.experiment import analyze


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "analyze",
        help="analyse a tracked experiment: did it jump straight out of pure rolling?",
        description="Reconstruct theta, l, b and the slip from a track of the axle and a "
        "marker, detect slip, lift-off and landing, fit the model (simulate) and give the "
        "verdict (jarm, slip_first or undetermined) with its evidence.",
    )
    p.add_argument("track", help="CSV with t,xc,yc,xm,ym (s; m or px) or Tracker's data export")
    p.add_argument("--radius", type=float, default=None, help="R [m] (or from --design)")
    p.add_argument("--chi", type=float, default=None, help="d/R (or from --design)")
    p.add_argument("--km", type=float, default=None, help="shell mass fraction (or --design)")
    p.add_argument(
        "--alpha",
        type=degrees_in(0.0, 90.0),
        default=None,
        help="ramp angle [deg] (default: from --design, else estimated from the track)",
    )
    p.add_argument(
        "--marker-radius", type=float, default=None, help="marker distance from the axle [m]"
    )
    p.add_argument(
        "--marker-angle",
        type=float,
        default=0.0,
        help="marker angle from the axle->CM direction, measured like theta [deg] (default 0)",
    )
    p.add_argument("--scale", type=float, default=None, help="pixels per metre (pixel tracks)")
    p.add_argument("--design", default=None, help="a sheet of eccjump design --json")
    p.add_argument("--g", type=float, default=9.81, help="gravity [m/s^2] (default 9.81)")
    p.add_argument(
        "--rule",
        choices=("paper", "normal_force"),
        default="paper",
        help="the model's lift-off rule (default paper)",
    )
    p.add_argument("--figure", default=None, help="draw data and model (needs eccjump[plot])")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    figure = check_output("--figure", args.figure, figure_suffixes()) if args.figure else None
    if args.alpha is not None:
        radians_hint("--alpha", args.alpha)
    res = analyze(
        args.track,
        radius=args.radius,
        chi=args.chi,
        km=args.km,
        alpha=None if args.alpha is None else math.radians(args.alpha),
        marker_angle=math.radians(args.marker_angle),
        marker_radius=args.marker_radius,
        scale=args.scale,
        design=args.design,
        g=args.g,
        rule=args.rule,
    )
    if args.json:
        print(json.dumps(res.to_dict(), indent=1, allow_nan=False))
    else:
        print(res)
        for note in res.notes:
            print(f"note: {note}")
    if figure is not None:
        save_figure("--figure", res.plot(), figure, dpi=110)
        if not args.json:
            print(f"figure: {figure}")
    return 0

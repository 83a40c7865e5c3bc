"""``eccjump analyze``: a tracked experiment (CSV ``t,xc,yc,xm,ym`` or Tracker's export) or
its video in, the verdict -- jarm, slip_first or undetermined -- with its evidence out, as
text or JSON, and optionally a figure of data and model (the site's page "Analysing an
experiment"). A video (known by its suffix or its first bytes) is tracked first, as
``eccjump track`` does (``cli.track.track_video``).

The ranges are ``eccjump.studies.experiment.inputs.BOUNDS``'s, checked by the parser (angles in
degrees); what depends on another value (``--marker-radius`` on R, the track on its scale)
is checked by ``eccjump.analyze``, whose messages name its keywords: :func:`_as_options`
turns the one they start with into the option."""

from __future__ import annotations

import argparse
import json
import math
import re
from collections.abc import Callable

from eccjump.cli._args import RAMP_RADIANS, Degrees, degrees_in, real_in
from eccjump.cli._output import check_output, figure_suffixes, save_figure
from eccjump.cli.track import add_video_options, track_video
from eccjump.studies.experiment import analyze
from eccjump.studies.experiment.inputs import cli_range
from eccjump.studies.experiment.video import is_video


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "analyze",
        help="analyse a tracked experiment: did it jump straight out of pure rolling?",
        description="Reconstruct theta, l, b and the slip from a track of the axle and a "
        "marker, detect slip, lift-off and landing, fit the model (simulate) and give the "
        "verdict (jarm, slip_first or undetermined) with its evidence.",
    )
    p.add_argument(
        "track",
        help="CSV with t,xc,yc,xm,ym (s; m or px; commas, semicolons or tabs) or Tracker's "
        "data export; - reads the standard input; or the video (tracked as eccjump track "
        "does, with --marker-radius or --scale)",
    )
    p.add_argument("--radius", type=_bounded("radius"), default=None, help="R [m] (or --design)")
    p.add_argument("--chi", type=float, default=None, help="d/R (or from --design)")
    p.add_argument("--km", type=float, default=None, help="shell mass fraction (or --design)")
    p.add_argument(
        "--alpha",
        action=Degrees,
        type=_bounded("alpha"),
        radians_up_to=RAMP_RADIANS,
        default=None,
        help="ramp angle [deg] (default: from --design, else estimated from the track)",
    )
    p.add_argument(
        "--marker-radius", type=float, default=None, help="marker distance from the axle [m]"
    )
    p.add_argument(
        "--marker-angle",
        action=Degrees,
        type=_bounded("marker_angle"),
        default=0.0,
        help="marker angle from the axle->CM direction, measured like theta [deg] (default 0)",
    )
    p.add_argument(
        "--scale", type=_bounded("scale"), default=None, help="pixels per metre (pixel tracks)"
    )
    p.add_argument("--design", default=None, help="a sheet of eccjump design --json")
    p.add_argument(
        "--mu-s",
        type=_bounded("mu_s"),
        default=None,
        help="static friction measured apart from the track, e.g. by a tilt test (with "
        "--mu-s-err; default: --design's if it gives an uncertainty): lets the verdict "
        "exclude a slip the track alone cannot",
    )
    p.add_argument(
        "--mu-s-err",
        type=_bounded("mu_s_err"),
        default=None,
        help="the standard deviation of --mu-s",
    )
    p.add_argument("--g", type=_bounded("g"), default=9.81, help="gravity [m/s^2] (default 9.81)")
    p.add_argument(
        "--rule",
        choices=("paper", "normal_force"),
        default="paper",
        help="the model's lift-off rule (default paper)",
    )
    p.add_argument("--figure", default=None, help="draw data and model (needs eccjump[plot])")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    video = p.add_argument_group("video input (eccjump track's options)")
    add_video_options(video)
    p.set_defaults(func=run)


def run(args: argparse.Namespace) -> int:
    figure = check_output("--figure", args.figure, figure_suffixes()) if args.figure else None
    video = track_video(args) if is_video(args.track) else None
    try:
        res = analyze(
            args.track if video is None else video,
            radius=args.radius,
            chi=args.chi,
            km=args.km,
            alpha=None if args.alpha is None else math.radians(args.alpha),
            marker_angle=math.radians(args.marker_angle),
            marker_radius=args.marker_radius,
            scale=args.scale if video is None else None,  # a video's track is in metres
            design=args.design,
            mu_s=args.mu_s,
            mu_s_err=args.mu_s_err,
            g=args.g,
            rule=args.rule,
        )
    except (ValueError, TypeError) as err:
        raise type(err)(_as_options(str(err))) from None
    if args.json:
        report = res.to_dict() | ({} if video is None else {"video": video.to_dict()})
        print(json.dumps(report, indent=1, allow_nan=False))
    else:
        if video is not None:
            print("\n".join(f"video: {line}" for line in video.summary()))
        print(res)
        for note in res.notes:
            print(f"note: {note}")
    if figure is not None:
        save_figure("--figure", res.plot(), figure, dpi=110)
        if not args.json:
            print(f"figure: {figure}")
    return 0


def _bounded(name: str) -> Callable[[str], float]:
    """The parser's type for BOUNDS[name]: its range in the command line's unit."""
    lo, hi, unit = cli_range(name)
    return degrees_in(lo, hi) if unit == "deg" else real_in(lo, hi, unit)


#: analyze's keywords and the options that give them.
_OPTIONS = {
    "radius": "--radius",
    "chi": "--chi",
    "km": "--km",
    "alpha": "--alpha",
    "marker_radius": "--marker-radius",
    "marker_angle": "--marker-angle",
    "scale": "--scale",
    "design": "--design",
    "mu_s": "--mu-s",
    "mu_s_err": "--mu-s-err",
    "g": "--g",
    "rule": "--rule",
}
_LEADING_NAME = re.compile(r"^([a-z_]+)\b")


def _as_options(message: str) -> str:
    """A message of eccjump.analyze with the keyword it starts with as its option
    (``marker_radius = ...`` -> ``--marker-radius = ...``)."""
    return _LEADING_NAME.sub(lambda m: _OPTIONS.get(m.group(1), m.group(1)), message, count=1)

"""``eccjump track``: a video of the experiment in, the track of its two dots out, as a CSV
that ``eccjump analyze`` reads (``eccjump.track``; the site's page "Analysing an
experiment"). The video options and the progress bar are shared with ``eccjump analyze``,
which takes a video too (:func:`add_video_options`, :func:`track_video`)."""

from __future__ import annotations

import argparse
import json
import math
import re

from eccjump._base.overwrite import check_overwrite
from eccjump._base.progress import reporting
from eccjump.cli._args import RAMP_RADIANS, Degrees, degrees_in, real_in, shows_progress
from eccjump.cli._output import check_output, writing
from eccjump.studies.experiment.inputs import cli_range
from eccjump.studies.experiment.video import COLORS, VideoTrack, is_track_file, track

#: track's keywords and the options that give them.
OPTIONS = {
    "marker_radius": "--marker-radius",
    "scale": "--scale",
    "axle_color": "--axle-color",
    "marker_color": "--marker-color",
    "alpha": "--alpha",
    "start": "--start",
    "end": "--end",
}
_LEADING = re.compile(r"^([a-z_]+)\b")


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "track",
        help="track the axle's and the marker's dots through a video into a CSV track",
        description="Find the two coloured dots on the body's end face in every frame of a "
        "video (sub-pixel centroids, frame times from the file), set the scale, estimate "
        "the ramp line and the camera's roll, and write the track as a CSV for eccjump "
        "analyze. Frames where a dot is lost are left out.",
    )
    p.add_argument("video", help="the video file (MP4, MOV, MKV, AVI, ...)")
    p.add_argument("-o", "--output", required=True, help="the track to write (.csv)")
    add_video_options(p)
    p.add_argument(
        "--alpha",
        action=Degrees,
        type=degrees_in(*cli_range("alpha")[:2]),
        radians_up_to=RAMP_RADIANS,
        default=None,
        help="ramp angle [deg]: reports the camera's roll against it",
    )
    p.add_argument(
        "--marker-radius", type=float, default=None, help="marker dot's distance from the axle [m]"
    )
    lo, hi, unit = cli_range("scale")
    p.add_argument("--scale", type=real_in(lo, hi, unit), default=None, help="pixels per metre")
    p.add_argument("--overwrite", action="store_true", help="replace a file at --output")
    p.add_argument("--json", action="store_true", help="print the report as JSON")
    p.set_defaults(func=run)


def add_video_options(p: argparse._ActionsContainer) -> None:
    """The options of the tracking that ``eccjump analyze`` shares (not --scale,
    --marker-radius and --alpha, which it has already)."""
    names = ", ".join(COLORS)
    p.add_argument(
        "--axle-color", default=None, help=f"the axle's dot: {names} or #rrggbb (default: found)"
    )
    p.add_argument(
        "--marker-color", default=None, help="the marker's dot, likewise (default: found)"
    )
    p.add_argument("--start", type=float, default=None, help="video time to start at [s]")
    p.add_argument("--end", type=float, default=None, help="video time to end at [s]")
    p.add_argument("-q", "--quiet", action="store_true", help="no progress bar")


def run(args: argparse.Namespace) -> int:
    _scale_source(args)
    output = check_output("--output", args.output, {".csv"})
    check_overwrite(output, overwrite=args.overwrite, option="--overwrite", ours=is_track_file,
                    what="a track of eccjump track", name="--output")  # fmt: skip
    tr = track_video(args)
    with writing("--output", output):
        tr.save(output, overwrite=True)  # checked above, before the work
    if args.json:
        print(json.dumps(tr.to_dict() | {"output": str(output)}, indent=1))
    else:
        print("\n".join(tr.summary()))
        print(f"track: {output}")
    return 0


def track_video(args: argparse.Namespace) -> VideoTrack:
    """``eccjump.track`` on ``args.video`` (or ``args.track``, analyze's) with the options,
    a progress bar on stderr (none with --quiet or when stderr is no terminal), and the
    messages naming the options."""
    _scale_source(args)
    video = getattr(args, "video", None) or args.track
    with reporting(shows_progress(args), "frame", unit_scale=False, leave=False) as progress:
        try:
            return track(
                video,
                marker_radius=args.marker_radius,
                scale=args.scale,
                axle_color=args.axle_color,
                marker_color=args.marker_color,
                alpha=None if args.alpha is None else math.radians(args.alpha),
                start=args.start,
                end=args.end,
                progress=progress,
            )
        except (ValueError, TypeError) as err:
            raise type(err)(as_options(str(err))) from None


def _scale_source(args: argparse.Namespace) -> None:
    if args.marker_radius is None and args.scale is None:
        raise ValueError("--marker-radius [m] or --scale [px/m] is due: it sets the scale")


def as_options(message: str) -> str:
    """A message of eccjump.track with the keyword it starts with, or the one it says to
    give, as its option (the file's name is left alone)."""
    message = message.replace("give axle_color", "give --axle-color")
    return _LEADING.sub(lambda m: OPTIONS.get(m.group(1), m.group(1)), message, count=1)

"""``eccjump figures``: write the gallery (the paper's Fig. 3b and 4, slices, a trajectory)."""

from __future__ import annotations

import argparse
import math
import time
from pathlib import Path

from eccjump import plot
from eccjump._base.body import Cylinder
from eccjump.cli._args import directory, int_in, short_text
from eccjump.cli._output import DPI_RANGE, check_outputs, save_figure
from eccjump.motion.roll import roll

#: Figure names, in the order they are written.
FIGURES = ("fig3b", "fig4a", "fig4b", "fig4_slices", "trajectory")
#: ``--n-scan``: the core's bound of ``alpha_intervals``' scan (docs/limits.md).
N_SCAN_MAX = 10**5


def add_parser(sub: argparse._SubParsersAction) -> None:
    p = sub.add_parser(
        "figures",
        help="write the figures (paper's Fig. 3b, Fig. 4a/b, slices, a trajectory) as PNG",
        description="Write fig3b.png, fig4a.png (mu_s = 0.7, n = 1, 2, 3), fig4b.png "
        "(mu_s = 1), fig4_slices.png (mu_s = 1) and trajectory.png (alpha = 40 deg, "
        "chi = 0.15, k_m = 0.02, mu_s = 1) into a directory; print the paths written.",
    )
    p.add_argument(
        "-o",
        "--outdir",
        type=directory,
        default=Path("."),
        help="output directory (made if missing; its parent must exist)",
    )
    p.add_argument(
        "--dpi",
        type=int_in(*DPI_RANGE),
        default=110,
        help=f"resolution of the PNG files, {DPI_RANGE[0]} ... {DPI_RANGE[1]} (default 110)",
    )
    p.add_argument(
        "--resolution",
        type=int_in(2, plot.MAX_RESOLUTION),
        default=36,
        help="(chi, k_m) mesh points per axis of the 3-D regions, 2 ... "
        f"{plot.MAX_RESOLUTION} (default 36)",
    )
    p.add_argument(
        "--slice-resolution",
        type=int_in(2, plot.MAX_SLICE_RESOLUTION),
        default=120,
        help=f"points along each 2-D slice, 2 ... {plot.MAX_SLICE_RESOLUTION} (default 120)",
    )
    p.add_argument(
        "--n-scan",
        type=int_in(2, N_SCAN_MAX),
        default=90,
        help="ramp angles scanned per body before the exact bisection, 2 ... "
        f"{N_SCAN_MAX} (default 90)",
    )
    p.add_argument(
        "--only", choices=FIGURES, nargs="+", default=None, help="write only these figures"
    )
    p.set_defaults(func=_cmd_figures)


def _outdir(path: Path) -> Path:
    """The output directory, made before any work if its parent exists (no parents are
    made: a typo in a parent is an error, not a new tree); ValueError naming --outdir if it
    cannot be."""
    try:
        path.mkdir(exist_ok=True)
    except (OSError, ValueError) as err:  # a file in the way, no permission, a long name
        why = getattr(err, "strerror", None) or str(err)
        raise ValueError(f"--outdir {short_text(str(path), 60)!r}: cannot make it: {why}") from None
    return path


def _cmd_figures(args: argparse.Namespace) -> int:
    import matplotlib

    matplotlib.use("Agg")
    names = args.only or FIGURES
    outdir = _outdir(args.outdir)
    paths = check_outputs("--outdir", (outdir / f"{n}.png" for n in names), {".png"})
    res, n_scan = args.resolution, args.n_scan
    makers = {
        "fig3b": lambda: plot.fig3b(0.5, 0.4),
        "fig4a": lambda: plot.fig4(0.7, (1, 2, 3), resolution=res, n_scan=n_scan),
        "fig4b": lambda: plot.fig4(1.0, (1, 2, 3), resolution=res, n_scan=n_scan),
        "fig4_slices": lambda: plot.fig4_slices(
            1.0, (1, 2, 3), resolution=args.slice_resolution, n_scan=n_scan
        ),
        "trajectory": lambda: plot.trajectory(
            roll(Cylinder(0.15, 0.02), math.radians(40.0), mu_s=1.0, dense_output=True)
        ),
    }
    for name, path in zip(names, paths, strict=True):
        start = time.perf_counter()
        save_figure("--outdir", makers[name](), path, args.dpi)
        print(f"{path}  ({time.perf_counter() - start:.1f} s)", flush=True)
    return 0

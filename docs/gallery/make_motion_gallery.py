"""Write the full-motion gallery: motion.png (plot.motion) and motion.gif (plot.animate_motion)
for the slip-then-jump case alpha = 30 deg, chi = 0.5, k_m = 0.4, mu_s = 1 from rest.

    python docs/gallery/make_motion_gallery.py [outdir]     (default: this directory)

Needs ``eccjump[plot]`` (matplotlib, pillow). The run is cut a while after the first landing
(a quarter of the time to it, at least 1 sqrt(R/g)), so the figure and the animation show the
roll, the slip, the flight and the landing at a readable scale.
"""

from __future__ import annotations

import math
import sys
from pathlib import Path

import matplotlib

matplotlib.use("Agg")
import matplotlib.pyplot as plt

from eccjump import Cylinder, plot

HERE = Path(__file__).resolve().parent

#: The case: it slips at theta ~ 316.47 deg (eccjump roll), then lifts off.
CASE = {"chi": 0.5, "km": 0.4, "alpha_deg": 30.0, "mu_s": 1.0}


def window(result) -> float:
    """The end time to show: a while after the first landing, else the whole run."""
    t_end = float(result.t[-1])
    if result.flights and math.isfinite(result.flights[0].t_landing):
        t_land = float(result.flights[0].t_landing)
        t_end = min(t_end, t_land + max(1.0, 0.25 * t_land))
    return t_end


def small_png(path: Path, colors: int = 128) -> None:
    """Re-save a figure as a palette PNG of ``colors`` colours (a third of its size: the
    gallery is committed, each picture under 100 kB)."""
    from PIL import Image

    with Image.open(path) as im:
        rgb = im.convert("RGB")
    rgb.quantize(colors, method=Image.Quantize.MEDIANCUT, dither=Image.Dither.NONE).save(
        path, optimize=True
    )


def main(outdir: str | Path = HERE) -> list[Path]:
    from eccjump.motion import simulate

    outdir = Path(outdir)
    outdir.mkdir(parents=True, exist_ok=True)
    body = Cylinder(CASE["chi"], CASE["km"])
    alpha = math.radians(CASE["alpha_deg"])
    full = simulate(body, alpha, mu_s=CASE["mu_s"])
    res = simulate(body, alpha, mu_s=CASE["mu_s"], t_max=window(full), dense_output=True)
    png, gif = outdir / "motion.png", outdir / "motion.gif"
    fig = plot.motion(res, body=body, alpha=alpha)
    fig.savefig(png, dpi=110)
    plt.close(fig)
    small_png(png)
    plot.animate_motion(res, gif, body=body, alpha=alpha)
    for tr in res.transitions:
        print(f"  t = {tr.t:10.6f}  {tr.from_mode or '-':>6} -> {tr.to_mode:<6}  {tr.reason}")
    for p in (png, gif):
        print(f"{p}  ({p.stat().st_size / 1024:.0f} KiB)")
    return [png, gif]


if __name__ == "__main__":
    main(sys.argv[1] if len(sys.argv) > 1 else HERE)

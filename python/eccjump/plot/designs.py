"""A design (eccjump.design) on its region slice: where its verdict holds over (χ, α) at
its k_m and worst-case μ_s, the design point, and its margins in α and in the rod
position (at fixed masses: along χ)."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from eccjump._base.checks import integer
from eccjump._base.palette import JARM_COLOR, MODE_COLORS, OTHER_COLOR
from eccjump.plot._common import checked_target, new_figure
from eccjump.studies.design import Design
from eccjump.studies.design.margins import verdict_holds

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

#: The most cells of the slice along a side.
MAX_RESOLUTION = 400


def _window(value: float, lo: float, hi: float, bottom: float, top: float) -> tuple[float, float]:
    """A range around [lo, hi] (an infinite end: the input's own bound) with room either side."""
    lo, hi = (lo if math.isfinite(lo) else bottom), (hi if math.isfinite(hi) else top)
    pad = max(0.5 * (hi - lo), 0.05 * (top - bottom))
    return max(bottom, min(lo, value) - pad), min(top, max(hi, value) + pad)


def design_panel(design: Design, ax: Axes, *, resolution: int = 120) -> Axes:
    """A :class:`~eccjump.studies.design.Design` on its region slice, drawn into ``ax``
    (``Design.plot(ax=ax)``): over (χ, α [deg]) at the design's k_m and worst-case
    μ_s, the cells (``resolution`` a side, at their centres) where its verdict holds under
    both rules; the design (a star), its α margin (vertical bar) and its rod margin
    (horizontal bar: the rod moves χ = ρ (1 - k_m)). Returns ``ax``."""
    if not isinstance(design, Design):
        raise TypeError(f"design must be a Design, not {type(design).__name__}")
    n = integer("resolution", resolution, 2, MAX_RESOLUTION)
    from matplotlib.colors import ListedColormap

    km, chi0, alpha0 = design.body.km, design.body.chi, design.alpha
    a_m, r_m = design.margin("alpha"), design.margin("rod")
    a_lo, a_hi = _window(alpha0, a_m.lo, a_m.hi, 0.0, math.pi / 2)
    c_lo, c_hi = _window(chi0, r_m.lo * (1 - km), r_m.hi * (1 - km), 0.0, 1.0 - km)
    alpha = a_lo + (np.arange(n) + 0.5) * (a_hi - a_lo) / n
    chi = c_lo + (np.arange(n) + 0.5) * (c_hi - c_lo) / n
    holds = verdict_holds(design.target, design.max_turns, design.turn, alpha[:, None],
                          chi[None, :], km, design.mu_s_worst)  # fmt: skip
    color = JARM_COLOR if design.target == "jarm" else MODE_COLORS["SLIP"]
    a_deg = np.degrees(alpha)
    ax.pcolormesh(chi, a_deg, holds.astype(float), cmap=ListedColormap([OTHER_COLOR, color]),
                  vmin=0.0, vmax=1.0, shading="nearest")  # fmt: skip
    _margins(ax, design)
    ax.set_xlabel(r"$\chi = d/R$")
    ax.set_ylabel(r"ramp angle $\alpha$ [deg]")
    verdict = "JARM" if design.target == "jarm" else "slip first"
    ax.set_title(
        rf"{verdict} (both rules) at $k_m = {km:.4g}$, $\mu_s = {design.mu_s_worst:.4g}$ "
        f"(worst case); robustness {100 * design.score:.1f} %",
        fontsize=9,
    )
    return ax


def _margins(ax: Axes, design: Design) -> None:
    """The design point and its margins in α and in the rod position."""
    km, chi0, a0 = design.body.km, design.body.chi, math.degrees(design.alpha)
    a_m, r_m, mu_m = (design.margin(k) for k in ("alpha", "rod", "mu_s"))
    # an infinite end (no boundary in the input's range) is drawn to the input's bound
    a_lo, a_hi = math.degrees(max(a_m.lo, 0.0)), math.degrees(min(a_m.hi, math.pi / 2))
    ax.errorbar([chi0], [a0], yerr=[[a0 - a_lo], [a_hi - a0]], color="k", capsize=4, lw=1.2,
                label=rf"$\alpha$ margin {math.degrees(a_m.margin):.3g}°")  # fmt: skip
    c_lo, c_hi = max(r_m.lo, 0.0) * (1 - km), min(r_m.hi, 1.0) * (1 - km)
    ax.errorbar([chi0], [a0], xerr=[[chi0 - c_lo], [c_hi - chi0]], color="0.35", capsize=4,
                lw=1.2, label=f"rod margin {r_m.margin:.3g} R")  # fmt: skip
    ax.plot([chi0], [a0], "*", ms=13, color="k", mec="white", gid="design",
            label=rf"design ($\mu_s$ margin {mu_m.margin:.3g})")  # fmt: skip
    ax.legend(fontsize=8, loc="best")


def design_slice(design: Design, *, fig: FigureBase | None = None, resolution: int = 120) -> Figure:
    """:func:`design_panel` in a figure of its own (``fig``: an empty Figure or SubFigure to
    draw into, else a new one)."""
    checked_target(None, fig)
    canvas, root = new_figure(fig, (6.0, 4.8))
    design_panel(design, canvas.subplots(), resolution=resolution)
    return root


__all__ = ["MAX_RESOLUTION", "design_panel", "design_slice"]

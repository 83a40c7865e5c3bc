"""A JARM classification over its points (eccjump.jarm): the lift-off angle θ_J, the
forces at the jump and the path condition (the largest friction ratio and the smallest normal
force on the rolling path), against the point's index or a coordinate of the caller's."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import optional_real
from eccjump._base.palette import JARM_COLOR, MODE_COLORS
from eccjump.classification.classify import JarmResult
from eccjump.plot._common import checked_target, new_figure

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase


def _points(
    result: JarmResult, x: Any, xlabel: object
) -> tuple[NDArray[np.float64], str, NDArray[np.bool_]]:
    """(x of every point, flattened; its label; is_jarm, flattened)."""
    if not isinstance(result, JarmResult):
        raise TypeError(f"result must be a JarmResult, not {type(result).__name__}")
    if not isinstance(xlabel, str):
        raise TypeError(f"xlabel must be a str, not {type(xlabel).__name__}")
    jarm = np.asarray(result.is_jarm).ravel()
    if x is None:
        return np.arange(jarm.size, dtype=float), xlabel or "point (flat index)", jarm
    try:
        xs = np.broadcast_to(np.asarray(x, dtype=float), result.shape).ravel()
    except (TypeError, ValueError):
        shown = np.shape(x) if isinstance(x, (list, tuple, np.ndarray)) else type(x).__name__
        raise ValueError(
            f"x must be real numbers of the result's shape {result.shape}, not {shown}"
        ) from None
    return xs, xlabel, jarm


def _flat(result: JarmResult, name: str) -> NDArray[np.float64]:
    return np.asarray(getattr(result, name), dtype=float).ravel()


def _theta_j(ax: Axes, result: JarmResult, x: NDArray, xlabel: str, jarm: NDArray) -> None:
    th = np.degrees(_flat(result, "theta_J"))
    ax.plot(x, th, "-", color="0.75", lw=0.8, zorder=1)
    ax.plot(x[~jarm], th[~jarm], "o", ms=3, color="0.5", label="lift-off, not a JARM")
    ax.plot(x[jarm], th[jarm], "o", ms=3, color=JARM_COLOR, label="JARM", gid="theta_J")
    ax.set_xlabel(xlabel)
    ax.set_ylabel(r"lift-off angle $\theta_J$ [deg]")
    ax.set_title(f"{int(jarm.sum())} JARM of {jarm.size} points", fontsize=10)
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8, loc="best")


def jarm_panel(result: JarmResult, ax: Axes, *, x: Any = None, xlabel: str = "") -> Axes:
    """The main panel of a :func:`eccjump.jarm` result, θ_J [deg] over its points (JARM
    points in the JARM colour; NaN where the body does not lift off), drawn into ``ax``
    (``JarmResult.plot(ax=ax)``). ``x``: a coordinate of the points (broadcast to the
    result's shape; default the flat index), ``xlabel`` its label. Returns ``ax``."""
    xs, label, jarm = _points(result, x, xlabel)
    _theta_j(ax, result, xs, label, jarm)
    return ax


def jarm_points(
    result: JarmResult,
    *,
    fig: FigureBase | None = None,
    x: Any = None,
    xlabel: str = "",
    mu_s: float | None = None,
) -> Figure:
    """Three panels of a :func:`eccjump.jarm` result over its points: θ_J [deg]; the
    forces at the jump F_x and F_y [M g]; and the path condition -- the largest friction
    ratio |F_x|/F_y on the rolling path (with the line ``mu_s`` if given) and the smallest
    normal force [M g] (right axis). ``x``/``xlabel`` as in :func:`jarm_panel`; ``fig``: an
    empty Figure or SubFigure to draw into (else a new one)."""
    xs, label, jarm = _points(result, x, xlabel)
    mu_s = optional_real("mu_s", mu_s)
    checked_target(None, fig)
    canvas, root = new_figure(fig, (7.5, 8.0))
    a_th, a_f, a_p = canvas.subplots(3, 1, sharex=True)
    _theta_j(a_th, result, xs, "", jarm)
    a_f.axhline(0.0, color="0.6", lw=0.7)
    a_f.plot(xs, _flat(result, "Fx_J"), "o-", ms=3, lw=0.8, color=MODE_COLORS["FLIGHT"],
             label=r"friction $F_{x,J}$", gid="Fx_J")  # fmt: skip
    a_f.plot(xs, _flat(result, "Fy_J"), "o-", ms=3, lw=0.8, color=MODE_COLORS["ROLL"],
             label=r"normal $F_{y,J}$", gid="Fy_J")  # fmt: skip
    a_f.set_ylabel("force at the jump [$Mg$]")
    a_f.legend(fontsize=8, loc="best")
    _path_condition(a_p, result, xs, mu_s)
    a_p.set_xlabel(label)
    for ax in (a_f, a_p):
        ax.grid(alpha=0.3)
    canvas.suptitle(r"JARM classification over its points (NaN: not computed or no lift-off)")
    return root


def _path_condition(ax: Axes, result: JarmResult, x: NDArray, mu_s: float | None) -> None:
    """The largest |F_x|/F_y on the rolling path (left) and the smallest F_y (right)."""
    ax.plot(x, _flat(result, "max_ratio"), "o-", ms=3, lw=0.8, color="k",
            label=r"largest $|F_x|/F_y$ on the path", gid="max_ratio")  # fmt: skip
    if mu_s is not None:
        ax.axhline(mu_s, color=MODE_COLORS["SLIP"], ls="--", lw=1.2, label=rf"$\mu_s = {mu_s:g}$")
    ax.set_ylabel(r"friction ratio $|F_x|/F_y$")
    ax.legend(fontsize=8, loc="upper left")
    right = ax.twinx()
    right.plot(x, _flat(result, "min_Fy"), "s", ms=3, color=MODE_COLORS["FLIGHT"],
               gid="min_Fy")  # fmt: skip
    right.set_ylabel(r"smallest $F_y$ on the path [$Mg$] (squares)")


__all__ = ["jarm_panel", "jarm_points"]

"""What every figure module shares: the turn colours, the point cap, matplotlib on demand, and
where a figure is drawn (:mod:`eccjump._base.canvas`, below the analysis figure too)."""

from __future__ import annotations

from typing import TYPE_CHECKING, cast

from eccjump._base.canvas import checked_target, new_figure, pyplot

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure


#: Colours of the turns n = 1, 2, 3 (the paper's green, purple, orange); later turns cycle.
TURN_COLORS = ("#2ca02c", "#8e44ad", "#ff7f0e", "#1f77b4", "#d62728")


#: The most points a curve is sampled at (a bound on memory, not on accuracy).
MAX_POINTS = 10**7


#: matplotlib.pyplot on demand (the base's one import of it).
_plt = pyplot


def _color(n: int) -> str:
    return TURN_COLORS[(n - 1) % len(TURN_COLORS)]


def _new_axes(ax: Axes | None, figsize: tuple[float, float]) -> tuple[Figure, Axes]:
    if ax is not None:
        # The figure the axes draw on (a subfigure's too: its root is what is saved).
        return cast("Figure", ax.get_figure(root=True)), ax
    plt = _plt()
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return fig, ax


__all__ = ["MAX_POINTS", "TURN_COLORS", "checked_target", "new_figure"]

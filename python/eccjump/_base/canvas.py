"""Where a figure is drawn, one rule for every ``.plot()``: ``ax=`` draws one panel into the
caller's Axes, ``fig=`` the full figure into the caller's empty Figure or SubFigure, neither a
new figure. In the base so that the figures' layer (``eccjump.plot``) and the analysis
figure below it (``eccjump.studies.experiment.figure``) share it; matplotlib is imported only
when a figure is drawn (``pip install eccjump[plot]``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

from eccjump._base.optional import require

if TYPE_CHECKING:
    from matplotlib.figure import Figure, FigureBase


def pyplot() -> Any:
    """matplotlib.pyplot, or ImportError naming ``pip install eccjump[plot]``."""
    return require("matplotlib.pyplot", purpose="eccjump.plot", extra="plot")


def checked_target(ax: Any, fig: Any) -> None:
    """Refuse an ``ax`` that is no matplotlib Axes, a ``fig`` that is no Figure or SubFigure
    or already holds axes (new panels would cover them), and both at once."""
    pyplot()
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, SubFigure

    if ax is not None and not isinstance(ax, Axes):
        raise TypeError(f"ax must be a matplotlib Axes or None, not {type(ax).__name__}")
    if fig is not None and not isinstance(fig, (Figure, SubFigure)):
        raise TypeError(
            f"fig must be a matplotlib Figure or SubFigure or None, not {type(fig).__name__}"
        )
    if ax is not None and fig is not None:
        raise TypeError("give ax= (one panel) or fig= (the full figure), not both")
    held = len(fig.get_axes()) if fig is not None else 0
    if held:
        raise ValueError(f"fig must be empty (it holds {held} axes): pass a new one")


def new_figure(fig: FigureBase | None, figsize: tuple[float, float]) -> tuple[FigureBase, Figure]:
    """(where to draw, the figure to return): the caller's ``fig`` (checked by
    :func:`checked_target`) or a new one of ``figsize`` inches; a SubFigure returns its root."""
    if fig is None:
        new = pyplot().figure(figsize=figsize, layout="constrained")
        return new, new
    return fig, fig.get_figure(root=True)


__all__ = ["checked_target", "new_figure", "pyplot"]

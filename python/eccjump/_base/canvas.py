"""Where a figure is drawn, one rule for every ``.plot()``: ``ax=`` draws one panel into the
caller's Axes, ``fig=`` the full figure into the caller's empty Figure or SubFigure, neither a
new figure. In the base so that the figures' layer (``eccjump.plot``) and the analysis
figure below it (``eccjump.studies.experiment.figure``) share it, with the ``.plot()`` of
every result (:class:`Plottable`); matplotlib is imported only when a figure is drawn
(``pip install eccjump[plot]``)."""

from __future__ import annotations

import functools
from typing import TYPE_CHECKING, Any, ClassVar, overload

from eccjump._base.optional import require

if TYPE_CHECKING:
    from matplotlib.axes import Axes
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


class Plottable:
    """A result's ``.plot()``, typed once: ``r.plot()`` is a new Figure, ``r.plot(ax=ax)``
    the Axes drawn into. A class says what its figure shows in ``_plot_doc``, and gets a
    ``plot`` of its own with that docstring (``help()``; the API reference reads it through
    ``docs/_ext/griffe_eccjump.py``)."""

    #: The docstring of the class's ``plot``: what its figure shows and what ``ax=`` draws.
    _plot_doc: ClassVar[str]

    def __init_subclass__(cls, **kwargs: Any) -> None:
        super().__init_subclass__(**kwargs)
        if "_plot_doc" in vars(cls):
            cls.plot = _own_plot(cls)  # type: ignore[method-assign]  # typed as Plottable.plot

    @overload
    def plot(self, *, ax: Axes, **kwargs: Any) -> Axes: ...
    @overload
    def plot(self, *, ax: None = None, fig: FigureBase | None = None, **kwargs: Any) -> Figure: ...
    def plot(
        self, *, ax: Axes | None = None, fig: FigureBase | None = None, **kwargs: Any
    ) -> Axes | Figure:
        """The result's figure (``eccjump.plot.draw``). ``ax=``: one panel, drawn into this
        matplotlib Axes and returned, to compose figures; ``fig=``: the full figure in this
        empty Figure or SubFigure. Needs ``pip install eccjump[plot]``."""
        from eccjump import plot  # figures: the layer on top of every result

        return plot.draw(self, ax=ax, fig=fig, **kwargs)


def _own_plot(cls: type[Plottable]) -> Any:
    """:meth:`Plottable.plot` as a method of ``cls`` with its ``_plot_doc`` (a wrapper:
    ``help()`` follows it to the signature), named where ``help()`` and tracebacks look."""

    @functools.wraps(Plottable.plot)
    def plot(self: Plottable, **kwargs: Any) -> Any:
        return Plottable.plot(self, **kwargs)

    plot.__module__, plot.__qualname__ = cls.__module__, f"{cls.__qualname__}.plot"
    plot.__doc__ = cls._plot_doc
    return plot


__all__ = ["Plottable", "checked_target", "new_figure", "pyplot"]

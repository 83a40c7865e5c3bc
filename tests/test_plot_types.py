"""The ``.plot()`` of every result, written once (``eccjump._base.canvas.Plottable``): mypy
checks this file (pyproject's ``[tool.mypy] files``) for the types, ``r.plot()`` a Figure and
``r.plot(ax=ax)`` the Axes drawn into; pytest checks that each class describes its own figure
(``help()``, the API reference) and, with one result, the same types at run time."""

from __future__ import annotations

import inspect
from typing import assert_type, get_args

import matplotlib
import numpy as np
import pytest

matplotlib.use("Agg")
import matplotlib.pyplot as plt
from matplotlib.axes import Axes
from matplotlib.figure import Figure

import eccjump
from eccjump._base.canvas import Plottable
from eccjump.plot.compose import PLOTS

#: Every result class with a ``.plot()`` (``test_every_result_is_here``: the figures' table).
Plotted = (
    eccjump.JarmResult
    | eccjump.Region
    | eccjump.StartMap
    | eccjump.MotionMap
    | eccjump.RollResult
    | eccjump.MotionResult
    | eccjump.Design
    | eccjump.Analysis
    | eccjump.Uncertainty
)
CLASSES: tuple[type[Plottable], ...] = get_args(Plotted)


def _typed_plots(result: Plotted, ax: Axes) -> None:
    """For mypy each class of the union on its own: a plot typed ``Axes | Figure`` fails."""
    assert_type(result.plot(), Figure)
    assert_type(result.plot(fig=plt.figure()), Figure)
    assert_type(result.plot(ax=ax, km_frac=0.1), Axes)


def test_every_result_is_here() -> None:
    assert set(CLASSES) == set(PLOTS)
    assert all(issubclass(cls, Plottable) for cls in CLASSES)


def test_each_class_describes_its_own_figure() -> None:
    docs = {cls: inspect.getdoc(cls.plot) or "" for cls in CLASSES}
    assert len(set(docs.values())) == len(CLASSES), "two classes share a description"
    for cls, doc in docs.items():
        assert cls.plot.__qualname__ == f"{cls.__name__}.plot"
        assert "``ax=``" in doc and doc != inspect.getdoc(Plottable.plot), cls


def test_the_types_hold_at_run_time() -> None:
    region = eccjump.region(np.radians([35.0, 40.0]), [0.1, 0.15], [0.0, 0.1], 1.0)
    try:
        _typed_plots(region, plt.figure().add_subplot())
        assert isinstance(region.plot(), Figure)
        ax = plt.figure().add_subplot()
        assert region.plot(ax=ax) is ax
        with pytest.raises(TypeError, match="ax must be a matplotlib Axes"):
            region.plot(ax="axes")  # type: ignore[call-overload]
    finally:
        plt.close("all")

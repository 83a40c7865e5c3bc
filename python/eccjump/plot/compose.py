"""The ``.plot()`` of every result, in one place: ``ax=`` draws the result's main panel into
the caller's Axes and returns it, ``fig=`` draws the full figure into the caller's empty
Figure or SubFigure, neither draws the full figure in a new one (the rule of
:mod:`eccjump._base.canvas`). Each result type names its panel and its figure here."""

from __future__ import annotations

from collections.abc import Callable
from typing import TYPE_CHECKING, Any

from eccjump.classification.classify import JarmResult, Region
from eccjump.classification.starts import StartMap
from eccjump.motion.maps import MotionMap
from eccjump.motion.roll import RollResult
from eccjump.motion.simulation import MotionResult
from eccjump.plot._common import checked_target
from eccjump.plot.designs import design_panel, design_slice
from eccjump.plot.full_motion import motion, motion_panel
from eccjump.plot.maps import (
    fraction_map,
    fraction_panel,
    region_map,
    region_panel,
    sequence_map,
    sequence_panel,
)
from eccjump.plot.points import jarm_panel, jarm_points
from eccjump.plot.trajectories import roll_panel, trajectory
from eccjump.plot.uncertainty_study import outcomes_panel, uncertainty
from eccjump.studies.design import Design
from eccjump.studies.experiment import figure
from eccjump.studies.experiment.analysis import Analysis
from eccjump.studies.uncertainty import Uncertainty

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

#: Each result type: (its main panel, drawn into an Axes; its full figure).
PLOTS: dict[type, tuple[Callable[..., Any], Callable[..., Any]]] = {
    RollResult: (roll_panel, trajectory),
    MotionResult: (motion_panel, motion),
    JarmResult: (jarm_panel, jarm_points),
    Region: (region_panel, region_map),
    MotionMap: (sequence_panel, sequence_map),
    StartMap: (fraction_panel, fraction_map),
    Uncertainty: (outcomes_panel, uncertainty),
    Design: (design_panel, design_slice),
    Analysis: (figure.theta_panel, figure.analysis_figure),
}


def draw(
    result: Any, *, ax: Axes | None = None, fig: FigureBase | None = None, **kwargs: Any
) -> Axes | Figure:
    """Draw ``result`` (any result with a ``.plot()``): its main panel into ``ax`` (returned),
    else its full figure into ``fig`` or a new figure (the Figure returned; a SubFigure's
    root). ``kwargs`` go to the panel's or the figure's function (``PLOTS``)."""
    checked_target(ax, fig)
    kind = next((k for k in PLOTS if isinstance(result, k)), None)
    if kind is None:
        raise TypeError(f"result must be an eccjump result, not {type(result).__name__}")
    panel, full = PLOTS[kind]
    if ax is not None:
        return panel(result, ax, **kwargs)
    return full(result, fig=fig, **kwargs)


__all__ = ["PLOTS", "draw"]

"""The figure of an analysis: data and fitted model against time -- θ, the slip velocity
and the height of the axle above the ramp -- with the modes as bands (observed on top of the
first panel's strip, the model's below). matplotlib is imported only when it is drawn
(``pip install eccjump[plot]``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from eccjump._base.canvas import checked_target, new_figure
from eccjump._base.palette import MODE_COLORS

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

NAMES = ("ROLL", "SLIP", "FLIGHT")


def _panels(result: Any) -> list[tuple[Any, Any, Any, str]]:
    """(data, its standard error, the model, the label) of each panel, against the track's
    time: θ [deg], the slip velocity [m/s], b - R [mm]."""
    rec, setup = result.rec, result.setup
    y = result.fit.states
    model_slip = (y[3] - y[1]) * setup.radius / setup.time_unit  # l̇ - R θ̇ in m/s
    return [
        (np.degrees(rec.theta), np.degrees(rec.theta_err), np.degrees(y[0]), "theta [deg]"),
        (rec.slip, rec.slip_err, model_slip, "slip velocity [m/s]"),
        (
            rec.height * 1e3,
            np.full(rec.t.size, rec.sigma * 1e3),
            (y[4] - 1) * result.setup.radius * 1e3,
            "b - R [mm]",
        ),
    ]


def _data_and_model(ax: Axes, result: Any, panel: tuple[Any, Any, Any, str]) -> None:
    """One panel: the model's modes as bands, the data with its band, the model's line."""
    data, err, model, label = panel
    t = result.rec.t
    run_t = t[0] + np.asarray(result.fit.run.t) * result.setup.time_unit
    _bands(ax, run_t, np.asarray(result.fit.run.mode), alpha=0.12)
    ax.fill_between(t, data - err, data + err, color="0.6", alpha=0.5, lw=0)
    ax.plot(t, data, ".", ms=2.5, color="k", label="track")
    ax.plot(t, model, "-", lw=1.2, color="#D55E00", label="model")
    ax.set_ylabel(label)


def _title(result: Any) -> str:
    title = f"verdict: {result.verdict}" + (f" ({result.reason})" if result.reason else "")
    return title + "  (bands: model modes; strip: observed)"


def theta_panel(result: Any, ax: Axes) -> Axes:
    """The main panel of an analysis, θ [deg] against t [s] (data with its band, the
    model, the modes: the model's as bands, the observed as a strip on top), drawn into
    ``ax`` (``Analysis.plot(ax=ax)``); returns ``ax``."""
    checked_target(ax, None)
    _data_and_model(ax, result, _panels(result)[0])
    _strip(ax, result.rec.t, result.observed.mode)
    ax.legend(loc="upper left", fontsize=8)
    ax.set_xlabel("t [s]")
    ax.set_title(_title(result), fontsize=10)
    return ax


def analysis_figure(
    result: Any, *, fig: FigureBase | None = None, figsize: tuple[float, float] = (8.0, 7.5)
) -> Figure:
    """Three panels against time [s]: θ [deg], slip velocity [m/s] and b - R [mm], the
    data with one-standard-error bands, the model as a line; modes as bands (the model's)
    and a strip of the observed modes at the top. ``fig``: an empty Figure or SubFigure to
    draw into (else a new one of ``figsize`` inches)."""
    checked_target(None, fig)
    canvas, root = new_figure(fig, figsize)
    axes = canvas.subplots(3, 1, sharex=True)
    for ax, panel in zip(axes, _panels(result), strict=True):
        _data_and_model(ax, result, panel)
    _strip(axes[0], result.rec.t, result.observed.mode)
    axes[0].legend(loc="upper left", fontsize=8)
    axes[-1].set_xlabel("t [s]")
    axes[0].set_title(_title(result), fontsize=10)
    return root


def _bands(ax: Axes, t: np.ndarray, mode: np.ndarray, alpha: float) -> None:
    if t.size < 2:
        return
    change = np.flatnonzero(np.diff(mode)) + 1
    for i, j in zip(np.r_[0, change], np.r_[change, t.size - 1], strict=True):
        ax.axvspan(t[i], t[j], color=MODE_COLORS[NAMES[int(mode[i])]], alpha=alpha, lw=0)


def _strip(ax: Axes, t: np.ndarray, mode: np.ndarray) -> None:
    """The observed modes as a thin strip along the top of ``ax``."""
    change = np.flatnonzero(np.diff(mode)) + 1
    for i, j in zip(np.r_[0, change], np.r_[change, t.size - 1], strict=True):
        ax.axvspan(t[i], t[j], ymin=0.94, ymax=1.0, color=MODE_COLORS[NAMES[int(mode[i])]], lw=0)

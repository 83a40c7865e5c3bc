"""The figure of an analysis: data and fitted model against time -- theta, the slip velocity
and the height of the axle above the ramp -- with the modes as bands (observed on top of the
first panel's strip, the model's below). matplotlib is imported only when it is drawn
(``pip install eccjump[plot]``)."""

from __future__ import annotations

from typing import TYPE_CHECKING, Any

import numpy as np

from eccjump._base.html import MODE_COLORS
from eccjump._base.optional import require

if TYPE_CHECKING:  # pragma: no cover
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

NAMES = ("ROLL", "SLIP", "FLIGHT")


def analysis_figure(result: Any, *, figsize: tuple[float, float] = (8.0, 7.5)) -> Figure:
    """Three panels against time [s]: theta [deg], slip velocity [m/s] and b - R [mm], the
    data with one-standard-error bands, the model as a line; modes as bands (the model's)
    and a strip of the observed modes at the top."""
    plt = require("matplotlib.pyplot", purpose="the analysis figure", extra="plot")
    rec, fitted, setup = result.rec, result.fit, result.setup
    t = rec.t
    y = fitted.states
    unit = setup.time_unit
    model_slip = (y[3] - y[1]) * setup.radius / unit  # ldot - R omega in m/s
    fig, axes = plt.subplots(3, 1, sharex=True, figsize=figsize, layout="constrained")
    panels = (
        (np.degrees(rec.theta), np.degrees(rec.theta_err), np.degrees(y[0]), "theta [deg]"),
        (rec.slip, rec.slip_err, model_slip, "slip velocity [m/s]"),
        (
            rec.height * 1e3,
            np.full(t.size, rec.sigma * 1e3),
            (y[4] - 1) * setup.radius * 1e3,
            "b - R [mm]",
        ),
    )
    model_mode = np.asarray(fitted.run.mode)
    run_t = t[0] + np.asarray(fitted.run.t) * unit
    for ax, (data, err, model, label) in zip(axes, panels, strict=True):
        _bands(ax, run_t, model_mode, alpha=0.12)
        ax.fill_between(t, data - err, data + err, color="0.6", alpha=0.5, lw=0)
        ax.plot(t, data, ".", ms=2.5, color="k", label="track")
        ax.plot(t, model, "-", lw=1.2, color="#d62728", label="model")
        ax.set_ylabel(label)
    _strip(axes[0], t, result.observed.mode)
    axes[0].legend(loc="upper left", fontsize=8)
    axes[-1].set_xlabel("t [s]")
    title = f"verdict: {result.verdict}" + (f" ({result.reason})" if result.reason else "")
    axes[0].set_title(title + "  (bands: model modes; strip: observed)", fontsize=10)
    return fig


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

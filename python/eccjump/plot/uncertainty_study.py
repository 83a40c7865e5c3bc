"""The figure of an uncertainty study (:func:`eccjump.uncertainty`): the outcomes with their
Wilson intervals, the samples over the two most spread parameters coloured JARM or not,
the distributions of the lift-off and the first flight, and the Sobol' indices (which
tolerance matters) where the study has them."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from eccjump._base.checks import integer
from eccjump._base.palette import JARM_COLOR
from eccjump.plot._common import checked_target, new_figure
from eccjump.studies.uncertainty import Uncertainty
from eccjump.studies.uncertainty.sampling import UNITS

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

#: How each distribution is shown: its label and the factor to its display unit.
_SHOWN = {
    "liftoff_theta": ("lift-off angle [deg]", 180 / math.pi),
    "liftoff_t": (r"lift-off time [$\sqrt{R/g}$]", 1.0),
    "flight_time": (r"flight time [$\sqrt{R/g}$]", 1.0),
    "apex": ("apex [R]", 1.0),
    "distance": ("flight distance [R]", 1.0),
}

#: The most samples drawn in the scatter panel (every k-th beyond it).
MAX_SCATTER = 20_000


def _checked(result: Uncertainty, outcomes: int) -> int:
    if not isinstance(result, Uncertainty):
        raise TypeError(f"result must be an Uncertainty, not {type(result).__name__}")
    return integer("outcomes", outcomes, 1, 64)


def outcomes_panel(result: Uncertainty, ax: Axes, *, outcomes: int = 6) -> Axes:
    """The main distribution of an uncertainty study, that of its outcomes: the ``outcomes``
    most frequent (reasons or sequences) as bars with their Wilson intervals, drawn into
    ``ax`` (``Uncertainty.plot(ax=ax)``); returns ``ax``."""
    _outcome_bars(ax, result, _checked(result, outcomes))
    return ax


def uncertainty(result: Uncertainty, *, fig: FigureBase | None = None, outcomes: int = 6) -> Figure:
    """The study in one figure: the ``outcomes`` most frequent outcomes (reasons or sequences)
    as bars with their Wilson intervals, the samples over the two varied parameters of
    largest relative spread (JARM in green), a histogram of each distribution with its
    median and central 95 %, and with ``indices=True`` the first-order and total Sobol'
    indices of each varied parameter as bars with their bootstrap intervals. ``fig``: an
    empty Figure or SubFigure to draw into (else a new one)."""
    outcomes = _checked(result, outcomes)
    checked_target(None, fig)
    shown = [k for k, s in result.distributions.items() if s.n]
    has_indices = bool(result.indices)
    panels = 2 + len(shown) + has_indices
    cols = min(panels, 3)
    rows = math.ceil(panels / cols)
    canvas, root = new_figure(fig, (4.2 * cols, 3.4 * rows))
    flat = list(np.atleast_1d(canvas.subplots(rows, cols)).ravel())
    _outcome_bars(flat[0], result, outcomes)
    _scatter(flat[1], result)
    for ax, name in zip(flat[2:], shown, strict=False):
        _histogram(ax, result, name)
    if has_indices:
        _index_bars(flat[panels - 1], result)
    for ax in flat[panels:]:
        ax.set_visible(False)
    lo, hi = result.p_jarm_ci
    canvas.suptitle(
        f"P(JARM) = {result.p_jarm:.4g} [{lo:.4g}, {hi:.4g}] "
        f"({100 * result.confidence:g} %, {result.n_valid} valid of {result.n}, "
        f"{result.sampling})"
    )
    return root


def _outcome_bars(ax: Axes, result: Uncertainty, most: int) -> None:
    names = list(result.counts)[:most]
    p = np.array([result.probabilities[k] for k in names])
    ci = np.array([result.interval(k) for k in names]).reshape(-1, 2)
    y = np.arange(len(names))
    err = np.vstack([p - ci[:, 0], ci[:, 1] - p]) if names else None
    ax.barh(y, p, xerr=err, color="#56B4E9", ecolor="k", capsize=3)
    ax.set_yticks(y, [n.replace("→", ">") for n in names], fontsize=7)
    ax.invert_yaxis()
    ax.set_xlim(0, 1)
    ax.set_xlabel("probability")
    ax.set_ylabel("outcome")
    ax.set_title("outcomes", fontsize=9)


def _index_bars(ax: Axes, result: Uncertainty) -> None:
    """Each varied parameter's first-order and total index, side by side, with intervals."""
    indices = result.indices or {}
    names = list(indices)
    y = np.arange(len(names))
    for k, (what, color) in enumerate((("first", "#9ecae1"), ("total", "#3182bd"))):
        est = np.array([getattr(indices[n], what) for n in names]).reshape(-1, 3)
        err = np.vstack([est[:, 0] - est[:, 1], est[:, 2] - est[:, 0]]).clip(min=0)
        ax.barh(y + (k - 0.5) * 0.4, est[:, 0], height=0.4, xerr=err, color=color,
                ecolor="k", capsize=2, label=what)  # fmt: skip
    ax.set_yticks(y, names, fontsize=8)
    ax.invert_yaxis()
    ax.set_xlim(min(0.0, ax.get_xlim()[0]), max(1.0, ax.get_xlim()[1]))
    ax.set_xlabel("Sobol' index of P(JARM)")
    ax.legend(fontsize=7, loc="best")
    ax.set_title(f"which tolerance matters ({100 * result.confidence:g} % bootstrap)", fontsize=9)


def _spread_order(result: Uncertainty) -> list[str]:
    """The varied parameters, most spread (relative to the nominal, or absolute) first."""

    def rel(name: str) -> float:
        x = result.samples[name]
        scale = abs(result.nominal[name]) or 1.0
        return float(np.nanstd(x)) / scale

    return sorted(result.samples, key=rel, reverse=True)


def _scatter(ax: Axes, result: Uncertainty) -> None:
    names = _spread_order(result)
    jarm = np.asarray(result.outcomes["is_jarm" if result.question == "jarm" else "jarm"])
    step = max(1, math.ceil(result.n_valid / MAX_SCATTER))
    idx = np.flatnonzero(result.valid)[::step]
    if not names:
        ax.text(0.5, 0.5, "no parameter varies", ha="center", va="center")
        ax.set_axis_off()
        return
    x = result.samples[names[0]][idx]
    y = result.samples[names[1]][idx] if len(names) > 1 else np.zeros(idx.size)
    j = jarm[idx]
    ax.scatter(x[~j], y[~j], s=2, c="#bbbbbb", label="not JARM", rasterized=True)
    ax.scatter(x[j], y[j], s=2, c=JARM_COLOR, label="JARM", rasterized=True)
    ax.set_xlabel(_label(names[0]))
    ax.set_ylabel(_label(names[1]) if len(names) > 1 else "")
    ax.legend(fontsize=7, markerscale=4, loc="best")
    ax.set_title("samples", fontsize=9)


def _label(name: str) -> str:
    return f"{name} [{UNITS[name]}]"


def _histogram(ax: Axes, result: Uncertainty, name: str) -> None:
    label, factor = _SHOWN[name]
    x = np.asarray(result.outcomes[name], dtype=float)[result.valid] * factor
    x = x[np.isfinite(x)]
    s = result.distributions[name]
    ax.hist(x, bins=min(80, max(10, int(math.sqrt(x.size)))), color="#56B4E9")
    for q, style in ((s.median, "-"), (s.q025, "--"), (s.q975, "--")):
        ax.axvline(q * factor, color="k", ls=style, lw=0.8)
    ax.set_xlabel(label)
    ax.set_ylabel("samples")
    ax.set_title(f"{name}: median {s.median * factor:.4g} (95 %: dashed)", fontsize=9)


__all__ = ["MAX_SCATTER", "outcomes_panel", "uncertainty"]

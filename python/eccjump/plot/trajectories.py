"""A pure-rolling run (eccjump.roll): θ against t, and the forces against θ."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer, optional_real
from eccjump._base.palette import MODE_COLORS
from eccjump.motion.roll import RollResult

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

from eccjump.plot._common import MAX_POINTS, checked_target, new_figure

# --------------------------------------------------------------------------------------------
# a pure-rolling run
# --------------------------------------------------------------------------------------------

_EVENT_STYLE = {
    "liftoff": ("#d62728", "lift-off (paper)"),
    "normal_force_zero": ("#9467bd", r"$F_y = 0$"),
    "slip": (MODE_COLORS["SLIP"], "slip"),
    "theta_limit": ("0.4", r"$\theta$ limit"),
}


def _dense_run(result: RollResult, n_points: int) -> tuple[NDArray[np.float64], ...]:
    """(t, θ, omega, Fx, Fy, |Fx|/Fy) on a fine time grid from the dense output (state,
    forces and friction ratio evaluated by the core), or the accepted steps."""
    r = result
    if r.sol is None or r.units is not None or len(r.t) < 2:
        return r.t, r.theta, r.omega, r.Fx, r.Fy, r.friction_ratio
    t = np.union1d(np.linspace(r.t[0], r.t[-1], n_points), r.t)
    k = r.sol.kinematics(t)
    return t, k["theta"], k["omega"], k["Fx"], k["Fy"], k["ratio"]


def _checked(result: RollResult, n_points: int) -> int:
    if not isinstance(result, RollResult):
        raise TypeError(f"result must be a RollResult, not {type(result).__name__}")
    return integer("n_points", n_points, 2, MAX_POINTS)


def _units(result: RollResult) -> tuple[str, str, str]:
    """The units of time, rate and force on the axes."""
    if result.units is not None:
        return "s", "rad/s", "N"
    return r"$\sqrt{R/g}$", r"$\sqrt{g/R}$", "$Mg$"


def roll_panel(result: RollResult, ax: Axes, *, n_points: int = 2000) -> Axes:
    """The main panel of a :func:`eccjump.roll` run, θ [deg] against t with its events,
    drawn into ``ax`` (``RollResult.plot(ax=ax)``); returns ``ax``."""
    n_points = _checked(result, n_points)
    t, theta = _dense_run(result, n_points)[:2]
    _theta_time(ax, result, t, np.degrees(theta))
    ax.grid(alpha=0.3)
    ax.legend(fontsize=8.5, loc="best")
    return ax


def _event_marks(result: RollResult) -> list[tuple[float, float, str, str | None]]:
    """(t, θ [deg], colour, legend label) of each event; one label per kind of event."""
    marks: list[tuple[float, float, str, str | None]] = []
    seen: set[str] = set()
    for e in result.events:
        color, name = _EVENT_STYLE.get(e.name, ("0.3", e.name))
        e_th = math.degrees(e.theta)
        label = None if e.name in seen else f"{name}: $\\theta$ = {e_th:.3f}°"
        seen.add(e.name)
        marks.append((e.t, e_th, color, label))
    return marks


def _theta_time(ax: Axes, result: RollResult, t: NDArray, th: NDArray) -> None:
    """θ against t with lines at each event."""
    ax.plot(t, th, color="k", lw=1.5, label=r"$\theta(t)$", gid="theta")
    ax.set_xlabel(f"time $t$ [{_units(result)[0]}]")
    ax.set_ylabel(r"$\theta$ [deg]")
    ax.set_title("angle against time")
    for e_t, e_th, color, label in _event_marks(result):
        ax.axhline(e_th, color=color, ls=":", lw=1.2)
        ax.axvline(e_t, color=color, ls=":", lw=1.2, label=label)


def trajectory(
    result: RollResult,
    *,
    fig: FigureBase | None = None,
    n_points: int = 2000,
    ratio_max: float | None = None,
) -> Figure:
    """Four panels of a :func:`eccjump.roll` run: θ against t, and θ̇, F_x, F_y and
    the friction ratio |F_x|/F_y (only where F_y > 0, with the line μ_s) against θ in
    degrees; every event marked with a vertical line. Uses the dense output if present.
    ``fig``: an empty Figure or SubFigure to draw into (else a new one)."""
    n_points = _checked(result, n_points)
    optional_real("ratio_max", ratio_max)
    checked_target(None, fig)
    canvas, root = new_figure(fig, (10.5, 7.2))
    _, u_w, u_f = _units(result)
    t, theta, omega, fx, fy, ratio = _dense_run(result, n_points)
    th = np.degrees(theta)
    axes = canvas.subplots(2, 2)
    (a_t, a_w), (a_f, a_r) = axes
    _theta_time(a_t, result, t, th)

    a_w.plot(th, omega, color="k", lw=1.5, label=r"$\dot\theta$")
    a_w.set_ylabel(rf"$\dot\theta$ [{u_w}]")
    a_w.set_title("angular velocity")

    a_f.axhline(0.0, color="0.6", lw=0.7)
    a_f.plot(th, fx, color="#0072B2", lw=1.5, label=r"$F_x$ (friction, + down the ramp)")
    a_f.plot(th, fy, color="#009E73", lw=1.5, label=r"$F_y$ (normal)")
    a_f.set_ylabel(f"contact force [{u_f}]")
    a_f.set_title("contact forces on the cylinder")

    ratio = np.where(np.isfinite(ratio), ratio, np.nan)  # +inf where F_y <= 0: not drawn
    a_r.plot(th, ratio, color="k", lw=1.5, label=r"$|F_x|/F_y$ ($F_y > 0$)")
    if result.mu_s is not None:
        a_r.axhline(
            result.mu_s, color="#E69F00", ls="--", lw=1.2, label=rf"$\mu_s = {result.mu_s:g}$"
        )
    top = ratio_max
    if top is None:
        finite = ratio[np.isfinite(ratio)]
        top = 1.1 * (max(float(np.max(finite)), result.mu_s or 0.0) if finite.size else 1.0)
        if result.mu_s is not None:
            top = min(top, 2.0 * result.mu_s)
    a_r.set_ylim(0.0, top)
    a_r.set_ylabel(r"friction ratio $|F_x|/F_y$")
    a_r.set_title("friction needed for rolling")
    for a in (a_w, a_f, a_r):
        a.set_xlabel(r"$\theta$ [deg]")
        a.set_xlim(th[0], th[-1] + 0.02 * (th[-1] - th[0] or 1.0))
    for _, e_th, color, label in _event_marks(result):
        for a in (a_w, a_f, a_r):
            a.axvline(e_th, color=color, ls=":", lw=1.2, label=label)
    for a in axes.ravel():
        a.grid(alpha=0.3)
        a.legend(fontsize=8.5, loc="best")
    b = result.body
    mu = "none" if result.mu_s is None else f"{result.mu_s:g}"
    canvas.suptitle(
        rf"Pure rolling from $\theta_0 = {math.degrees(result.theta[0]):g}°$: "
        rf"$\alpha = {math.degrees(result.alpha):g}°$, $\chi = {b.chi:g}$, $k_m = {b.km:g}$, "
        rf"$\mu_s = {mu}$ ({result.rule} rule) — {result.message}",
        fontsize=11,
    )
    return root

"""A pure-rolling run (eccjump.roll): theta against t, and the forces against theta."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer, optional_real
from eccjump.motion.roll import RollResult

if TYPE_CHECKING:
    from matplotlib.figure import Figure

from eccjump.plot._common import MAX_POINTS, _plt

# --------------------------------------------------------------------------------------------
# a pure-rolling run
# --------------------------------------------------------------------------------------------

_EVENT_STYLE = {
    "liftoff": ("#d62728", "lift-off (paper)"),
    "normal_force_zero": ("#9467bd", r"$F_y = 0$"),
    "slip": ("#ff7f0e", "slip"),
    "theta_limit": ("0.4", r"$\theta$ limit"),
}


def _dense_run(result: RollResult, n_points: int) -> tuple[NDArray[np.float64], ...]:
    """(t, theta, omega, Fx, Fy, |Fx|/Fy) on a fine time grid from the dense output (state,
    forces and friction ratio evaluated by the core), or the accepted steps."""
    r = result
    if r.sol is None or r.units is not None or len(r.t) < 2:
        return r.t, r.theta, r.omega, r.Fx, r.Fy, r.friction_ratio
    t = np.union1d(np.linspace(r.t[0], r.t[-1], n_points), r.t)
    k = r.sol.kinematics(t)
    return t, k["theta"], k["omega"], k["Fx"], k["Fy"], k["ratio"]


def trajectory(
    result: RollResult, *, n_points: int = 2000, ratio_max: float | None = None
) -> Figure:
    """Four panels of a :func:`eccjump.roll` run: theta against t, and theta', F_x, F_y and
    the friction ratio |F_x|/F_y (only where F_y > 0, with the line mu_s) against theta in
    degrees; every event marked with a vertical line. Uses the dense output if present."""
    if not isinstance(result, RollResult):
        raise TypeError(f"result must be a RollResult, not {type(result).__name__}")
    n_points = integer("n_points", n_points, 2, MAX_POINTS)
    optional_real("ratio_max", ratio_max)
    plt = _plt()
    si = result.units is not None
    u_t, u_w, u_f = ("s", "rad/s", "N") if si else (r"$\sqrt{R/g}$", r"$\sqrt{g/R}$", "$Mg$")
    t, theta, omega, fx, fy, ratio = _dense_run(result, n_points)
    th = np.degrees(theta)
    fig, axes = plt.subplots(2, 2, figsize=(10.5, 7.2), layout="constrained")
    (a_t, a_w), (a_f, a_r) = axes

    a_t.plot(t, th, color="k", lw=1.5, label=r"$\theta(t)$")
    a_t.set_xlabel(f"time $t$ [{u_t}]")
    a_t.set_ylabel(r"$\theta$ [deg]")
    a_t.set_title("angle against time")

    a_w.plot(th, omega, color="k", lw=1.5, label=r"$\dot\theta$")
    a_w.set_ylabel(rf"$\dot\theta$ [{u_w}]")
    a_w.set_title("angular velocity")

    a_f.axhline(0.0, color="0.6", lw=0.7)
    a_f.plot(th, fx, color="#1f77b4", lw=1.5, label=r"$F_x$ (friction, + down the ramp)")
    a_f.plot(th, fy, color="#2ca02c", lw=1.5, label=r"$F_y$ (normal)")
    a_f.set_ylabel(f"contact force [{u_f}]")
    a_f.set_title("contact forces on the cylinder")

    ratio = np.where(np.isfinite(ratio), ratio, np.nan)  # +inf where F_y <= 0: not drawn
    a_r.plot(th, ratio, color="k", lw=1.5, label=r"$|F_x|/F_y$ ($F_y > 0$)")
    if result.mu_s is not None:
        a_r.axhline(
            result.mu_s, color="#ff7f0e", ls="--", lw=1.2, label=rf"$\mu_s = {result.mu_s:g}$"
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
    seen: set[str] = set()
    for e in result.events:
        color, name = _EVENT_STYLE.get(e.name, ("0.3", e.name))
        e_th = math.degrees(e.theta)
        label = f"{name}: $\\theta$ = {e_th:.3f}°" if e.name not in seen else None
        seen.add(e.name)
        a_t.axhline(e_th, color=color, ls=":", lw=1.2)
        a_t.axvline(e.t, color=color, ls=":", lw=1.2, label=label)
        for a in (a_w, a_f, a_r):
            a.axvline(e_th, color=color, ls=":", lw=1.2, label=label)
    for a in axes.ravel():
        a.grid(alpha=0.3)
        a.legend(fontsize=8.5, loc="best")
    b = result.body
    mu = "none" if result.mu_s is None else f"{result.mu_s:g}"
    fig.suptitle(
        rf"Pure rolling from $\theta_0 = {math.degrees(result.theta[0]):g}°$: "
        rf"$\alpha = {math.degrees(result.alpha):g}°$, $\chi = {b.chi:g}$, $k_m = {b.km:g}$, "
        rf"$\mu_s = {mu}$ ({result.rule} rule) — {result.message}",
        fontsize=11,
    )
    return fig

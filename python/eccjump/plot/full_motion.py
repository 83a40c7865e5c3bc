"""The full motion (eccjump.simulate): its panels against time and an animated GIF."""

from __future__ import annotations

import math
from collections.abc import Sequence
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer, real
from eccjump._base.palette import MODE_COLORS

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

    from eccjump._base.body import Cylinder
from eccjump.plot._common import _plt, checked_target, new_figure

# --------------------------------------------------------------------------------------------
# The full motion (eccjump.simulate / eccjump simulate)
# --------------------------------------------------------------------------------------------

#: The modes of :func:`eccjump.simulate`, by their code in ``MotionResult.mode``.
MODE_NAMES = ("ROLL", "SLIP", "FLIGHT")

#: The most frames :func:`animate_motion` writes (keeps the GIF small).
MAX_FRAMES = 150
#: Frames given to each flight of an animation (of the first ones that fit).
FLIGHT_FRAMES = 24


def _mode_runs(t: NDArray[np.float64], mode: NDArray[Any]) -> list[tuple[float, float, str]]:
    """(t_start, t_end, name) of each run of one mode in the recorded points."""
    if t.size == 0:
        return []
    change = np.flatnonzero(np.diff(mode) != 0) + 1
    starts, ends = np.r_[0, change], np.r_[change - 1, t.size - 1]
    return [
        (float(t[i]), float(t[j]), MODE_NAMES[int(mode[i])] if 0 <= mode[i] < 3 else "?")
        for i, j in zip(starts, ends, strict=True)
    ]


def _body_alpha(
    result: Any, body: Cylinder | None, alpha: float | None
) -> tuple[Cylinder | None, float | None]:
    """The body and ramp angle: the arguments, else the result's own (if it has them)."""
    body = body if body is not None else getattr(result, "body", None)
    alpha = alpha if alpha is not None else getattr(result, "alpha", None)
    if alpha is not None:
        alpha = real("alpha", alpha)
    return body, alpha


def _motion_title(result: Any, body: Cylinder | None, alpha: float | None) -> str:
    parts = []
    if alpha is not None:
        parts.append(rf"$\alpha = {math.degrees(alpha):g}°$")
    if body is not None:
        parts.append(rf"$\chi = {body.chi:g}$, $k_m = {body.km:g}$")
    head = "Full motion" + (": " + ", ".join(parts) if parts else "")
    return f"{head} — {result.status}: {result.message}"


def _motion_units(result: Any) -> tuple[str, ...]:
    """The units of t, rates, speeds, forces, lengths, energies (SI or g = R = M = 1)."""
    if getattr(result, "units", None) is not None:
        return "s", "rad/s", "m/s", "N", "m", "J"
    return r"$\sqrt{R/g}$", r"$\sqrt{g/R}$", r"$\sqrt{gR}$", "$Mg$", "$R$", "$MgR$"


def _modes_and_impacts(ax: Axes, result: Any, runs: list[tuple[float, float, str]]) -> None:
    """The modes as background bands, each impact a dotted line, a light grid."""
    for t0, t1, name in runs:
        ax.axvspan(t0, t1, color=MODE_COLORS.get(name, "0.8"), alpha=0.14, lw=0, zorder=0)
    for imp in result.impacts:
        ax.axvline(imp.t, color="0.25", ls=":", lw=1.0)
    ax.grid(alpha=0.3)


def _mode_legend(ax: Axes, result: Any, runs: list[tuple[float, float, str]]) -> None:
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    present = [n for n in MODE_NAMES if any(name == n for _, _, name in runs)]
    handles: list[Any] = [Patch(color=MODE_COLORS[n], alpha=0.35, label=n) for n in present]
    if result.impacts:
        handles.append(Line2D([], [], color="0.25", ls=":", lw=1.0, label="impact"))
    ax.legend(handles=handles, loc="upper left", ncol=len(handles) or 1, fontsize=8)


def motion_panel(
    result: Any, ax: Axes, *, body: Cylinder | None = None, alpha: float | None = None
) -> Axes:
    """The main panel of an :func:`eccjump.simulate` run, θ̇ against time with the modes
    as bands and the impacts as dotted lines, drawn into ``ax`` (``MotionResult.plot(ax=ax)``;
    ``body`` and ``alpha`` [rad] label the title); returns ``ax``."""
    body, alpha = _body_alpha(result, body, alpha)
    u_t, u_w = _motion_units(result)[:2]
    t = np.asarray(result.t, dtype=float)
    runs = _mode_runs(t, np.asarray(result.mode))
    ax.axhline(0.0, color="0.6", lw=0.7)
    ax.plot(t, np.asarray(result.omega, dtype=float), color="k", lw=1.3, gid="theta_dot")
    ax.set_ylabel(rf"$\dot\theta$ [{u_w}]")
    ax.set_xlabel(f"time $t$ [{u_t}]")
    _modes_and_impacts(ax, result, runs)
    _mode_legend(ax, result, runs)
    ax.set_title(_motion_title(result, body, alpha), fontsize=9)
    return ax


def motion(
    result: Any,
    *,
    axes: Sequence[Axes] | None = None,
    fig: FigureBase | None = None,
    body: Cylinder | None = None,
    alpha: float | None = None,
) -> Figure:
    """Six stacked panels of an :func:`eccjump.simulate` run against time (shared axis):
    θ̇, the slip velocity v = l̇ - θ̇, F_x, F_y, the gap b - 1 between the body and
    the ramp (b: the height of the axis C above the ramp, 1 in contact), and
    the mechanical energy E with E + dissipated (dashed: flat when the ledger closes). The
    modes are coloured background bands (ROLL, SLIP, FLIGHT), impacts dotted vertical lines.

    ``axes``: six axes to draw into, or ``fig``: an empty Figure or SubFigure (else a new
    figure). ``body`` and ``alpha`` [rad] only
    label the title (taken from the result if it has them). The curves have gids
    ``theta_dot``, ``slip_velocity``, ``Fx``, ``Fy``, ``height``, ``energy``,
    ``energy_total``."""
    checked_target(None, fig)
    if axes is None:
        canvas, root = new_figure(fig, (9.0, 12.0))
        axs = list(canvas.subplots(6, 1, sharex=True))
    else:
        axs = list(axes)
        if len(axs) != 6:
            raise ValueError(f"axes must be 6 axes, not {len(axs)}")
        if fig is not None:
            raise TypeError("give axes= (six axes) or fig= (a figure), not both")
        canvas = root = axs[0].figure
    body, alpha = _body_alpha(result, body, alpha)
    u_t, u_w, u_v, u_f, u_l, u_e = _motion_units(result)
    t = np.asarray(result.t, dtype=float)
    mode = np.asarray(result.mode)
    energy = np.asarray(result.energy, dtype=float)
    total = energy + np.asarray(result.dissipated, dtype=float)
    panels = (
        ("theta_dot", result.omega, rf"$\dot\theta$ [{u_w}]"),
        ("slip_velocity", result.slip_velocity, rf"slip $v = \dot l - \dot\theta$ [{u_v}]"),
        ("Fx", result.Fx, rf"friction $F_x$ [{u_f}]"),
        ("Fy", result.Fy, rf"normal $F_y$ [{u_f}]"),
        ("height", result.height, rf"gap to the ramp $b - 1$ [{u_l}]"),
    )
    for ax, (gid, y, label) in zip(axs, panels, strict=False):
        ax.axhline(0.0, color="0.6", lw=0.7)
        (line,) = ax.plot(t, np.asarray(y, dtype=float), color="k", lw=1.3)
        line.set_gid(gid)
        ax.set_ylabel(label)
    a_e = axs[5]
    (line,) = a_e.plot(t, energy, color="k", lw=1.3, label="mechanical $E$")
    line.set_gid("energy")
    (line,) = a_e.plot(
        t, total, color="#D55E00", ls="--", lw=1.3, label="$E$ + dissipated (slip, impacts)"
    )
    line.set_gid("energy_total")
    a_e.set_ylabel(f"energy [{u_e}]")
    a_e.legend(fontsize=8, loc="best")
    a_e.set_xlabel(f"time $t$ [{u_t}]")

    runs = _mode_runs(t, mode)
    for ax in axs:
        _modes_and_impacts(ax, result, runs)
    if t.size:
        axs[0].set_xlim(t[0], t[-1] if t[-1] > t[0] else t[0] + 1.0)
    _mode_legend(axs[0], result, runs)
    canvas.suptitle(_motion_title(result, body, alpha), fontsize=11)
    return root


def _resample(
    result: Any, ts: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], list[str]]:
    """(θ, l, b, mode name) at the times ts: from the dense output ``result.sol`` if
    present, else linear interpolation of the recorded points; the mode is that of the last
    transition at or before each time."""
    t = np.asarray(result.t, dtype=float)
    if getattr(result, "sol", None) is not None:
        y = np.asarray(result.sol(ts), dtype=float).reshape(6, -1)
        theta, l_, b = y[0], y[2], y[4]
    else:
        theta, l_, b = (
            np.interp(ts, t, np.asarray(getattr(result, k), dtype=float))
            for k in ("theta", "l", "b")
        )
    trs = result.transitions
    if trs:
        tt = np.array([tr.t for tr in trs], dtype=float)
        k = np.clip(np.searchsorted(tt, ts, side="right") - 1, 0, len(trs) - 1)
        names = [trs[i].to_mode for i in k]
    else:
        mode = np.asarray(result.mode)
        k = np.clip(np.searchsorted(t, ts, side="right") - 1, 0, t.size - 1)
        names = [MODE_NAMES[int(mode[i])] for i in k]
    return theta, l_, b, names


def animate_motion(
    result: Any,
    path: str | Path,
    *,
    fps: int = 30,
    seconds: float | None = None,
    body: Cylinder | None = None,
    alpha: float | None = None,
    dpi: int = 100,
    view: float = 2.6,
) -> Path:
    """Write an animated GIF of an :func:`eccjump.simulate` run (pillow's GIF writer).

    The ramp slopes down to the right at ``alpha``; the body is the unit circle centred at
    C = (l, b) in the ramp frame, its centre of mass C + χ (sin θ, cos θ) a dot
    with the spoke C -> CM; the body and the title take the colour of the mode. The camera
    follows C (a window ``view`` R either side); ticks on the ramp every R show the travel,
    a trail the path of the centre of mass. Frames are evenly spaced in simulated time, at
    most :data:`MAX_FRAMES` of them, except that each of the first flights gets at least
    :data:`FLIGHT_FRAMES` (shown in slow motion: a flight of a few hundredths of the run would
    else fall between two frames); the title gives the time and, in flight, the gap b - 1.
    They play at ``fps`` (or over ``seconds``); the state comes from ``result.sol`` if
    present, else from the recorded points. 600 × 450 pixels at the default ``dpi``.

    ``body`` (for χ) and ``alpha`` [rad] are required unless the result carries them.
    Returns the path written."""
    body, alpha = _body_alpha(result, body, alpha)
    if body is None or alpha is None:
        raise ValueError("animate_motion needs the body and alpha: pass body= and alpha=")
    if getattr(result, "units", None) is not None:
        raise ValueError("animate_motion draws results in units g = R = M = 1, not SI")
    path = Path(path)
    if path.suffix.lower() != ".gif":
        raise ValueError(f"{path}: animate_motion writes a .gif file")
    fps = integer("fps", fps, 1, 1000)
    dpi = integer("dpi", dpi, 10, 1000)
    view = real("view", view)
    t = np.asarray(result.t, dtype=float)
    if t.size == 0:
        raise ValueError("the result has no recorded points")
    if seconds is None:
        n = MAX_FRAMES
        play_fps = float(fps)
    else:
        seconds = real("seconds", seconds)
        if not (math.isfinite(seconds) and seconds > 0.0):
            raise ValueError(f"seconds = {seconds:g} is outside the allowed range (0, inf)")
        n = int(min(MAX_FRAMES, max(1, round(fps * seconds))))
        play_fps = n / seconds
    if t[-1] <= t[0]:
        n = 1
    ts = _frame_times(t[0], t[-1], n, result.flights)
    n = ts.size
    theta, l_, b, names = _resample(result, ts)

    plt = _plt()
    from matplotlib.animation import FuncAnimation, PillowWriter
    from matplotlib.patches import Circle

    chi = body.chi
    ca, sa = math.cos(alpha), math.sin(alpha)

    def lab(x: Any, y: Any) -> tuple[Any, Any]:
        """Ramp frame (x down the ramp, y normal) -> lab frame (ramp down to the right)."""
        return x * ca + y * sa, -x * sa + y * ca

    cx, cy = lab(l_, b)
    mx, my = lab(l_ + chi * np.sin(theta), b + chi * np.cos(theta))

    fig, ax = plt.subplots(figsize=(6.0, 4.5), dpi=dpi)
    fig.subplots_adjust(left=0.02, right=0.98, bottom=0.02, top=0.92)  # no per-frame layout
    ax.set_aspect("equal")
    ax.set_xticks([])
    ax.set_yticks([])
    x_lo, x_hi = float(np.min(l_)) - 3.0 * view - 2.0, float(np.max(l_)) + 3.0 * view + 2.0
    rx, ry = lab(np.array([x_lo, x_hi]), np.zeros(2))
    ax.plot(rx, ry, color="0.2", lw=2.0, zorder=2)
    depth = 4.0 * view
    gx, gy = lab(np.array([x_lo, x_hi, x_hi, x_lo]), np.array([0.0, 0.0, -depth, -depth]))
    ax.fill(gx, gy, color="0.93", lw=0, zorder=0)
    (hatch,) = ax.plot([], [], color="0.45", lw=0.8, zorder=1)
    (trail,) = ax.plot([], [], color="0.55", lw=0.9, alpha=0.7, zorder=3)
    circle = Circle((cx[0], cy[0]), 1.0, lw=2.0, fill=True, zorder=4)
    ax.add_patch(circle)
    (spoke,) = ax.plot([], [], color="k", lw=1.6, zorder=5)
    (cm,) = ax.plot([], [], "o", color="k", ms=6, zorder=6)
    (centre,) = ax.plot([], [], "+", color="k", ms=6, zorder=6)
    title = ax.set_title("", fontsize=10)

    def draw(k: int) -> list[Any]:
        color = MODE_COLORS.get(names[k], "0.5")
        circle.center = (cx[k], cy[k])
        circle.set_edgecolor(color)
        circle.set_facecolor((*_rgb(color), 0.18))
        spoke.set_data([cx[k], mx[k]], [cy[k], my[k]])
        cm.set_data([mx[k]], [my[k]])
        centre.set_data([cx[k]], [cy[k]])
        trail.set_data(mx[: k + 1], my[: k + 1])
        ticks = np.arange(math.floor(l_[k] - 2.0 * view - 2.0), l_[k] + 2.0 * view + 2.0)
        hx0, hy0 = lab(ticks, 0.0 * ticks)
        hx1, hy1 = lab(ticks - 0.3, 0.0 * ticks - 0.3)
        nan = np.full_like(ticks, np.nan)
        hatch.set_data(
            np.column_stack([hx0, hx1, nan]).ravel(), np.column_stack([hy0, hy1, nan]).ravel()
        )
        ax.set_xlim(cx[k] - view, cx[k] + view)
        ax.set_ylim(cy[k] - 0.75 * view, cy[k] + 0.9 * view)
        gap = f", gap {b[k] - 1.0:.3f} R" if names[k] == "FLIGHT" else ""
        title.set_text(f"t = {ts[k]:7.3f} sqrt(R/g)   {names[k]}{gap}")
        title.set_color(color)
        return [circle, spoke, cm, centre, trail, hatch, title]

    anim = FuncAnimation(fig, draw, frames=n, blit=False)
    try:
        # A float rate works (the frame duration is 1000/fps); the stub says int.
        anim.save(path, writer=PillowWriter(fps=play_fps), dpi=dpi)  # type: ignore[arg-type]
    finally:
        plt.close(fig)
    return path


def _frame_times(t0: float, t1: float, n: int, flights: Sequence[Any]) -> NDArray[np.float64]:
    """``n`` frame times evenly spaced over [t0, t1], with :data:`FLIGHT_FRAMES` more over
    each of the first flights that fit within :data:`MAX_FRAMES` (taken from the even
    ones), sorted and distinct."""
    if n <= 1 or not t1 > t0:
        return np.array([t0])
    extra: list[NDArray[np.float64]] = []
    for f in flights:
        end = f.t_landing if math.isfinite(f.t_landing) else t1
        if n - FLIGHT_FRAMES * (len(extra) + 1) < FLIGHT_FRAMES or not end > f.t_liftoff:
            break
        extra.append(np.linspace(f.t_liftoff, min(end, t1), FLIGHT_FRAMES))
    even = np.linspace(t0, t1, n - FLIGHT_FRAMES * len(extra))
    return np.unique(np.concatenate([even, *extra]))


def _rgb(color: str) -> tuple[float, float, float]:
    from matplotlib.colors import to_rgb

    return to_rgb(color)

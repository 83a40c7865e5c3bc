"""Figures: the paper's Fig. 3b and Fig. 4 (JARM regions), a pure-rolling trajectory, and the
full motion of :func:`eccjump.simulate` (panels and an animated GIF).

Every function returns a :class:`matplotlib.figure.Figure` (:func:`animate_motion` writes a GIF
instead; matplotlib is imported only when a function is called: ``pip install eccjump[plot]``).
Angles are shown in degrees; units are g = R = M = 1 (forces in M g, rates in sqrt(g/R), times
in sqrt(R/g)).

The Fig. 4 regions are drawn from their exact boundary surfaces alpha_lo(chi, k_m) and
alpha_hi(chi, k_m) (:func:`eccjump.alpha_intervals`, bisection to 1e-12), not from a
thresholded grid, so thin regions keep their true thickness in alpha.
"""

from __future__ import annotations

import math
from collections.abc import Sequence
from dataclasses import dataclass
from pathlib import Path
from typing import TYPE_CHECKING, Any

import numpy as np
from numpy.typing import NDArray

from eccjump import closed_form
from eccjump._checks import U32_MAX, integer, optional_real, real
from eccjump.boundary import alpha_interval_around, alpha_intervals
from eccjump.classification import Region, jarm
from eccjump.motion_fields import sequence_name
from eccjump.motion_maps import MotionMap
from eccjump.rolling import RollResult
from eccjump.starts import OptimalStart, StartMap

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

    from eccjump.body import Cylinder

__all__ = [
    "MODE_COLORS",
    "TURN_COLORS",
    "JarmSurfaces",
    "animate_motion",
    "fig3b",
    "fig4",
    "fig4_slices",
    "fraction_map",
    "jarm_surfaces",
    "motion",
    "trajectory",
]

#: Colours of the turns n = 1, 2, 3 (the paper's green, purple, orange); later turns cycle.
TURN_COLORS = ("#2ca02c", "#8e44ad", "#ff7f0e", "#1f77b4", "#d62728")


#: The most points a curve is sampled at (a bound on memory, not on accuracy).
MAX_POINTS = 10**7


def _plt() -> Any:
    try:
        import matplotlib.pyplot as plt
    except ImportError as err:  # pragma: no cover - depends on the environment
        raise ImportError("eccjump.plot needs matplotlib: pip install eccjump[plot]") from err
    return plt


def _color(n: int) -> str:
    return TURN_COLORS[(n - 1) % len(TURN_COLORS)]


def _new_axes(ax: Axes | None, figsize: tuple[float, float]) -> tuple[Figure, Axes]:
    if ax is not None:
        return ax.figure, ax
    plt = _plt()
    fig, ax = plt.subplots(figsize=figsize, layout="constrained")
    return fig, ax


# --------------------------------------------------------------------------------------------
# Fig. 3b: mu(chi, k_m, theta_J)
# --------------------------------------------------------------------------------------------


def fig3b(
    chi: float = 0.5,
    km: float = 0.4,
    ax: Axes | None = None,
    *,
    mu_s: float | None = 1.6,
    n: int = 1,
    ylim: tuple[float, float] = (-6.0, 6.0),
    n_points: int = 2001,
) -> Figure:
    """The paper's Fig. 3b: mu(chi, k_m, theta_J) of Eq. ineq2 over one turn (n - 1) 360 deg to
    n 360 deg, with the green window (the quarter turn before 360 n deg, where a JARM can
    happen) shaded, mu_s,min marked, and the line mu = ``mu_s`` with theta_J,min and
    theta_J,max (the ends of the interval where mu <= mu_s) marked. ``mu_s=None`` omits it.

    The curve's line has gid ``"mu"``, the minimum's marker gid ``"mu_s_min"``.
    """
    n_points = integer("n_points", n_points, 2, MAX_POINTS)
    n = integer("n", n, 1, U32_MAX)
    fig, ax = _new_axes(ax, (7.5, 4.8))
    base = 360.0 * (n - 1)
    theta_deg = np.linspace(base, base + 360.0, n_points)
    with np.errstate(all="ignore"):
        m = closed_form.mu(chi, km, np.radians(theta_deg))
    # break the curve at the poles (sin theta_J = 0) instead of joining +inf to -inf
    m_plot = np.where(np.abs(m) > 50.0 * max(abs(ylim[0]), abs(ylim[1])), np.nan, m)
    ax.axvspan(base + 270.0, base + 360.0, color="#2ca02c", alpha=0.15, lw=0)
    ax.text(
        base + 315.0,
        ylim[0] + 0.04 * (ylim[1] - ylim[0]),
        "green window\n$2\\pi n-\\pi/2<\\theta_J<2\\pi n$",
        ha="center",
        va="bottom",
        fontsize=8.5,
        color="#1b6e1b",
    )
    ax.axhline(0.0, color="0.6", lw=0.7)
    (line,) = ax.plot(
        theta_deg, m_plot, color="k", lw=1.6, label=r"$\mu(\chi, k_m, \theta_J)$ (Eq. ineq2)"
    )
    line.set_gid("mu")
    mmin, phi = closed_form.mu_s_min(chi, km)
    mmin, phi_deg = float(mmin), base + 360.0 + math.degrees(float(phi))
    (pt,) = ax.plot(
        [phi_deg],
        [mmin],
        "o",
        color="#d62728",
        ms=7,
        zorder=5,
        label=rf"$\mu_{{s,\min}} = {mmin:.4f}$ at $\theta_J = {phi_deg:.2f}^\circ$",
    )
    pt.set_gid("mu_s_min")
    ax.annotate(
        rf"$\mu_{{s,\min}}\approx{mmin:.4f}$",
        (phi_deg, mmin),
        xytext=(-12, -22),
        textcoords="offset points",
        ha="right",
        fontsize=9,
        color="#d62728",
    )
    if mu_s is not None:
        ax.axhline(mu_s, color="#1f77b4", ls="--", lw=1.2, label=rf"$\mu_s = {mu_s:g}$")
        lo, hi = closed_form.theta_J_range(chi, km, mu_s, n)
        lo, hi = float(lo), float(hi)
        if np.isfinite(lo) and np.isfinite(hi):
            lo_d, hi_d = math.degrees(lo), math.degrees(hi)
            ax.plot(
                [lo_d, hi_d],
                [mu_s, mu_s],
                color="#1f77b4",
                lw=4,
                alpha=0.5,
                solid_capstyle="butt",
                label=rf"$\mu \leq \mu_s$: ${lo_d:.2f}^\circ \leq \theta_J \leq {hi_d:.2f}^\circ$",
            )
            for x, name in ((lo_d, r"$\theta_{J,\min}$"), (hi_d, r"$\theta_{J,\max}$")):
                ax.axvline(x, color="#1f77b4", ls=":", lw=1)
                ax.annotate(
                    name,
                    (x, mu_s),
                    xytext=(0, 26),
                    textcoords="offset points",
                    ha="center",
                    fontsize=10,
                    color="#1f77b4",
                    arrowprops={"arrowstyle": "-", "color": "#1f77b4", "lw": 0.8},
                )
    ax.set_xlim(base, base + 360.0)
    ax.set_ylim(*ylim)
    ax.set_xticks(np.arange(base, base + 361.0, 45.0))
    ax.set_xlabel(r"jump angle $\theta_J$ [deg]")
    ax.set_ylabel(r"$\mu(\chi, k_m, \theta_J) = -F_{x,J}/F_{y,J}$")
    ax.set_title(rf"Friction needed at the jump ($\chi = {chi:g}$, $k_m = {km:g}$)")
    ax.legend(loc="upper left", fontsize=8.5, framealpha=0.9)
    ax.grid(alpha=0.3)
    return fig


# --------------------------------------------------------------------------------------------
# Fig. 4: JARM regions in (alpha, chi, k_m)
# --------------------------------------------------------------------------------------------


@dataclass(frozen=True)
class JarmSurfaces:
    """The boundary surfaces of the JARM region for one (mu_s, n) on a (chi, k_m) mesh.

    ``lo``/``hi`` [rad] have shape (len(chi), len(km)): the first JARM alpha-interval of each
    body (NaN where there is none, or where k_m > 1 - chi); ``n_intervals`` counts the
    intervals (almost always 0 or 1; a second one is only drawn in the slices).
    """

    mu_s: float
    n: int
    chi: NDArray[np.float64]
    km: NDArray[np.float64]
    lo: NDArray[np.float64]
    hi: NDArray[np.float64]
    n_intervals: NDArray[np.int64]

    @property
    def any(self) -> bool:
        return bool(np.any(self.n_intervals > 0))


def _is_jarm(
    a: NDArray[np.float64], c: NDArray[np.float64], k: NDArray[np.float64], mu_s: float, n: int
) -> NDArray[np.bool_]:
    return jarm(a, c, k, mu_s, n, refine_extrema=False).is_jarm


def _grid_intervals(
    c: NDArray[np.float64], k: NDArray[np.float64], mu_s: float, n: int, n_scan: int
) -> list[list[tuple[float, float]]]:
    """alpha-intervals of every body of a 1-D or 2-D grid (c, k), flat in C order, [] where
    k > 1 - c. A first pass scans ``n_scan`` angles (:func:`eccjump.alpha_intervals`). Then a
    flood fill: an empty body next to a body with a JARM (along the grid axes) is probed at
    angles spread over its neighbours' intervals, and where a probe is a JARM the interval
    around it is found by bisection (:func:`eccjump.jarm`), repeatedly. This recovers the
    thin parts of a region (alpha-intervals narrower than the scan step, common on later
    turns) at a fraction of the cost of a fine scan."""
    shape = c.shape
    flat_c, flat_k = c.ravel(), k.ravel()
    valid = flat_k <= 1.0 - flat_c
    out: list[list[tuple[float, float]]] = [[] for _ in range(flat_c.size)]
    idx = np.flatnonzero(valid)
    if idx.size:
        ivs = alpha_intervals(flat_c[idx], flat_k[idx], mu_s, n, n_scan=n_scan)
        for i, iv in zip(idx, ivs, strict=True):
            out[i] = iv
    probed = ~valid
    offsets = np.linspace(-0.5, 1.5, 9)
    while True:
        hit = np.array([bool(iv) for iv in out])
        todo, probes = [], []
        for i in np.flatnonzero(~hit & ~probed):
            pos = np.unravel_index(i, shape)
            p: list[float] = []
            for axis in range(len(shape)):
                for step in (1, -1):
                    q = list(pos)
                    q[axis] += step
                    if 0 <= q[axis] < shape[axis]:
                        j = int(np.ravel_multi_index(tuple(q), shape))
                        for lo, hi in out[j]:
                            p.extend(lo + (hi - lo) * offsets)
            if p:
                todo.append(i)
                probes.append(np.clip(p, 1e-9, 0.5 * math.pi))
        if not todo:
            return out
        probed[todo] = True
        sizes = np.array([len(p) for p in probes])
        a = np.concatenate(probes)
        body = np.repeat(np.array(todo), sizes)
        ok = _is_jarm(a, flat_c[body], flat_k[body], mu_s, n)
        first = np.r_[0, np.cumsum(sizes)[:-1]]
        seeds, where = [], []
        for b, (f, sz) in enumerate(zip(first, sizes, strict=True)):
            hits = np.flatnonzero(ok[f : f + sz])
            if hits.size:
                seeds.append(a[f + hits[0]])
                where.append(todo[b])
        if not seeds:
            return out
        w = np.array(where)
        lo, hi = alpha_interval_around(np.array(seeds), flat_c[w], flat_k[w], mu_s, n)
        for i, lo_i, hi_i in zip(w, lo, hi, strict=True):
            out[i] = [(float(lo_i), float(hi_i))]


def _not_wrapped(shape: tuple[int, ...], axis: int, step: int) -> NDArray[np.bool_]:
    """Mask of the cells that np.roll(., step, axis) filled from inside the array."""
    m = np.ones(shape, dtype=bool)
    edge = [slice(None)] * len(shape)
    edge[axis] = slice(0, 1) if step > 0 else slice(-1, None)
    m[tuple(edge)] = False
    return m


def _intervals_on_mesh(
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu_s: float,
    n: int,
    n_scan: int,
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.int64]]:
    c, k = np.meshgrid(chi, km, indexing="ij")
    ivs = _grid_intervals(c, k, mu_s, n, n_scan)
    lo = np.full(c.shape, np.nan)
    hi = np.full(c.shape, np.nan)
    count = np.zeros(c.shape, dtype=np.int64)
    for i, iv in enumerate(ivs):
        count.flat[i] = len(iv)
        if iv:
            lo.flat[i], hi.flat[i] = iv[0]
    return lo, hi, count


def jarm_surfaces(
    mu_s: float,
    n: int,
    *,
    resolution: int = 36,
    chi_range: tuple[float, float] | None = None,
    km_range: tuple[float, float] | None = None,
    n_scan: int = 90,
) -> JarmSurfaces:
    """alpha_lo/alpha_hi of the JARM region on turn ``n`` over a ``resolution``^2 (chi, k_m)
    mesh. Without explicit ranges, a coarse scan of the whole body triangle
    0 <= k_m <= 1 - chi finds the footprint of the region and the mesh is fitted to it
    (two coarse cells wider).
    Each body's ramp angles are scanned at ``n_scan`` points over (0, 90 deg], and intervals
    narrower than the scan step are recovered next to found ones (see ``_grid_intervals``)."""
    if chi_range is None or km_range is None:
        cc = np.linspace(0.0, 1.0, 21)
        kk = np.linspace(0.0, 1.0, 21)
        _, _, cnt = _intervals_on_mesh(cc, kk, mu_s, n, max(n_scan, 180))
        hit_c, hit_k = np.nonzero(cnt > 0)
        if hit_c.size == 0:
            c_box, k_box = (0.0, 1.0), (0.0, 1.0)
        else:
            dc, dk = 2.0 * (cc[1] - cc[0]), 2.0 * (kk[1] - kk[0])
            c_box = (max(0.0, cc[hit_c.min()] - dc), min(1.0, cc[hit_c.max()] + dc))
            k_box = (max(0.0, kk[hit_k.min()] - dk), min(1.0, kk[hit_k.max()] + dk))
        chi_range = chi_range if chi_range is not None else c_box
        km_range = km_range if km_range is not None else k_box
    chi = np.linspace(*chi_range, resolution)
    km = np.linspace(*km_range, resolution)
    lo, hi, cnt = _intervals_on_mesh(chi, km, mu_s, n, n_scan)
    return JarmSurfaces(float(mu_s), int(n), chi, km, lo, hi, cnt)


def _solid_polygons(s: JarmSurfaces) -> list[NDArray[np.float64]]:
    """Quads of the closed solid between alpha_lo and alpha_hi: bottom, top and the side
    walls along the edge of the footprint (x = chi, y = k_m, z = alpha in degrees)."""
    c, k = np.meshgrid(s.chi, s.km, indexing="ij")
    lo, hi = np.degrees(s.lo), np.degrees(s.hi)
    ok = np.isfinite(lo) & np.isfinite(hi)
    cell = ok[:-1, :-1] & ok[1:, :-1] & ok[1:, 1:] & ok[:-1, 1:]
    polys: list[NDArray[np.float64]] = []
    corners = ((0, 0), (1, 0), (1, 1), (0, 1))
    for i, j in zip(*np.nonzero(cell), strict=True):
        for z in (lo, hi):
            polys.append(
                np.array([(c[i + a, j + b], k[i + a, j + b], z[i + a, j + b]) for a, b in corners])
            )
        # walls on cell edges that border a missing cell or the mesh edge
        edges = (
            ((0, 0), (1, 0), (i, j - 1)),
            ((1, 0), (1, 1), (i + 1, j)),
            ((1, 1), (0, 1), (i, j + 1)),
            ((0, 1), (0, 0), (i - 1, j)),
        )
        for (a1, b1), (a2, b2), (ni, nj) in edges:
            inside = 0 <= ni < cell.shape[0] and 0 <= nj < cell.shape[1]
            if inside and cell[ni, nj]:
                continue
            p1, p2 = (i + a1, j + b1), (i + a2, j + b2)
            polys.append(
                np.array(
                    [
                        (c[p1], k[p1], lo[p1]),
                        (c[p2], k[p2], lo[p2]),
                        (c[p2], k[p2], hi[p2]),
                        (c[p1], k[p1], hi[p1]),
                    ]
                )
            )
    return polys


def fig4(
    mu_s: float,
    ns: Sequence[int] = (1, 2, 3),
    *,
    resolution: int = 36,
    n_scan: int = 90,
    surfaces: Sequence[JarmSurfaces] | None = None,
    ax: Axes | None = None,
    elev: float = 22.0,
    azim: float = -128.0,
    title: str | None = None,
) -> Figure:
    """The paper's Fig. 4: the JARM regions in (alpha, chi, k_m) for fixed ``mu_s`` and turns
    ``ns`` (green, purple, orange for n = 1, 2, 3), from rest at theta0 = 0, as closed solids
    between the exact boundary surfaces alpha_lo and alpha_hi on a ``resolution``^2 mesh
    fitted to each region (see :func:`jarm_surfaces`; pass precomputed ``surfaces`` to skip
    the computation). ``ax`` must be a 3-D axes if given."""
    plt = _plt()
    from matplotlib.patches import Patch
    from matplotlib.ticker import MaxNLocator
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    if ax is None:
        fig = plt.figure(figsize=(7.5, 6.5), layout="constrained")
        ax = fig.add_subplot(projection="3d")
    else:
        fig = ax.figure
    if surfaces is None:
        surfaces = [jarm_surfaces(mu_s, n, resolution=resolution, n_scan=n_scan) for n in ns]
    handles = []
    c_max, k_max = 0.05, 0.05
    for s in surfaces:
        color = _color(s.n)
        polys = _solid_polygons(s)
        if polys:
            coll = Poly3DCollection(
                polys, facecolors=color, edgecolors=color, linewidths=0.0, alpha=0.55, shade=True
            )
            ax.add_collection3d(coll)
            ok = np.isfinite(s.lo)
            c, k = np.meshgrid(s.chi, s.km, indexing="ij")
            c_max, k_max = max(c_max, float(c[ok].max())), max(k_max, float(k[ok].max()))
        hit = s.n_intervals > 0
        if np.any(hit):
            lo_d, hi_d = np.degrees(np.nanmin(s.lo)), np.degrees(np.nanmax(s.hi))
            label = rf"$n = {s.n}$: $\alpha$ {lo_d:.1f}°–{hi_d:.1f}°"
        else:
            label = rf"$n = {s.n}$: none"
        handles.append(Patch(facecolor=color, alpha=0.7, label=label))
    ax.set_xlim(0.0, round(c_max * 1.05 + 0.005, 2))
    ax.set_ylim(0.0, round(k_max * 1.05 + 0.005, 2))
    ax.set_zlim(0.0, 90.0)
    ax.set_zticks(np.arange(0.0, 91.0, 15.0))
    ax.xaxis.set_major_locator(MaxNLocator(6))
    ax.yaxis.set_major_locator(MaxNLocator(5))
    ax.set_xlabel(r"$\chi = d/R$")
    ax.set_ylabel(r"$k_m = m_C/M$")
    ax.set_zlabel(r"ramp angle $\alpha$ [deg]")
    ax.view_init(elev=elev, azim=azim)
    ax.legend(handles=handles, loc="upper left", fontsize=9, title="turn of the jump")
    ax.set_title(
        title
        if title is not None
        else rf"JARM regions, $\mu_s = {mu_s:g}$ (from rest at $\theta_0 = 0$)"
    )
    return fig


def _fill_intervals(
    ax: Axes, x: NDArray[np.float64], ivs: list[list[tuple[float, float]]], color: str, label: str
) -> bool:
    """Fill between alpha_lo(x) and alpha_hi(x) [deg] for each interval index; True if any."""
    m = max((len(iv) for iv in ivs), default=0)
    for j in range(m):
        lo = np.array([math.degrees(iv[j][0]) if len(iv) > j else np.nan for iv in ivs])
        hi = np.array([math.degrees(iv[j][1]) if len(iv) > j else np.nan for iv in ivs])
        ok = np.isfinite(lo)
        ax.fill_between(
            x, lo, hi, where=ok, color=color, alpha=0.45, lw=0, label=label if j == 0 else None
        )
        for z in (lo, hi):
            ax.plot(x, z, color=color, lw=0.9)
        # close isolated points (an interval present at a single x) with a bar
        lone = ok & ~np.r_[False, ok[:-1]] & ~np.r_[ok[1:], False]
        ax.vlines(x[lone], lo[lone], hi[lone], color=color, lw=2)
    return m > 0


def fig4_slices(
    mu_s: float,
    ns: Sequence[int] = (1, 2, 3),
    *,
    km_values: Sequence[float] = (0.0, 0.04, 0.1, 0.15),
    chi_values: Sequence[float] = (0.1, 0.2, 0.4),
    resolution: int = 120,
    n_scan: int = 90,
) -> Figure:
    """2-D slices of the Fig. 4 regions: top row, the JARM alpha-interval against chi at fixed
    (absolute) k_m; bottom row, against k_m at fixed chi; filled between the exact alpha_lo and
    alpha_hi, one colour per turn n. ``resolution`` points along each slice."""
    plt = _plt()
    ncol = max(len(km_values), len(chi_values))
    fig, axes = plt.subplots(
        2, ncol, figsize=(3.1 * ncol, 6.6), layout="constrained", squeeze=False
    )
    chi_x = np.linspace(0.0, 0.7, resolution)
    for col in range(ncol):
        for row, values in enumerate((km_values, chi_values)):
            ax = axes[row, col]
            if col >= len(values):
                ax.set_visible(False)
                continue
            v = float(values[col])
            if row == 0:
                x = chi_x
                xs = (x, np.full_like(x, v))
            else:
                x = np.linspace(0.0, min(0.25, 1.0 - v), resolution)
                xs = (np.full_like(x, v), x)
            for n in ns:
                ivs = _grid_intervals(*xs, mu_s, n, n_scan)
                _fill_intervals(ax, x, ivs, _color(n), rf"$n = {n}$")
            ax.set_ylim(0.0, 90.0)
            ax.set_yticks(np.arange(0.0, 91.0, 15.0))
            ax.set_xlim(x[0], x[-1])
            ax.grid(alpha=0.3)
            if row == 0:
                ax.set_title(rf"$k_m = {v:g}$", fontsize=10)
                ax.set_xlabel(r"$\chi = d/R$")
            else:
                ax.set_title(rf"$\chi = {v:g}$", fontsize=10)
                ax.set_xlabel(r"$k_m = m_C/M$")
            if col == 0:
                ax.set_ylabel(r"ramp angle $\alpha$ [deg]")
    handles, labels = [], []
    for ax in axes.ravel():
        for h, lab in zip(*ax.get_legend_handles_labels(), strict=True):
            if lab not in labels:
                handles.append(h)
                labels.append(lab)
    order = np.argsort(labels)
    fig.legend(
        [handles[i] for i in order],
        [labels[i] for i in order],
        loc="outside upper right",
        ncol=len(labels) or 1,
        title="JARM on turn",
        fontsize=9,
    )
    fig.suptitle(
        rf"JARM $\alpha$-intervals, $\mu_s = {mu_s:g}$, from rest at $\theta_0 = 0$"
        "\n(slices of Fig. 4 at fixed $k_m$, top, and fixed $\\chi$, bottom)",
        fontsize=11,
    )
    return fig


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


# --------------------------------------------------------------------------------------------
# A computed region map (eccjump.region / eccjump map)
# --------------------------------------------------------------------------------------------


def region_map(region: Region, *, panels: int = 4) -> Figure:
    """A computed :class:`~eccjump.Region` in the (chi, alpha) plane, JARM points coloured by
    their turn n (turns past 5 share one colour). The first panel projects over k_m (the
    smallest n of any k_m on the grid); the others are the ``panels - 1`` k_m slices with the
    most JARM points."""
    if not isinstance(region, Region):
        raise TypeError(f"region must be a Region, not {type(region).__name__}")
    panels = integer("panels", panels, 1, 64)
    plt = _plt()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    last = len(TURN_COLORS) + 1  # category for n > len(TURN_COLORS)
    colors = [*TURN_COLORS, "#7f7f7f"]
    res = region.result
    is_jarm = np.asarray(res.is_jarm)
    cat = np.where(is_jarm, np.minimum(np.asarray(res.n, dtype=float), last), np.nan)
    cmap = ListedColormap(colors)
    counts = is_jarm.sum(axis=(0, 1))
    best = np.argsort(-counts, kind="stable")[: max(panels - 1, 0)]
    best = np.sort(best[counts[best] > 0])
    with np.errstate(all="ignore"):
        projected = np.nanmin(np.where(is_jarm, cat, np.inf), axis=2)
    projected[~np.isfinite(projected)] = np.nan
    views = [("any $k_m$ on the grid", projected)]
    views += [(rf"$k_m = {region.km_frac[j]:.3g}\,(1-\chi)$", cat[:, :, j]) for j in best]
    fig, axes = plt.subplots(
        1,
        len(views),
        figsize=(3.3 * len(views) + 1.6, 3.7),
        layout="constrained",
        sharey=True,
        squeeze=False,
    )
    a_deg = np.degrees(region.alpha)
    for ax, (title, img) in zip(axes[0], views, strict=True):
        ax.pcolormesh(
            region.chi, a_deg, img, cmap=cmap, vmin=0.5, vmax=last + 0.5, shading="nearest"
        )
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(r"$\chi = d/R$")
        ax.set_xlim(region.chi[0], region.chi[-1])
        ax.set_ylim(a_deg[0], a_deg[-1])
        ax.grid(alpha=0.3)
    axes[0, 0].set_ylabel(r"ramp angle $\alpha$ [deg]")
    present = {int(k) for k in np.unique(cat[np.isfinite(cat)])}
    handles = [
        Patch(color=colors[k - 1], label=f"$n = {k}$" if k < last else f"$n > {last - 1}$")
        for k in sorted(present)
    ]
    if handles:
        fig.legend(handles=handles, title="JARM on turn", loc="outside right upper", fontsize=9)
    start = (
        rf", start $\theta_0 = {math.degrees(region.theta0):.4g}°$, "
        rf"$\dot\theta_0 = {region.omega0:.4g}$"
        if region.theta0 or region.omega0
        else ""
    )
    fig.suptitle(
        f"JARM region, $\\mu_s = {region.mu_s:g}$, rule: {region.rule}, route: {region.method}"
        f"{start} ({100.0 * region.fraction():.2f}% of {is_jarm.size} grid points)"
    )
    return fig


# --------------------------------------------------------------------------------------------
# Initial conditions (eccjump.start_map / eccjump starts)
# --------------------------------------------------------------------------------------------


def fraction_map(smap: StartMap, *, optimum: OptimalStart | None = None) -> Figure:
    """The JARM fraction over the starts (theta0, omega0) of a :class:`~eccjump.StartMap`
    (left), and the shares of the parameter cube blocked at the start: immediate flight and
    rocking back (right). ``optimum`` is marked with its uncertainty; starts with no JARM on
    the grid are hatched."""
    if not isinstance(smap, StartMap):
        raise TypeError(f"smap must be a StartMap, not {type(smap).__name__}")
    if optimum is not None and not isinstance(optimum, OptimalStart):
        raise TypeError(f"optimum must be an OptimalStart or None, not {type(optimum).__name__}")
    plt = _plt()
    from matplotlib.colors import PowerNorm

    fig, axes = plt.subplots(1, 3, figsize=(13.5, 4.0), layout="constrained", sharey=True)
    th = np.degrees(smap.theta0)
    views = (
        ("JARM fraction (colour scale: square root)", smap.fraction, "viridis"),
        ("immediate flight (LIFTOFF_EARLIER)", smap.immediate_flight, "Blues"),
        ("rocks back (ROCKS_BACK)", smap.rocks_back, "Oranges"),
    )
    for k, (ax, (title, img, cmap)) in enumerate(zip(axes, views, strict=True)):
        norm = PowerNorm(0.5, vmin=0.0, vmax=max(float(img.max()), 1e-12)) if k == 0 else None
        mesh = ax.pcolormesh(th, smap.omega0, img.T, cmap=cmap, shading="nearest", norm=norm,
                             vmin=None if k == 0 else 0.0)  # fmt: skip
        fig.colorbar(mesh, ax=ax, shrink=0.9)
        ax.set_title(title, fontsize=10)
        ax.set_xlabel(r"$\theta_0$ [deg]")
        ax.set_xticks(np.arange(0.0, 361.0, 90.0))
        if smap.impossible.any():
            ax.contourf(th, smap.omega0, smap.impossible.T.astype(float), levels=[0.5, 1.5],
                        colors="none", hatches=["//"])  # fmt: skip
        if optimum is not None:
            ax.errorbar(
                math.degrees(optimum.theta0),
                optimum.omega0,
                xerr=max(math.degrees(optimum.theta0_err), 1e-9),
                yerr=max(optimum.omega0_err, 1e-9),
                fmt="*",
                color="#d62728",
                ms=11,
                mec="white",
                label="optimum",
            )
    axes[0].scatter([0.0], [0.0], marker="o", color="#d62728", s=30, clip_on=False,
                    label="from rest", zorder=3)  # fmt: skip
    axes[0].set_ylabel(r"$\dot\theta_0$ [$\sqrt{g/R}$]")
    axes[0].legend(loc="upper left", fontsize=8)
    best = "" if optimum is None else (
        f"; optimum {100 * optimum.fraction:.2f}% at $\\theta_0 = "
        f"{math.degrees(optimum.theta0):.1f}°$, $\\dot\\theta_0 = {optimum.omega0:.3f}$"
    )  # fmt: skip
    fig.suptitle(
        f"Share of (α, χ, $k_m$) by start, $\\mu_s = {smap.mu_s:g}$, rule: {smap.rule}, "
        f"{smap.grid}³ midpoint grid{best}",
        fontsize=11,
    )
    return fig


#: Colours of the most frequent sequences of :func:`sequence_map` (the rest share grey).
SEQUENCE_COLORS = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
    "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#aec7e8",
)  # fmt: skip


def sequence_map(m: MotionMap, *, panels: int = 4) -> Figure:
    """A motion map over (chi, alpha), one panel per k_m slice (``panels`` evenly spaced
    slices), every point coloured by its sequence of modes (the 10 most frequent sequences
    of the map; the others grey, points not run white). Like the paper's Fig. 4, but for
    every outcome; the JARM points are the ROLL→FLIGHT→... sequences."""
    if not isinstance(m, MotionMap):
        raise TypeError(f"m must be a MotionMap, not {type(m).__name__}")
    panels = integer("panels", panels, 1, 64)
    if tuple(m.coords)[:2] != ("alpha", "chi") or len(m.coords) > 3:
        raise ValueError("sequence_map needs a map over alpha, chi (and km) only")
    plt = _plt()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    seq = np.asarray(m.fields["sequence"])
    if seq.ndim == 2:
        seq = seq[:, :, None]
    km = m.coords.get("km", np.array([m.scalars.get("km") or 0.0]))
    top = [c for c in m.sequences() if c != 0][: len(SEQUENCE_COLORS)]
    cat = np.full(seq.shape, float(len(top)))  # "other"
    for k, code in enumerate(top):
        cat[seq == code] = k
    cat[seq == 0] = np.nan
    colors = [*SEQUENCE_COLORS[: len(top)], "#c7c7c7"]
    ran = np.flatnonzero(np.isfinite(cat).any(axis=(0, 1)))  # slices with points that ran
    ran = ran if ran.size else np.arange(seq.shape[2])
    slices = ran[np.unique(np.linspace(0, ran.size - 1, min(panels, ran.size)).round().astype(int))]
    fig, axes = plt.subplots(
        1,
        slices.size,
        figsize=(3.3 * slices.size + 3.2, 3.8),
        layout="constrained",
        sharey=True,
        squeeze=False,
    )
    a_deg = np.degrees(m.coords["alpha"])
    chi = m.coords["chi"]
    jarm = np.asarray(m.fields["jarm"]).reshape(seq.shape)
    for ax, j in zip(axes[0], slices.astype(int), strict=True):
        ia, ic = np.nonzero(jarm[:, :, j])
        ax.plot(chi[ic], a_deg[ia], "k.", ms=1.5, zorder=3)  # the paper's Fig. 4 region
        ax.pcolormesh(
            chi,
            a_deg,
            cat[:, :, j],
            cmap=ListedColormap(colors),
            vmin=-0.5,
            vmax=len(top) + 0.5,
            shading="nearest",
        )
        ax.set_title(rf"$k_m = {km[j]:.3g}\,(1-\chi)$", fontsize=10)
        ax.set_xlabel(r"$\chi = d/R$")
        ax.grid(alpha=0.3)
    axes[0, 0].set_ylabel(r"ramp angle $\alpha$ [deg]")
    handles = [
        Patch(color=colors[k], label=sequence_name(code).replace("→", " → "))
        for k, code in enumerate(top)
    ]
    if (cat == len(top)).any():
        handles.append(Patch(color=colors[-1], label="other sequences"))
    handles.append(Patch(color="k", label="JARM (ROLL → FLIGHT by the lift-off rule)"))
    fig.legend(handles=handles, title="modes, to the first landing", loc="outside right upper",
               fontsize=8)  # fmt: skip
    o, sc = m.options, m.scalars
    mu_k = sc.get("mu_k")
    fig.suptitle(
        f"Full motion to the first landing: $\\mu_s = {sc.get('mu_s', float('nan')):g}$, "
        f"$\\mu_k = {sc.get('mu_s') if mu_k is None else mu_k:g}$, "
        f"$e = {sc.get('restitution', 0.0):g}$, rule: {o.get('rule', 'paper')}"
    )
    return fig


# --------------------------------------------------------------------------------------------
# The full motion (eccjump.simulate / eccjump simulate)
# --------------------------------------------------------------------------------------------

#: The modes of :func:`eccjump.simulate`, by their code in ``MotionResult.mode``.
MODE_NAMES = ("ROLL", "SLIP", "FLIGHT")

#: Colours of the modes (background bands of :func:`motion`, the body in :func:`animate_motion`).
MODE_COLORS = {"ROLL": "#2ca02c", "SLIP": "#ff7f0e", "FLIGHT": "#1f77b4"}

#: The most frames :func:`animate_motion` writes (keeps the GIF small).
MAX_FRAMES = 150


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


def motion(
    result: Any,
    *,
    axes: Sequence[Axes] | None = None,
    body: Cylinder | None = None,
    alpha: float | None = None,
) -> Figure:
    """Six stacked panels of an :func:`eccjump.simulate` run against time (shared axis):
    theta', the slip velocity v = l' - theta', F_x, F_y, the height b - 1 of the centre, and
    the mechanical energy E with E + dissipated (dashed: flat when the ledger closes). The
    modes are coloured background bands (ROLL, SLIP, FLIGHT), impacts dotted vertical lines.

    ``axes``: six axes to draw into (else a new figure). ``body`` and ``alpha`` [rad] only
    label the title (taken from the result if it has them). The curves have gids
    ``theta_dot``, ``slip_velocity``, ``Fx``, ``Fy``, ``height``, ``energy``,
    ``energy_total``."""
    plt = _plt()
    from matplotlib.lines import Line2D
    from matplotlib.patches import Patch

    if axes is None:
        fig, ax_arr = plt.subplots(6, 1, sharex=True, figsize=(9.0, 12.0), layout="constrained")
        axs = list(ax_arr)
    else:
        axs = list(axes)
        if len(axs) != 6:
            raise ValueError(f"axes must be 6 axes, not {len(axs)}")
        fig = axs[0].figure
    body, alpha = _body_alpha(result, body, alpha)
    si = getattr(result, "units", None) is not None
    if si:
        u_t, u_w, u_v, u_f, u_l, u_e = "s", "rad/s", "m/s", "N", "m", "J"
    else:
        u_t, u_w, u_v, u_f, u_l, u_e = (
            r"$\sqrt{R/g}$",
            r"$\sqrt{g/R}$",
            r"$\sqrt{gR}$",
            "$Mg$",
            "$R$",
            "$MgR$",
        )
    t = np.asarray(result.t, dtype=float)
    mode = np.asarray(result.mode)
    energy = np.asarray(result.energy, dtype=float)
    total = energy + np.asarray(result.dissipated, dtype=float)
    panels = (
        ("theta_dot", result.omega, rf"$\dot\theta$ [{u_w}]"),
        ("slip_velocity", result.slip_velocity, rf"slip $v = \dot l - \dot\theta$ [{u_v}]"),
        ("Fx", result.Fx, rf"friction $F_x$ [{u_f}]"),
        ("Fy", result.Fy, rf"normal $F_y$ [{u_f}]"),
        ("height", result.height, rf"height $b - 1$ [{u_l}]"),
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
        t, total, color="#d62728", ls="--", lw=1.3, label="$E$ + dissipated (slip, impacts)"
    )
    line.set_gid("energy_total")
    a_e.set_ylabel(f"energy [{u_e}]")
    a_e.legend(fontsize=8, loc="best")
    a_e.set_xlabel(f"time $t$ [{u_t}]")

    runs = _mode_runs(t, mode)
    for ax in axs:
        for t0, t1, name in runs:
            ax.axvspan(t0, t1, color=MODE_COLORS.get(name, "0.8"), alpha=0.14, lw=0, zorder=0)
        for imp in result.impacts:
            ax.axvline(imp.t, color="0.25", ls=":", lw=1.0)
        ax.grid(alpha=0.3)
    if t.size:
        axs[0].set_xlim(t[0], t[-1] if t[-1] > t[0] else t[0] + 1.0)
    present = [n for n in MODE_NAMES if any(name == n for _, _, name in runs)]
    handles: list[Any] = [Patch(color=MODE_COLORS[n], alpha=0.35, label=n) for n in present]
    if result.impacts:
        handles.append(Line2D([], [], color="0.25", ls=":", lw=1.0, label="impact"))
    axs[0].legend(handles=handles, loc="upper left", ncol=len(handles) or 1, fontsize=8)
    fig.suptitle(_motion_title(result, body, alpha), fontsize=11)
    return fig


def _resample(
    result: Any, ts: NDArray[np.float64]
) -> tuple[NDArray[np.float64], NDArray[np.float64], NDArray[np.float64], list[str]]:
    """(theta, l, b, mode name) at the times ts: from the dense output ``result.sol`` if
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
    dpi: int = 80,
    view: float = 2.6,
) -> Path:
    """Write an animated GIF of an :func:`eccjump.simulate` run (pillow's GIF writer).

    The ramp slopes down to the right at ``alpha``; the body is the unit circle centred at
    C = (l, b) in the ramp frame, its centre of mass C + chi (sin theta, cos theta) a dot
    with the spoke C -> CM; the body and the title take the colour of the mode. The camera
    follows C (a window ``view`` R either side); ticks on the ramp every R show the travel,
    a trail the path of the centre of mass. Frames are evenly spaced in simulated time, at
    most :data:`MAX_FRAMES` of them, played at ``fps`` (or over ``seconds``); the state comes
    from ``result.sol`` if present, else from the recorded points.

    ``body`` (for chi) and ``alpha`` [rad] are required unless the result carries them.
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
    ts = np.linspace(t[0], t[-1], n)
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

    fig, ax = plt.subplots(figsize=(4.4, 3.6), dpi=dpi)
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
        title.set_text(f"t = {ts[k]:7.3f}   {names[k]}")
        title.set_color(color)
        return [circle, spoke, cm, centre, trail, hatch, title]

    anim = FuncAnimation(fig, draw, frames=n, blit=False)
    try:
        anim.save(path, writer=PillowWriter(fps=play_fps), dpi=dpi)
    finally:
        plt.close(fig)
    return path


def _rgb(color: str) -> tuple[float, float, float]:
    from matplotlib.colors import to_rgb

    return to_rgb(color)

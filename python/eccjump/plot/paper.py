"""The paper's figures: Fig. 3b (μ(χ, k_m, θ_J)) and Fig. 4 (the JARM regions in
(α, χ, k_m) from their exact boundary surfaces, and its slices). The surfaces are
computed by :mod:`eccjump.classification.surfaces` (:func:`jarm_surfaces`, re-exported here
and by :mod:`eccjump.plot`); this module only draws them."""

from __future__ import annotations

import math
from collections.abc import Sequence
from typing import TYPE_CHECKING, Any, cast

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import U32_MAX, integer
from eccjump.classification import closed_form
from eccjump.classification.surfaces import (
    MAX_RESOLUTION,
    JarmSurfaces,
    grid_intervals,
    jarm_surfaces,
)

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure

from eccjump.plot._common import MAX_POINTS, _color, _new_axes, _plt

#: The most points along a slice of :func:`fig4_slices` (about 20 s per turn at 10**4).
MAX_SLICE_RESOLUTION = 10_000

# The surfaces' names stay importable from here, where they were computed before 0.2.
__all__ = [
    "MAX_RESOLUTION",
    "MAX_SLICE_RESOLUTION",
    "JarmSurfaces",
    "fig3b",
    "fig4",
    "fig4_slices",
    "jarm_surfaces",
]

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
    """The paper's Fig. 3b: μ(χ, k_m, θ_J) of Eq. ineq2 over one turn (n - 1) 360 deg to
    n 360 deg, with the green window (the quarter turn before 360 n deg, where a JARM can
    happen) shaded, μ_s,min marked, and the line μ = ``mu_s`` with θ_J,min and
    θ_J,max (the ends of the interval where μ ≤ μ_s) marked. ``mu_s=None`` omits it.

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
    mmin_at, phi = closed_form.mu_s_min(chi, km)
    mmin, phi_deg = float(mmin_at), base + 360.0 + math.degrees(float(phi))
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
        lo_at, hi_at = closed_form.theta_J_range(chi, km, mu_s, n)
        lo, hi = float(lo_at), float(hi_at)
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


def _solid_polygons(s: JarmSurfaces) -> list[NDArray[np.float64]]:
    """Quads of the closed solid between alpha_lo and alpha_hi: bottom, top and the side
    walls along the edge of the footprint (x = χ, y = k_m, z = α in degrees)."""
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
    """The paper's Fig. 4: the JARM regions in (α, χ, k_m) for fixed ``mu_s`` and turns
    ``ns`` (green, purple, orange for n = 1, 2, 3), from rest at theta0 = 0, as closed solids
    between the exact boundary surfaces alpha_lo and alpha_hi on a ``resolution``² mesh
    fitted to each region (see :func:`jarm_surfaces`, ``resolution`` 2 ... :data:`MAX_RESOLUTION`;
    pass precomputed ``surfaces`` to skip the computation). ``ax`` must be a 3-D axes if given."""
    plt = _plt()
    from matplotlib.patches import Patch
    from matplotlib.ticker import MaxNLocator
    from mpl_toolkits.mplot3d.art3d import Poly3DCollection

    # A 3-D axes (mplot3d's Axes3D, which matplotlib's stubs do not name).
    ax3d: Any
    if ax is None:
        fig = plt.figure(figsize=(7.5, 6.5), layout="constrained")
        ax3d = fig.add_subplot(projection="3d")
    else:
        fig, ax3d = cast("Figure", ax.get_figure(root=True)), ax
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
            ax3d.add_collection3d(coll)
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
    ax3d.set_xlim(0.0, round(c_max * 1.05 + 0.005, 2))
    ax3d.set_ylim(0.0, round(k_max * 1.05 + 0.005, 2))
    ax3d.set_zlim(0.0, 90.0)
    ax3d.set_zticks(np.arange(0.0, 91.0, 15.0))
    ax3d.xaxis.set_major_locator(MaxNLocator(6))
    ax3d.yaxis.set_major_locator(MaxNLocator(5))
    ax3d.set_xlabel(r"$\chi = d/R$")
    ax3d.set_ylabel(r"$k_m = m_C/M$")
    ax3d.set_zlabel(r"ramp angle $\alpha$ [deg]")
    ax3d.view_init(elev=elev, azim=azim)
    ax3d.legend(handles=handles, loc="upper left", fontsize=9, title="turn of the jump")
    ax3d.set_title(
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
    """2-D slices of the Fig. 4 regions: top row, the JARM α-interval against χ at fixed
    (absolute) k_m; bottom row, against k_m at fixed χ; filled between the exact alpha_lo and
    alpha_hi, one colour per turn n. ``resolution`` points along each slice, 2 ...
    :data:`MAX_SLICE_RESOLUTION`."""
    resolution = integer("resolution", resolution, 2, MAX_SLICE_RESOLUTION)
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
                ivs = grid_intervals(*xs, mu_s, n, n_scan)
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

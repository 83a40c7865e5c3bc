"""Maps: a computed JARM region, the JARM fraction over the starts, the motion map's
sequences of modes, P(JARM) under tolerances."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING

import numpy as np

from eccjump._base.checks import integer
from eccjump.classification.classify import Region
from eccjump.classification.starts import OptimalStart, StartMap
from eccjump.motion.fields import sequence_name
from eccjump.motion.maps import MotionMap
from eccjump.studies.uncertainty.map import UncertaintyMap

if TYPE_CHECKING:
    from matplotlib.figure import Figure

from eccjump.plot._common import TURN_COLORS, _plt

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
    views += [
        (rf"$k_m = {region.km_frac[j]:.3g}\,(1-\chi)$ (most JARM points)", cat[:, :, j])
        for j in best
    ]
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
        f"{start} ({100.0 * region.fraction():.2f}% of {is_jarm.size} grid points)\n"
        "JARM: the body leaves the ramp straight out of pure rolling (no slip before). "
        f"Panels: the projection over $k_m$, then the {len(best)} $k_m$ slices with the most "
        "JARM points",
        fontsize=10,
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
        raise ValueError("sequence_map needs a map over alpha, chi (and km_frac) only")
    plt = _plt()
    from matplotlib.colors import ListedColormap
    from matplotlib.patches import Patch

    seq = np.asarray(m.fields["sequence"])
    if seq.ndim == 2:
        seq = seq[:, :, None]
    km = m.coords.get("km_frac", np.array([m.scalars.get("km_frac") or 0.0]))
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
# P(JARM) under tolerances (eccjump.uncertainty_map / eccjump map --kind uncertainty)
# --------------------------------------------------------------------------------------------

#: The contours of :func:`probability_map`: an even chance and the 95 % design target.
PROBABILITY_LEVELS = (0.5, 0.95)


def probability_map(m: UncertaintyMap, *, km_index: int | None = None) -> Figure:
    """P(JARM) of an :class:`~eccjump.UncertaintyMap` over (chi, alpha) on one km_frac slice
    (``km_index``; None: the slice of largest mean P(JARM)), with its 0.5 and 0.95
    contours. A lazy map is computed first."""
    if not isinstance(m, UncertaintyMap):
        raise TypeError(f"m must be an UncertaintyMap, not {type(m).__name__}")
    m = m.compute()
    p = np.asarray(m.fields["p_jarm"], dtype=np.float64)
    if km_index is None:
        with np.errstate(invalid="ignore"):
            means = np.nan_to_num(np.nanmean(p, axis=(0, 1)) if p.size else np.zeros(0), nan=-1)
        k = int(np.argmax(means)) if means.size else 0
    else:
        k = integer("km_index", km_index, 0, max(m.km_frac.size - 1, 0))
    plt = _plt()
    fig, ax = plt.subplots(figsize=(6.2, 4.6), layout="constrained")
    a_deg = np.degrees(m.alpha)
    mesh = ax.pcolormesh(m.chi, a_deg, p[:, :, k], cmap="viridis", vmin=0.0, vmax=1.0,
                         shading="nearest")  # fmt: skip
    fig.colorbar(mesh, ax=ax, label="P(JARM)")
    if min(m.alpha.size, m.chi.size) >= 2 and np.isfinite(p[:, :, k]).any():
        lines = ax.contour(m.chi, a_deg, p[:, :, k], levels=PROBABILITY_LEVELS,
                           colors=["white", "red"], linewidths=[1.0, 1.6])  # fmt: skip
        ax.clabel(lines, fmt={v: f"{v:g}" for v in PROBABILITY_LEVELS}, fontsize=8)
    ax.set_xlabel(r"$\chi = d/R$")
    ax.set_ylabel(r"ramp angle $\alpha$ [deg]")
    spreads = _tolerances(m)
    ax.set_title(
        f"P(JARM) at $k_m = {m.km_frac[k]:.3g}\\,(1-\\chi)$, $\\mu_s = {m.mu_s:g}$, "
        f"{m.n} samples per point\ntolerances: {spreads}; contours 0.5 (white), 0.95 (red)",
        fontsize=9,
    )
    return fig


def _tolerances(m: UncertaintyMap) -> str:
    """The map's tolerances in a line, the ramp angle's in degrees."""

    def shown(name: str, x: float) -> str:
        return f"{math.degrees(x):.3g}°" if name == "alpha" else f"{x:.3g}"

    out = [f"{k} ± {shown(k, v)}" for k, v in m.sd.items() if v > 0]
    out += [f"{k} + [{shown(k, lo)}, {shown(k, hi)}]" for k, (lo, hi) in m.bounds.items()]
    return "; ".join(out) or "none"

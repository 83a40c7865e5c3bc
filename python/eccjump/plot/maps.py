"""Maps: a computed JARM region, the JARM fraction over the starts, the motion map's
sequences of modes, P(JARM) under tolerances."""

from __future__ import annotations

import math
from typing import TYPE_CHECKING, Any, NamedTuple, overload

import numpy as np
from numpy.typing import NDArray

from eccjump._base.checks import integer, real
from eccjump.classification.classify import Region
from eccjump.classification.starts import OptimalStart, StartMap
from eccjump.motion.fields import sequence_name
from eccjump.motion.maps import MotionMap
from eccjump.studies.uncertainty.map import UncertaintyMap
from eccjump.studies.uncertainty.map_fields import PROBABILITY_LEVELS

if TYPE_CHECKING:
    from matplotlib.axes import Axes
    from matplotlib.figure import Figure, FigureBase

from eccjump.plot._common import TURN_COLORS, checked_target, new_figure

# --------------------------------------------------------------------------------------------
# A computed region map (eccjump.region / eccjump map)
# --------------------------------------------------------------------------------------------


def _nearest_slice(values: NDArray[np.float64], km_frac: object, default: int) -> int:
    """The index of the k_m slice nearest ``km_frac`` (None: ``default``)."""
    if km_frac is None:
        return default
    x = real("km_frac", km_frac)
    if not (math.isfinite(x) and values.size):
        raise ValueError(f"km_frac = {x:g} must be a finite k_m/(1 - chi) of the map")
    return int(np.argmin(np.abs(values - x)))


def _turns(region: Region) -> tuple[NDArray[np.float64], int, list[str]]:
    """(the turn category of every point, NaN where not JARM; the category of the late
    turns; the colour of each category)."""
    last = len(TURN_COLORS) + 1  # category for n > len(TURN_COLORS)
    is_jarm = np.asarray(region.result.is_jarm)
    cat = np.where(is_jarm, np.minimum(np.asarray(region.result.n, dtype=float), last), np.nan)
    return cat, last, [*TURN_COLORS, "#7f7f7f"]


def _turn_mesh(ax: Axes, region: Region, img: NDArray[np.float64], title: str) -> None:
    from matplotlib.colors import ListedColormap

    _, last, colors = _turns(region)
    a_deg = np.degrees(region.alpha)
    ax.pcolormesh(region.chi, a_deg, img, cmap=ListedColormap(colors), vmin=0.5,
                  vmax=last + 0.5, shading="nearest")  # fmt: skip
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(r"$\chi = d/R$")
    ax.set_ylabel(r"ramp angle $\alpha$ [deg]")
    ax.set_xlim(region.chi[0], region.chi[-1])
    ax.set_ylim(a_deg[0], a_deg[-1])
    ax.grid(alpha=0.3)


def _turn_handles(region: Region, cat: NDArray[np.float64]) -> list[Any]:
    from matplotlib.patches import Patch

    _, last, colors = _turns(region)
    present = {int(k) for k in np.unique(cat[np.isfinite(cat)])}
    return [
        Patch(color=colors[k - 1], label=f"$n = {k}$" if k < last else f"$n > {last - 1}$")
        for k in sorted(present)
    ]


def _checked_region(region: Region) -> Region:
    if not isinstance(region, Region):
        raise TypeError(f"region must be a Region, not {type(region).__name__}")
    return region


def region_panel(region: Region, ax: Axes, *, km_frac: float | None = None) -> Axes:
    """One k_m slice of a :class:`~eccjump.Region` in the (χ, α) plane, JARM points
    coloured by their turn, drawn into ``ax`` (``Region.plot(ax=ax)``): the slice nearest
    ``km_frac`` = k_m/(1 - χ), else the one with the most JARM points. Returns ``ax``."""
    cat = _turns(_checked_region(region))[0]
    most = int(np.argmax(np.isfinite(cat).sum(axis=(0, 1)))) if cat.size else 0
    j = _nearest_slice(np.asarray(region.km_frac), km_frac, most)
    _turn_mesh(ax, region, cat[:, :, j], rf"JARM region, $k_m = {region.km_frac[j]:.3g}\,(1-\chi)$")
    handles = _turn_handles(region, cat[:, :, j])
    if handles:
        ax.legend(handles=handles, title="turn", fontsize=8, loc="best")
    return ax


def region_map(region: Region, *, fig: FigureBase | None = None, panels: int = 4) -> Figure:
    """A computed :class:`~eccjump.Region` in the (χ, α) plane, JARM points coloured by
    their turn n (turns past 5 share one colour). The first panel projects over k_m (the
    smallest n of any k_m on the grid); the others are the ``panels - 1`` k_m slices with the
    most JARM points. ``fig``: an empty Figure or SubFigure to draw into (else a new one)."""
    _checked_region(region)
    panels = integer("panels", panels, 1, 64)
    checked_target(None, fig)
    cat = _turns(region)[0]
    is_jarm = np.isfinite(cat)
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
    canvas, root = new_figure(fig, (3.3 * len(views) + 1.6, 3.7))
    axes = canvas.subplots(1, len(views), sharey=True, squeeze=False)
    for ax, (title, img) in zip(axes[0], views, strict=True):
        _turn_mesh(ax, region, img, title)
    for ax in axes[0, 1:]:
        ax.set_ylabel("")
    handles = _turn_handles(region, cat)
    if handles:
        canvas.legend(handles=handles, title="JARM on turn", loc="outside right upper", fontsize=9)
    start = (
        rf", start $\theta_0 = {math.degrees(region.theta0):.4g}°$, "
        rf"$\dot\theta_0 = {region.omega0:.4g}$"
        if region.theta0 or region.omega0
        else ""
    )
    canvas.suptitle(
        f"JARM region, $\\mu_s = {region.mu_s:g}$, rule: {region.rule}, route: {region.method}"
        f"{start} ({100.0 * region.fraction():.2f}% of {is_jarm.size} grid points)\n"
        "JARM: the body leaves the ramp straight out of pure rolling (no slip before). "
        f"Panels: the projection over $k_m$, then the {len(best)} $k_m$ slices with the most "
        "JARM points",
        fontsize=10,
    )
    return root


# --------------------------------------------------------------------------------------------
# Initial conditions (eccjump.start_map / eccjump starts)
# --------------------------------------------------------------------------------------------


def _checked_starts(smap: StartMap, optimum: OptimalStart | None) -> None:
    if not isinstance(smap, StartMap):
        raise TypeError(f"smap must be a StartMap, not {type(smap).__name__}")
    if optimum is not None and not isinstance(optimum, OptimalStart):
        raise TypeError(f"optimum must be an OptimalStart or None, not {type(optimum).__name__}")


def _start_view(ax: Axes, smap: StartMap, view: int, optimum: OptimalStart | None) -> Any:
    """One view of a start map (0: the JARM fraction, 1: immediate flight, 2: rocking back)
    over (theta0, omega0); returns its mesh (for a colour bar)."""
    from matplotlib.colors import PowerNorm

    title, img, cmap = (
        ("JARM fraction (colour scale: square root)", smap.fraction, "viridis"),
        ("immediate flight (LIFTOFF_EARLIER)", smap.immediate_flight, "Blues"),
        ("rocks back (ROCKS_BACK)", smap.rocks_back, "Oranges"),
    )[view]
    th = np.degrees(smap.theta0)
    norm = PowerNorm(0.5, vmin=0.0, vmax=max(float(img.max()), 1e-12)) if view == 0 else None
    mesh = ax.pcolormesh(th, smap.omega0, img.T, cmap=cmap, shading="nearest", norm=norm,
                         vmin=None if view == 0 else 0.0)  # fmt: skip
    ax.set_title(title, fontsize=10)
    ax.set_xlabel(r"$\theta_0$ [deg]")
    ax.set_ylabel(r"$\dot\theta_0$ [$\sqrt{g/R}$]")
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
            color="#D55E00",
            ms=11,
            mec="white",
            label="optimum",
        )
    if view == 0:
        ax.scatter([0.0], [0.0], marker="o", color="#D55E00", s=30, clip_on=False,
                   label="from rest", zorder=3)  # fmt: skip
        ax.legend(loc="upper left", fontsize=8)
    return mesh


def fraction_panel(smap: StartMap, ax: Axes, *, optimum: OptimalStart | None = None) -> Axes:
    """The JARM fraction over the starts (theta0, omega0) of a :class:`~eccjump.StartMap`
    drawn into ``ax`` (``StartMap.plot(ax=ax)``; ``optimum`` marked); returns ``ax``."""
    _checked_starts(smap, optimum)
    _start_view(ax, smap, 0, optimum)
    return ax


def fraction_map(
    smap: StartMap, *, fig: FigureBase | None = None, optimum: OptimalStart | None = None
) -> Figure:
    """The JARM fraction over the starts (theta0, omega0) of a :class:`~eccjump.StartMap`
    (left), and the shares of the parameter cube blocked at the start: immediate flight and
    rocking back (right). ``optimum`` is marked with its uncertainty; starts with no JARM on
    the grid are hatched. ``fig``: an empty Figure or SubFigure to draw into (else a new
    one)."""
    _checked_starts(smap, optimum)
    checked_target(None, fig)
    canvas, root = new_figure(fig, (13.5, 4.0))
    axes = canvas.subplots(1, 3, sharey=True)
    for view, ax in enumerate(axes):
        canvas.colorbar(_start_view(ax, smap, view, optimum), ax=ax, shrink=0.9)
    for ax in axes[1:]:
        ax.set_ylabel("")
    best = "" if optimum is None else (
        f"; optimum {100 * optimum.fraction:.2f}% at $\\theta_0 = "
        f"{math.degrees(optimum.theta0):.1f}°$, $\\dot\\theta_0 = {optimum.omega0:.3f}$"
    )  # fmt: skip
    canvas.suptitle(
        f"Share of (α, χ, $k_m$) by start, $\\mu_s = {smap.mu_s:g}$, rule: {smap.rule}, "
        f"{smap.grid}³ midpoint grid{best}",
        fontsize=11,
    )
    return root


#: Colours of the most frequent sequences of :func:`sequence_map` (the rest share grey).
SEQUENCE_COLORS = (
    "#1f77b4", "#ff7f0e", "#2ca02c", "#d62728", "#9467bd",
    "#8c564b", "#e377c2", "#bcbd22", "#17becf", "#aec7e8",
)  # fmt: skip


class _Sequences(NamedTuple):
    """A motion map's points by category: the ``top`` sequence codes (category k), the rest
    (category len(top)), NaN where not run; shaped (α, χ, km_frac)."""

    cat: NDArray[np.float64]
    top: list[int]
    colors: list[str]
    jarm: NDArray[np.bool_]
    km: NDArray[np.float64]


def _sequences(m: MotionMap) -> _Sequences:
    if not isinstance(m, MotionMap):
        raise TypeError(f"m must be a MotionMap, not {type(m).__name__}")
    if tuple(m.coords)[:2] != ("alpha", "chi") or len(m.coords) > 3:
        raise ValueError("sequence_map needs a map over alpha, chi (and km_frac) only")
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
    jarm = np.asarray(m.fields["jarm"]).reshape(seq.shape)
    return _Sequences(cat, top, colors, jarm, np.asarray(km, dtype=float))


def _sequence_slice(ax: Axes, m: MotionMap, s: _Sequences, j: int) -> None:
    from matplotlib.colors import ListedColormap

    a_deg = np.degrees(m.coords["alpha"])
    chi = m.coords["chi"]
    ia, ic = np.nonzero(s.jarm[:, :, j])
    ax.plot(chi[ic], a_deg[ia], "k.", ms=1.5, zorder=3)  # the paper's Fig. 4 region
    ax.pcolormesh(chi, a_deg, s.cat[:, :, j], cmap=ListedColormap(s.colors), vmin=-0.5,
                  vmax=len(s.top) + 0.5, shading="nearest")  # fmt: skip
    ax.set_title(rf"$k_m = {s.km[j]:.3g}\,(1-\chi)$", fontsize=10)
    ax.set_xlabel(r"$\chi = d/R$")
    ax.set_ylabel(r"ramp angle $\alpha$ [deg]")
    ax.grid(alpha=0.3)


def _sequence_handles(s: _Sequences, cat: NDArray[np.float64]) -> list[Any]:
    from matplotlib.patches import Patch

    shown = {int(k) for k in np.unique(cat[np.isfinite(cat)])}
    handles = [
        Patch(color=s.colors[k], label=sequence_name(code).replace("→", " → "))
        for k, code in enumerate(s.top)
        if k in shown
    ]
    if len(s.top) in shown:
        handles.append(Patch(color=s.colors[-1], label="other sequences"))
    handles.append(Patch(color="k", label="JARM (ROLL → FLIGHT by the lift-off rule)"))
    return handles


def sequence_panel(m: MotionMap, ax: Axes, *, km_frac: float | None = None) -> Axes:
    """One k_m slice of a motion map over (χ, α), every point coloured by its sequence
    of modes, drawn into ``ax`` (``MotionMap.plot(ax=ax)``): the slice nearest ``km_frac``,
    else the first with points that ran. Returns ``ax``."""
    s = _sequences(m)
    ran = np.flatnonzero(np.isfinite(s.cat).any(axis=(0, 1)))
    j = _nearest_slice(s.km, km_frac, int(ran[0]) if ran.size else 0)
    _sequence_slice(ax, m, s, j)
    ax.legend(handles=_sequence_handles(s, s.cat[:, :, j]), fontsize=7, loc="best")
    return ax


def sequence_map(m: MotionMap, *, fig: FigureBase | None = None, panels: int = 4) -> Figure:
    """A motion map over (χ, α), one panel per k_m slice (``panels`` evenly spaced
    slices), every point coloured by its sequence of modes (the 10 most frequent sequences
    of the map; the others grey, points not run white). Like the paper's Fig. 4, but for
    every outcome; the JARM points are the ROLL→FLIGHT→... sequences. ``fig``: an empty
    Figure or SubFigure to draw into (else a new one)."""
    s = _sequences(m)
    panels = integer("panels", panels, 1, 64)
    checked_target(None, fig)
    ran = np.flatnonzero(np.isfinite(s.cat).any(axis=(0, 1)))  # slices with points that ran
    ran = ran if ran.size else np.arange(s.cat.shape[2])
    slices = ran[np.unique(np.linspace(0, ran.size - 1, min(panels, ran.size)).round().astype(int))]
    canvas, root = new_figure(fig, (3.3 * slices.size + 3.2, 3.8))
    axes = canvas.subplots(1, slices.size, sharey=True, squeeze=False)
    for ax, j in zip(axes[0], slices.astype(int), strict=True):
        _sequence_slice(ax, m, s, int(j))
    for ax in axes[0, 1:]:
        ax.set_ylabel("")
    canvas.legend(handles=_sequence_handles(s, s.cat), title="modes, to the first landing",
                  loc="outside right upper", fontsize=8)  # fmt: skip
    o, sc = m.options, m.scalars
    mu_k = sc.get("mu_k")
    canvas.suptitle(
        f"Full motion to the first landing: $\\mu_s = {sc.get('mu_s', float('nan')):g}$, "
        f"$\\mu_k = {sc.get('mu_s') if mu_k is None else mu_k:g}$, "
        f"$e = {sc.get('restitution', 0.0):g}$, rule: {o.get('rule', 'paper')}"
    )
    return root


# --------------------------------------------------------------------------------------------
# P(JARM) under tolerances (eccjump.uncertainty_map / eccjump map --kind uncertainty)
# --------------------------------------------------------------------------------------------


@overload
def probability_map(
    m: UncertaintyMap, *, km_index: int | None = ..., ax: Axes, fig: None = ...
) -> Axes: ...
@overload
def probability_map(
    m: UncertaintyMap,
    *,
    km_index: int | None = ...,
    ax: None = ...,
    fig: FigureBase | None = ...,
) -> Figure: ...
def probability_map(
    m: UncertaintyMap,
    *,
    km_index: int | None = None,
    ax: Axes | None = None,
    fig: FigureBase | None = None,
) -> Figure | Axes:
    """P(JARM) of an :class:`~eccjump.UncertaintyMap` over (χ, α) on one km_frac slice
    (``km_index``; None: the slice of largest mean P(JARM)), with its 0.5 and 0.95
    contours. A lazy map is computed first. ``ax``: draw into these Axes and return them;
    ``fig``: an empty Figure or SubFigure to draw into (else a new one)."""
    if not isinstance(m, UncertaintyMap):
        raise TypeError(f"m must be an UncertaintyMap, not {type(m).__name__}")
    checked_target(ax, fig)
    m = m.compute()
    p = np.asarray(m.fields["p_jarm"], dtype=np.float64)
    if km_index is None:
        with np.errstate(invalid="ignore"):
            means = np.nan_to_num(np.nanmean(p, axis=(0, 1)) if p.size else np.zeros(0), nan=-1)
        k = int(np.argmax(means)) if means.size else 0
    else:
        k = integer("km_index", km_index, 0, max(m.km_frac.size - 1, 0))
    if ax is not None:
        _probability_panel(ax, m, p[:, :, k], k)
        return ax
    canvas, root = new_figure(fig, (6.2, 4.6))
    _probability_panel(canvas.subplots(), m, p[:, :, k], k)
    return root


def _probability_panel(ax: Axes, m: UncertaintyMap, p: NDArray[np.float64], k: int) -> None:
    a_deg = np.degrees(m.alpha)
    mesh = ax.pcolormesh(m.chi, a_deg, p, cmap="viridis", vmin=0.0, vmax=1.0, shading="nearest")
    ax.figure.colorbar(mesh, ax=ax, label="P(JARM)")
    if min(m.alpha.size, m.chi.size) >= 2 and np.isfinite(p).any():
        lines = ax.contour(m.chi, a_deg, p, levels=PROBABILITY_LEVELS,
                           colors=["white", "red"], linewidths=[1.0, 1.6])  # fmt: skip
        ax.clabel(lines, fmt={v: f"{v:g}" for v in PROBABILITY_LEVELS}, fontsize=8)
    ax.set_xlabel(r"$\chi = d/R$")
    ax.set_ylabel(r"ramp angle $\alpha$ [deg]")
    ax.set_title(
        f"P(JARM) at $k_m = {m.km_frac[k]:.3g}\\,(1-\\chi)$, $\\mu_s = {m.mu_s:g}$, "
        f"{m.estimate}\ntolerances: {_tolerances(m)}; contours 0.5 (white), "
        "0.95 (red)",
        fontsize=9,
    )


def _tolerances(m: UncertaintyMap) -> str:
    """The map's tolerances in a line, the ramp angle's in degrees."""

    def shown(name: str, x: float) -> str:
        return f"{math.degrees(x):.3g}°" if name == "alpha" else f"{x:.3g}"

    out = [f"{k} ± {shown(k, v)}" for k, v in m.sd.items() if v > 0]
    out += [f"{k} + [{shown(k, lo)}, {shown(k, hi)}]" for k, (lo, hi) in m.bounds.items()]
    return "; ".join(out) or "none"


__all__ = [
    "SEQUENCE_COLORS",
    "fraction_map",
    "fraction_panel",
    "probability_map",
    "region_map",
    "region_panel",
    "sequence_map",
    "sequence_panel",
]

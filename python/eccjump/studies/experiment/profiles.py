"""Profiles of the fit's cost along one parameter (the others refitted at each value), and
the intervals they give: a local (Jacobian) interval misses a second minimum or a kink.
"""

from __future__ import annotations

import math
from collections.abc import Callable

import numpy as np
from numpy.typing import NDArray

from eccjump.studies.experiment.fit import (
    MU_MAX,
    PROFILE_NFEV,
    Fit,
    Model,
    Setup,
    theta0_is_loose,
)
from eccjump.studies.experiment.reconstruction import Reconstruction
from eccjump.studies.experiment.track import Track


def profile(
    best: Fit, setup: Setup, track: Track, rec: Reconstruction, name: str = "mu_k", n: int = 11
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """The profile of the cost along one parameter: at each of ``n`` values over its range
    the other parameters are refitted. A local (Jacobian) interval misses a second minimum
    (e.g. a landing that a lower μ_k with some bounce explains as well) or a kink (a
    slip's onset, where μ_s acts); the profile does not, within its grid. ``name`` is one
    of the fit's parameters or ``"mu_s"`` (μ_k + Δμ, each value held by the model: the
    grid also brackets by 5 and 15 % the fitted μ_s, or what the fitted rolling needs
    where that is less, a rolling fit's μ_s being anything above it). The values are
    refitted outward from the fitted one, each from its neighbour's solution (half the
    work of starting each from the best fit)."""
    if name == "mu_s":
        v0 = min(float(best.run.mu_s), best.mu_s_bound) if best.mu_s_bound > 0 else best.run.mu_s
        grid = np.unique(
            np.r_[np.linspace(0.0, MU_MAX / 2, n), v0 * np.array([0.85, 0.95, 1.0, 1.05, 1.15])]
        )
        held = best.names.index("dmu")  # no say while the model holds mu_s

        def fit_at(k: int, x: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
            model = Model(setup, track, rec, jarm_only=False, mu_s_range=(grid[k], grid[k]))
            return _profile_fit(best, model, held, x, float(best.x[held]))
    else:
        held = best.names.index(name)
        v0 = float(best.x[held])
        grid = np.unique(np.r_[np.linspace(best.lower[held], best.upper[held] / 2, n), v0])
        model = Model(setup, track, rec, jarm_only=best.jarm_only)

        def fit_at(k: int, x: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
            return _profile_fit(best, model, held, x, float(grid[k]))

    return grid, _sweep(best, grid, v0, fit_at)[0]


def _sweep(
    best: Fit,
    grid: NDArray[np.float64],
    v0: float,
    fit_at: Callable[[int, NDArray[np.float64]], tuple[float, NDArray[np.float64]]],
) -> tuple[NDArray[np.float64], list[NDArray[np.float64]]]:
    """The least cost at each grid value and its solution, refitted outward from the one
    nearest ``v0``, each from its neighbour's solution."""
    costs = np.empty(grid.size)
    xs: list[NDArray[np.float64]] = [best.x] * grid.size
    k0 = int(np.argmin(np.abs(grid - v0)))
    for sweep in (range(k0, grid.size), range(k0 - 1, -1, -1)):
        x = best.x
        for k in sweep:
            costs[k], x = fit_at(k, x)
            xs[k] = x
    return costs, xs


#: The step [rad] of the walk along θ₀ (half the screen's :data:`fit.THETA0_STEP`).
WALK_STEP = 0.25


def theta0_walk(
    best: Fit, setup: Setup, track: Track, rec: Reconstruction
) -> dict[str, float] | None:
    """A start in a deeper basin than ``best``'s, from the profile of the cost along θ₀
    over its whole range (every :data:`WALK_STEP`), or None: walked only where the
    smoothed θ₀ is a guess (:func:`fit.theta0_is_loose`). The screen's starts in θ₀ end
    in the basins near them; the walk carries the other parameters along as θ₀ turns.
    On the independent model's 60 fps, 2 px track of a 59-frame slip (a frame's θ
    uncertain by 1.3 rad) the screen's best fit had μ_k 0.316 ± 0.005 against the truth's
    0.382; the walk found a basin lower by Δχ² 59, refitted to μ_k 0.383."""
    if not theta0_is_loose(rec):
        return None
    held = best.names.index("theta0")
    grid = np.arange(best.lower[held], best.upper[held] + 1e-9, WALK_STEP)
    model = Model(setup, track, rec, jarm_only=best.jarm_only)

    def fit_at(k: int, x: NDArray[np.float64]) -> tuple[float, NDArray[np.float64]]:
        return _profile_fit(best, model, held, x, float(grid[k]))

    costs, xs = _sweep(best, grid, float(best.x[held]), fit_at)
    k = int(np.argmin(costs))
    if not costs[k] < best.cost:
        return None
    return {n: float(v) for n, v in zip(best.names, xs[k], strict=True)}


def _profile_fit(
    best: Fit, model: Model, held: int, x0: NDArray[np.float64], value: float
) -> tuple[float, NDArray[np.float64]]:
    """The least cost of ``model`` with parameter ``held`` at ``value`` and the solution,
    refitted from ``x0`` and, where the best fit bounces, from no bounce (a bounce can
    mimic friction)."""
    from scipy.optimize import least_squares

    free = [j for j in range(best.x.size) if j != held]
    starts = [x0[free]]
    if "e" in best.names and best.value("e") > 0.05:
        y = x0.copy()
        y[best.names.index("e")] = 0.0
        starts.append(y[free])

    def fun(y: NDArray[np.float64]) -> NDArray[np.float64]:
        x = best.x.copy()
        x[free] = y
        x[held] = value
        return model.residuals(x)

    out = (math.inf, x0)
    for y0 in starts:
        res = least_squares(
            fun,
            y0,
            bounds=(best.lower[free], best.upper[free]),
            x_scale="jac",
            diff_step=1e-6,
            max_nfev=PROFILE_NFEV,
            method="trf",
        )
        if res.cost < out[0]:
            x = best.x.copy()
            x[free], x[held] = res.x, value
            out = (float(res.cost), x)
    return out


def profile_interval(
    grid: NDArray[np.float64],
    costs: NDArray[np.float64],
    best: Fit,
    local: tuple[float, float],
    bounds: tuple[float, float],
    level: float = 3.84,
) -> tuple[float, float]:
    """The ``local`` ~95 % interval, widened to every grid value of the profile whose cost
    is within ``level`` / 2 (in units of the reduced χ²) of the least, plus one
    grid step beyond it (a second minimum narrower than a step can be missed), within
    ``bounds``; out to the bound where the grid's end value is accepted (the profile is
    flat there: a rolling track leaves μ_k open above, and μ_s too)."""
    lo, hi = local
    low = min(float(costs.min()), best.cost)
    ok = 2.0 * (costs - low) / best.variance_factor <= level
    accepted = grid[ok]
    far = accepted[(accepted < lo) | (accepted > hi)]
    if far.size:
        step = float(np.max(np.diff(grid))) if grid.size > 1 else 0.0
        lo = max(min(lo, float(far.min()) - step), bounds[0])
        hi = min(max(hi, float(far.max()) + step), bounds[1])
    if ok[-1]:
        hi = bounds[1]
    return lo, hi


def mu_s_interval(f: Fit) -> tuple[float, float]:
    """μ_s's local ~95 % interval (μ_k + Δμ, from the covariance), (μ_k, ∞) where the
    fit does not constrain it."""
    i, j = f.names.index("mu_k"), f.names.index("dmu")
    var = f.cov[i, i] + f.cov[j, j] + 2 * f.cov[i, j]
    v = f.value("mu_k") + f.value("dmu")
    if not math.isfinite(var):
        return f.value("mu_k"), math.inf
    e = 1.96 * math.sqrt(max(var, 0.0))
    return max(v - e, 0.0), v + e

"""JARM boundaries found by bisection, without a dense grid: the alpha-intervals of the
paper's Figure 4 surfaces for given bodies, and the smallest mu_s that gives a JARM."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._arrays import broadcast_flat, turn
from eccjump._checks import U64_MAX, Rule, integer, real, text


def _threads(n_threads: object) -> int:
    return integer("n_threads", n_threads, 0, U64_MAX)


def alpha_intervals(
    chi: ArrayLike,
    km: ArrayLike,
    mu_s: float,
    n: int | None = None,
    *,
    rule: Rule = "paper",
    n_scan: int = 180,
    n_threads: int = 0,
) -> list[list[tuple[float, float]]]:
    """For each body (chi, km) (broadcast, flattened): the intervals (alpha_lo, alpha_hi) [rad]
    of ramp angles that give a JARM, each end located to 1e-12 by bisection after a scan of
    ``n_scan`` angles over (0, pi/2] (2 ... 10**5; an interval narrower than pi/(2 n_scan)
    can be missed). An invalid body or mu_s is a ValueError naming it and its index."""
    scan = integer("n_scan", n_scan, 2, U64_MAX)
    _, (c, k) = broadcast_flat(chi=chi, km=km)
    return _core.alpha_intervals(
        c, k, real("mu_s", mu_s), turn(n) or 0, text("rule", rule), scan, _threads(n_threads)
    )


def mu_s_min_path(
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    n: int | None = None,
    *,
    rule: Rule = "paper",
    n_threads: int = 0,
) -> NDArray[np.float64]:
    """The smallest mu_s that gives a JARM at each (alpha, chi, km) (relative 1e-12; inf if
    none up to 1e6). Under the paper's rule it equals the largest friction ratio |Fx|/Fy on
    the rolling path up to the jump, including mu(theta_J)."""
    shape, (a, c, k) = broadcast_flat(alpha=alpha, chi=chi, km=km)
    out = _core.mu_s_min_path(a, c, k, turn(n) or 0, text("rule", rule), _threads(n_threads))
    return out.reshape(shape)


def alpha_interval_around(
    seed: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    mu_s: float,
    n: int | None = None,
    *,
    rule: Rule = "paper",
    step: float = 1e-3,
    n_threads: int = 0,
) -> tuple[NDArray[np.float64], NDArray[np.float64]]:
    """For each JARM angle ``seed`` [rad] of a body (chi, km) (broadcast): the ends (lo, hi)
    of the JARM alpha-interval that holds it, stepping outwards from the seed by ``step``
    (doubling) and bisecting each end to 1e-12; NaN where the seed is not a JARM. Finds thin
    parts of a region that the scan of :func:`alpha_intervals` misses."""
    shape, (s, c, k) = broadcast_flat(seed=seed, chi=chi, km=km)
    lo, hi = _core.alpha_interval_around(
        s,
        c,
        k,
        real("mu_s", mu_s),
        turn(n) or 0,
        text("rule", rule),
        real("step", step),
        _threads(n_threads),
    )
    return lo.reshape(shape), hi.reshape(shape)

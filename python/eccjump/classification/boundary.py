"""JARM boundaries found by bisection, without a dense grid: the α-intervals of the
paper's Figure 4 surfaces for given bodies, and the smallest μ_s that gives a JARM."""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.arrays import broadcast_flat, turn
from eccjump._base.checks import U64_MAX, Rule, integer, real, text
from eccjump._base.docs import fill
from eccjump._base.units import ramp_angles


def _options(n: object, rule: object, n_threads: object) -> _core.BoundaryOptions:
    """The options every boundary search takes, checked (TypeError naming one of the wrong
    type) and converted by the bridge (ValueError for an unknown rule)."""
    return _core.BoundaryOptions(
        n=turn(n) or 0,
        rule=text("rule", rule),
        n_threads=integer("n_threads", n_threads, 0, U64_MAX),
    )


@fill
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
    """The intervals of ramp angles that give a JARM, for each body (χ, km).

    A scan of ``n_scan`` angles over (0, π/2] finds the intervals; each end is then located
    to 1e-12 rad by bisection. An interval narrower than π/(2 n_scan) can be missed
    (:func:`alpha_interval_around` finds it from a seed).

    Parameters
    ----------
    chi : array_like of float
        The bodies' d/R, each in [0, 1] (broadcast with ``km``, then flattened).
    km : array_like of float
        The bodies' shell mass fraction k_m, each in [0, 1 - χ].
    %(mu_s)s
    %(n_first)s
    %(rule)s
    n_scan : int, default 180
        Angles of the scan, 2 ... 10**5.
    %(n_threads)s

    Returns
    -------
    list of list of tuple of (float, float)
        For each body in flattened order, its intervals (alpha_lo, alpha_hi) [rad], in
        increasing order; an empty list where no angle gives a JARM.

    Raises
    ------
    ValueError
        For an invalid body or ``mu_s`` (naming it and the index of the body), or an
        option out of range.

    Examples
    --------
    >>> import eccjump
    >>> [(round(lo, 6), round(hi, 6)) for lo, hi in eccjump.alpha_intervals(0.15, 0.02, 1.0)[0]]
    [(0.347488, 0.370761), (0.632248, 0.881102)]
    """
    scan = integer("n_scan", n_scan, 2, U64_MAX)
    _, (c, k) = broadcast_flat(chi=chi, km=km)
    return _core.alpha_intervals(
        c, k, real("mu_s", mu_s), n_scan=scan, options=_options(n, rule, n_threads)
    )


@fill
def mu_s_min_path(
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    n: int | None = None,
    *,
    rule: Rule = "paper",
    n_threads: int = 0,
) -> NDArray[np.float64]:
    """The smallest static friction coefficient that gives a JARM at each (α, χ, km).

    Located by bisection to a relative 1e-12. Under the paper's rule it equals the largest
    friction ratio |Fx|/Fy on the rolling path up to the jump, including μ(θ_J).

    Parameters
    ----------
    %(alpha_points)s
    %(chi)s
    %(km)s
    %(n_first)s
    %(rule)s
    %(n_threads)s

    Returns
    -------
    numpy.ndarray of float64
        μ_s,min of each point, of the broadcast shape: inf where no μ_s up to 1e6 gives
        a JARM, NaN for an invalid point.

    Raises
    ------
    ValueError
        For inputs that do not broadcast or an option out of range.

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> print(f"{eccjump.mu_s_min_path(np.radians(40), 0.15, 0.02):.11f}")
    0.33471000675
    """
    shape, (a, c, k) = broadcast_flat(alpha=ramp_angles("alpha", alpha), chi=chi, km=km)
    out = _core.mu_s_min_path(a, c, k, options=_options(n, rule, n_threads))
    return out.reshape(shape)


@fill
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
    """The JARM α-interval that holds each seed angle, found by stepping out from it.

    From each seed the search steps outwards by ``step`` (doubling) until the point is no
    longer a JARM, then bisects each end to 1e-12 rad. It finds thin parts of a region that
    the scan of :func:`alpha_intervals` misses.

    Parameters
    ----------
    seed : array_like of float
        A ramp angle [rad] in [0, π/2] that gives a JARM for the body (broadcast with
        ``chi`` and ``km``), guarded as ``alpha`` of :func:`jarm` (radians, not degrees).
    %(chi)s
    %(km)s
    %(mu_s)s
    %(n_first)s
    %(rule)s
    step : float, default 1e-3
        First step of the search [rad], in (0, π/2].
    %(n_threads)s

    Returns
    -------
    lo, hi : numpy.ndarray of float64
        The ends of the interval [rad], of the broadcast shape; NaN where the seed is not a
        JARM.

    Raises
    ------
    ValueError
        For an invalid body, ``mu_s``, ``step`` or option (the message names it).

    Examples
    --------
    >>> import numpy as np
    >>> import eccjump
    >>> lo, hi = eccjump.alpha_interval_around(np.radians(40), 0.15, 0.02, 1.0)
    >>> print(f"[{np.degrees(lo):.4f}, {np.degrees(hi):.4f}] deg")
    [36.2251, 50.4834] deg
    """
    shape, (s, c, k) = broadcast_flat(seed=ramp_angles("seed", seed), chi=chi, km=km)
    lo, hi = _core.alpha_interval_around(
        s, c, k, real("mu_s", mu_s), step=real("step", step), options=_options(n, rule, n_threads)
    )
    return lo.reshape(shape), hi.reshape(shape)

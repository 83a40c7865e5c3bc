"""The probability that a design keeps its verdict when the body, the angle and the friction
vary within the lab's tolerances (issue 38): the samples of :mod:`eccjump.uncertainty`, each
judged as the design judges its nominal point (the verdict under both lift-off rules within
the turns allowed, and, with ``min_apex``, a first flight at least that high under both).

The same seed gives the same cube points for every candidate (common random numbers), so
that the candidates' probabilities differ by their designs, not by their samples.
"""

from __future__ import annotations

from collections.abc import Mapping

import numpy as np
from numpy.typing import NDArray

from eccjump.motion.points import motion_points
from eccjump.studies.design._common import RULES
from eccjump.studies.design.margins import _holds, _Spec
from eccjump.studies.design.results import Success
from eccjump.studies.uncertainty.results import wilson
from eccjump.studies.uncertainty.sampling import Spread, draw, spread

#: What a tolerance may name: the inputs of the verdict.
TOLERATED = ("chi", "km", "alpha", "mu_s")


def tolerance_spread(tolerances: object, alpha: float, chi: float, km: float, mu: float) -> Spread:
    """The checked normal standard deviations by name (``tolerances``) around a design."""
    nominal = dict.fromkeys(("mu_k", "restitution", "theta0", "omega0"), 0.0)
    nominal.update(chi=chi, km=km, alpha=alpha, mu_s=mu, mu_k=mu)
    return spread(nominal, tolerances, None, TOLERATED, mu_k_follows=True, sd_option="tolerances")


def success(spec: _Spec, spreads: Spread, n: int, seed: int, apex_min: float = 0.0) -> Success:
    """P(the verdict holds) over ``n`` samples of ``spreads`` (truncated to the physical
    range), with the apex condition when ``apex_min`` > 0."""
    cols, valid = draw(spreads, n, seed, "random", "truncate")
    a, c, k, mu = (cols[p] for p in ("alpha", "chi", "km", "mu_s"))
    ok = valid & _holds(spec)(a, c, k, mu)
    if apex_min > 0 and ok.any():
        ok[ok] = apex(a[ok], c[ok], k[ok], mu[ok]) >= apex_min
    n_valid = int(valid.sum())
    hits = int(ok.sum())
    low, high = wilson(hits, n_valid)
    return Success(hits / max(n_valid, 1), low, high, n_valid)


def apex(
    alpha: NDArray[np.float64],
    chi: NDArray[np.float64],
    km: NDArray[np.float64],
    mu: float | NDArray[np.float64],
) -> NDArray[np.float64]:
    """The apex of the first flight [R] of each point, the lower of the two rules' (0
    without a flight, or for km = 0), by the full motion from rest to the first landing."""
    apexes = []
    for rule in RULES:
        m = motion_points(alpha, chi, km, mu, rule=rule, t_max=1e4)
        apexes.append(np.where(np.isfinite(m.apex), m.apex, 0.0))
    return np.minimum(*apexes)


def best(
    spec: _Spec,
    candidates: list[tuple[float, float, float]],
    tolerances: Mapping[str, float],
    mu: float,
    n: int,
    seed: int,
    apex_min: float,
) -> tuple[int, list[Success]]:
    """The index of the candidate (α, km, χ) most likely to keep its verdict (the
    first on a tie: the candidates come best margin first), and every candidate's odds."""
    odds = [
        success(spec, tolerance_spread(tolerances, a, c, k, mu), n, seed, apex_min)
        for a, k, c in candidates
    ]
    return int(np.argmax([s.p for s in odds])), odds

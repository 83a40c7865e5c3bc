"""``design(..., p_target=)``: a design whose P(JARM) under the lab's tolerances reaches a
target (issue 50, item 5).

P(JARM) is :func:`eccjump.uncertainty`'s: the closed-form JARM classification of samples
spread by the normal standard deviations ``tolerances`` around the design (truncated to the
physical range, at the nominal μ_s), under each lift-off rule. The design's P(JARM) is the
lower of the two rules' values: the rule is a modelling uncertainty, not a random one, so
the target must be reached whichever rule holds.

Every candidate is scored in one batch per rule through the path of
:func:`eccjump.uncertainty_map` (:func:`.grid.point_fields`), with the same unit-cube points
for every candidate (common random numbers): with the same seed and samples, a candidate's
P(JARM) is bit for bit ``uncertainty``'s at that design.

A candidate reaches the target when the lower end of its 95 % Wilson interval does (with
95 % confidence the probability is at least ``p_target``), not only its point estimate.
"""

from __future__ import annotations

import math
from collections.abc import Mapping, Sequence

import numpy as np

from eccjump._base.checks import real, short
from eccjump.studies.design._common import RULES
from eccjump.studies.design.probability import tolerance_spread
from eccjump.studies.design.results import PJarm
from eccjump.studies.uncertainty.grid import GridSpread, point_fields
from eccjump.studies.uncertainty.sampling import unit_cube

#: The level of the Wilson interval whose lower end must reach ``p_target``.
CONFIDENCE = 0.95


def check_p_target(p_target: object, tolerances: object, target: str) -> float | None:
    """The checked target probability (None: no target)."""
    if p_target is None:
        return None
    p = real("p_target", p_target)
    if not (0.0 < p < 1.0):
        raise ValueError(f"p_target = {short(p)} is outside the allowed range (0, 1)")
    if tolerances is None:
        raise ValueError("p_target needs tolerances (sd by parameter name)")
    if target != "jarm":
        raise ValueError("p_target is a P(JARM): it needs target='jarm'")
    return p


def chances(
    candidates: Sequence[tuple[float, float, float]],
    tolerances: Mapping[str, float],
    mu: float,
    n: int,
    seed: int,
) -> list[PJarm]:
    """P(JARM) of each candidate (α, k_m, χ) under ``tolerances``: the lower rule's, with
    its Wilson interval (``n`` samples of ``seed``, the same for every candidate)."""
    alpha, km, chi = (np.array(col, dtype=np.float64) for col in zip(*candidates, strict=True))
    nominal = {"alpha": alpha, "chi": chi, "km": km, "mu_s": np.full(alpha.size, mu)}
    spec = tolerance_spread(tolerances, float(alpha[0]), float(chi[0]), float(km[0]), mu)
    cube = unit_cube(n, len(spec.varied), seed, "random")
    per_rule = [
        point_fields(nominal, cube, GridSpread(spec.sd, {}, spec.varied, True, mu, r, CONFIDENCE))
        for r in RULES
    ]
    out = []
    for i in range(alpha.size):
        # the lower rule (NaN, no valid sample, counts as 0; the first rule on a tie)
        j = min(range(len(RULES)), key=lambda r: np.nan_to_num(per_rule[r]["p_jarm"][i]))
        f = per_rule[j]
        p, low, high = (float(f[k][i]) for k in ("p_jarm", "p_jarm_low", "p_jarm_high"))
        out.append(PJarm(p, low, high, int(f["n_valid"][i]), RULES[j]))
    return out


def reach(
    candidates: Sequence[tuple[float, float, float]],
    tolerances: Mapping[str, float],
    mu: float,
    n: int,
    seed: int,
    p_target: float,
    by_odds: bool,
) -> tuple[int, PJarm]:
    """The candidate whose P(JARM) reaches ``p_target`` (its Wilson lower bound): the first
    (the candidates come best margin first), or with ``by_odds`` the most likely one. A
    ValueError with the best P(JARM) found when none does."""
    odds = chances(candidates, tolerances, mu, n, seed)
    ok = [i for i, s in enumerate(odds) if s.low >= p_target]
    if not ok:
        b = max(odds, key=lambda s: -1.0 if math.isnan(s.p) else s.p)
        raise ValueError(
            f"p_target = {p_target:g}: no design reaches it (Wilson lower bound); the best of "
            f"{len(odds)} has P(JARM) {b.p:.4f} [{b.low:.4f}, {b.high:.4f}]: loosen tolerances, "
            "widen ranges or lower p_target"
        )
    pick = max(ok, key=lambda i: (odds[i].p, -i)) if by_odds else ok[0]
    return pick, odds[pick]


__all__ = ["CONFIDENCE", "chances", "check_p_target", "reach"]

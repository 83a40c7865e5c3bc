"""Verdicts under both rules at the worst μ_s, and the margins to the exact boundaries."""

from __future__ import annotations

import math
from collections.abc import Callable
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump.classification.boundary import alpha_interval_around, mu_s_min_path
from eccjump.classification.classify import jarm
from eccjump.studies.design._common import _HALF_PI, _MU_CAP, _SCAN, _SLIPS, RULES
from eccjump.studies.design.results import Margin


class _Spec(NamedTuple):
    """What a verdict is: the target, the turns the ramp allows, and (JARM) the turn n of
    the jump (None: any turn up to ``turns``)."""

    target: str
    turns: int
    n: int | None = None


def _classify(
    alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, mu: ArrayLike, spec: _Spec
) -> tuple[NDArray[np.bool_], list[Any]]:
    """(the verdict holds under both rules, the results per rule)."""
    size = max(np.size(x) for x in (alpha, chi, km, mu))
    threads = 1 if size < 1024 else 0  # a pool costs more than a few hundred points
    res = [
        jarm(
            alpha,
            chi,
            km,
            mu,
            spec.n,
            rule=r,
            max_turns=spec.turns,
            refine_extrema=False,
            n_threads=threads,
        )
        for r in RULES
    ]
    if spec.target == "jarm":
        ok = res[0].is_jarm & res[1].is_jarm
    else:
        ok = np.isin(res[0].reason, _SLIPS) & np.isin(res[1].reason, _SLIPS)
    return ok, res


def _holds(spec: _Spec) -> Callable[[ArrayLike, ArrayLike, ArrayLike, ArrayLike], NDArray]:
    def pred(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, mu: ArrayLike) -> NDArray:
        return _classify(alpha, chi, km, mu, spec)[0]

    return pred


def _boundaries(
    ok: Callable[[NDArray], NDArray], x0: float, lo_end: float, hi_end: float, tol: float
) -> tuple[float, float]:
    """The nearest points below and above ``x0`` (where ``ok`` holds) at which ``ok`` stops
    holding, within [lo_end, hi_end]: an outward scan of _SCAN samples per side (a gap
    narrower than a sample spacing can be missed), then bisection of both brackets together
    to ``tol``. -inf/inf where ``ok`` holds up to the end."""
    k = np.arange(1, _SCAN + 1) / _SCAN
    xs = np.concatenate([x0 - (x0 - lo_end) * k, x0 + (hi_end - x0) * k])
    good = ok(xs)
    brackets: list[list[float]] = []
    for side in (0, 1):
        g = good[side * _SCAN : (side + 1) * _SCAN]
        bad = np.flatnonzero(~g)
        if bad.size == 0 or (side == 0 and x0 == lo_end) or (side == 1 and x0 == hi_end):
            brackets.append([math.nan, math.nan])
        else:
            i = int(bad[0])
            inner = x0 if i == 0 else float(xs[side * _SCAN + i - 1])
            brackets.append([inner, float(xs[side * _SCAN + i])])
    live = [b for b in brackets if not math.isnan(b[0])]
    for _ in range(200):
        if not any(abs(b[1] - b[0]) > tol for b in live):
            break
        mids = np.array([0.5 * (b[0] + b[1]) for b in live])
        for b, m, g in zip(live, mids, ok(mids), strict=True):
            b[0 if g else 1] = float(m)
    lo = -math.inf if math.isnan(brackets[0][0]) else brackets[0][1]
    hi = math.inf if math.isnan(brackets[1][0]) else brackets[1][1]
    return lo, hi


def _relative(name: str, value: float, lo: float, hi: float) -> Margin:
    m = min(value - lo, hi - value)
    rel = m / value if value > 0 else (math.inf if m > 0 else 0.0)
    return Margin(name, value, lo, hi, m, rel)


def _margins(
    spec: _Spec, alpha: float, km: float, rho: float, mu: float, mu_err: float, tol: float
) -> tuple[Margin, ...] | None:
    """The three margins at a point, or None if the verdict fails there. A JARM's margins
    are those of a JARM on the same turn (the jump where the sheet predicts it)."""
    chi = rho * (1.0 - km)
    jump = spec.target == "jarm"
    worst = mu - mu_err if jump else mu + mu_err
    ok, res = _classify(alpha, chi, km, worst, spec)
    if not bool(ok):
        return None
    if jump:
        turns = {int(r.n) for r in res}
        if len(turns) != 1:  # the rules jump on different turns: not a clear design
            return None
        spec = spec._replace(n=turns.pop())
    holds = _holds(spec)
    # alpha: the JARM alpha-interval of the turn (both rules), or a scan for a slip
    if jump:
        ends = [
            alpha_interval_around(alpha, chi, km, worst, spec.n, rule=r, n_threads=1) for r in RULES
        ]
        a_lo = max(float(e[0]) for e in ends)
        a_hi = min(float(e[1]) for e in ends)
    else:
        a_lo, a_hi = _boundaries(lambda a: holds(a, chi, km, worst), alpha, 0.0, _HALF_PI, tol)
    # mu_s: JARM needs mu_s >= mu_min (no upper side); slip needs mu_s < mu_star
    if jump:
        mu_min = max(
            float(mu_s_min_path(alpha, chi, km, spec.n, rule=r, n_threads=1)) for r in RULES
        )
        m = worst - mu_min
        mu_m = Margin("mu_s", mu, mu_min, math.inf, m, m / mu)
    else:
        mu_star = _mu_star(holds, alpha, chi, km, worst, tol)
        m = mu_star - worst
        mu_m = Margin("mu_s", mu, 0.0, mu_star, m, m / mu)
    # rod position at fixed masses
    r_lo, r_hi = _boundaries(lambda r: holds(alpha, r * (1.0 - km), km, worst), rho, 0.0, 1.0, tol)
    return (_relative("alpha", alpha, a_lo, a_hi), mu_m, _relative("rod", rho, r_lo, r_hi))


def _mu_star(
    holds: Callable[..., NDArray], alpha: float, chi: float, km: float, mu: float, tol: float
) -> float:
    """The smallest μ_s ≥ μ at which the body no longer slips first (inf up to 1e6)."""
    lo, hi = mu, max(2.0 * mu, 1e-3)
    while bool(holds(alpha, chi, km, hi)):
        lo, hi = hi, 2.0 * hi
        if hi > _MU_CAP:
            return math.inf
    while hi - lo > tol * hi:
        mid = 0.5 * (lo + hi)
        if bool(holds(alpha, chi, km, mid)):
            lo = mid
        else:
            hi = mid
    return hi


def _score(margins: tuple[Margin, ...] | None) -> float:
    return -math.inf if margins is None else min(m.relative for m in margins)


def verdict_holds(
    target: str, max_turns: int, turn: int | None, alpha: ArrayLike, chi: ArrayLike,
    km: ArrayLike, mu: ArrayLike,
) -> NDArray[np.bool_]:  # fmt: skip
    """Where a design's verdict holds, for arrays: under both rules, within ``max_turns``,
    a JARM on ``turn`` (the boundary its margins measure to; ``Design.plot`` draws it)."""
    spec = _Spec(target, max_turns, turn if target == "jarm" else None)
    return _classify(alpha, chi, km, mu, spec)[0]

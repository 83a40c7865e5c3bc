"""The explorer's requests, as plain functions of a query (a mapping of strings, as
a URL gives it): ``controls`` (the sliders, and the colours of the modes: the one palette of
:mod:`eccjump._base.palette`), ``region`` (the JARM region slice over (χ, α)
at the current k_m and μ_s), ``motion`` (the full motion of the current point, sampled
for the animation, and its numbers) and ``uncertainty`` (P(JARM) of the uncertainty map the
explorer was given, on the slice of the current k_m: :mod:`.probability`). The HTTP server
and the Jupyter widget both answer through :func:`handle`, so the page behaves the same in
both.

Every answer is JSON-ready data; a bad or impossible query is a short message for the page
(status 400), never a traceback.
"""

from __future__ import annotations

import math
import time
import traceback
from collections.abc import Callable, Mapping
from functools import lru_cache, partial
from typing import Any

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump._base.checks import Rule
from eccjump._base.palette import MODE_COLORS
from eccjump.classification.classify import Reason, jarm
from eccjump.explorer import controls, probability
from eccjump.motion.simulation import MODES, MotionResult, simulate
from eccjump.studies.uncertainty.map import UncertaintyMap

#: What each verdict of the JARM classification means, for the page.
REASON_TEXT: dict[str, str] = {
    "JARM": "jumps straight out of pure rolling",
    "NO_ROOT": "never lifts off while rolling",
    "LIFTOFF_EARLIER": "the lift-off rule holds already at the start",
    "NORMAL_FORCE_LOST": "the normal force vanishes before the lift-off",
    "SLIP_BEFORE": "slips before it would lift off",
    "SLIP_AT_JUMP": "friction fails on the final approach to the jump",
    "ROCKS_BACK": "stops and rolls back",
    "TURN_LIMIT": "nothing happens within the turn limit",
    "INVALID_PARAMS": "no such body (k_m > 1 − χ)",
    "SOLVER_FAILED": "the integrator failed",
    "SLIP": "slips before it would lift off",
}

#: Animation samples per unit of time sqrt(R/g), and their bounds (the page draws one per
#: frame; 60 a unit is smooth at the page's playback speeds).
SAMPLES_PER_TIME = 60
SAMPLES_RANGE = (200, 3600)
#: Transitions a run may make within its duration (the rest of the run is cut there).
MAX_TRANSITIONS = 1000

#: Digits kept in the arrays sent to the page (a pixel is 1e-3 R at the page's scale).
DIGITS = 5


class BadQuery(ValueError):
    """A query the page should explain (status 400)."""


# --------------------------------------------------------------------------------------------
# reading a query
# --------------------------------------------------------------------------------------------


def number(query: Mapping[str, str], key: str) -> float:
    """The slider ``key``'s value in ``query`` (its default when absent), checked against its
    range."""
    text = query.get(key)
    if text is None:
        return controls.BY_KEY[key].default
    try:
        value = float(text)
    except (TypeError, ValueError):
        raise BadQuery(f"{key} = {str(text)[:30]!r} is not a number") from None
    try:
        return controls.checked(key, value)
    except ValueError as err:
        raise BadQuery(str(err)) from None


def rule(query: Mapping[str, str]) -> Rule:
    try:
        return controls.rule_checked(str(query.get("rule", controls.RULES[0])))
    except ValueError as err:
        raise BadQuery(str(err)) from None


def point(query: Mapping[str, str]) -> dict[str, float]:
    """Every slider's value (μ_k = μ_s when the query says ``tie=1`` or gives no μ_k)."""
    p = {c.key: number(query, c.key) for c in controls.CONTROLS}
    if query.get("tie", "0") == "1" or "mu_k" not in query:
        p["mu_k"] = p["mu_s"]
    if p["mu_k"] > p["mu_s"]:
        raise BadQuery(
            f"mu_k = {p['mu_k']:g} is above mu_s = {p['mu_s']:g}: kinetic friction cannot exceed "
            "static friction. Lower μ_k, or tie it to μ_s."
        )
    return p


# --------------------------------------------------------------------------------------------
# the answers
# --------------------------------------------------------------------------------------------


def controls_spec(query: Mapping[str, str]) -> dict[str, Any]:
    # The page's mode colours come from here: one palette for it, the figures and the reprs.
    return {
        **controls.spec(),
        "reasons": REASON_TEXT,
        "modes": list(MODES),
        "mode_colors": dict(MODE_COLORS),
    }


def region(query: Mapping[str, str]) -> dict[str, Any]:
    """The JARM verdict on a GRID x GRID slice: χ along x, α along y (rows), at the query's
    k_m, μ_s, rule and start."""
    key = (
        number(query, "km"),
        number(query, "mu_s"),
        rule(query),
        number(query, "theta0"),
        number(query, "omega0"),
    )
    start = time.perf_counter()
    answer = _region(*key)  # the same slice again (a slider moved back) comes from the cache
    return {**answer, "compute_ms": round(1e3 * (time.perf_counter() - start), 2)}


@lru_cache(maxsize=64)
def _region(km: float, mu_s: float, rule: Rule, theta0: float, omega0: float) -> dict[str, Any]:
    n = controls.GRID
    chi = (np.arange(n) + 0.5) / n  # cell centres: never 0 or 1
    alpha_deg = 90.0 * (np.arange(n) + 0.5) / n
    res = jarm(
        np.radians(alpha_deg)[:, None],
        chi[None, :],
        km,
        mu_s,
        rule=rule,
        theta0=math.radians(theta0),
        omega0=omega0,
    )
    codes = res.reason
    valid = codes != Reason.INVALID_PARAMS
    return {
        "n": n,
        "chi": _rounded(chi),
        "alpha_deg": _rounded(alpha_deg),
        "codes": codes.ravel().tolist(),  # row j (alpha), column i (chi): j * n + i
        "names": {int(r): r.name for r in Reason},
        "counts": {r.name: int(np.count_nonzero(codes == r)) for r in Reason if (codes == r).any()},
        "jarm_fraction": float(res.is_jarm[valid].mean()) if valid.any() else 0.0,
        "params": {"km": km, "mu_s": mu_s, "rule": rule, "theta0": theta0, "omega0": omega0},
    }


def motion(query: Mapping[str, str]) -> dict[str, Any]:
    """The full motion of the query's point, sampled evenly in time for the animation, with
    its modes, its transitions and its numbers."""
    p = point(query)
    how = rule(query)
    problem = controls.body_problem(p["chi"], p["km"])
    if problem:
        raise BadQuery(problem)
    api = controls.to_api(p)
    start = time.perf_counter()
    body = Cylinder(p["chi"], p["km"])
    res = simulate(
        body,
        api["alpha"],
        mu_s=p["mu_s"],
        mu_k=p["mu_k"],
        restitution=p["restitution"],
        rule=how,
        theta0=api["theta0"],
        omega0=p["omega0"],
        t_max=p["t_max"],
        max_transitions=MAX_TRANSITIONS,
        dense_output=True,
    )
    verdict = jarm(
        api["alpha"],
        p["chi"],
        p["km"],
        p["mu_s"],
        rule=how,
        theta0=api["theta0"],
        omega0=p["omega0"],
    )
    return {
        **sampled(res),
        "segments": [
            {"mode": s.mode, "reason": s.reason, "t_start": _num(s.t_start), "t_end": _num(s.t_end)}
            for s in res.segments
        ],
        "transitions": [
            {
                "t": _num(tr.t),
                "theta_deg": _num(math.degrees(tr.theta)),
                "from": tr.from_mode,
                "to": tr.to_mode,
                "reason": tr.reason,
            }
            for tr in res.transitions
        ],
        "numbers": numbers(res),
        "verdict": {
            "reason": Reason(int(verdict.reason)).name,
            "is_jarm": bool(verdict.is_jarm),
            "theta_J_deg": _num(math.degrees(float(verdict.theta_J))),
        },
        "params": {**p, "rule": how},
        "compute_ms": round(1e3 * (time.perf_counter() - start), 2),
    }


def uncertainty(query: Mapping[str, str], m: UncertaintyMap | None) -> dict[str, Any]:
    """P(JARM) of the explorer's uncertainty map ``m`` on the slice of the query's k_m and
    χ (:func:`.probability.panel`); ``{"available": False}`` when it was given none."""
    if m is None:
        return {"available": False}
    return probability.panel(m, number(query, "km"), number(query, "chi"))


def sampled(res: MotionResult) -> dict[str, Any]:
    """The run at evenly spaced times: the axis C and the centre of mass G in ramp
    coordinates (x down the ramp, y along its normal, in R), θ and the mode of each time."""
    assert res.sol is not None  # dense_output=True
    t_end = float(res.t[-1])
    lo, hi = SAMPLES_RANGE
    count = int(min(hi, max(lo, math.ceil(t_end * SAMPLES_PER_TIME) + 1)))
    t = np.linspace(0.0, t_end, count)
    theta, _, along, _, b, _ = res.sol(t)
    chi = res.body.chi
    starts = np.array([s.t_start for s in res.segments])
    segment = np.clip(np.searchsorted(starts, t, side="right") - 1, 0, len(starts) - 1)
    mode_of_segment = np.array([MODES.index(s.mode) for s in res.segments], dtype=np.int8)
    return {
        "t": _rounded(t),
        "theta": _rounded(theta),
        "cx": _rounded(along),
        "cy": _rounded(b),
        "gx": _rounded(along + chi * np.sin(theta)),
        "gy": _rounded(b + chi * np.cos(theta)),
        "mode": mode_of_segment[segment].tolist(),  # an index into "modes"
        "modes": list(MODES),
        "t_end": t_end,
        "status": res.status,
        "message": res.message,
    }


def numbers(res: MotionResult) -> dict[str, Any]:
    """The numbers panel: the first slip, the first lift-off and its flight, the counts."""
    slip = next((tr for tr in res.transitions if tr.to_mode == "SLIP"), None)
    takeoff = next((tr for tr in res.transitions if tr.to_mode == "FLIGHT"), None)
    flight = res.flights[0] if res.flights else None
    return {
        "slip": None
        if slip is None
        else {
            "t": _num(slip.t),
            "theta_deg": _num(math.degrees(slip.theta)),
            "reason": slip.reason,
        },
        "liftoff": None
        if takeoff is None or flight is None
        else {
            "t": _num(flight.t_liftoff),
            "theta_deg": _num(math.degrees(flight.theta_liftoff)),
            "from": takeoff.from_mode,
            "reason": takeoff.reason,
        },
        "flight": None
        if flight is None
        else {
            "apex": _num(flight.apex),
            "distance": _num(flight.distance),
            "t_landing": _num(flight.t_landing),
        },
        "flights": len(res.flights),
        "impacts": len(res.impacts),
        "sequence": res.mode_names()[:12],
        "more_transitions": max(0, len(res.transitions) - 12),
    }


def _num(x: float) -> float | None:
    """A float for JSON: NaN and infinities (not JSON) become None."""
    x = float(x)
    return x if math.isfinite(x) else None


def _rounded(a: NDArray[np.float64]) -> list[float | None]:
    """``a`` rounded to :data:`DIGITS` decimals as a list, NaN and infinities as None."""
    finite = np.isfinite(a)
    values: list[float | None] = np.round(np.where(finite, a, 0.0), DIGITS).tolist()
    if not finite.all():
        values = [v if ok else None for v, ok in zip(values, finite.tolist(), strict=True)]
    return values


# --------------------------------------------------------------------------------------------
# one entry for the server and the widget
# --------------------------------------------------------------------------------------------

ENDPOINTS: dict[str, Callable[[Mapping[str, str]], dict[str, Any]]] = {
    "controls": controls_spec,
    "region": region,
    "motion": motion,
}


def handle(
    endpoint: str, query: Mapping[str, str], uncertainty_map: UncertaintyMap | None = None
) -> tuple[int, dict[str, Any]]:
    """(HTTP status, JSON-ready answer) of a request: 200 and the data, 400 and
    ``{"error": message}`` for a query the page should explain, 404 for an unknown request.
    Library errors (a ValueError or TypeError naming a parameter) are 400 too; anything else
    is 500 with a one-line message (the page shows it; the traceback goes to the server's
    stderr, never to the page). ``uncertainty_map``: the map of the ``uncertainty`` request
    (checked by :func:`.probability.checked_map`), the one request that needs the
    explorer's own data."""
    fn = ENDPOINTS.get(endpoint)
    if endpoint == "uncertainty":
        fn = partial(uncertainty, m=uncertainty_map)
    if fn is None:
        return 404, {"error": f"no such request: {endpoint[:40]!r}"}
    try:
        return 200, fn(query)
    except (ValueError, TypeError) as err:
        return 400, {"error": str(err)[:300]}
    except MemoryError:
        return 500, {"error": "out of memory"}
    except Exception as err:  # the boundary of the server: report, keep serving
        traceback.print_exc()
        return 500, {"error": f"internal error ({type(err).__name__}); see the server's log"}

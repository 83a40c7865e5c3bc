"""The first-order (delta-method) estimate beside the Monte Carlo one, from the exact
derivatives at the nominal point: of the lift-off (``jarm(..., derivatives=True)``) for the
JARM question, of the first lift-off and landing (``simulate(..., sensitivities=True)``) for
the full motion.

To first order a quantity q(x) of the inputs x varies as q(x0) + g·(x - x0), g its gradient at
the nominal point x0, so its standard deviation is √(sum_i g_i² var_i) for independent
inputs (var_i = sd_i² for a normal, (hi - lo)² / 12 for a uniform). For the lift-off angle
θ_J, g = ``d_theta_J`` (with respect to α, χ, km; μ_s does not move it).

P(JARM) follows where the verdict is decided by the friction the jump needs: the JARM holds
while μ_s exceeds the friction ratio at the jump, μ_J, so P(JARM) ~ Phi(m0 / sd_m), m0 = μ_s
- μ_J at the nominal point and sd_m the first-order spread of μ_s - μ_J. It is given only
where that ratio is the largest along the path (``max_ratio`` = μ_J): where an earlier
ratio binds, or the nominal point is no JARM, the margin has no derivative here (None). Both
estimates are exact only in the limit of small tolerances; the Monte Carlo ones are the
answer, these say how much of it a linearisation explains. P(JARM)'s fails where the
tolerances reach another verdict: samples that slip before the jump (the path's largest ratio
changes hands at a kink: 0.997 against 0.79 by sampling with the tutorial's tolerances), or a
nominal point that is no JARM (None); ``tests/test_uncertainty.py`` checks both sides.

Over a grid (``uncertainty_map(..., method="delta")``) :func:`first_order` applies the same
rule to one batched ``jarm(..., derivatives=True)`` over the nominal points (it is the rule
of :func:`delta_method` too, the same bits), marking where it gives no P(JARM) and why
(:class:`Status`): no JARM at the nominal point, an earlier ratio deciding there (a kink),
singular or one-sided derivatives, the classical rule. A kink that only the tolerances reach
(the 0.997 against 0.79 above) is not seen at the nominal point: the map probes for it
(:mod:`.grid_delta`, status REACHES); :func:`delta_method` does not.

For the full motion the gradients are those of the first lift-off's time and angle and of the
first flight's duration with respect to all eight inputs (where μ_k follows μ_s, a change of
μ_s moves both). P(JARM) has no first-order estimate there (None).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from enum import IntEnum
from statistics import NormalDist
from typing import Any, NamedTuple, Protocol

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump._base.checks import Rule, rule_name
from eccjump.classification.classify import JarmResult, jarm
from eccjump.classification.fields import Reason
from eccjump.motion.simulation import SENSITIVITY_PARAMETERS, MotionResult, simulate
from eccjump.studies.uncertainty.sampling import Spread

#: The inputs the derivatives are taken with respect to, in their order.
WRT = ("alpha", "chi", "km")
#: The standard normal CDF.
_PHI = NormalDist().cdf


class Spreads(Protocol):
    """The tolerances by name: a :class:`.sampling.Spread` at one point, a grid's spreads."""

    @property
    def sd(self) -> Mapping[str, float]: ...
    @property
    def bounds(self) -> Mapping[str, tuple[float, float]]: ...


class Delta(NamedTuple):
    """The first-order estimate: the standard deviation of the lift-off angle [rad] (θ_J;
    for the full motion the first lift-off's angle), P(JARM) from the nominal point's
    derivatives (None where the friction ratio at the jump does not decide the verdict, and
    for the full motion), and for the full motion the standard deviations of the first
    lift-off's time and of the first flight's duration [√(R/g)] (None if it does not
    land)."""

    theta_J_sd: float
    p_jarm: float | None
    liftoff_t_sd: float | None = None
    flight_time_sd: float | None = None


def _spread(gradient: list[float], var: list[float]) -> float | None:
    """The delta method's standard deviation √(sum g_i² var_i); a parameter held fixed
    (var 0) takes no part, so its derivative may be NaN (k_m's, one-sided at k_m = 0); None
    where a NaN derivative meets a spread."""
    terms = [g * g * v for g, v in zip(gradient, var, strict=True) if v > 0.0]
    if not all(map(math.isfinite, terms)):
        return None
    return math.sqrt(sum(terms))


def _spreads(gradient: NDArray[np.float64], var: NDArray[np.float64]) -> NDArray[np.float64]:
    """:func:`_spread` of each row of ``gradient`` (shape (G, 3)), NaN for its None; the
    terms summed in the same order, so a row gives the same bits."""
    terms = gradient[:, var > 0.0] ** 2 * var[var > 0.0]
    total = np.zeros(gradient.shape[0])
    for j in range(terms.shape[1]):  # left to right, as sum() adds
        total = total + terms[:, j]
    with np.errstate(invalid="ignore"):
        return np.where(np.isfinite(terms).all(axis=1), np.sqrt(total), np.nan)


class Status(IntEnum):
    """Whether a point has a first-order P(JARM), or why not (``delta_status`` of a map of
    ``uncertainty_map(..., method="delta")``): the failures this linearisation can see at the
    nominal point. A kink that only the tolerances reach is not among them (module
    docstring)."""

    #: P(JARM) and the spread of θ_J are given.
    ESTIMATE = 0
    #: The nominal point is no JARM: a verdict change, no estimate (sample there).
    NO_JARM = 1
    #: An earlier friction ratio decides the verdict (the path's largest ratio has a kink):
    #: the margin has no derivative; the spread of θ_J is given.
    KINK = 2
    #: The derivatives are singular, or one-sided (k_m = 0) where a tolerance varies them;
    #: the spread of θ_J is given where it is finite.
    SINGULAR = 3
    #: The classical rule: the jump sits on the friction cone, no margin; θ_J's spread given.
    CLASSICAL = 4
    #: The nominal point lies outside the physical range.
    INVALID = 5
    #: P(JARM) is given but the tolerances reach another verdict than the margin's (a probe
    #: along a varied input slips before the jump, or finds no jump): near a kink of the
    #: boundary, where the first order is too high (over a grid only: :mod:`.grid_delta`).
    REACHES = 6


class FirstOrder(NamedTuple):
    """The first-order estimates at many nominal points: the spread of θ_J [rad] and
    P(JARM), NaN where there is none, and why (:class:`Status` codes, uint8)."""

    theta_J_sd: NDArray[np.float64]
    p_jarm: NDArray[np.float64]
    status: NDArray[np.uint8]


def first_order(r: JarmResult, mu_s: NDArray[np.float64], spec: Spreads, rule: str) -> FirstOrder:
    """The delta-method estimates at the points of ``r`` (``jarm(..., derivatives=True)`` at
    1-D nominal points with static friction ``mu_s``), under the tolerances of ``spec``
    (anything with ``sd`` and ``bounds``): the one rule of :func:`delta_method`, over arrays."""
    var = np.array([variance(spec, p) for p in WRT])
    is_jarm = np.asarray(r.is_jarm, dtype=bool)
    status = np.where(is_jarm, Status.ESTIMATE, Status.NO_JARM).astype(np.uint8)
    status[np.asarray(r.reason) == Reason.INVALID_PARAMS] = Status.INVALID
    theta_sd = _spreads(np.asarray(r.d_theta_J, dtype=np.float64).reshape(-1, 3), var)
    singular = is_jarm & (np.asarray(r.d_singular, dtype=bool) | np.isnan(theta_sd))
    status[singular] = Status.SINGULAR
    theta_sd = np.where(is_jarm & ~singular, theta_sd, np.nan)
    with np.errstate(invalid="ignore", divide="ignore"):
        mu_j = -np.asarray(r.Fx_J, dtype=np.float64) / np.asarray(r.Fy_J, dtype=np.float64)
        spread_mu = _spreads(np.asarray(r.d_mu_J, dtype=np.float64).reshape(-1, 3), var)
        sd_m = np.sqrt(spread_mu**2 + variance(spec, "mu_s"))
        margin = mu_s - mu_j
    live = status == Status.ESTIMATE
    if rule != "paper":  # under the classical rule the jump sits on the friction cone
        status[live] = Status.CLASSICAL
    else:
        status[live & ~(np.isfinite(mu_j) & np.isfinite(spread_mu))] = Status.SINGULAR
        status[live & (np.asarray(r.max_ratio) > mu_j * (1 + 1e-9))] = Status.KINK
    return FirstOrder(theta_sd, _probability(margin, sd_m, status == Status.ESTIMATE), status)


def _probability(
    margin: NDArray[np.float64], sd_m: NDArray[np.float64], where: NDArray[np.bool_]
) -> NDArray[np.float64]:
    """Phi(margin / sd_m) where ``where`` (the step 1 or 0 at sd_m = 0), NaN elsewhere: the
    scalar normal CDF per estimate, after the batched derivatives."""
    p = np.full(margin.shape, np.nan)
    for i in np.flatnonzero(where):
        m, s = float(margin[i]), float(sd_m[i])
        p[i] = (1.0 if m > 0 else 0.0) if s == 0.0 else _PHI(m / s)
    return p


def variance(spec: Spreads, name: str) -> float:
    """The variance of one input: sd², (hi - lo)² / 12, or 0 where it does not vary."""
    if name in spec.sd:
        return spec.sd[name] ** 2
    if name in spec.bounds:
        lo, hi = spec.bounds[name]
        return (hi - lo) ** 2 / 12.0
    return 0.0


def delta_method(
    spec: Spread, question: str, rule: Rule = "paper", options: Mapping[str, Any] | None = None
) -> Delta | None:
    """The delta-method estimate for ``spec`` under ``rule`` (and, for the full motion, the
    run's ``options``: t_max, max_transitions, rtol, atol, integrator): None where the
    nominal point is no JARM ("jarm") or does not fly ("motion"), or the quantity is not
    differentiable there; P(JARM) under the paper's rule only."""
    if question == "motion":
        return _motion(spec, rule, options or {})
    x0 = {k: np.array([v]) for k, v in spec.nominal.items()}
    r = jarm(x0["alpha"], x0["chi"], x0["km"], x0["mu_s"], rule=rule, derivatives=True)
    est = first_order(r, x0["mu_s"], spec, rule_name(rule))
    theta_sd, p = float(est.theta_J_sd[0]), float(est.p_jarm[0])
    if math.isnan(theta_sd):
        return None
    return Delta(theta_sd, None if math.isnan(p) else p)


def _motion(spec: Spread, rule: Rule, options: Mapping[str, Any]) -> Delta | None:
    """The full motion's estimate from the sensitivities of one run at the nominal point,
    ended right after its first landing (the transitions before it are the same bits)."""
    x0 = spec.nominal
    if x0["km"] <= 0:  # simulate needs km > 0
        return None
    kw = {
        "mu_s": x0["mu_s"],
        "mu_k": x0["mu_k"],
        "restitution": x0["restitution"],
        "theta0": x0["theta0"],
        "omega0": x0["omega0"],
        "rule": rule,
        **{k: options[k] for k in ("t_max", "rtol", "atol", "integrator") if k in options},
    }
    body = Cylinder(x0["chi"], x0["km"])
    run = simulate(body, x0["alpha"], max_transitions=options.get("max_transitions", 50), **kw)
    lift, land = _first_flight(run)
    if lift is None:
        return None
    budget = max(1, lift if land is None else land)
    run = simulate(body, x0["alpha"], max_transitions=budget, sensitivities=True, **kw)
    d, singular = run.d_transitions, run.d_singular
    if d is None or singular is None or singular[lift]:
        return None
    var = np.array([variance(spec, p) for p in SENSITIVITY_PARAMETERS])

    def sd(g: NDArray[np.float64]) -> float:
        if spec.mu_k_follows and "mu_k" not in spec.varied:  # mu_k is mu_s, sample by sample
            g = g.copy()
            g[SENSITIVITY_PARAMETERS.index("mu_s")] += g[SENSITIVITY_PARAMETERS.index("mu_k")]
        return math.sqrt(float(np.sum(g * g * var)))

    flight = None if land is None or singular[land] else sd(d[land, 0] - d[lift, 0])
    return Delta(sd(d[lift, 1]), None, sd(d[lift, 0]), flight)


def _first_flight(run: MotionResult) -> tuple[int | None, int | None]:
    """The indices of the first transition into flight and of the landing that ends it."""
    lift = next((i for i, t in enumerate(run.transitions) if t.to_mode == "FLIGHT"), None)
    if lift is None:
        return None, None
    land = next(
        (i for i, t in enumerate(run.transitions) if i > lift and t.reason in ("impact", "settle")),
        None,
    )
    return lift, land


__all__ = [
    "WRT",
    "Delta",
    "FirstOrder",
    "Spreads",
    "Status",
    "delta_method",
    "first_order",
    "variance",
]

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

For the full motion the gradients are those of the first lift-off's time and angle and of the
first flight's duration with respect to all eight inputs (where μ_k follows μ_s, a change of
μ_s moves both). P(JARM) has no first-order estimate there (None).
"""

from __future__ import annotations

import math
from collections.abc import Mapping
from statistics import NormalDist
from typing import Any, NamedTuple

import numpy as np
from numpy.typing import NDArray

from eccjump._base.body import Cylinder
from eccjump._base.checks import Rule
from eccjump.classification.classify import jarm
from eccjump.motion.simulation import SENSITIVITY_PARAMETERS, MotionResult, simulate
from eccjump.studies.uncertainty.sampling import Spread

#: The inputs the derivatives are taken with respect to, in their order.
WRT = ("alpha", "chi", "km")


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


def variance(spec: Spread, name: str) -> float:
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
    x0 = spec.nominal
    r = jarm(x0["alpha"], x0["chi"], x0["km"], x0["mu_s"], rule=rule, derivatives=True)
    if not bool(r.is_jarm) or bool(r.d_singular):
        return None
    if r.d_theta_J is None or r.d_mu_J is None:  # pragma: no cover - asked for: always there
        return None
    var = [variance(spec, p) for p in WRT]
    theta_sd = _spread(r.d_theta_J.tolist(), var)
    if theta_sd is None:  # a one-sided derivative (k_m = 0) meets a spread in k_m
        return None
    if rule != "paper":  # under the classical rule the jump sits on the friction cone
        return Delta(theta_sd, None)
    mu_j = float(-r.Fx_J / r.Fy_J)
    d_mu = r.d_mu_J.tolist()
    if not math.isfinite(mu_j):
        return Delta(theta_sd, None)
    if float(r.max_ratio) > mu_j * (1 + 1e-9):  # an earlier ratio decides: no derivative
        return Delta(theta_sd, None)
    margin = x0["mu_s"] - mu_j
    spread_mu = _spread(d_mu, var)
    if spread_mu is None:
        return Delta(theta_sd, None)
    sd_m = math.sqrt(spread_mu**2 + variance(spec, "mu_s"))
    if sd_m == 0.0:
        return Delta(theta_sd, 1.0 if margin > 0 else 0.0)
    return Delta(theta_sd, NormalDist().cdf(margin / sd_m))


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


__all__ = ["WRT", "Delta", "delta_method", "variance"]

"""The first-order (delta-method) estimate beside the Monte Carlo one, from the exact
derivatives of the lift-off at the nominal point (``jarm(..., derivatives=True)``).

To first order a quantity q(x) of the inputs x varies as q(x0) + g·(x - x0), g its gradient at
the nominal point x0, so its standard deviation is sqrt(sum_i g_i^2 var_i) for independent
inputs (var_i = sd_i^2 for a normal, (hi - lo)^2 / 12 for a uniform). For the lift-off angle
theta_J, g = ``d_theta_J`` (with respect to alpha, chi, km; mu_s does not move it).

P(JARM) follows where the verdict is decided by the friction the jump needs: the JARM holds
while mu_s exceeds the friction ratio at the jump, mu_J, so P(JARM) ~ Phi(m0 / sd_m), m0 = mu_s
- mu_J at the nominal point and sd_m the first-order spread of mu_s - mu_J. It is given only
where that ratio is the largest along the path (``max_ratio`` = mu_J): where an earlier
ratio binds, or the nominal point is no JARM, the margin has no derivative here (None). Both
estimates are exact only in the limit of small tolerances; the Monte Carlo ones are the
answer, these say how much of it a linearisation explains.
"""

from __future__ import annotations

import math
from statistics import NormalDist
from typing import NamedTuple

from eccjump._checks import Rule
from eccjump.classification import jarm
from eccjump.uncertainty.sampling import Spread

#: The inputs the derivatives are taken with respect to, in their order.
WRT = ("alpha", "chi", "km")


class Delta(NamedTuple):
    """The first-order estimate: the standard deviation of the lift-off angle theta_J [rad]
    and P(JARM) from the nominal point's derivatives (None where the friction ratio at the
    jump does not decide the verdict)."""

    theta_J_sd: float
    p_jarm: float | None


def variance(spec: Spread, name: str) -> float:
    """The variance of one input: sd^2, (hi - lo)^2 / 12, or 0 where it does not vary."""
    if name in spec.sd:
        return spec.sd[name] ** 2
    if name in spec.bounds:
        lo, hi = spec.bounds[name]
        return (hi - lo) ** 2 / 12.0
    return 0.0


def delta_method(spec: Spread, question: str, rule: Rule = "paper") -> Delta | None:
    """The delta-method estimate for ``spec`` under ``rule``: None for the full motion (its
    transitions are not differentiated yet) and where the nominal point is no JARM or is a
    non-differentiable point of the lift-off; P(JARM) under the paper's rule only."""
    if question != "jarm":
        return None
    x0 = spec.nominal
    r = jarm(x0["alpha"], x0["chi"], x0["km"], x0["mu_s"], rule=rule, derivatives=True)
    if not bool(r.is_jarm) or bool(r.d_singular):
        return None
    if r.d_theta_J is None or r.d_mu_J is None:  # pragma: no cover - asked for: always there
        return None
    var = [variance(spec, p) for p in WRT]
    theta_sd = math.sqrt(sum(g * g * v for g, v in zip(r.d_theta_J.tolist(), var, strict=True)))
    if rule != "paper":  # under the classical rule the jump sits on the friction cone
        return Delta(theta_sd, None)
    mu_j = float(-r.Fx_J / r.Fy_J)
    d_mu = r.d_mu_J.tolist()
    if not (math.isfinite(mu_j) and all(map(math.isfinite, d_mu))):
        return Delta(theta_sd, None)
    if float(r.max_ratio) > mu_j * (1 + 1e-9):  # an earlier ratio decides: no derivative
        return Delta(theta_sd, None)
    margin = x0["mu_s"] - mu_j
    sd_m = math.sqrt(
        sum(g * g * v for g, v in zip(d_mu, var, strict=True)) + variance(spec, "mu_s")
    )
    if sd_m == 0.0:
        return Delta(theta_sd, 1.0 if margin > 0 else 0.0)
    return Delta(theta_sd, NormalDist().cdf(margin / sd_m))


__all__ = ["WRT", "Delta", "delta_method", "variance"]

"""The first-order (delta-method) estimate beside the Monte Carlo one: a place kept for it.

With the exact derivatives of the lift-off angle (``jarm(..., derivatives=True)``: the
fields ``d_theta_J`` etc., shape (..., 3) with respect to (alpha, chi, km), issue 38 item 2,
built separately), the spread of theta_J to first order is sqrt(g^T Sigma g), g the gradient
at the nominal point and Sigma the covariance of (alpha, chi, km) (diagonal: ``sd**2``; a
uniform's variance (hi - lo)^2 / 12), and P(JARM) follows from the margins to the region's
boundaries the same way. Until then :func:`delta_method` returns None and
:attr:`eccjump.Uncertainty.delta` is None.
"""

from __future__ import annotations

from typing import NamedTuple

from eccjump.uncertainty.sampling import Spread


class Delta(NamedTuple):
    """The first-order estimate: the standard deviation of the lift-off angle theta_J [rad]
    and P(JARM) from the nominal point's derivatives."""

    theta_J_sd: float
    p_jarm: float


def delta_method(spec: Spread, question: str) -> Delta | None:
    """The delta-method estimate for ``spec`` (not yet: None). To be filled in once
    ``jarm(..., derivatives=True)`` is on main; it must not change the Monte Carlo part."""
    del spec, question
    return None


__all__ = ["Delta", "delta_method"]

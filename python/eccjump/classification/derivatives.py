"""The derivative fields of a classification (``derivatives=True`` of :func:`eccjump.jarm` and
:func:`eccjump.region`): computed by the core from the classified lift-off angles, after the
classification call, so that a call without them does no extra work.

The derivatives are exact (implicit differentiation of the function whose root θ_J is;
the user guide's "JARM analysis" page, section "Derivatives", derives them), with respect to
(α, χ, km) in a trailing axis of length 3 (:data:`eccjump.classification.fields.WRT`).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import NDArray

from eccjump import _core
from eccjump._base.bridge import CallOptions
from eccjump.classification.fields import DERIVATIVES


def derivative_fields(
    points: tuple[NDArray[np.float64], ...],
    raw: dict[str, NDArray],
    opts: CallOptions,
    shape: tuple[int, ...],
) -> dict[str, NDArray]:
    """The derivative fields of the classification ``raw`` (flat fields, as the bridge gives
    them) of the flat points ``(alpha, chi, km, mu_s)`` made with ``opts``, each reshaped to
    ``shape`` (plus the trailing axis ``wrt``).

    The forces' and ``mu_J``'s derivatives are NaN where the result has no forces (every
    point but a JARM), like ``Fx_J`` and ``Fy_J`` themselves.
    """
    alpha, chi, km, mu_s = points
    theta = np.ascontiguousarray(raw["theta_J"], dtype=np.float64)
    d_theta, d_fx, d_fy, d_mu, singular = _core.jarm_derivatives(
        alpha, chi, km, mu_s, theta, rule=opts.rule, theta0=opts.theta0, omega0=opts.omega0
    )
    no_forces = np.isnan(raw["Fx_J"])[:, None]
    for d in (d_fx, d_fy, d_mu):
        d[np.broadcast_to(no_forces, d.shape)] = np.nan
    values = (d_theta, d_fx, d_fy, d_mu)
    out: dict[str, NDArray] = {
        k: v.reshape(*shape, 3) for k, v in zip(DERIVATIVES[:4], values, strict=True)
    }
    out["d_singular"] = singular.reshape(shape)
    return out


__all__ = ["derivative_fields"]

"""The catalogue of the reference cases the tests share: the named points, as Python and the
command line take them, in one place, and the set of points that jump from pure rolling
given enough friction, for properties that need such a point.

The named points are the physics notes' (``shared/physics.md``): the JARM point of the
paper (α = 40°, χ = 0.15, k_m = 0.02: θ_J = 334.344°, F_y,J = +0.01543 M g) and the paper's
Fig. 3b body on a 30° ramp, which slips first at θ = 316.47° with μ_s = 1
(μ_s,min ≈ 1.3916). A test that uses one of these bodies or points takes it from here by
name; its reference values (from the mpmath reference, ``tests/reference_physics.py``)
stand beside it. A test that means a number for its own reason (a body just outside a
range, a value a parser must read back) writes the number.
"""

from __future__ import annotations

import math
from functools import cache

import numpy as np

import eccjump

#: (χ, k_m) of the paper's JARM point, and its ramp angle α [rad] (40°).
JARM_BODY = (0.15, 0.02)
JARM_ALPHA_DEG = 40
JARM_ALPHA = math.radians(JARM_ALPHA_DEG)
#: Its jump from rolling at μ_s = 1: θ_J [deg] and the contact forces there [M g].
JARM_THETA_J_DEG = 334.34383789184907204
JARM_FY_J = 0.015427991249042646579
JARM_FX_J = -0.0051639030551486398888

#: (χ, k_m) of the paper's Fig. 3b body, and the ramp angle α [rad] (30°) on which it slips
#: first at μ_s = 1.
SLIP_FIRST_BODY = (0.5, 0.4)
SLIP_FIRST_ALPHA_DEG = 30
SLIP_FIRST_ALPHA = math.radians(SLIP_FIRST_ALPHA_DEG)
#: The angle at which it slips at μ_s = 1 [deg].
SLIP_FIRST_THETA_DEG = 316.47167723304615645

#: (body, α) pairs as ``simulate`` and ``roll`` take them.
JARM = (eccjump.Cylinder(*JARM_BODY), JARM_ALPHA)
SLIP_FIRST = (eccjump.Cylinder(*SLIP_FIRST_BODY), SLIP_FIRST_ALPHA)
#: The same points as keywords (``explore``, the reference motion, parameter dicts).
JARM_KW = {"alpha": JARM_ALPHA, "chi": JARM_BODY[0], "km": JARM_BODY[1]}
SLIP_FIRST_KW = {"alpha": SLIP_FIRST_ALPHA, "chi": SLIP_FIRST_BODY[0], "km": SLIP_FIRST_BODY[1]}


def _body_args(body: tuple[float, float]) -> tuple[str, ...]:
    return ("--chi", f"{body[0]:g}", "--km", f"{body[1]:g}")


#: The same points on the command line (α in degrees), μ_s left to the test: ``--chi 0.15
#: --km 0.02`` is the JARM body, ``JARM_ARGS`` adds ``--alpha 40``.
JARM_BODY_ARGS = _body_args(JARM_BODY)
JARM_ARGS = ("--alpha", f"{JARM_ALPHA_DEG:g}", *JARM_BODY_ARGS)
SLIP_FIRST_ARGS = ("--alpha", f"{SLIP_FIRST_ALPHA_DEG:g}", *_body_args(SLIP_FIRST_BODY))

#: An ordinary run for the mechanics of a result (its dense output, SI units, step limit,
#: input checks): the body (0.3, 0.2) on α = 0.5 rad rolls about 125 steps to its lift-off
#: (and slips first with μ_s = 1); no verdict of it is a reference value.
ROLLS = (eccjump.Cylinder(0.3, 0.2), 0.5)

#: μ_s large enough that friction never decides: a point is then JARM exactly when it
#: jumps from pure rolling (θ_J in a window [2πn − α, 2πn] with F_y > 0 along the path).
AMPLE_FRICTION = 1e3


@cache
def jump_points() -> tuple[tuple[float, float, float, int, float], ...]:
    """The points (α, χ, k_m, n, μ_needed) of a 12³ grid over the part of the parameter space
    where the JARM region lies (α ∈ [0.3, 1.3], χ ∈ [0.05, 0.4], k_m ∈ [0.002, 0.05]) that
    jump from pure rolling, with the turn n of the jump and the largest friction ratio
    μ_needed along their path (JARM exactly for μ_s ≥ μ_needed): about a quarter of the grid.
    A property that needs such a point draws one from here, so that it reaches its assertion
    in every example rather than in the few that a filter over the whole space lets through.
    """
    axes = (np.linspace(0.3, 1.3, 12), np.linspace(0.05, 0.4, 12), np.linspace(0.002, 0.05, 12))
    alpha, chi, km = (a.ravel() for a in np.meshgrid(*axes, indexing="ij"))
    r = eccjump.jarm(alpha, chi, km, AMPLE_FRICTION, refine_extrema=True)  # the exact maximum
    jumps = np.asarray(r.is_jarm, dtype=bool)
    return tuple(
        (float(a), float(c), float(k), int(n), float(m))
        for a, c, k, n, m in zip(
            alpha[jumps], chi[jumps], km[jumps], r.n[jumps], r.max_ratio[jumps], strict=True
        )
    )

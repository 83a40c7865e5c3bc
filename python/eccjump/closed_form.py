"""The paper's closed forms (Sections 3.1 and 3.2), element-wise over numpy arrays.

All angles in radians, forces per M g. Every function broadcasts its array arguments and
raises ``ValueError`` naming the parameter and the index of the first invalid point.
The formulas were re-derived from Newton–Euler and checked against the printed ones
(``docs/paper_formulas.md``).
"""

from __future__ import annotations

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._arrays import broadcast_flat, turn
from eccjump._checks import real

F = NDArray[np.float64]


def _call(
    name: str, n: int, theta0: float = 0.0, omega0: float = 0.0, **inputs: ArrayLike
) -> list[F]:
    shape, flat = broadcast_flat(**inputs)
    outs = _core.pointwise(name, flat, n, real("theta0", theta0), real("omega0", omega0))
    return [o.reshape(shape) for o in outs]


def _n(n: object) -> int:
    """A turn n >= 1 (None is not allowed here: these formulas are for one given turn)."""
    if n is None:
        raise TypeError("n must be an integer >= 1 here, not None")
    return turn(n)  # type: ignore[return-value]


def jump_forces(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, theta_J: ArrayLike) -> tuple[F, F]:
    """(F_x,J, F_y,J): friction and normal force at a jump point theta_J (Eqs. jump6,
    Njumpfn), with theta'_J^2 = cos(alpha)/(chi cos theta_J). Valid only at a true jump
    point (chi > 0, cos theta_J > 0)."""
    fx, fy = _call("jump_forces", 0, alpha=alpha, chi=chi, km=km, theta_J=theta_J)
    return fx, fy


def mu(chi: ArrayLike, km: ArrayLike, theta_J: ArrayLike) -> F:
    """mu(chi, k_m, theta_J) of Eq. ineq2: the signed ratio -F_x,J/F_y,J. It is the friction
    ratio |F_x,J|/F_y,J only where sin theta_J < 0 (the green window)."""
    return _call("mu", 0, chi=chi, km=km, theta_J=theta_J)[0]


def green_turn(alpha: ArrayLike, theta_J: ArrayLike) -> NDArray[np.int64]:
    """n such that 2 pi n - alpha < theta_J < 2 pi n (where F_y,J > 0), or 0 if none."""
    return _call("green", 0, alpha=alpha, theta_J=theta_J)[0].astype(np.int64)


def in_green_interval(
    alpha: ArrayLike, theta_J: ArrayLike, n: int | None = None
) -> NDArray[np.bool_]:
    """The green-interval test 2 pi n - alpha < theta_J < 2 pi n (any n >= 1 if None)."""
    g = green_turn(alpha, theta_J)
    return np.asarray(g > 0 if n is None else g == _n(n))


def mu_s_min(chi: ArrayLike, km: ArrayLike) -> tuple[F, F]:
    """(mu_s,min, phi): the smallest static friction that allows a JARM for the body, and the
    angle phi in (-pi/2, 0) (relative to 2 pi n) where mu(chi, k_m, .) takes it."""
    m, phi = _call("mu_s_min", 0, chi=chi, km=km)
    return m, phi


def theta_J_range(chi: ArrayLike, km: ArrayLike, mu_s: ArrayLike, n: int = 1) -> tuple[F, F]:
    """(theta_J,min, theta_J,max) on turn n: where mu(chi, k_m, theta_J) <= mu_s inside the
    quarter turn before 2 pi n; NaN where mu_s < mu_s,min."""
    lo, hi = _call("theta_j_range", _n(n), chi=chi, km=km, mu_s=mu_s)
    return lo, hi


def alpha_min(chi: ArrayLike, km: ArrayLike, mu_s: ArrayLike, n: int = 1) -> F:
    """alpha_min = 2 pi n - theta_J,max: no JARM on turn n on a gentler ramp."""
    return _call("alpha_min", _n(n), chi=chi, km=km, mu_s=mu_s)[0]


def gamma(chi: ArrayLike, km: ArrayLike) -> F:
    """gamma = (I_C + 1 + 2 chi)/(4 pi chi) of Eq. dega2 (infinite for chi = 0)."""
    return _call("gamma", 0, chi=chi, km=km)[0]


def J(theta: ArrayLike, alpha: ArrayLike, chi: ArrayLike, km: ArrayLike) -> F:
    """The paper's J(theta) (Eq. Jta) as printed, from rest at theta0 = 0. It divides by
    cos(alpha): prefer :func:`liftoff_function`, equal to cos(alpha) J(theta)."""
    return _call("J", 0, theta=theta, alpha=alpha, chi=chi, km=km)[0]


def liftoff_function(
    theta: ArrayLike,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    *,
    theta0: float = 0.0,
    omega0: float = 0.0,
) -> F:
    """chi theta'^2 cos(theta) - cos(alpha) along pure rolling from (theta0, omega0), with
    theta'^2 from conservation of energy; its rising zero is the paper's lift-off."""
    return _call("liftoff", 0, theta0, omega0, theta=theta, alpha=alpha, chi=chi, km=km)[0]


def J_brackets(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, n: int = 1) -> tuple[F, F]:
    """(J(2 pi n - alpha), J(2 pi n)) of Eqs. JtaC1, JtaC2: a root of J on turn n is bracketed
    iff the first is < 0 and the second > 0."""
    c1, c2 = _call("jtac", _n(n), alpha=alpha, chi=chi, km=km)
    return c1, c2


def theta_nJ(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, n: int = 1) -> F:
    """theta_{n,J}: the root of the lift-off function in [2 pi n - alpha, 2 pi n] by bisection
    to the last bit (NaN if JtaC1/JtaC2 fail). Whether the body gets there in pure rolling is
    what :func:`eccjump.jarm` decides."""
    return _call("theta_nj", _n(n), alpha=alpha, chi=chi, km=km)[0]


def path_forces(
    theta: ArrayLike,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    *,
    theta0: float = 0.0,
    omega0: float = 0.0,
) -> tuple[F, F]:
    """(F_x(theta), F_y(theta)) along pure rolling from (theta0, omega0): the paper's Eqs. FxL2,
    FyL2 for the start from rest, computed from theta'^2 by energy and theta'' by the rolling
    equation (not from the long printed forms)."""
    fx, fy = _call("path_forces", 0, theta0, omega0, theta=theta, alpha=alpha, chi=chi, km=km)
    return fx, fy

"""The paper's closed forms (Sections 3.1 and 3.2), element-wise over numpy arrays.

All angles in radians, forces per M g. Every function broadcasts its array arguments and
raises ``ValueError`` naming the parameter and the index of the first invalid point.
The formulas were re-derived from Newton–Euler and checked against the printed ones (the
user guide's "The paper's formulas" page).

Examples
--------
The paper's JARM point (α = 40 deg, χ = 0.15, k_m = 0.02) and Fig. 3b body
(χ = 0.5, k_m = 0.4):

>>> import numpy as np
>>> from eccjump import closed_form
>>> theta_J = closed_form.theta_nJ(np.radians(40), 0.15, 0.02)
>>> print(f"{np.degrees(theta_J):.6f} deg")
334.343838 deg
>>> print(f"{closed_form.mu_s_min(0.5, 0.4)[0]:.6f}")
1.391619

"""

from __future__ import annotations

from collections.abc import Callable

import numpy as np
from numpy.typing import ArrayLike, NDArray

from eccjump import _core
from eccjump._base.arrays import broadcast_flat, turn
from eccjump._base.checks import real
from eccjump._base.docs import fill

F = NDArray[np.float64]


def _call(
    kernel: Callable[..., list[F]],
    /,
    n: int | None = None,
    start: tuple[object, object] | None = None,
    **inputs: ArrayLike,
) -> list[F]:
    """The closed form ``kernel`` of the bridge at every point of the broadcast ``inputs``, on
    turn ``n`` or along rolling from ``start`` (theta0, omega0) if it takes them; each output
    in the broadcast shape."""
    shape, flat = broadcast_flat(**inputs)
    options: dict[str, float] = {}
    if n is not None:
        options["n"] = n
    if start is not None:
        options["theta0"] = real("theta0", start[0])
        options["omega0"] = real("omega0", start[1])
    return [o.reshape(shape) for o in kernel(*flat, **options)]


def _n(n: object) -> int:
    """A turn n ≥ 1 (None is not allowed here: these formulas are for one given turn)."""
    if n is None:
        raise TypeError("n must be an integer >= 1 here, not None")
    return turn(n)  # type: ignore[return-value]


@fill
def jump_forces(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, theta_J: ArrayLike) -> tuple[F, F]:
    """The friction and normal force at a jump point θ_J (Eqs. jump6, Njumpfn).

    With θ̇_J² = cos(α)/(χ cos θ_J): valid only at a true jump point
    (χ > 0, cos θ_J > 0).

    Parameters
    ----------
    %(alpha)s
    %(chi)s
    %(km)s
    %(theta_J)s

    Returns
    -------
    Fx_J, Fy_J : numpy.ndarray of float64
        Friction (positive down the ramp) and normal force at the jump [M g], of the
        broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> a = np.radians(40)
    >>> fx, fy = closed_form.jump_forces(a, 0.15, 0.02, closed_form.theta_nJ(a, 0.15, 0.02))
    >>> print(f"Fx_J = {fx:.6f}, Fy_J = {fy:.6f} M g")
    Fx_J = -0.005164, Fy_J = 0.015428 M g
    """
    fx, fy = _call(_core.jump_forces, alpha=alpha, chi=chi, km=km, theta_J=theta_J)
    return fx, fy


@fill
def mu(chi: ArrayLike, km: ArrayLike, theta_J: ArrayLike) -> F:
    """μ(χ, k_m, θ_J) of Eq. ineq2: the signed ratio -F_x,J/F_y,J.

    It is the friction ratio |F_x,J|/F_y,J only where sin θ_J < 0 (the green window).

    Parameters
    ----------
    %(chi)s
    %(km)s
    %(theta_J)s

    Returns
    -------
    numpy.ndarray of float64
        μ, dimensionless, of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> print(f"{closed_form.mu(0.5, 0.4, np.radians(302.49)):.6f}")
    1.391619
    """
    return _call(_core.mu, chi=chi, km=km, theta_J=theta_J)[0]


@fill
def green_turn(alpha: ArrayLike, theta_J: ArrayLike) -> NDArray[np.int64]:
    """The turn n with 2π n - α < θ_J < 2π n (where F_y,J > 0), or 0 if none.

    Parameters
    ----------
    %(alpha)s
    %(theta_J)s

    Returns
    -------
    numpy.ndarray of int64
        n ≥ 1, or 0, of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> closed_form.green_turn(np.radians(40), np.radians([334.3, 300.0, 694.3])).tolist()
    [1, 0, 2]
    """
    return _call(_core.green_turn, alpha=alpha, theta_J=theta_J)[0].astype(np.int64)


@fill
def in_green_interval(
    alpha: ArrayLike, theta_J: ArrayLike, n: int | None = None
) -> NDArray[np.bool_]:
    """The green-interval test 2π n - α < θ_J < 2π n.

    Parameters
    ----------
    %(alpha)s
    %(theta_J)s
    n : int or None, default None
        The turn, ≥ 1; None: any turn.

    Returns
    -------
    numpy.ndarray of bool
        Of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> bool(closed_form.in_green_interval(np.radians(40), np.radians(334.3), n=1))
    True
    """
    g = green_turn(alpha, theta_J)
    return np.asarray(g > 0 if n is None else g == _n(n))


@fill
def mu_s_min(chi: ArrayLike, km: ArrayLike) -> tuple[F, F]:
    """The smallest static friction that allows a JARM for the body, and where.

    Parameters
    ----------
    %(chi)s
    %(km)s

    Returns
    -------
    mu_s_min : numpy.ndarray of float64
        The minimum of μ(χ, k_m, .) over the green window, dimensionless.
    phi : numpy.ndarray of float64
        The angle [rad] in (-π/2, 0), relative to 2π n, where it is taken.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    The paper's Fig. 3b body:

    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> m, phi = closed_form.mu_s_min(0.5, 0.4)
    >>> print(f"{m:.6f} at {360 + np.degrees(phi):.2f} deg")
    1.391619 at 302.49 deg
    """
    m, phi = _call(_core.mu_s_min, chi=chi, km=km)
    return m, phi


@fill
def theta_J_range(chi: ArrayLike, km: ArrayLike, mu_s: ArrayLike, n: int = 1) -> tuple[F, F]:
    """The jump angles allowed by friction on turn n: (θ_J,min, θ_J,max).

    Where μ(χ, k_m, θ_J) ≤ μ_s inside the quarter turn before 2π n.

    Parameters
    ----------
    %(chi)s
    %(km)s
    %(mu_s_array)s
    %(n_turn)s

    Returns
    -------
    theta_J_min, theta_J_max : numpy.ndarray of float64
        [rad], of the broadcast shape; NaN where μ_s < μ_s,min.

    Raises
    ------
    %(value_error_broadcast)s
    TypeError
        If ``n`` is None or not an integer.

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> lo, hi = closed_form.theta_J_range(0.5, 0.4, 1.6)
    >>> print(f"[{np.degrees(lo):.2f}, {np.degrees(hi):.2f}] deg")
    [272.43, 324.78] deg
    """
    lo, hi = _call(_core.theta_j_range, _n(n), chi=chi, km=km, mu_s=mu_s)
    return lo, hi


@fill
def alpha_min(chi: ArrayLike, km: ArrayLike, mu_s: ArrayLike, n: int = 1) -> F:
    """alpha_min = 2π n - θ_J,max: no JARM on turn n on a gentler ramp.

    Parameters
    ----------
    %(chi)s
    %(km)s
    %(mu_s_array)s
    %(n_turn)s

    Returns
    -------
    numpy.ndarray of float64
        alpha_min [rad], of the broadcast shape; NaN where μ_s < μ_s,min.

    Raises
    ------
    %(value_error_broadcast)s
    TypeError
        If ``n`` is None or not an integer.

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> print(f"{np.degrees(closed_form.alpha_min(0.5, 0.4, 1.6)):.4f} deg")
    35.2185 deg
    """
    return _call(_core.alpha_min, _n(n), chi=chi, km=km, mu_s=mu_s)[0]


@fill
def gamma(chi: ArrayLike, km: ArrayLike) -> F:
    """γ = (I_C + 1 + 2 χ)/(4π χ) of Eq. dega2.

    Parameters
    ----------
    %(chi)s
    %(km)s

    Returns
    -------
    numpy.ndarray of float64
        γ, dimensionless; inf for χ = 0.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> from eccjump import closed_form
    >>> print(f"{closed_form.gamma(0.15, 0.02):.6f}")
    0.712462
    """
    return _call(_core.gamma, chi=chi, km=km)[0]


@fill
def J(theta: ArrayLike, alpha: ArrayLike, chi: ArrayLike, km: ArrayLike) -> F:
    """The paper's J(θ) (Eq. Jta) as printed, from rest at theta0 = 0.

    It divides by cos(α): prefer :func:`liftoff_function`, equal to cos(α) J(θ).

    Parameters
    ----------
    %(theta)s
    %(alpha)s
    %(chi)s
    %(km)s

    Returns
    -------
    numpy.ndarray of float64
        J, dimensionless, of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> print(f"{closed_form.J(np.radians(300), np.radians(40), 0.15, 0.02):.6f}")
    -0.451845
    """
    return _call(_core.j_paper, theta=theta, alpha=alpha, chi=chi, km=km)[0]


@fill
def liftoff_function(
    theta: ArrayLike,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    *,
    theta0: float = 0.0,
    omega0: float = 0.0,
) -> F:
    """The lift-off function χ θ̇² cos(θ) - cos(α) along pure rolling.

    θ̇² comes from conservation of energy from (theta0, omega0); its rising zero is the
    paper's lift-off.

    Parameters
    ----------
    %(theta)s
    %(alpha)s
    %(chi)s
    %(km)s
    %(theta0)s
    %(omega0)s

    Returns
    -------
    numpy.ndarray of float64
        Dimensionless (per g/R), of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> print(f"{closed_form.liftoff_function(np.radians(300), np.radians(40), 0.15, 0.02):.6f}")
    -0.346133
    """
    return _call(
        _core.liftoff_function, start=(theta0, omega0), theta=theta, alpha=alpha, chi=chi, km=km
    )[0]


@fill
def J_brackets(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, n: int = 1) -> tuple[F, F]:
    """(J(2π n - α), J(2π n)) of Eqs. JtaC1, JtaC2.

    A root of J on turn n is bracketed iff the first is < 0 and the second > 0.

    Parameters
    ----------
    %(alpha)s
    %(chi)s
    %(km)s
    %(n_turn)s

    Returns
    -------
    J_lo, J_hi : numpy.ndarray of float64
        Dimensionless, of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s
    TypeError
        If ``n`` is None or not an integer.

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> lo, hi = closed_form.J_brackets(np.radians(40), 0.15, 0.02)
    >>> print(f"{lo:.6f} {hi:.6f}")
    -0.162087 0.177747
    """
    c1, c2 = _call(_core.j_brackets, _n(n), alpha=alpha, chi=chi, km=km)
    return c1, c2


@fill
def theta_nJ(alpha: ArrayLike, chi: ArrayLike, km: ArrayLike, n: int = 1) -> F:
    """theta_{n,J}: the root of the lift-off function in [2π n - α, 2π n].

    Found by bisection to the last bit. Whether the body gets there in pure rolling is what
    :func:`eccjump.jarm` decides.

    Parameters
    ----------
    %(alpha)s
    %(chi)s
    %(km)s
    %(n_turn)s

    Returns
    -------
    numpy.ndarray of float64
        theta_{n,J} [rad], of the broadcast shape; NaN if JtaC1/JtaC2 fail.

    Raises
    ------
    %(value_error_broadcast)s
    TypeError
        If ``n`` is None or not an integer.

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> print(f"{np.degrees(closed_form.theta_nJ(np.radians(40), 0.15, 0.02)):.6f} deg")
    334.343838 deg
    """
    return _call(_core.theta_nj, _n(n), alpha=alpha, chi=chi, km=km)[0]


@fill
def path_forces(
    theta: ArrayLike,
    alpha: ArrayLike,
    chi: ArrayLike,
    km: ArrayLike,
    *,
    theta0: float = 0.0,
    omega0: float = 0.0,
) -> tuple[F, F]:
    """The contact forces (F_x(θ), F_y(θ)) along pure rolling from (theta0, omega0).

    The paper's Eqs. FxL2, FyL2 for the start from rest, computed from θ̇² by energy
    and θ̈ by the rolling equation (not from the long printed forms).

    Parameters
    ----------
    %(theta)s
    %(alpha)s
    %(chi)s
    %(km)s
    %(theta0)s
    %(omega0)s

    Returns
    -------
    Fx, Fy : numpy.ndarray of float64
        Friction (positive down the ramp) and normal force [M g], of the broadcast shape.

    Raises
    ------
    %(value_error_broadcast)s

    Examples
    --------
    >>> import numpy as np
    >>> from eccjump import closed_form
    >>> fx, fy = closed_form.path_forces(np.radians([90, 180]), np.radians(40), 0.15, 0.02)
    >>> fy.round(6).tolist()
    [0.606559, 1.674246]
    """
    fx, fy = _call(
        _core.path_forces, start=(theta0, omega0), theta=theta, alpha=alpha, chi=chi, km=km
    )
    return fx, fy

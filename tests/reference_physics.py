"""Independent high-precision reference of the eccentric-cylinder model.

This module does NOT import eccjump. It re-derives the model from Newton-Euler and
evaluates it with mpmath at ``DPS`` (30) significant digits, so that the package's
floating-point results can be compared against it.

Units and conventions (as in the paper, Sections 2-3): g = R = M = 1, so time is in
units of sqrt(R/g) and forces in units of M g. ``x`` points down the ramp, ``y`` along
the outward ramp normal; gravity is ``(sin a, -cos a)``. ``theta`` is the angle of the
vector C -> CM from the ramp normal, growing as the body rolls down; ``l`` is the
distance of C along the ramp, ``b`` the height of C above the ramp (b = 1 in contact).
The body enters only through chi = d/R and k_m = m_C/M (shell + line-mass model).

Derivation (Newton-Euler, M = R = g = 1)
-----------------------------------------
CM position: r = (l + chi sin th, b + chi cos th). The contact force F = (F_x, F_y)
acts at the contact point P = (l, 0); Newton: F + (sin a, -cos a) = r'' gives::

    F_x = l'' + chi (sin th)'' - sin a,   F_y = b'' + chi (cos th)'' + cos a.

Torque about CM (lever arm P - r = (-chi sin th, -(b + chi cos th)); clockwise
rotation is positive theta)::

    I_CM th'' = chi sin th F_y - (b + chi cos th) F_x.

Pure rolling: b = 1, l'' = th''. Substituting and collecting th''::

    th'' (I_CM + chi^2 sin^2 th + (1 + chi cos th)^2)
        = chi th'^2 sin th + sin a + chi sin(a + th),

and I_CM + chi^2 sin^2 + (1 + chi cos)^2 = I_C + 1 + 2 chi cos th = I_P (moment of
inertia about the contact point).  Energy (height of CM = -th sin a + chi cos(a + th)
+ const): E = I_P th'^2 / 2 + chi cos(a + th) - th sin a, so from rest at th = 0::

    th'^2 = 2 (th sin a + chi cos a - chi cos(a + th)) / I_P.

Shell (mass k_m, radius 1) + line mass (1 - k_m) at distance chi/(1 - k_m) from C::

    I_C = k_m + chi^2/(1 - k_m),   I_CM = I_C - chi^2 = k_m (1 - k_m + chi^2)/(1 - k_m).

Lift-off (paper's rule): the free-flight normal acceleration b''_free =
chi th'^2 cos th - cos a reaches 0.  At such a point th'^2 = cos a/(chi cos th).

Public functions accept floats, ints, mpf or decimal strings (``"0.15"`` gives 0.15
to 30 digits) and return Python floats, or mpf when called with ``as_mpf=True``.
"""

from __future__ import annotations

from dataclasses import dataclass

from mpmath import mp, mpf

DPS = 30
"""Working precision (significant decimal digits) of every function here."""

__all__ = [
    "DPS",
    "PathViolation",
    "deg",
    "energy_rolling",
    "first_liftoff",
    "flight_accelerations",
    "forces_at_jump",
    "forces_rolling",
    "forces_rolling_from_rest",
    "gamma",
    "ic_tilde",
    "icm_tilde",
    "liftoff_function",
    "mu_jump",
    "mu_s_min",
    "path_check",
    "slip_dynamics",
    "theta_ddot_rolling",
    "theta_dot_sq_from_rest",
    "theta_jump",
]


def _out(x, as_mpf):
    return x if as_mpf else float(x)


def deg(x, as_mpf=False):
    """Degrees -> radians at working precision (``deg("40")`` is exact to 30 digits)."""
    with mp.workdps(DPS):
        return _out(mpf(x) * mp.pi / 180, as_mpf)


# ---------------------------------------------------------------------------
# Body parameters
# ---------------------------------------------------------------------------


def _check_body(chi, km):
    tol = mpf(10) ** -12  # accept k_m = (1 - chi) rounded in double precision
    if chi < 0 or chi > 1 or km < 0 or km > 1 - chi + tol:
        raise ValueError(f"need 0 <= chi <= 1 and 0 <= k_m <= 1 - chi, got {chi}, {km}")


def _ic(chi, km):
    _check_body(chi, km)
    if chi == 0:
        return km  # chi^2/(1 - k_m) -> 0 even at k_m = 1
    return km + chi**2 / (1 - km)


def _icm(chi, km):
    _check_body(chi, km)
    if chi == 0:
        return km
    return km * (1 - km + chi**2) / (1 - km)  # no cancellation against chi^2


def ic_tilde(chi, km, as_mpf=False):
    """I_C/(M R^2) = k_m + chi^2/(1 - k_m)  (moment of inertia about the centre C)."""
    with mp.workdps(DPS):
        return _out(_ic(mpf(chi), mpf(km)), as_mpf)


def icm_tilde(chi, km, as_mpf=False):
    """I_CM/(M R^2) = I_C - chi^2 = k_m (1 - k_m + chi^2)/(1 - k_m)."""
    with mp.workdps(DPS):
        return _out(_icm(mpf(chi), mpf(km)), as_mpf)


def gamma(chi, km, as_mpf=False):
    """The paper's gamma = (I_C + 1 + 2 chi)/(4 pi chi); +inf at chi = 0.

    Follows from writing th'^2 (from rest) as chi th'^2 = (...)/(2 pi gamma + cos th - 1).
    """
    with mp.workdps(DPS):
        chi, km = mpf(chi), mpf(km)
        ic = _ic(chi, km)
        if chi == 0:
            return _out(mp.inf, as_mpf)
        return _out((ic + 1 + 2 * chi) / (4 * mp.pi * chi), as_mpf)


# ---------------------------------------------------------------------------
# Pure rolling
# ---------------------------------------------------------------------------


def _thdd(th, td2, a, chi, ic):
    """th'' of pure rolling given th'^2 (see module docstring)."""
    ip = ic + 1 + 2 * chi * mp.cos(th)
    if ip == 0:
        raise ZeroDivisionError("I_C + 1 + 2 chi cos(theta) = 0 (chi = 1, k_m = 0, theta = pi)")
    return (chi * td2 * mp.sin(th) + chi * mp.sin(a + th) + mp.sin(a)) / ip


def _forces(th, td2, a, chi, ic):
    """(F_x, F_y) of pure rolling: b'' = 0, l'' = th'' in the Newton equations."""
    thdd = _thdd(th, td2, a, chi, ic)
    s, c = mp.sin(th), mp.cos(th)
    fx = -mp.sin(a) - chi * td2 * s + (1 + chi * c) * thdd
    fy = mp.cos(a) - chi * td2 * c - chi * thdd * s
    return fx, fy


def _td2_rest(th, a, chi, ic):
    """th'^2 from rest at th = 0; chi (cos a - cos(a+th)) written without cancellation."""
    num = th * mp.sin(a) + 2 * chi * mp.sin(a + th / 2) * mp.sin(th / 2)
    return 2 * num / (ic + 1 + 2 * chi * mp.cos(th))


def theta_ddot_rolling(theta, theta_dot, alpha, chi, km, as_mpf=False):
    """Pure-rolling angular acceleration.

    th'' (I_C + 1 + 2 chi cos th) = chi th'^2 sin th + chi sin(a + th) + sin a.
    """
    with mp.workdps(DPS):
        th, td, a, chi, km = map(mpf, (theta, theta_dot, alpha, chi, km))
        return _out(_thdd(th, td**2, a, chi, _ic(chi, km)), as_mpf)


def forces_rolling(theta, theta_dot, alpha, chi, km, as_mpf=False):
    """Contact force (F_x, F_y) per M g in pure rolling at state (theta, theta_dot).

    F_x = -sin a - chi th'^2 sin th + (1 + chi cos th) th'',
    F_y =  cos a - chi th'^2 cos th - chi th'' sin th.
    """
    with mp.workdps(DPS):
        th, td, a, chi, km = map(mpf, (theta, theta_dot, alpha, chi, km))
        fx, fy = _forces(th, td**2, a, chi, _ic(chi, km))
        return _out(fx, as_mpf), _out(fy, as_mpf)


def theta_dot_sq_from_rest(theta, alpha, chi, km, as_mpf=False):
    """th'^2(th) by energy conservation in pure rolling from rest at th0 = 0."""
    with mp.workdps(DPS):
        th, a, chi, km = map(mpf, (theta, alpha, chi, km))
        return _out(_td2_rest(th, a, chi, _ic(chi, km)), as_mpf)


def forces_rolling_from_rest(theta, alpha, chi, km, as_mpf=False):
    """(F_x, F_y) along the rolling path from rest at th0 = 0 (the paper's FxL2, FyL2)."""
    with mp.workdps(DPS):
        th, a, chi, km = map(mpf, (theta, alpha, chi, km))
        ic = _ic(chi, km)
        fx, fy = _forces(th, _td2_rest(th, a, chi, ic), a, chi, ic)
        return _out(fx, as_mpf), _out(fy, as_mpf)


def energy_rolling(theta, theta_dot, alpha, chi, km, as_mpf=False):
    """Mechanical energy in pure rolling, up to a constant.

    E = (I_C + 1 + 2 chi cos th) th'^2/2 + chi cos(a + th) - th sin a
    (kinetic energy about the contact point + height of the CM, l = th).
    """
    with mp.workdps(DPS):
        th, td, a, chi, km = map(mpf, (theta, theta_dot, alpha, chi, km))
        ip = _ic(chi, km) + 1 + 2 * chi * mp.cos(th)
        return _out(ip * td**2 / 2 + chi * mp.cos(a + th) - th * mp.sin(a), as_mpf)


# ---------------------------------------------------------------------------
# Flight and slipping
# ---------------------------------------------------------------------------


def flight_accelerations(theta, theta_dot, alpha, chi, as_mpf=False):
    """Free flight (F = 0): th'' = 0, l'' = chi th'^2 sin th + sin a,
    b'' = chi th'^2 cos th - cos a.  Returns (th'', l'', b'')."""
    with mp.workdps(DPS):
        th, td, a, chi = map(mpf, (theta, theta_dot, alpha, chi))
        ldd = chi * td**2 * mp.sin(th) + mp.sin(a)
        bdd = chi * td**2 * mp.cos(th) - mp.cos(a)
        return _out(mpf(0), as_mpf), _out(ldd, as_mpf), _out(bdd, as_mpf)


def slip_dynamics(theta, theta_dot, alpha, chi, km, mu_k, sigma, as_mpf=False):
    """Sliding contact (b = 1, l free) with F_x = sigma mu_k F_y.

    Torque: I_CM th'' = K F_y with K = chi sin th - sigma mu_k (1 + chi cos th).
    Normal equation: F_y = cos a - chi th'^2 cos th - chi th'' sin th.  Hence
    F_y = I_CM (cos a - chi th'^2 cos th) / D,  D = I_CM + chi K sin th,
    th'' = K (cos a - chi th'^2 cos th)/D, l'' = F_x + sin a - chi (sin th)''.
    Returns (th'', l'', F_x, F_y, D); D <= 0 is the Painleve case (no consistent
    sliding contact) and then th'', l'', F_x, F_y are returned as nan.
    """
    with mp.workdps(DPS):
        th, td, a, chi, km, mu_k, sigma = map(mpf, (theta, theta_dot, alpha, chi, km, mu_k, sigma))
        icm = _icm(chi, km)
        s, c = mp.sin(th), mp.cos(th)
        k = chi * s - sigma * mu_k * (1 + chi * c)
        d = icm + chi * k * s
        if d <= 0:
            vals = (mp.nan,) * 4 + (d,)
        else:
            q = mp.cos(a) - chi * td**2 * c
            fy = icm * q / d
            thdd = k * q / d
            fx = sigma * mu_k * fy
            ldd = fx + mp.sin(a) - chi * (c * thdd - s * td**2)
            vals = (thdd, ldd, fx, fy, d)
        return tuple(_out(v, as_mpf) for v in vals)


# ---------------------------------------------------------------------------
# Lift-off and the jump point
# ---------------------------------------------------------------------------


def _lift(th, a, chi, ic):
    return chi * _td2_rest(th, a, chi, ic) * mp.cos(th) - mp.cos(a)


def liftoff_function(theta, alpha, chi, km, theta_dot=None, as_mpf=False):
    """chi th'^2 cos th - cos a (free-flight b''); th'^2 from rest unless theta_dot is given.

    The paper's J(th) equals this divided by cos a (so J is undefined at a = pi/2).
    """
    with mp.workdps(DPS):
        th, a, chi, km = map(mpf, (theta, alpha, chi, km))
        ic = _ic(chi, km)
        if theta_dot is None:
            return _out(_lift(th, a, chi, ic), as_mpf)
        return _out(chi * mpf(theta_dot) ** 2 * mp.cos(th) - mp.cos(a), as_mpf)


def _refine_root(f, lo, hi):
    """Root of f in [lo, hi] (f(lo), f(hi) of opposite sign): findroot, else bisection."""
    try:
        x = mp.findroot(f, (lo, hi), solver="anderson")
        if lo <= x <= hi and abs(f(x)) < mpf(10) ** (-(DPS - 8)):
            return x
    except (ValueError, ZeroDivisionError):
        pass
    flo = f(lo)
    for _ in range(4 * DPS):
        mid = (lo + hi) / 2
        fm = f(mid)
        if (fm < 0) == (flo < 0):
            lo, flo = mid, fm
        else:
            hi = mid
    return (lo + hi) / 2


def _first_up_crossing(f, lo, hi, nsamp):
    """First point of [lo, hi] where f goes from < 0 to >= 0 (sampled, then refined).

    f(lo) == 0 counts as a root at lo; if f(lo) > 0 the scan waits for f to go negative
    first (the rule was met before lo; callers that care must look before lo).
    """
    prev_x, prev_f = lo, f(lo)
    if prev_f == 0:
        return lo
    for i in range(1, nsamp + 1):
        x = lo + (hi - lo) * i / nsamp
        fx = f(x)
        if fx >= 0 and prev_f < 0:
            return x if fx == 0 else _refine_root(f, prev_x, x)
        prev_x, prev_f = x, fx
    return None


def theta_jump(n, alpha, chi, km, nsamp=200, as_mpf=False):
    """The paper's theta_J on turn n: the first root of chi th'^2 cos th - cos a
    (th'^2 from rest) in the green window [2 pi n - a, 2 pi n], or None.

    The window is scanned (nsamp points) for the first sign change, which is then
    refined with mpmath.findroot (Anderson, bracketing) with a bisection fallback.
    This does not check that the lift-off rule was not met earlier on the path;
    see ``first_liftoff`` for that.
    """
    with mp.workdps(DPS):
        a, chi, km = map(mpf, (alpha, chi, km))
        ic = _ic(chi, km)
        if chi == 0:
            return None
        lo, hi = 2 * mp.pi * n - a, 2 * mp.pi * n
        root = _first_up_crossing(lambda t: _lift(t, a, chi, ic), lo, hi, nsamp)
        return None if root is None else _out(root, as_mpf)


def first_liftoff(alpha, chi, km, n_max=20, samples_per_turn=2000, as_mpf=False):
    """First theta > 0 where the paper's lift-off rule holds on the path from rest.

    Scans chi th'^2 cos th - cos a with a step of at most min(a/20, 2 pi/samples_per_turn)
    over 0 < th <= 2 pi n_max (windows of positivity can be as narrow as a) and refines
    the first sign change.  Returns (theta, n) with n the turn (ceil(theta/2pi)), or None.
    """
    with mp.workdps(DPS):
        a, chi, km = map(mpf, (alpha, chi, km))
        ic = _ic(chi, km)
        if chi == 0:
            return None

        def f(t):
            return _lift(t, a, chi, ic)

        step = 2 * mp.pi / samples_per_turn
        if a > 0:
            step = min(step, a / 20)
        per_turn = int(mp.ceil(2 * mp.pi / step))
        for n in range(1, n_max + 1):
            # lift-off needs cos th > 0: scan (2pi(n-1), +pi/2] and [2pi n - pi/2, 2pi n]
            for lo, hi in (
                (2 * mp.pi * (n - 1), 2 * mp.pi * (n - 1) + mp.pi / 2),
                (2 * mp.pi * n - mp.pi / 2, 2 * mp.pi * n),
            ):
                if n == 1 and lo == 0:
                    lo = mpf(10) ** (-DPS)
                r = _first_up_crossing(f, lo, hi, per_turn // 4 + 1)
                if r is not None:
                    return _out(r, as_mpf), n
        return None


def forces_at_jump(theta_j, alpha, chi, km, as_mpf=False):
    """(F_x, F_y) of pure rolling at a jump point, th'^2 = cos a/(chi cos th_J).

    Independent of the initial conditions; needs chi > 0 and cos th_J > 0.
    """
    with mp.workdps(DPS):
        th, a, chi, km = map(mpf, (theta_j, alpha, chi, km))
        td2 = mp.cos(a) / (chi * mp.cos(th))
        fx, fy = _forces(th, td2, a, chi, _ic(chi, km))
        return _out(fx, as_mpf), _out(fy, as_mpf)


def _mu(th, chi, km):
    icm = _icm(chi, km)
    s, c = mp.sin(th), mp.cos(th)
    tail = -chi * s / (1 + chi * c)
    if icm == 0:
        return tail
    den = chi * s * (1 + chi * c)
    if den == 0:
        return mp.inf if s <= 0 else -mp.inf
    return -icm / den + tail


def mu_jump(chi, km, theta_j, as_mpf=False):
    """Signed mu = -F_x,J/F_y,J at a jump point (the paper's Eq. ineq2).

    From forces_at_jump: F_x,J/F_y,J = (I_C - chi^2 cos^2)/(chi sin th (1 + chi cos th)),
    written here as -I_CM/(chi s (1 + chi c)) - chi s/(1 + chi c) (I_C - chi^2 c^2 =
    I_CM + chi^2 s^2), which stays finite at k_m = 0.  Independent of alpha.  It equals
    |F_x/F_y| only where sin th_J < 0.
    """
    with mp.workdps(DPS):
        th, chi, km = map(mpf, (theta_j, chi, km))
        return _out(_mu(th, chi, km), as_mpf)


def mu_s_min(chi, km, alpha=None, as_mpf=False):
    """min of mu(chi, k_m, th) over the green window th in (2 pi - a, 2 pi) (a = pi/2 if None).

    Returns (mu_min, theta_at_min) with theta in (3pi/2, 2pi); the minimum is found by a
    scan followed by mpmath.findroot on d mu/d theta.  If the minimum is at the window's
    lower end (2 pi - a) that end is returned.
    """
    with mp.workdps(DPS):
        chi, km = mpf(chi), mpf(km)
        a = mp.pi / 2 if alpha is None else mpf(alpha)
        lo, hi = 2 * mp.pi - a, 2 * mp.pi

        def f(t):
            return _mu(t, chi, km)

        nsamp = 400
        xs = [lo + (hi - lo) * i / nsamp for i in range(1, nsamp)]
        vals = [f(x) for x in xs]
        i = min(range(len(xs)), key=lambda j: vals[j])
        if i == 0 and f(lo) <= vals[0]:
            x = lo
        else:

            def d(t):
                return mp.diff(f, t)

            left = xs[i - 1] if i > 0 else lo
            right = xs[i + 1] if i + 1 < len(xs) else hi
            try:
                x = mp.findroot(d, (left, right), solver="anderson")
                if not left <= x <= right:
                    raise ValueError
            except (ValueError, ZeroDivisionError):
                x = _refine_root(d, left, right)
        return _out(f(x), as_mpf), _out(x, as_mpf)


# ---------------------------------------------------------------------------
# Path check
# ---------------------------------------------------------------------------


@dataclass(frozen=True)
class PathViolation:
    """First violation of pure rolling on 0 < theta < theta_end.

    kind is "friction" (mu_s F_y - |F_x| first < 0 with F_y > 0) or "normal"
    (F_y <= 0 there); theta is the boundary where the margin crosses 0, refined by
    bisection to working precision (float, or mpf with as_mpf); fx, fy the forces there.
    """

    theta: object
    kind: str
    fx: object
    fy: object


def path_check(alpha, chi, km, mu_s, theta_end=None, samples_per_turn=3600, as_mpf=False):
    """Dense-sampling check of pure rolling from rest at th0 = 0.

    Tests F_y > 0 and mu_s F_y - |F_x| >= 0 (not the ratio) at samples with step
    <= 2 pi/samples_per_turn on 0 < th < theta_end (default: first_liftoff).  Returns
    None if the path passes, else the first PathViolation.  Sampling can miss a
    violation window narrower than the step.
    """
    with mp.workdps(DPS):
        a, chi, km, mu_s = map(mpf, (alpha, chi, km, mu_s))
        ic = _ic(chi, km)
        if theta_end is None:
            r = first_liftoff(a, chi, km, as_mpf=True)
            if r is None:
                raise ValueError("no lift-off found; pass theta_end")
            theta_end = r[0]
        theta_end = mpf(theta_end)

        def margin(t):
            fx, fy = _forces(t, _td2_rest(t, a, chi, ic), a, chi, ic)
            return mu_s * fy - abs(fx), fx, fy

        nsamp = max(10, int(mp.ceil(theta_end / (2 * mp.pi) * samples_per_turn)))
        prev = mpf(0)
        for i in range(1, nsamp):
            t = theta_end * i / nsamp
            m, fx, fy = margin(t)
            if m < 0 or fy <= 0:
                lo, hi = prev, t
                if margin(lo)[0] < 0:
                    hi = lo
                else:
                    for _ in range(4 * DPS):
                        mid = (lo + hi) / 2
                        mm = margin(mid)
                        if mm[0] < 0 or mm[2] <= 0:
                            hi = mid
                        else:
                            lo = mid
                _, fx, fy = margin(hi)
                kind = "normal" if fy <= 0 else "friction"
                return PathViolation(_out(hi, as_mpf), kind, _out(fx, as_mpf), _out(fy, as_mpf))
            prev = t
        return None

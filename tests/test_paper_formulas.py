"""Check every printed closed form of the paper (Sections 2-3) against Newton-Euler.

The equations of motion are derived here with sympy from scratch (CM kinematics,
Newton's law, torque as a cross product about the CM), in dimensional form (M, R, g,
d, I_CM); each printed formula is then typed in exactly as printed in
``eccentric-cylinder-jump.tex`` (dimensional symbols, sec/tan and all) and shown to
agree: symbolically (difference simplifies to 0) where that is fast, and otherwise
numerically at random points with mpmath at 30 digits.  The reference points of
``physics.md`` are checked with the independent module ``reference_physics``.
"""

from __future__ import annotations

import random

import pytest
import reference_physics as rp
import sympy as sp
from hypothesis import given, settings
from hypothesis import strategies as st
from mpmath import mp, mpf

# ---------------------------------------------------------------------------
# Symbols and the independent Newton-Euler derivation
# ---------------------------------------------------------------------------

t = sp.Symbol("t", real=True)
M, R, g, d, I_CM = sp.symbols("M R g d I_CM", positive=True)
alpha, theta = sp.symbols("alpha theta", real=True)
chi, k_m = sp.symbols("chi k_m", positive=True)
thd, thdd, ldd, bdd, b_ = sp.symbols("thetadot thetaddot lddot bddot b", real=True)
ld, bd = sp.symbols("ldot bdot", real=True)
mu_k, sigma = sp.symbols("mu_k sigma", real=True)
n = sp.Symbol("n", integer=True, positive=True)
Fx_s, Fy_s = sp.symbols("F_x F_y", real=True)

th_t, l_t, b_t = sp.Function("theta")(t), sp.Function("l")(t), sp.Function("b")(t)


def _to_symbols(expr):
    """Replace theta(t), l(t), b(t) and their derivatives by plain symbols."""
    rep = {
        sp.Derivative(th_t, (t, 2)): thdd,
        sp.Derivative(l_t, (t, 2)): ldd,
        sp.Derivative(b_t, (t, 2)): bdd,
        sp.Derivative(th_t, t): thd,
        sp.Derivative(l_t, t): ld,
        sp.Derivative(b_t, t): bd,
    }
    return expr.subs(rep).subs({th_t: theta, l_t: sp.Symbol("l"), b_t: b_})


# CM position (x down the ramp, y along the outward normal), gravity, contact point.
r_cm = sp.Matrix([l_t + d * sp.sin(th_t), b_t + d * sp.cos(th_t), 0])
g_vec = sp.Matrix([g * sp.sin(alpha), -g * sp.cos(alpha), 0])
P = sp.Matrix([l_t, 0, 0])

# Newton: F + M g_vec = M r''  ->  contact force F.
F_vec = _to_symbols(M * r_cm.diff(t, 2) - M * g_vec)
# Euler about the CM: (P - r_cm) x F = I_CM * omega', omega = -theta' k (theta grows clockwise).
torque_z = _to_symbols((P - r_cm).cross(sp.Matrix([Fx_s, Fy_s, 0])))[2]
euler = sp.Eq(torque_z, -I_CM * thdd)

I_C = I_CM + M * d**2  # parallel axis
ICT_km = k_m + chi**2 / (1 - k_m)  # I_C/(M R^2) of the shell + line model (Eq. imoment)
KM_SUBS = {d: chi * R, I_CM: M * R**2 * (ICT_km - chi**2)}


def _solve_rolling():
    """Pure rolling: b = R, l'' = R theta''; solve Newton-Euler for theta'' and the force."""
    fx = F_vec[0].subs({ldd: R * thdd, b_: R})
    fy = F_vec[1].subs({bdd: 0, b_: R})
    eq = euler.subs({Fx_s: fx, Fy_s: fy, b_: R})
    sol = sp.solve(eq, thdd)
    assert len(sol) == 1
    return sp.simplify(sol[0]), fx, fy


THDD_ROLL, FX_ROLL, FY_ROLL = _solve_rolling()  # theta''(theta, theta'), F(theta, theta', theta'')


def _zero(expr):
    """True if expr simplifies to 0 symbolically."""
    e = sp.simplify(sp.expand_trig(sp.together(expr)))
    return e == 0


def _num_zero(expr, syms, draw, n_pts=60, tol="1e-22"):
    """expr vanishes at n_pts random points (mpmath, 30 digits)."""
    f = sp.lambdify(syms, expr, modules="mpmath")
    rng = random.Random(12345)
    with mp.workdps(30):
        for _ in range(n_pts):
            vals = draw(rng)
            v = f(*vals)
            assert abs(v) < mpf(tol), (vals, v)


def _draw_body(rng):
    c = mpf(rng.uniform(0.02, 0.98))
    km = mpf(rng.uniform(0.0, 0.999)) * (1 - c)
    return c, km


# ---------------------------------------------------------------------------
# Section 2: equations of motion
# ---------------------------------------------------------------------------


def test_ffs_and_theta_eq():
    """Eqs. ffs and theta-eq follow from the independent Newton-Euler derivation."""
    ffs_x = M * ldd + M * d * sp.diff(sp.sin(th_t), t, 2) - M * g * sp.sin(alpha)
    ffs_y = M * bdd + M * d * sp.diff(sp.cos(th_t), t, 2) + M * g * sp.cos(alpha)
    assert sp.simplify(F_vec[0] - _to_symbols(ffs_x)) == 0
    assert sp.simplify(F_vec[1] - _to_symbols(ffs_y)) == 0
    theta_eq_rhs = d * sp.sin(theta) * Fy_s - (b_ + d * sp.cos(theta)) * Fx_s
    assert euler.rhs == -I_CM * thdd
    assert sp.simplify(-euler.lhs - theta_eq_rhs) == 0  # I_CM th'' = -torque_z


def test_rolling_contact_kinematics():
    """No slip at P: v_C + omega x (P - C) = 0 with omega = -theta' k gives l' = R theta'."""
    v_c = sp.Matrix([ld, 0, 0])
    v_p = v_c + sp.Matrix([0, 0, -thd]).cross(sp.Matrix([0, -R, 0]))
    assert sp.simplify(v_p - sp.Matrix([ld - R * thd, 0, 0])) == sp.zeros(3, 1)


def test_roll_eq():
    """Eq. roll-eq, typed as printed, vanishes on the derived rolling theta''."""
    X = d / R
    roll_eq = (
        thdd * (I_C / (M * R**2) + 1 + 2 * X * sp.cos(theta))
        - X * thd**2 * sp.sin(theta)
        - g / R * (X * sp.sin(alpha + theta) + sp.sin(alpha))
    )
    assert _zero(roll_eq.subs(thdd, THDD_ROLL))


def test_flight_lb_eq2():
    """Eq. lb-eq2: with F = 0, theta'' = 0 (I_CM > 0) and l'', b'' as printed."""
    eqs = [F_vec[0], F_vec[1], euler.subs({Fx_s: 0, Fy_s: 0})]
    sol = sp.solve(eqs, [ldd, bdd, thdd], dict=True)[0]
    assert sol[thdd] == 0
    assert sp.simplify(sol[ldd] - (d * thd**2 * sp.sin(theta) + g * sp.sin(alpha))) == 0
    assert sp.simplify(sol[bdd] - (d * thd**2 * sp.cos(theta) - g * sp.cos(alpha))) == 0


def test_normalslip1():
    """Eq. normalslip1: slip (b = R, l'' free) with F_x = sigma mu_k F_y."""
    eqs = [
        sp.Eq(Fx_s, F_vec[0].subs(b_, R)),
        sp.Eq(Fy_s, F_vec[1].subs({bdd: 0, b_: R})),
        euler.subs(b_, R),
        sp.Eq(Fx_s, sigma * mu_k * Fy_s),
    ]
    sol = sp.solve(eqs, [Fx_s, Fy_s, ldd, thdd], dict=True)[0]
    printed = (M * I_CM * (d * thd**2 * sp.cos(theta) - g * sp.cos(alpha))) / (
        M * d * (sigma * mu_k * sp.sin(theta) * (d * sp.cos(theta) + R) - d * sp.sin(theta) ** 2)
        - I_CM
    )
    assert sp.simplify(sol[Fy_s] - printed) == 0
    # physics.md's dimensionless form: K = chi s - sigma mu_k (1 + chi c), D = I_CM + chi K s
    s, c = sp.sin(theta), sp.cos(theta)
    K = chi * s - sigma * mu_k * (1 + chi * c)
    D = (ICT_km - chi**2) + chi * K * s
    fy_notes = (ICT_km - chi**2) * (sp.cos(alpha) - chi * thd**2 * c) / D
    thdd_notes = K * (sp.cos(alpha) - chi * thd**2 * c) / D
    unit = {M: 1, R: 1, g: 1}
    assert sp.simplify(sol[Fy_s].subs(KM_SUBS).subs(unit) - fy_notes) == 0
    assert sp.simplify(sol[thdd].subs(KM_SUBS).subs(unit) - thdd_notes) == 0
    # and the reference module's slip branch
    with mp.workdps(30):
        args = (
            mpf("5.1"),
            mpf("1.3"),
            mpf("0.6"),
            mpf("0.4"),
            mpf("0.3"),
            mpf("0.25"),
            -1,
        )
        thdd_r, _, fx_r, fy_r, d_r = rp.slip_dynamics(*args, as_mpf=True)
        assert d_r > 0  # not the Painleve case
        subs = {
            theta: args[0],
            thd: args[1],
            alpha: args[2],
            chi: args[3],
            k_m: args[4],
        }
        subs |= {mu_k: args[5], sigma: args[6]}
        assert abs(fy_r - sp.N(fy_notes.subs(subs), 30)) < mpf(10) ** -25
        assert abs(thdd_r - sp.N(thdd_notes.subs(subs), 30)) < mpf(10) ** -25
        assert abs(fx_r - args[6] * args[5] * fy_r) < mpf(10) ** -25


def test_imoment():
    """Eq. imoment: shell (k_m M, radius R) + line mass at distance d + s from C."""
    m_c, m_p = k_m * M, (1 - k_m) * M
    s = k_m / (1 - k_m) * chi * R
    # CM at distance d = chi R from C: the line mass sits on the far side at d + s
    assert sp.simplify(m_p * (chi * R + s) - M * chi * R) == 0
    ic = m_c * R**2 + m_p * (chi * R + s) ** 2
    assert sp.simplify(ic / (M * R**2) - ICT_km) == 0
    assert sp.simplify(ICT_km - chi**2 - (k_m + k_m * chi**2 / (1 - k_m))) == 0
    assert sp.simplify(ICT_km - chi**2 - k_m * (1 - k_m + chi**2) / (1 - k_m)) == 0


# ---------------------------------------------------------------------------
# Section 3: the jump point
# ---------------------------------------------------------------------------

THD2_J = g * sp.cos(alpha) / (d * sp.cos(theta))  # Eq. jumpingeq3
THDD_J = THDD_ROLL.subs(thd, sp.sqrt(THD2_J))
FX_J = FX_ROLL.subs(thdd, THDD_J).subs(thd, sp.sqrt(THD2_J))
FY_J = FY_ROLL.subs(thdd, THDD_J).subs(thd, sp.sqrt(THD2_J))
ICT_PRINTED = k_m + chi**2 / (1 - k_m)


def test_jumpcondition_is_free_flight_bdd():
    """Eqs. jumpcondition / jumpingeq3: b''_free = 0  <=>  theta'^2 = g cos a/(d cos theta)."""
    bdd_free = d * thd**2 * sp.cos(theta) - g * sp.cos(alpha)
    assert sp.simplify(bdd_free.subs(thd, sp.sqrt(THD2_J))) == 0


def test_njump():
    """Eq. Njump: forces with b'' = 0, l'' = R theta'' (theta'' kept free)."""
    X = chi
    fx = (
        M
        * R
        * (-g / R * sp.sin(alpha) - X * thd**2 * sp.sin(theta) + (1 + X * sp.cos(theta)) * thdd)
    )
    fy = M * R * (g / R * sp.cos(alpha) - X * thd**2 * sp.cos(theta) - X * thdd * sp.sin(theta))
    assert sp.simplify(FX_ROLL.subs(d, chi * R) - fx) == 0
    assert sp.simplify(FY_ROLL.subs(d, chi * R) - fy) == 0


def test_njump3():
    """Eq. Njump3: theta''_J."""
    printed = (
        g
        * (1 + chi * sp.cos(theta))
        * sp.sec(theta)
        * sp.sin(alpha + theta)
        / (R * (ICT_PRINTED + 1 + 2 * chi * sp.cos(theta)))
    )
    assert _zero(THDD_J.subs(KM_SUBS) - printed)


def test_jump6_and_njumpfn():
    """Eqs. jump6 (F_x,J) and Njumpfn (F_y,J)."""
    den = ICT_PRINTED + 1 + 2 * chi * sp.cos(theta)
    fxj = -(
        g
        * M
        * (ICT_PRINTED - chi**2 * sp.cos(theta) ** 2)
        * sp.sec(theta)
        * sp.sin(alpha + theta)
        / den
    )
    fyj = -(g * M * chi * (1 + chi * sp.cos(theta)) * sp.tan(theta) * sp.sin(alpha + theta) / den)
    assert _zero(FX_J.subs(KM_SUBS) - fxj)
    assert _zero(FY_J.subs(KM_SUBS) - fyj)


MU_PRINTED = ((-(k_m**2) + k_m + chi**2) / ((k_m - 1) * chi**2) + sp.cos(theta) ** 2) / (
    sp.sin(theta) * (1 / chi + sp.cos(theta))
)


def test_ineq2_is_signed_force_ratio():
    """Eq. ineq2: mu(chi, k_m, theta_J) = -F_x,J / F_y,J (signed), independent of alpha."""
    assert _zero(-FX_J.subs(KM_SUBS) / FY_J.subs(KM_SUBS) - MU_PRINTED)
    # and the reference module's mu agrees with the printed form
    f = sp.lambdify((chi, k_m, theta), MU_PRINTED, modules="mpmath")
    rng = random.Random(7)
    with mp.workdps(30):
        for _ in range(50):
            c, km = _draw_body(rng)
            th = mpf(rng.uniform(-7, 7))
            assert abs(rp.mu_jump(c, km, th, as_mpf=True) - f(c, km, th)) < mpf(10) ** -20 * (
                1 + abs(f(c, km, th))
            )


@settings(max_examples=60, deadline=None, database=None)
@given(
    c=st.floats(0.02, 0.98),
    u=st.floats(0.0, 0.999),
    th=st.floats(-8.0, 8.0),
    a=st.floats(0.01, 1.56),
)
def test_ineq2_equals_friction_ratio_only_where_sin_negative(c, u, th, a):
    """physics.md remark 1: mu of ineq2 = |F_x/F_y| at a jump point iff sin(theta_J) < 0."""
    km = u * (1 - c)
    with mp.workdps(30):
        # a jump point needs cos(theta_J) > 0 (theta'^2 = cos a/(chi cos theta_J))
        if mp.cos(th) < 1e-3 or abs(mp.sin(th)) < 1e-3 or abs(mp.sin(a + th)) < 1e-6:
            return
        fx, fy = rp.forces_at_jump(th, a, c, km, as_mpf=True)
        mu = rp.mu_jump(c, km, th, as_mpf=True)
        assert abs(mu - (-fx / fy)) < mpf(10) ** -20 * (1 + abs(mu))
        if mp.sin(th) < 0:
            assert abs(mu - abs(fx / fy)) < mpf(10) ** -20 * (1 + abs(mu))
        else:  # sin > 0: mu = -|F_x/F_y| < 0, so "mu <= mu_s" holds vacuously
            assert mu < 0
            assert abs(mu + abs(fx / fy)) < mpf(10) ** -20 * (1 + abs(mu))


def test_km0_mu_vanishes_at_full_turn():
    """physics.md remark 2: at k_m = 0 (I_CM = 0) mu -> 0 as theta_J -> 2 pi n;
    for k_m > 0 it diverges (the paper's alpha = 0 argument)."""
    mu0 = sp.simplify(MU_PRINTED.subs(k_m, 0))
    assert sp.simplify(mu0 + chi * sp.sin(theta) / (1 + chi * sp.cos(theta))) == 0
    for nn in (1, 2, 3):
        lim = sp.limit(mu0.subs(chi, sp.Rational(1, 2)), theta, 2 * sp.pi * nn, dir="-")
        assert lim == 0
        lim_pos = sp.limit(
            MU_PRINTED.subs({chi: sp.Rational(1, 2), k_m: sp.Rational(1, 5)}),
            theta,
            2 * sp.pi * nn,
            dir="-",
        )
        assert lim_pos == sp.oo
    with mp.workdps(30):
        eps = mpf(10) ** -12
        assert abs(rp.mu_jump("0.5", 0, 2 * mp.pi - eps, as_mpf=True)) < 1e-12
        assert rp.mu_jump("0.5", "0.2", 2 * mp.pi - eps, as_mpf=True) > 1e10


# ---------------------------------------------------------------------------
# Section 3: from rest at theta_0 = 0
# ---------------------------------------------------------------------------


def _energy_td2():
    """theta'^2(theta) from energy conservation, derived and verified against roll-eq."""
    v_cm = sp.Matrix([R * thd + d * sp.cos(theta) * thd, -d * sp.sin(theta) * thd])
    height = -(R * theta + d * sp.sin(theta)) * sp.sin(alpha) + (R + d * sp.cos(theta)) * sp.cos(
        alpha
    )
    E = M * (v_cm.dot(v_cm)) / 2 + I_CM * thd**2 / 2 + M * g * height
    dE = sp.diff(E, theta) * thd + sp.diff(E, thd) * thdd  # chain rule along the motion
    assert sp.simplify(dE.subs(thdd, THDD_ROLL)) == 0  # energy conserved in rolling
    td2 = sp.Symbol("td2", positive=True)
    sol = sp.solve(sp.Eq(E.subs(thd, sp.sqrt(td2)), E.subs({theta: 0, thd: 0})), td2)
    assert len(sol) == 1
    assert thd not in sol[0].free_symbols
    return sp.simplify(sol[0])


TD2_REST = _energy_td2()
GAMMA_PRINTED = (k_m**2 + 2 * k_m * chi - chi**2 - 2 * chi - 1) / (4 * sp.pi * (k_m - 1) * chi)


def _J_printed(th):
    return -1 + (
        (chi * sp.cos(alpha) - chi * sp.cos(alpha + th) + th * sp.sin(alpha)) * sp.cos(th)
    ) / ((2 * sp.pi * GAMMA_PRINTED + sp.cos(th) - 1) * sp.cos(alpha))


def test_dega2():
    """Eq. dega2: gamma = (I_C + 1 + 2 chi)/(4 pi chi)."""
    assert sp.simplify(GAMMA_PRINTED - (ICT_km + 1 + 2 * chi) / (4 * sp.pi * chi)) == 0
    with mp.workdps(30):
        exact = GAMMA_PRINTED.subs({chi: sp.Rational(1, 2), k_m: sp.Rational(2, 5)})
        assert abs(rp.gamma("0.5", "0.4", as_mpf=True) - mpf(str(sp.N(exact, 40)))) < 1e-28


def test_jta():
    """Eq. Jta: J = d theta'^2 cos(theta)/(g cos a) - 1 with theta'^2 from rest."""
    J_derived = (d * TD2_REST * sp.cos(theta) / (g * sp.cos(alpha)) - 1).subs(KM_SUBS)
    assert _zero(J_derived - _J_printed(theta))


def test_jtac1_jtac2():
    """Eqs. JtaC1, JtaC2: J at the ends of the green window (n an integer)."""
    c1 = (chi * sp.cos(alpha) + (2 * sp.pi * n - alpha) * sp.sin(alpha) - chi) / (
        sp.cos(alpha) + 2 * sp.pi * GAMMA_PRINTED - 1
    ) - 1
    c2 = n * sp.tan(alpha) / GAMMA_PRINTED - 1
    assert _zero(_J_printed(2 * sp.pi * n - alpha) - c1)
    assert _zero(_J_printed(2 * sp.pi * n) - c2)


def _fl2_printed():
    G, a, th, X = GAMMA_PRINTED, alpha, theta, chi
    pi, sin, cos = sp.pi, sp.sin, sp.cos
    fx = (
        -g
        * M
        / (4 * X * (2 * pi * G + cos(th) - 1) ** 2)
        * (
            sin(a)
            * (
                16 * pi**2 * G**2 * X
                - 16 * pi * G * X
                - 4 * pi * G
                - X**2
                + 3 * X
                + 2
                + 2 * pi * G * X**2
                + 2 * (-1 + (-3 + 6 * pi * G) * X) * cos(th)
                + X * cos(2 * th)
                - 2 * th * sin(th)
                - 4 * th * X * sin(th)
                + 8 * pi * G * th * X * sin(th)
                + th * X * sin(2 * th)
            )
            + X
            * (
                2 * cos(a) * (-1 - 2 * X + 4 * pi * G * X + X * cos(th)) * sin(th)
                - (-2 + 4 * pi * G + X) * sin(a + th)
                - X * ((-3 + 6 * pi * G) * sin(a + 2 * th) + sin(a + 3 * th))
            )
        )
    )
    fy = (
        g
        * M
        / (4 * (2 * pi * G + cos(th) - 1) ** 2)
        * (
            cos(a)
            * (
                6
                - 16 * pi * G
                + 16 * pi**2 * G**2
                - 4 * X
                + 2 * pi * G * X
                + (-8 - 8 * pi * G * (-2 + X) + 7 * X) * cos(th)
                + (2 - 4 * X + 6 * pi * G * X) * cos(2 * th)
                + X * cos(3 * th)
            )
            - sin(a)
            * (
                3 * th
                + 4 * (-1 + 2 * pi * G) * th * cos(th)
                + th * cos(2 * th)
                - 2 * sin(th)
                + 4 * pi * G * sin(th)
                + 3 * X * sin(th)
                + sin(2 * th)
                - 3 * X * sin(2 * th)
                + 6 * pi * G * X * sin(2 * th)
                + X * sin(3 * th)
            )
        )
    )
    return fx, fy


def _path_forces_derived():
    fx = FX_ROLL.subs(thdd, THDD_ROLL).subs(thd, sp.sqrt(TD2_REST))
    fy = FY_ROLL.subs(thdd, THDD_ROLL).subs(thd, sp.sqrt(TD2_REST))
    assert thd not in fx.free_symbols | fy.free_symbols
    return fx.subs(KM_SUBS), fy.subs(KM_SUBS)


def test_fxl2_fyl2():
    """Eqs. FxL2, FyL2 (numerically, 30 digits, 60 random points each): printed closed
    forms vs the sympy-derived path forces and vs the reference module."""
    fx_p, fy_p = _fl2_printed()
    fx_d, fy_d = _path_forces_derived()
    syms = (M, R, g, alpha, chi, k_m, theta)

    def draw(rng):
        c, km = _draw_body(rng)
        return (
            mpf(rng.uniform(0.5, 3)),
            mpf(rng.uniform(0.5, 3)),
            mpf(rng.uniform(0.5, 12)),
            mpf(rng.uniform(0.01, 1.55)),
            c,
            km,
            mpf(rng.uniform(0, 40)),
        )

    _num_zero((fx_p - fx_d) / (g * M), syms, draw)
    _num_zero((fy_p - fy_d) / (g * M), syms, draw)
    f_p = sp.lambdify(syms[3:], (fx_p / (g * M), fy_p / (g * M)), modules="mpmath")
    rng = random.Random(99)
    with mp.workdps(30):
        for _ in range(60):
            args = draw(rng)[3:]  # alpha, chi, k_m, theta
            fx_r, fy_r = rp.forces_rolling_from_rest(args[3], *args[:3], as_mpf=True)
            px, py = f_p(*args)
            assert abs(px - fx_r) < mpf(10) ** -22 * (1 + abs(fx_r))
            assert abs(py - fy_r) < mpf(10) ** -22 * (1 + abs(fy_r))


# ---------------------------------------------------------------------------
# The reference module against the sympy derivation
# ---------------------------------------------------------------------------


_UNIT = {M: 1, R: 1, g: 1}
_ROLL_NUM = sp.lambdify(
    (theta, thd, alpha, chi, k_m),
    [
        e.subs(KM_SUBS).subs(_UNIT)
        for e in (
            THDD_ROLL,
            FX_ROLL.subs(thdd, THDD_ROLL),
            FY_ROLL.subs(thdd, THDD_ROLL),
        )
    ],
    modules="mpmath",
)


@settings(max_examples=80, deadline=None, database=None)
@given(
    c=st.floats(0.0, 0.999),
    u=st.floats(0.0, 1.0),
    th=st.floats(-20.0, 20.0),
    td=st.floats(-5.0, 5.0),
    a=st.floats(0.0, 1.5707963),
)
def test_reference_rolling_matches_sympy(c, u, th, td, a):
    """theta'', F_x, F_y of the reference module = the sympy Newton-Euler solution."""
    km = u * (1 - c)
    if km >= 1:
        return  # chi = 0, k_m = 1: sympy's chi^2/(1 - k_m) is 0/0 (the module uses I_C = k_m)
    with mp.workdps(30):
        e_thdd, e_fx, e_fy = _ROLL_NUM(mpf(th), mpf(td), mpf(a), mpf(c), mpf(km))
        got = rp.theta_ddot_rolling(th, td, a, c, km, as_mpf=True)
        fx, fy = rp.forces_rolling(th, td, a, c, km, as_mpf=True)
        for x, y in ((got, e_thdd), (fx, e_fx), (fy, e_fy)):
            assert abs(x - y) < mpf(10) ** -22 * (1 + abs(y))


def test_reference_energy_and_td2_from_rest():
    """Along the from-rest path: E is constant and d(theta'^2)/dtheta = 2 theta''."""
    rng = random.Random(3)
    with mp.workdps(30):
        for _ in range(20):
            c, km = _draw_body(rng)
            a = mpf(rng.uniform(0.05, 1.5))
            e0 = rp.energy_rolling(0, 0, a, c, km, as_mpf=True)
            for th in (mpf(rng.uniform(0, 30)) for _ in range(5)):
                td2 = rp.theta_dot_sq_from_rest(th, a, c, km, as_mpf=True)
                if td2 < 0:
                    continue
                e = rp.energy_rolling(th, mp.sqrt(td2), a, c, km, as_mpf=True)
                assert abs(e - e0) < mpf(10) ** -25
                h = mpf(10) ** -9  # central difference, truncation error ~ h^2
                dtd2 = (
                    rp.theta_dot_sq_from_rest(th + h, a, c, km, as_mpf=True)
                    - rp.theta_dot_sq_from_rest(th - h, a, c, km, as_mpf=True)
                ) / (2 * h)
                thdd_r = rp.theta_ddot_rolling(th, mp.sqrt(td2), a, c, km, as_mpf=True)
                assert abs(dtd2 - 2 * thdd_r) < mpf(10) ** -14
                lf = rp.liftoff_function(th, a, c, km, as_mpf=True)
                J = _J_printed(theta).subs({alpha: a, chi: c, k_m: km, theta: th})
                assert abs(lf / mp.cos(a) - mpf(str(sp.N(J, 30)))) < mpf(10) ** -20


def test_reference_jump_forces_match_closed_forms():
    rng = random.Random(5)
    unit = {M: 1, R: 1, g: 1}
    fxj = FX_J.subs(KM_SUBS).subs(unit)
    fyj = FY_J.subs(KM_SUBS).subs(unit)
    f = sp.lambdify((alpha, chi, k_m, theta), (fxj, fyj), modules="mpmath")
    with mp.workdps(30):
        for _ in range(30):
            c, km = _draw_body(rng)
            a = mpf(rng.uniform(0.01, 1.55))
            th = 2 * mp.pi * rng.randint(1, 3) - mpf(rng.uniform(0, 1.5))
            ex, ey = f(a, c, km, th)
            fx, fy = rp.forces_at_jump(th, a, c, km, as_mpf=True)
            assert abs(fx - ex) < mpf(10) ** -22 and abs(fy - ey) < mpf(10) ** -22


# ---------------------------------------------------------------------------
# Reference points of physics.md
# ---------------------------------------------------------------------------


def test_reference_point_jarm_40deg():
    """alpha = 40 deg, chi = 0.15, k_m = 0.02, mu_s = 1: a JARM at theta_J ~ 334.344 deg."""
    with mp.workdps(30):
        a = rp.deg(40, as_mpf=True)
        first = rp.first_liftoff(a, "0.15", "0.02", as_mpf=True)
        tj = rp.theta_jump(1, a, "0.15", "0.02", as_mpf=True)
        assert first is not None and first[1] == 1
        assert abs(first[0] - tj) < mpf(10) ** -20  # the root on turn 1 is the first lift-off
        tj_deg = tj * 180 / mp.pi
        print("theta_J [deg] =", mp.nstr(tj_deg, 20))
        assert abs(tj_deg - mpf("334.344")) < mpf("0.0005")
        assert abs(rp.liftoff_function(tj, a, "0.15", "0.02", as_mpf=True)) < mpf(10) ** -25
        fx, fy = rp.forces_at_jump(tj, a, "0.15", "0.02", as_mpf=True)
        print("F_x,J =", mp.nstr(fx, 20), " F_y,J =", mp.nstr(fy, 20))
        assert abs(fy - mpf("0.01543")) < mpf("0.000005")
        assert abs(fx - mpf("-0.00516")) < mpf("0.000005")
        # from-rest forces at theta_J equal the jump-point forces
        fx2, fy2 = rp.forces_rolling_from_rest(tj, a, "0.15", "0.02", as_mpf=True)
        assert abs(fx2 - fx) < mpf(10) ** -24 and abs(fy2 - fy) < mpf(10) ** -24
        mu = rp.mu_jump("0.15", "0.02", tj, as_mpf=True)
        print("mu(theta_J) =", mp.nstr(mu, 20))
        assert 0 < mu <= 1
        assert rp.path_check(a, "0.15", "0.02", 1, theta_end=tj) is None


def test_reference_point_slip_first_30deg():
    """alpha = 30 deg, chi = 0.5, k_m = 0.4, mu_s = 1: rolling needs > mu_s near 316.47 deg."""
    with mp.workdps(30):
        a = rp.deg(30, as_mpf=True)
        v = rp.path_check(a, "0.5", "0.4", 1, as_mpf=True)
        assert v is not None and v.kind == "friction"
        deg_ = v.theta * 180 / mp.pi
        print("theta_slip [deg] =", mp.nstr(deg_, 20), " F_x =", mp.nstr(v.fx, 20))
        assert abs(deg_ - mpf("316.47")) < mpf("0.005")
        first = rp.first_liftoff(a, "0.5", "0.4", as_mpf=True)
        assert first is not None and v.theta < first[0]
        print("first lift-off (rule 1) [deg] =", mp.nstr(first[0] * 180 / mp.pi, 20))
        assert abs(v.fy - v.fx) < mpf(10) ** -20  # mu_s F_y = |F_x| with mu_s = 1, F_x > 0


def test_reference_point_mu_s_min():
    """chi = 0.5, k_m = 0.4 (Fig. 3b): mu_s,min ~ 1.3916."""
    with mp.workdps(30):
        m, th = rp.mu_s_min("0.5", "0.4", as_mpf=True)
        print(
            "mu_s,min =",
            mp.nstr(m, 20),
            " at theta [deg] =",
            mp.nstr(th * 180 / mp.pi, 20),
        )
        assert abs(m - mpf("1.3916")) < mpf("0.00005")
        assert 3 * mp.pi / 2 < th < 2 * mp.pi
        dmu = sp.diff(MU_PRINTED, theta).subs({chi: sp.Rational(1, 2), k_m: sp.Rational(2, 5)})
        assert abs(sp.N(dmu.subs(theta, sp.Float(str(th), 30)), 30)) < 1e-20


@pytest.mark.parametrize(
    "alpha_deg,chi_,km_",
    [(40, "0.15", "0.02"), (30, "0.5", "0.4"), (60, "0.1", "0.05"), (10, "0.3", "0.2")],
)
def test_theta_jump_in_window_and_bracket_signs(alpha_deg, chi_, km_):
    """theta_J (if any) lies in [2 pi n - a, 2 pi n] and the JtaC1/JtaC2 signs hold there."""
    with mp.workdps(30):
        a = rp.deg(alpha_deg, as_mpf=True)
        for nn in (1, 2, 3):
            tj = rp.theta_jump(nn, a, chi_, km_, as_mpf=True)
            sub = {alpha: a, chi: mpf(chi_), k_m: mpf(km_), n: nn}
            c1 = sp.N(_J_printed(2 * sp.pi * n - alpha).subs(sub), 30)
            c2 = sp.N(_J_printed(2 * sp.pi * n).subs(sub), 30)
            if c1 < 0 < c2:
                assert tj is not None
            if tj is not None:
                assert 2 * nn * mp.pi - a <= tj <= 2 * nn * mp.pi
                fy = rp.forces_at_jump(tj, a, chi_, km_, as_mpf=True)[1]
                assert fy > 0  # green window: F_y,J > 0 (Eq. signs0)


def test_reference_edge_cases():
    """chi = 0, k_m = 0, chi = 1 and alpha = pi/2 are handled on purpose."""
    with mp.workdps(30):
        assert rp.ic_tilde(0, 1) == 1.0 and rp.icm_tilde(0, "0.3") == pytest.approx(0.3)
        assert rp.gamma(0, "0.5") == float("inf")
        assert rp.theta_jump(1, rp.deg(30), 0, "0.5") is None
        assert rp.first_liftoff(rp.deg(30), 0, "0.5") is None
        assert rp.icm_tilde(1, 0) == 0.0 and rp.icm_tilde("0.4", 0) == 0.0
        # k_m = 0 (I_CM = 0): mu stays finite at sin(theta) = 0
        assert abs(rp.mu_jump("0.4", 0, 2 * mp.pi)) < 1e-28
        assert rp.mu_jump("0.4", "0.1", 0) == float("inf")  # k_m > 0: diverges
        with pytest.raises(ValueError):
            rp.ic_tilde("0.5", "0.6")  # k_m > 1 - chi
        # alpha = pi/2: J of the paper divides by cos(alpha) = 0; the lift-off function doesn't
        a = mp.pi / 2
        v = rp.liftoff_function(5.5, a, "0.3", "0.1", as_mpf=True)
        assert v > 0  # cos(theta) > 0, theta'^2 > 0 and cos(alpha) = 0
        # chi = 1, k_m = 0: the one singular point of the rolling equation
        with pytest.raises(ZeroDivisionError):
            rp.theta_ddot_rolling(mp.pi, 1, "0.3", 1, 0)
        # Painleve case of the slip branch: D <= 0 is reported, not divided through
        *_, dd = rp.slip_dynamics(1.0, 1.0, "0.3", "0.9", 0, 2, 1, as_mpf=True)
        assert dd <= 0

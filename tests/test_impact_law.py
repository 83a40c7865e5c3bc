"""The landing impact law of the core (``mechanics/impact.rs``, ``docs/impact_law.md``),
through the private bridge ``_core.impact``: W and the velocities after an impulse against a
symbolic derivation from the impulse–momentum equations of a rigid body, the energy balance
by an independent route, and the validation of every input."""

import math

import numpy as np
import pytest
import sympy as sp

from eccjump import _core

chi, th, icm, pt, pn = sp.symbols("chi theta I_CM P_t P_n", real=True)
vx, vy, wz = sp.symbols("v_x v_y omega_z", real=True)


def cross(a, b):
    return a[0] * b[1] - a[1] * b[0]


def symbolic_impact():
    """(Δu as a function of the impulse, the velocities after it) from first principles: the
    centre of mass at C + χ(sin θ, cos θ), the contact point P = C − (0, 1), an impulse
    (P_t, P_n) at P; Δv_CM = P (M = 1), I_CM Δω_z = (P − CM) × P; the material point at P
    moves with v_CM + ω_z ẑ × (P − CM), the centre C with v_CM + ω_z ẑ × (C − CM)."""
    r_p = sp.Matrix([-chi * sp.sin(th), -1 - chi * sp.cos(th)])  # P − CM
    r_c = sp.Matrix([-chi * sp.sin(th), -chi * sp.cos(th)])  # C − CM
    imp = sp.Matrix([pt, pn])
    dv, dw = imp, cross(r_p, imp) / icm

    def point(r, v, w):  # velocity of the body point at CM + r
        return sp.Matrix([v[0] - w * r[1], v[1] + w * r[0]])

    du = point(r_p, dv, dw)
    w_matrix = du.jacobian([pt, pn]).applyfunc(sp.simplify)
    after_c = point(r_c, sp.Matrix([vx, vy]) + dv, wz + dw)
    return w_matrix, after_c, dw


W_SYM, AFTER_C, DW = symbolic_impact()
W_NUM = sp.lambdify((chi, th, icm), W_SYM.tolist(), "math")


def test_symbolic_w_is_the_documented_form():
    a, s = 1 + chi * sp.cos(th), chi * sp.sin(th)
    doc = sp.Matrix([[1 + a**2 / icm, -a * s / icm], [-a * s / icm, 1 + s**2 / icm]])
    assert (W_SYM - doc).applyfunc(sp.simplify) == sp.zeros(2, 2)


def random_bodies(n, seed):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        c = rng.uniform(0.0, 1.0)
        km = (1.0 - c) * rng.uniform(0.01, 1.0)
        state = rng.uniform(-3.0, 3.0, 3)
        yield c, km, rng.uniform(0.0, 2 * math.pi), state[0], state[1], -abs(state[2]) - 0.01


def icm_of(c, km):
    _, i_cm, _ = _core.body_derived(c, km)
    return i_cm


def test_w_matches_the_symbolic_derivation():
    for c, km, theta, omega, ldot, bdot in random_bodies(200, 1):
        r = _core.impact(c, km, (theta, omega, ldot, bdot), (0.5, 0.4, 0.5))
        want = W_NUM(c, theta, icm_of(c, km))
        got = [[r["wtt"], r["wtn"]], [r["wtn"], r["wnn"]]]
        scale = abs(want[0][0]) + abs(want[1][1])
        assert np.allclose(got, np.array(want, dtype=float), rtol=1e-12, atol=1e-13 * scale)


def test_velocities_after_the_impulse_match_the_symbolic_body():
    for c, km, theta, omega, ldot, bdot in random_bodies(200, 2):
        r = _core.impact(c, km, (theta, omega, ldot, bdot), (1.0, 0.7, 0.3))
        i_cm = icm_of(c, km)
        # The state's velocities as a rigid body: ω_z = −θ̇, v_CM = (l̇ + χ cos θ θ̇, ḃ − χ sin θ θ̇).
        subs = {
            chi: c,
            th: theta,
            icm: i_cm,
            pt: r["pt"],
            pn: r["pn"],
            wz: -omega,
            vx: ldot + c * math.cos(theta) * omega,
            vy: bdot - c * math.sin(theta) * omega,
        }
        ldot_after, bdot_after = (float(x) for x in AFTER_C.subs(subs))
        omega_after = omega - float(DW.subs(subs))
        assert r["omega"] == pytest.approx(omega_after, rel=1e-12, abs=1e-12)
        assert r["ldot"] == pytest.approx(ldot_after, rel=1e-12, abs=1e-12)
        assert r["bdot"] == pytest.approx(bdot_after, rel=1e-12, abs=1e-12)
        # The contact velocity reported is that of the state after the impact.
        assert r["ut"] == pytest.approx(r["ldot"] - r["omega"], abs=1e-12)
        assert r["un"] == r["bdot"]


def kinetic(c, km, theta, omega, ldot, bdot):
    v2 = (ldot + c * math.cos(theta) * omega) ** 2 + (bdot - c * math.sin(theta) * omega) ** 2
    return 0.5 * v2 + 0.5 * icm_of(c, km) * omega**2


@pytest.mark.parametrize(
    "law", [(0.0, 0.0, 1.0), (0.5, 0.3, 0.6), (2.0, 2.0, 0.0), (1e12, 1e12, 0.0)]
)
def test_energy_lost_equals_the_work_of_the_impulse(law):
    for c, km, theta, omega, ldot, bdot in random_bodies(200, 3):
        r = _core.impact(c, km, (theta, omega, ldot, bdot), law)
        before = kinetic(c, km, theta, omega, ldot, bdot)
        after = kinetic(c, km, theta, r["omega"], r["ldot"], r["bdot"])
        assert after <= before * (1 + 1e-12)
        lost = -(r["normal_work"] + r["friction_work"])
        assert before - after == pytest.approx(lost, abs=1e-10 * before)
        if law[2] == 0.0:
            assert r["un"] == 0.0 and r["bdot"] == 0.0
        if r["sticking"]:
            assert r["ut"] == 0.0


@pytest.mark.parametrize(
    ("args", "name"),
    [
        ((1.5, 0.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.5, 0.5), "chi"),
        ((0.5, 0.6, 0.0, 0.0, 0.0, -1.0, 1.0, 0.5, 0.5), "km"),
        ((0.5, 0.0, 0.0, 0.0, 0.0, -1.0, 1.0, 0.5, 0.5), "km"),  # I_CM = 0: W singular
        ((0.5, 0.3, math.nan, 0.0, 0.0, -1.0, 1.0, 0.5, 0.5), "theta"),
        ((0.5, 0.3, 0.0, math.inf, 0.0, -1.0, 1.0, 0.5, 0.5), "omega"),
        ((0.5, 0.3, 0.0, 0.0, math.nan, -1.0, 1.0, 0.5, 0.5), "ldot"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -math.inf, 1.0, 0.5, 0.5), "bdot"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -1.0, -1.0, 0.0, 0.5), "mu_s"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -1.0, math.nan, 0.0, 0.5), "mu_s"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -1.0, 0.5, 0.6, 0.5), "mu_k"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -1.0, 0.5, -0.1, 0.5), "mu_k"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -1.0, 0.5, 0.5, 1.5), "restitution"),
        ((0.5, 0.3, 0.0, 0.0, 0.0, -1.0, 0.5, 0.5, math.nan), "restitution"),
    ],
)
def test_invalid_input_raises_value_error_naming_it(args, name):
    with pytest.raises(ValueError, match=rf"^{name} ="):
        _core.impact(*args[:2], args[2:6], args[6:])  # body, state, law


def test_separating_contact_gets_no_impulse():
    r = _core.impact(0.5, 0.3, (1.0, 0.4, 0.9, 0.2), (1.0, 0.5, 0.5))
    assert (r["pt"], r["pn"]) == (0.0, 0.0)
    assert (r["omega"], r["ldot"], r["bdot"]) == pytest.approx((0.4, 0.9, 0.2), abs=1e-15)

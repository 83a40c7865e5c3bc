"""Self-checks of the independent scipy full-motion reference (tests/reference_motion.py).

These tests check the reference against itself and against independent routes (the closed
forms of physics.md, a generalized-coordinate mass matrix, conservation laws); they do not
import eccjump.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import reference_motion as rm
from reference_points import JARM_KW, SLIP_FIRST_KW

D = math.radians
JARM = {**JARM_KW, "mu_s": 1.0}
SLIPJ = {**SLIP_FIRST_KW, "mu_s": 1.0}


def ledger_residual(res):
    return res["energy0"] - (res["energy_end"] + res["dissipated_slip"] + res["dissipated_impacts"])


def seq(res, n=None):
    return [(tr[1], tr[2], tr[3]) for tr in res["transitions"][:n]]


# --- Newton–Euler against the closed forms of physics.md (an independent route) -----------


def test_newton_euler_matches_closed_forms():
    rng = np.random.default_rng(0)
    for _ in range(200):
        chi = rng.uniform(0.0, 0.95)
        km = rng.uniform(0.01, 1.0 - chi)
        body = rm.Body(chi, km, rng.uniform(0.0, math.pi / 2))
        th, om = rng.uniform(-7, 7), rng.uniform(-4, 4)
        s, c = math.sin(th), math.cos(th)
        sa, ca = body.sa, body.ca
        ic = body.icm + chi * chi
        # ROLL: roll-eq and the contact forces
        thdd, ldd, bdd, fx, fy = rm.newton_euler(body, rm.ROLL, th, om)
        ref = (chi * om * om * s + chi * math.sin(body.alpha + th) + sa) / (ic + 1 + 2 * chi * c)
        assert thdd == pytest.approx(ref, rel=1e-12, abs=1e-12)
        assert ldd == pytest.approx(thdd, abs=1e-12) and abs(bdd) < 1e-12
        assert fx == pytest.approx(-sa - chi * om * om * s + (1 + chi * c) * thdd, abs=1e-12)
        assert fy == pytest.approx(ca - chi * om * om * c - chi * thdd * s, abs=1e-12)
        # SLIP: K, D of physics.md (Eq. normalslip1)
        for sigma in (-1.0, 1.0):
            mu = rng.uniform(0.0, 2.0)
            k = chi * s - sigma * mu * (1 + chi * c)
            dd = rm.slip_d(body, th, sigma, mu)
            assert dd == pytest.approx(body.icm + chi * k * s, abs=1e-14)
            if abs(dd) < 1e-3:
                continue
            bb = ca - chi * om * om * c
            thdd, ldd, bdd, fx, fy = rm.newton_euler(body, rm.SLIP, th, om, sigma, mu)
            assert thdd == pytest.approx(k * bb / dd, rel=1e-9, abs=1e-11)
            assert fy == pytest.approx(body.icm * bb / dd, rel=1e-9, abs=1e-11)
            assert fx == pytest.approx(sigma * mu * fy, rel=1e-9, abs=1e-11)
            assert ldd == pytest.approx(sa + fx - chi * (c * thdd - s * om * om), abs=1e-9)
        # FLIGHT: the free equations the flight segment integrates
        thdd, ldd, bdd, fx, fy = rm.newton_euler(body, rm.FLIGHT, th, om)
        assert abs(thdd) < 1e-14 and abs(fx) < 1e-14 and abs(fy) < 1e-14
        assert ldd == pytest.approx(chi * om * om * s + sa, abs=1e-13)
        assert bdd == pytest.approx(chi * om * om * c - ca, abs=1e-13)


# --- impact law ------------------------------------------------------------------------------


def mass_matrix(body, th):
    """Generalized mass matrix in (θ̇, l̇, ḃ) from T = ½|ṙ_CM|² + ½ Ĩ_CM θ̇²."""
    chi = body.chi
    s, c = math.sin(th), math.cos(th)
    return np.array(
        [[body.icm + chi * chi, chi * c, -chi * s], [chi * c, 1.0, 0.0], [-chi * s, 0.0, 1.0]]
    )


JAC = np.array([[-1.0, 1.0, 0.0], [0.0, 0.0, 1.0]])  # (u_t, u_n) = JAC (θ̇, l̇, ḃ)


def kinetic(body, th, om, ld, bd):
    return rm.energy(body, th, om, 0.0, ld, 1.0, bd) - rm.energy(body, th, 0.0, 0.0, 0.0, 1.0, 0.0)


def momentum_about_contact(body, th, om, ld, bd):
    """Clockwise angular momentum about the contact point P = (l, 0)."""
    chi = body.chi
    s, c = math.sin(th), math.cos(th)
    xd, yd = ld + chi * c * om, bd - chi * s * om
    return body.icm * om + (1 + chi * c) * xd - chi * s * yd


def random_impacts(n, seed):
    rng = np.random.default_rng(seed)
    for _ in range(n):
        chi = rng.uniform(0.0, 0.98)
        km = rng.uniform(0.005, 1.0 - chi)
        body = rm.Body(chi, km, rng.uniform(0.0, math.pi / 2))
        th, om = rng.uniform(-7, 7), rng.uniform(-5, 5)
        ld, bd = rng.uniform(-5, 5), -rng.uniform(1e-3, 3.0)
        mu_s = rng.choice([0.0, 0.1, 0.5, 1.0, 3.0, rng.uniform(0, 2)])
        mu_k = mu_s * rng.choice([1.0, rng.uniform(0.3, 1.0)])
        e = rng.choice([0.0, 0.3, 0.5, 1.0, rng.uniform()])
        yield body, th, om, ld, bd, mu_s, mu_k, e


def test_w_matches_mass_matrix_and_the_velocity_update():
    for body, th, om, ld, bd, *_ in random_impacts(200, 1):
        w = np.array(rm.contact_w(body, th))
        w = np.array([[w[0], w[1]], [w[1], w[2]]])
        ref = JAC @ np.linalg.solve(mass_matrix(body, th), JAC.T)
        np.testing.assert_allclose(w, ref, rtol=1e-9, atol=1e-9)
        assert np.all(np.linalg.eigvalsh(w) > 0)
        # the velocity update of apply_impact realises Δu = W P
        om2, ld2, bd2, pt, pn = rm.apply_impact(body, th, om, ld, bd, 0.7, 0.5, 0.4)
        du = np.array([(ld2 - om2) - (ld - om), bd2 - bd])
        np.testing.assert_allclose(du, w @ [pt, pn], rtol=1e-9, atol=1e-9)


def test_impacts_never_gain_energy_and_conserve_momentum_about_contact():
    worst = 0.0
    for body, th, om, ld, bd, mu_s, mu_k, e in random_impacts(3000, 2):
        om2, ld2, bd2, pt, pn = rm.apply_impact(body, th, om, ld, bd, mu_s, mu_k, e)
        k0, k1 = kinetic(body, th, om, ld, bd), kinetic(body, th, om2, ld2, bd2)
        assert k1 <= k0 + 1e-12 * (1 + k0)
        worst = max(worst, (k1 - k0) / (1 + k0))
        h0 = momentum_about_contact(body, th, om, ld, bd)
        h1 = momentum_about_contact(body, th, om2, ld2, bd2)
        assert h1 == pytest.approx(h0, rel=1e-10, abs=1e-10)
        assert pn > 0.0 and bd2 >= -1e-12  # no interpenetration after it
        assert abs(pt) <= max(mu_s, mu_k) * pn * (1 + 1e-12) + 1e-15  # inside the cone
        if e == 0.0:
            assert abs(bd2) < 1e-12  # e = 0 leaves u_n = 0
    print(f"largest relative KE change over 3000 impacts: {worst:+.2e}")


def test_frictionless_elastic_impact_conserves_kinetic_energy():
    for body, th, om, ld, bd, *_ in random_impacts(500, 3):
        om2, ld2, bd2, pt, _ = rm.apply_impact(body, th, om, ld, bd, 0.0, 0.0, 1.0)
        assert pt == 0.0
        k0, k1 = kinetic(body, th, om, ld, bd), kinetic(body, th, om2, ld2, bd2)
        assert k1 == pytest.approx(k0, rel=1e-11, abs=1e-12)


def test_huge_friction_plastic_impact_rolls_iff_normal_speed_stays_nonpositive():
    """physics.md: with e = 0, μ → ∞ the body leaves rolling exactly when u_n stays ≤ 0
    while u_t is removed by the tangential impulse at p = 0⁺."""
    sticking = sliding = 0
    for body, th, om, ld, bd, *_ in random_impacts(1000, 4):
        wtt, wtn, _ = rm.contact_w(body, th)
        ut, un = ld - om, bd
        un_after_t = un + wtn * (-ut / wtt)  # u_n once u_t is removed
        if abs(un_after_t) < 1e-6:
            continue
        om2, ld2, *_ = rm.apply_impact(body, th, om, ld, bd, 1e9, 1e9, 0.0)
        ut2 = ld2 - om2
        if un_after_t < 0:
            assert abs(ut2) < 1e-6 * (1 + abs(ut))
            sticking += 1
        else:
            assert abs(ut2) > 1e-9  # compression ended while the contact point slid
            sliding += 1
    assert sticking > 0 and sliding > 0
    print(f"mu -> inf, e = 0: {sticking} stick, {sliding} leave sliding")


# --- full runs -------------------------------------------------------------------------------


def test_jarm_reference_numbers_and_first_transitions():
    res = rm.simulate_reference(**JARM, t_max=8.0)
    print(rm.format_transitions(res))
    _, frm, to, reason, th, om, *_ = res["transitions"][1]
    assert (frm, to, reason) == ("ROLL", "FLIGHT", "liftoff")
    assert math.degrees(th) == pytest.approx(334.344, abs=1e-3)
    body = rm.Body(JARM["chi"], JARM["km"], JARM["alpha"])
    _, _, _, fx, fy = rm.newton_euler(body, rm.ROLL, th, om)
    assert fy == pytest.approx(0.01543, abs=1e-5)
    assert fx == pytest.approx(-0.00516, abs=1e-5)
    assert seq(res, 4) == [
        (None, "ROLL", "start"),
        ("ROLL", "FLIGHT", "liftoff"),
        ("FLIGHT", "SLIP", "impact"),
        ("SLIP", "ROLL", "stick"),
    ]
    assert abs(ledger_residual(res)) < 1e-7


def test_jarm_normal_force_rule_leaves_later_at_slip_onset():
    paper = rm.simulate_reference(**JARM, t_max=4.5)
    nf = rm.simulate_reference(**JARM, rule="normal_force", t_max=4.5)
    print(rm.format_transitions(nf))
    assert seq(nf, 2) == [(None, "ROLL", "start"), ("ROLL", "FLIGHT", "slip_inconsistent")]
    th_p, th_n = paper["transitions"][1][4], nf["transitions"][1][4]
    assert 0.0 < math.degrees(th_n - th_p) < 2.0  # physics.md: later, by up to about 2°


def test_slip_first_reference_numbers_and_first_transitions():
    res = rm.simulate_reference(**SLIPJ, t_max=7.5)
    print(rm.format_transitions(res))
    assert math.degrees(res["transitions"][1][4]) == pytest.approx(316.47, abs=0.01)
    # outside the JARM region the first lift-off is from SLIP (at F_y = 0, both rules agree)
    first = seq(res, 4)
    assert first == [
        (None, "ROLL", "start"),
        ("ROLL", "SLIP", "slip"),
        ("SLIP", "FLIGHT", "normal_force"),
        ("FLIGHT", "SLIP", "impact"),
    ]
    nf = rm.simulate_reference(**SLIPJ, rule="normal_force", t_max=7.5)
    assert seq(nf) == seq(res)
    for a, b in zip(nf["transitions"], res["transitions"], strict=True):
        assert a[0] == pytest.approx(b[0], abs=1e-9)


@pytest.mark.parametrize(
    "kw",
    [
        {**JARM, "restitution": 0.5},
        {**SLIPJ, "mu_k": 0.6},
        {**SLIPJ, "mu_s": 0.2},
        {**SLIPJ, "restitution": 1.0},
        {"chi": 0.3, "km": 0.3, "alpha": D(30.0), "mu_s": 0.5, "slip0": -2.0},
        {"chi": 0.5, "km": 0.2, "alpha": D(20.0), "mu_s": 1.0, "omega0": 2.0},
    ],
)
def test_energy_ledger_closes(kw):
    res = rm.simulate_reference(**kw, t_max=12.0, max_transitions=30)
    assert res["status"] in ("t_max", "max_transitions")
    assert res["dissipated_slip"] >= 0.0 and res["dissipated_impacts"] >= 0.0
    assert abs(ledger_residual(res)) < 1e-7


def test_start_modes():
    flies = rm.simulate_reference(
        chi=0.5, km=0.2, alpha=D(20.0), mu_s=1.0, omega0=2.0, t_max=1.0
    )  # χθ̇0² cos θ0 = 2 > cos α
    assert seq(flies, 1) == [(None, "FLIGHT", "start")]
    slips = rm.simulate_reference(chi=0.3, km=0.3, alpha=D(60.0), mu_s=0.1, t_max=1.0)
    assert seq(slips, 1) == [(None, "SLIP", "start")]
    sliding = rm.simulate_reference(chi=0.3, km=0.3, alpha=D(30.0), mu_s=0.5, slip0=1.0, t_max=1)
    assert seq(sliding, 2) == [(None, "SLIP", "start"), ("SLIP", "ROLL", "stick")]
    assert sliding["transitions"][0][7] - sliding["transitions"][0][5] == 1.0


def test_jam_and_painleve(monkeypatch):
    # sliding with v > 0 at θ ≈ 271° on a heavy far-off-centre point mass: D < 0, L < 0
    jam = rm.simulate_reference(
        chi=0.7, km=0.05, alpha=D(2.5), mu_s=1.1, theta0=4.73, omega0=0.08, slip0=1.0
    )
    assert jam["status"] == "jam" and len(jam["transitions"]) == 1
    # A true Painlevé jam: continued in the impulse, D decays like exp(−cP) and would reach
    # about 1e-156 before the slip velocity (4.4 when D = 1e-12) returned to 0.
    kw = {"chi": 0.9, "km": 0.05, "alpha": D(85.0), "mu_s": 1.0, "t_max": 10.0}
    pl = rm.simulate_reference(**kw)
    print(rm.format_transitions(pl))
    assert pl["status"] == "painleve" and pl["message"].startswith("Painlevé jam")
    assert seq(pl) == [(None, "ROLL", "start"), ("ROLL", "SLIP", "slip")]
    assert pl["impulse_pieces"] == 1
    t, _, th, om, _, ld, *_ = pl["end"]
    assert 260.0 < math.degrees(th) < 280.0  # physics.md: near θ ≈ 270°
    body = rm.Body(0.9, 0.05, D(85.0))
    sigma = -math.copysign(1.0, ld - om)
    assert rm.slip_d(body, th, sigma, 1.0) == pytest.approx(rm.D_JAM, rel=1e-3)
    assert abs(ld - om) > 4.0  # the slip is still fast
    assert abs(ledger_residual(pl)) < 1e-8
    # t and θ hardly depend on the thresholds, the velocities do (physics.md): dt/dP and
    # dθ/dP vanish with D, the velocities change linearly in P ∝ −log D
    monkeypatch.setattr(rm, "D_JAM", 1e-10)
    monkeypatch.setattr(rm, "D_SWITCH", 1e-2)
    pl10 = rm.simulate_reference(**kw)
    assert pl10["status"] == "painleve"
    assert pl10["end"][0] == pytest.approx(t, abs=1e-9)
    assert pl10["end"][2] == pytest.approx(th, abs=1e-9)
    assert 1e-3 < abs(pl10["end"][3] - om) < 0.1


def test_impulse_form_is_the_slip_divided_by_the_normal_force():
    rng = np.random.default_rng(5)
    checked = 0
    for _ in range(300):
        chi = rng.uniform(0.0, 0.95)
        body = rm.Body(chi, rng.uniform(0.01, 1.0 - chi), rng.uniform(0.0, math.pi / 2))
        th, om, sigma, mu = rng.uniform(-7, 7), rng.uniform(-4, 4), rng.choice([-1.0, 1.0]), 1.3
        if abs(rm.slip_d(body, th, sigma, mu)) < 1e-3 or abs(rm.lift_l(body, th, om)) < 1e-3:
            continue
        thdd, ldd, _, _, fy = rm.newton_euler(body, rm.SLIP, th, om, sigma, mu)
        x = rm.newton_euler_impulse(body, th, om, sigma, mu)
        np.testing.assert_allclose(x, [thdd / fy, ldd / fy, 1.0 / fy], rtol=1e-9, atol=1e-12)
        checked += 1
    assert checked > 200


def test_impulse_form_is_finite_where_d_vanishes():
    from scipy.optimize import brentq

    body = rm.Body(0.9, 0.05, D(85.0))
    sigma, mu, om = -1.0, 1.0, 1.4
    th = brentq(lambda x: rm.slip_d(body, x, sigma, mu), D(265.0), D(275.0), xtol=1e-15)
    a, b, w = rm.newton_euler_impulse(body, th, om, sigma, mu)
    k = body.chi * math.sin(th) - sigma * mu * (1.0 + body.chi * math.cos(th))
    assert abs(w) < 1e-12  # 1/F_y = D/(Ĩ_CM B), D at rounding level, Ĩ_CM B = 0.008
    assert a == pytest.approx(k / body.icm, rel=1e-12)  # θ̈/F_y = K/Ĩ_CM
    assert b == pytest.approx(sigma * mu - body.chi * math.cos(th) * a, rel=1e-12)


#: Issue 38's reproducer: chi, km, alpha, then the options.
ISSUE38 = (
    (0.677301413067792, 0.17587848529965222, 1.3179033062341512),
    {
        "mu_s": 1.4800299961460412,
        "mu_k": 1.0117188986517158,
        "theta0": 3.479669684013747,
        "omega0": 0.08695780632623507,
        "t_max": 30.0,
    },
)


def test_the_issue_38_slip_goes_on_through_its_painleve_point():
    args, kw = ISSUE38
    res = rm.simulate_reference(*args, **kw)
    print(rm.format_transitions(res))
    assert res["status"] == "t_max" and res["impulse_pieces"] >= 1
    assert seq(res) == [
        (None, "SLIP", "start"),
        ("SLIP", "SLIP", "reverse"),
        ("SLIP", "FLIGHT", "normal_force"),
        ("FLIGHT", "SLIP", "impact"),
        ("SLIP", "FLIGHT", "normal_force"),
    ]
    times = [tr[0] for tr in res["transitions"]]
    # the issue's figures, to their printed digits
    assert times[1] == pytest.approx(4.1456228514, abs=1e-10)
    assert times[2] == pytest.approx(4.1599367580, abs=1e-10)
    assert times[3] == pytest.approx(14.028, abs=1e-3)
    th = res["transitions"][1][4]
    d_before = rm.slip_d(rm.Body(*args), th, -1.0, kw["mu_k"])  # the slip had σ = −1
    assert d_before == pytest.approx(2.1e-7, rel=0.05)  # v = 0 while D is still 2.1e-7
    assert abs(ledger_residual(res)) < 1e-8


@pytest.mark.parametrize("switch", [1e-1, 1e-2, 1e-4])
def test_the_switch_to_the_impulse_changes_nothing_but_rounding(monkeypatch, switch):
    args, kw = ISSUE38
    base = rm.simulate_reference(*args, **kw)
    monkeypatch.setattr(rm, "D_SWITCH", switch)
    other = rm.simulate_reference(*args, **kw)
    assert seq(other) == seq(base)
    for a, b in zip(other["transitions"], base["transitions"], strict=True):
        np.testing.assert_allclose(a[4:], b[4:], rtol=1e-8, atol=1e-8)
        assert a[0] == pytest.approx(b[0], abs=1e-8)


def exact_gap(body, th0, om, bd0, tau):
    """b − 1 in flight from a contact start (b = 1): C's height = the CM's parabola minus
    χ cos θ, θ linear in τ (docs/motion.md)."""
    chi = body.chi
    yd0 = bd0 - chi * math.sin(th0) * om  # the CM's normal velocity
    half = 0.5 * om * tau  # cos θ0 − cos(θ0 + ωτ) without cancellation
    return yd0 * tau - 0.5 * body.ca * tau**2 + 2.0 * chi * np.sin(th0 + half) * np.sin(half)


@pytest.mark.parametrize(
    "kw",
    [
        {**JARM},
        {**JARM, "rule": "normal_force"},
        {**SLIPJ},
        {**JARM, "restitution": 0.5},
        {"chi": 0.5, "km": 0.2, "alpha": D(20.0), "mu_s": 1.0, "omega0": 2.0},
    ],
)
def test_flight_lands_at_the_first_root_of_the_exact_gap(kw):
    """The flight segment neither lands at the lift-off itself nor misses an earlier touch:
    compare every landing with the first root of the closed-form gap (fine scan + brentq)."""
    from scipy.optimize import brentq

    body = rm.Body(kw["chi"], kw["km"], kw["alpha"])
    res = rm.simulate_reference(**kw, t_max=12.0, max_transitions=12)
    checked = 0
    for a, b in zip(res["transitions"], res["transitions"][1:], strict=False):
        if a[2] != "FLIGHT" or b[1] != "FLIGHT":
            continue
        t0, th0, om, bd0 = a[0], a[4], a[5], a[9]
        dur = b[0] - t0
        assert dur > 0.0
        end = dur + 0.1
        taus = np.union1d(np.linspace(0.0, end, 20001)[1:], np.geomspace(1e-7, end, 2001))
        g = exact_gap(body, th0, om, bd0, taus)
        first = int(np.argmax(g < -1e-15))  # below the rounding of the closed form
        assert g[first] < 0.0
        assert first > 0
        lo = taus[first - 1]
        args = (body, th0, om, bd0)
        root = brentq(lambda s, args=args: exact_gap(*args, s), lo, taus[first], xtol=1e-15)
        assert dur == pytest.approx(root, abs=1e-8 + 1e-8 * root)
        checked += 1
    assert checked >= 1


def test_first_transitions_do_not_depend_on_the_settle_speed(monkeypatch):
    kw = {**JARM, "restitution": 0.5, "t_max": 6.0, "max_transitions": 12}
    base = rm.simulate_reference(**kw)
    print(rm.format_transitions(base))
    assert ("FLIGHT", "ROLL", "settle") in seq(base)
    monkeypatch.setattr(rm, "SETTLE_SPEED", 1e-4)
    coarse = rm.simulate_reference(**kw)
    n = 6  # start, lift-off and four bounces: all above 1e-4
    assert seq(coarse, n) == seq(base, n)
    for a, b in zip(coarse["transitions"][:n], base["transitions"][:n], strict=True):
        np.testing.assert_allclose(a[4:], b[4:], rtol=1e-12, atol=1e-12)
    assert len(coarse["transitions"]) < len(base["transitions"])

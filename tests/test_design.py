"""Experiment design (eccjump.design): the margins are confirmed by classifying perturbed
inputs, the control design really slips first, the body conversions round-trip against an
independent route (sympy mass integrals), the sheet and the command line, bad input."""

from __future__ import annotations

import json
import math

import numpy as np
import pytest
import sympy as sp
from fuzz_cases import run_cli_inprocess
from reference_points import JARM_BODY, JARM_BODY_ARGS, SLIP_FIRST_BODY

import eccjump
from eccjump import Cylinder, Reason, build, design, jarm, simulate

RULES = ("paper", "normal_force")
SLIPS = (int(Reason.SLIP_BEFORE), int(Reason.SLIP_AT_JUMP))
RANGE = (math.radians(10), math.radians(40))


@pytest.fixture(scope="module")
def jump() -> eccjump.Design:
    return design(RANGE, 0.6, 0.1, radius=0.05, mass=0.5, grid=12)


@pytest.fixture(scope="module")
def control() -> eccjump.Design:
    return design(RANGE, 0.6, 0.1, target="slip", radius=0.05, mass=0.5, grid=8)


def verdict(d, alpha, chi, km, mu, n=None):
    """The design's verdict at a point under both rules (a JARM on turn n if given); none
    beyond the ramp's range (a scalar alpha there is an error of jarm, not a point)."""
    if not 0.0 <= alpha <= math.pi / 2:
        return False
    res = [jarm(alpha, chi, km, mu, n, rule=r, max_turns=d.max_turns) for r in RULES]
    if d.target == "jarm":
        return bool(res[0].is_jarm & res[1].is_jarm)
    return all(int(r.reason) in SLIPS for r in res)


def nearest_side(m):
    """+1 if the nearer boundary is above the value, -1 if below."""
    return 1.0 if m.hi - m.value < m.value - m.lo else -1.0


# --- the margins are confirmed by classifying perturbed inputs -----------------------------


@pytest.mark.parametrize("which", ["jump", "control"])
def test_alpha_margin(which, request):
    d = request.getfixturevalue(which)
    m, b, mu = d.margin("alpha"), d.body, d.mu_s_worst
    n = d.turn if d.target == "jarm" else None
    assert m.margin > 0 and m.relative == pytest.approx(m.margin / d.alpha)
    for t in np.linspace(-1, 1, 11) * (1 - 1e-6):  # inside: kept, both ways (in [0, pi/2])
        alpha = min(d.alpha + t * m.margin, math.pi / 2)
        assert verdict(d, alpha, b.chi, b.km, mu, n), t
    side = nearest_side(m)
    assert not verdict(d, d.alpha + side * (m.margin + 1e-9), b.chi, b.km, mu, n)
    assert m.lo < d.alpha < m.hi


@pytest.mark.parametrize("which", ["jump", "control"])
def test_rod_position_margin(which, request):
    d = request.getfixturevalue(which)
    m, km, mu = d.margin("rod"), d.body.km, d.mu_s_worst
    n = d.turn if d.target == "jarm" else None
    assert m.value == pytest.approx(d.rod_position, rel=1e-12)
    assert m.margin > 0
    for t in np.linspace(-1, 1, 11) * (1 - 1e-6):
        rho = min(m.value + t * m.margin, 1.0)  # a side without a boundary ends at the rim
        assert verdict(d, d.alpha, rho * (1 - km), km, mu, n), t
    side = nearest_side(m)
    rho = m.value + side * (m.margin + 1e-9)
    assert not verdict(d, d.alpha, rho * (1 - km), km, mu, n)


def test_mu_margin_of_the_jarm(jump):
    d, m, b = jump, jump.margin("mu_s"), jump.body
    mu_min = m.lo
    assert m.margin == pytest.approx(d.mu_s - d.mu_s_err - mu_min, abs=1e-12)
    assert math.isinf(m.hi)  # no upper side: a JARM is monotone in mu_s
    for mu in (d.mu_s - d.mu_s_err, d.mu_s, d.mu_s + d.mu_s_err, 10 * d.mu_s):
        assert verdict(d, d.alpha, b.chi, b.km, mu, d.turn)
    # slightly less than the margin below the worst case: kept; slightly more: lost
    assert verdict(d, d.alpha, b.chi, b.km, d.mu_s_worst - m.margin * (1 - 1e-6), d.turn)
    assert not verdict(d, d.alpha, b.chi, b.km, d.mu_s_worst - m.margin * (1 + 1e-6), d.turn)


def test_mu_margin_of_the_control(control):
    d, m, b = control, control.margin("mu_s"), control.body
    assert d.mu_s_worst == d.mu_s + d.mu_s_err
    for mu in (d.mu_s - d.mu_s_err, d.mu_s, d.mu_s_worst):
        assert verdict(d, d.alpha, b.chi, b.km, mu)
    if math.isfinite(m.hi):
        assert verdict(d, d.alpha, b.chi, b.km, d.mu_s_worst + m.margin * (1 - 1e-6))
        assert not verdict(d, d.alpha, b.chi, b.km, d.mu_s_worst + m.margin * (1 + 1e-6))


def test_the_score_is_the_smallest_relative_margin(jump, control):
    for d in (jump, control):
        assert d.score == min(m.relative for m in d.margins) > 0
        assert RANGE[0] <= d.alpha <= RANGE[1]
        assert 0.01 <= d.body.km <= 0.9 and 0.05 <= d.rod_position <= 0.95 + 1e-12


def test_the_design_beats_the_grid_points_it_started_from(jump):
    """The refinement ends no worse than a few nearby points of the design space."""
    from eccjump.studies.design.margins import _margins, _score, _Spec

    spec = _Spec("jarm", jump.max_turns)
    km, rho = jump.body.km, jump.rod_position
    for da, dr in ((0.02, 0), (-0.02, 0), (0, 0.02), (0, -0.02)):
        ms = _margins(spec, jump.alpha + da, km, rho + dr, 0.6, 0.1, 1e-9)
        assert _score(ms) <= jump.score + 1e-6


def test_sensitivity_agrees_with_the_margins(jump, control):
    """A 5 % error in alpha or the rod position changes the verdict exactly when it moves
    the input past its margin, in that direction."""
    for d in (jump, control):
        rows = {s.input: s for s in d.sensitivity}
        for name, key in (("ramp angle alpha", "alpha"), ("rod position r", "rod")):
            m, s = d.margin(key), rows[name]
            for cell, sign in ((s.minus, -1.0), (s.plus, 1.0)):
                moved = m.value * (1 + sign * d.error)
                assert (cell == "kept") == (m.lo < moved < m.hi), (name, cell)
        assert rows["friction mu_s"].minus == "kept"  # relative mu margin > 5 % here
        assert d.margin("mu_s").relative > d.error


# --- the control really slips first ---------------------------------------------------------


def test_the_control_slips_first_under_both_rules(control):
    b = control.body
    assert set(control.reasons.values()) <= {"SLIP_BEFORE", "SLIP_AT_JUMP"}
    for mu in (0.5, 0.6, 0.7):
        for r in RULES:
            assert int(jarm(control.alpha, b.chi, b.km, mu, rule=r).reason) in SLIPS
            run = simulate(b, control.alpha, mu_s=mu, rule=r, max_transitions=3)
            assert run.transitions[0].to_mode == "ROLL"
            assert run.transitions[1].to_mode == "SLIP", run.mode_names()
    for f in control.flights:
        assert f.modes[:2] == ("ROLL", "SLIP")


def test_the_jarm_jumps_out_of_rolling(jump):
    for f in jump.flights:
        assert f.modes[:2] == ("ROLL", "FLIGHT")
        assert f.apex > 0 and f.distance > 0 and f.duration > 0
    assert jump.flights[0].theta_liftoff_deg == pytest.approx(jump.theta_deg["paper"], abs=1e-6)
    assert jump.flights[1].theta_liftoff_deg == pytest.approx(
        jump.theta_deg["normal_force"], abs=1e-3
    )
    # SI: the first flight in metres and seconds, the dimensionless run scaled
    b = jump.body
    run = simulate(b, jump.alpha, mu_s=0.6, max_transitions=2, t_max=1e4).flights[0]
    assert jump.flights[0].apex == pytest.approx(run.apex * 0.05, rel=1e-12)
    assert jump.flights[0].distance == pytest.approx(run.distance * 0.05, rel=1e-12)
    T = math.sqrt(0.05 / 9.81)
    assert jump.flights[0].duration == pytest.approx((run.t_landing - run.t_liftoff) * T)


def test_a_fixed_body_keeps_its_body():
    body = Cylinder(*JARM_BODY)

    d = design((math.radians(5), math.radians(60)), 1.0, body=body, grid=8)
    assert d.body.km == body.km and d.body.chi == pytest.approx(body.chi, abs=1e-15)
    assert verdict(d, d.alpha, body.chi, body.km, 1.0)
    lo, hi = eccjump.classification.boundary.alpha_interval_around(
        d.alpha, body.chi, body.km, 1.0, d.turn
    )
    assert d.margin("alpha").lo >= lo - 1e-12 and d.margin("alpha").hi <= hi + 1e-12


# --- the body conversions --------------------------------------------------------------------


def shell_and_rod_by_integrals():
    """M, the CM offset d and I_C about the axis of a uniform ring (mass m_C, radius R) plus
    a point rod (m_P at distance r), by integrating over the ring (sympy)."""
    m_c, m_p, R, r, phi = sp.symbols("m_C m_P R r phi", positive=True)
    lam = m_c / (2 * sp.pi)  # mass per radian of the ring
    M = sp.integrate(lam, (phi, 0, 2 * sp.pi)) + m_p
    x_cm = (sp.integrate(lam * R * sp.cos(phi), (phi, 0, 2 * sp.pi)) + m_p * r) / M
    y_cm = sp.integrate(lam * R * sp.sin(phi), (phi, 0, 2 * sp.pi)) / M
    I_C = sp.integrate(lam * R**2, (phi, 0, 2 * sp.pi)) + m_p * r**2
    assert sp.simplify(y_cm) == 0
    return (m_c, m_p, R, r), sp.lambdify((m_c, m_p, R, r), (M, sp.simplify(x_cm), I_C))


@pytest.mark.parametrize(
    ("chi", "km", "R", "M"),
    [
        (*JARM_BODY, 0.05, 0.5),
        (*SLIP_FIRST_BODY, 1.0, 1.0),
        (0.0, 0.3, 0.2, 3.0),
        (0.9, 0.1, 2.0, 0.1),
    ],
)
def test_build_round_trips(chi, km, R, M):
    body = Cylinder(chi, km)
    b = build(body, radius=R, mass=M)
    # independent route: the mass integrals of the ring plus rod
    _, f = shell_and_rod_by_integrals()
    M_int, d_int, I_int = f(b.shell_mass, b.rod_mass, R, b.rod_position)
    assert M_int == pytest.approx(M, rel=1e-14)
    assert d_int == pytest.approx(b.d, rel=1e-12, abs=1e-15)
    assert I_int == pytest.approx(b.I_C, rel=1e-12)
    assert b.d / R == pytest.approx(chi, abs=1e-15)
    # the paper's relations: rod at r/R = chi/(1 - km), Ic = km + chi^2/(1 - km)
    assert b.rod_position / R == pytest.approx(chi / (1 - km), rel=1e-12, abs=1e-15)
    # back through the core's constructors
    s = Cylinder.from_shell_and_line(b.shell_mass, b.rod_mass, R, b.d)
    i = Cylinder.from_inertia(M, R, b.d, b.I_C)
    for c in (s, i):
        assert c.chi == pytest.approx(chi, abs=1e-12) and c.km == pytest.approx(km, abs=1e-12)


def test_km_from_inertia_is_the_root_in_range():
    """Ic = km + chi^2/(1 - km) is increasing in km on [0, 1 - chi], from chi^2 to 1: one
    root, which the sympy solution and the core agree on."""
    k, chi, ic = sp.symbols("k chi I", real=True)
    roots = sp.solve(sp.Eq(ic, k + chi**2 / (1 - k)), k)
    for c, icv in ((0.3, 0.2), (0.5, 0.6), (0.1, 0.011), (0.7, 0.99)):
        vals = [float(r.subs({chi: c, ic: icv})) for r in roots]
        inside = [v for v in vals if -1e-12 <= v <= 1 - c + 1e-12]
        assert len(inside) == 1
        assert Cylinder.from_inertia(1.0, 1.0, c, icv).km == pytest.approx(inside[0], abs=1e-12)


# --- the sheet and the command line ----------------------------------------------------------


def test_the_sheet_says_what_the_lab_needs(jump, control):
    text = str(jump)
    for words in ("shell", "rod", "alpha =", "lift-off", "margins", "apex", "sensitivity"):
        assert words in text
    assert "0.05 m" in text and "kg" in text
    assert "slips" in control.sheet()
    s = json.loads(json.dumps(jump.to_dict()))
    assert s["alpha_deg"] == pytest.approx(math.degrees(jump.alpha))
    assert {m["name"] for m in s["margins"]} == {"alpha", "mu_s", "rod"}
    assert len(s["sensitivity"]) == len(jump.sensitivity)


@pytest.mark.slow
def test_cli_design():
    argv = ["design", "--alpha-range", "10", "40", "--mu-s", "0.6", "--mu-s-err", "0.1"]
    argv += ["--radius", "0.05", "--mass", "0.5", "--grid", "8"]
    code, out, err = run_cli_inprocess(argv)
    assert code == 0, err
    assert "lift-off" in out and "robustness" in out
    code, out, err = run_cli_inprocess([*argv, "--json", "--target", "slip"])
    assert code == 0, err
    assert json.loads(out)["target"] == "slip"
    code, out, err = run_cli_inprocess(["design", "--alpha-range", "10", "40", "--mu-s", "-1"])
    assert code == 2 and "mu_s" in err and "Traceback" not in err
    odds = ["--sd", "alpha", "2", "--sd", "chi", "0.02", "--samples", "200"]
    fixed = [*JARM_BODY_ARGS, "--grid", "4"]  # only the angle is searched
    code, out, err = run_cli_inprocess(
        [*argv, *fixed, *odds, "--maximise", "probability", "--json"]
    )
    assert code == 0, err
    sheet = json.loads(out)
    assert sheet["tolerances"] == {"alpha": math.radians(2), "chi": 0.02}
    assert 0 <= sheet["p_success"]["low"] <= sheet["p_success"]["p"] <= 1
    code, out, err = run_cli_inprocess([*argv, "--sd", "chi", "x"])
    assert code == 2 and "--sd chi" in err and "Traceback" not in err


# --- a design that reaches P(JARM) >= p_target (issue 50, item 5) ---------------------------

WIDE_CHI = {"chi": 0.03}  # the best-margin design has P(JARM) 0.71; another candidate 0.84


def test_p_target_moves_the_design_to_one_that_reaches_it():
    kw = {"grid": 8, "tolerances": WIDE_CHI, "samples": 1000, "seed": 3}
    plain = design(RANGE, 0.6, 0.1, **kw)
    d = design(RANGE, 0.6, 0.1, p_target=0.8, **kw)
    assert d.p_jarm.low >= 0.8 and d.p_jarm.n_valid == 1000
    assert d.score < plain.score  # it gave up margin to reach the target
    assert d.reasons == {"paper": "JARM", "normal_force": "JARM"}
    # checked by an independent uncertainty study at the design: the same samples, bit for bit
    by_rule = {
        r: eccjump.uncertainty(d.body, d.alpha, d.mu_s, sd=WIDE_CHI, n=1000, seed=3, rule=r)
        for r in ("paper", "normal_force")
    }
    lower = by_rule[d.p_jarm.rule]
    assert lower.p_jarm == min(u.p_jarm for u in by_rule.values()) == d.p_jarm.p
    assert lower.p_jarm_ci == (d.p_jarm.low, d.p_jarm.high)
    assert "P(JARM)" in str(d) and json.loads(json.dumps(d.to_dict()))["p_jarm"]["p"] == d.p_jarm.p


def test_p_target_scores_every_candidate_in_one_batch_per_rule(monkeypatch):
    from eccjump.studies.design import target

    calls = []
    real_fields = target.point_fields

    def counted(nominal, *args, **kwargs):
        calls.append(nominal["alpha"].size)
        return real_fields(nominal, *args, **kwargs)

    monkeypatch.setattr(target, "point_fields", counted)
    design(RANGE, 0.6, 0.1, grid=8, tolerances=WIDE_CHI, samples=200, p_target=0.5)
    assert len(calls) == 2 and calls[0] == calls[1] > 1  # the two rules, all candidates


def test_an_unreachable_p_target_says_the_best_found():
    with pytest.raises(ValueError, match=r"^p_target = 0\.99: no design .* P\(JARM\) 0\.8") as info:
        design(RANGE, 0.6, 0.1, grid=8, tolerances=WIDE_CHI, samples=1000, seed=3, p_target=0.99)
    assert len(str(info.value)) <= 200


def test_without_a_target_nothing_changes():
    plain = design(RANGE, 0.6, 0.1, grid=8)
    assert plain == design(RANGE, 0.6, 0.1, grid=8, p_target=None)
    assert plain.p_jarm is None and plain.p_target is None
    odds = design(RANGE, 0.6, 0.1, grid=8, tolerances=WIDE_CHI, samples=500)
    assert odds.p_jarm is None and odds.alpha == plain.alpha and odds.body == plain.body


def test_the_cli_targets_p_jarm_with_the_maps_tolerances():
    argv = ["design", "--alpha-range", "10", "40", "--mu-s", "0.6", "--mu-s-err", "0.1"]
    argv += ["--grid", "8", "--samples", "1000", "--sd", "chi=0.03", "--json"]
    code, out, err = run_cli_inprocess([*argv, "--p-target", "0.8"])
    assert code == 0, err
    sheet = json.loads(out)
    assert sheet["p_target"] == 0.8 and sheet["p_jarm"]["low"] >= 0.8
    code, out, err = run_cli_inprocess([*argv, "--p-target", "1.5"])
    assert code == 2 and "p_target" in err and "Traceback" not in err
    code, out, err = run_cli_inprocess([*argv, "--sd", "alpha=0.25,chi=0.002"])
    assert code == 2 and "--sd chi: given twice" in err


# --- bad input --------------------------------------------------------------------------------


@pytest.mark.parametrize(
    ("kwargs", "exc", "name"),
    [
        ({"alpha_range": (0.5, 0.2)}, ValueError, "alpha_range"),
        ({"alpha_range": (0.1, 2.0)}, ValueError, "alpha_range"),
        ({"alpha_range": 0.3}, TypeError, "alpha_range"),
        ({"alpha_range": (0.1, 0.2, 0.3)}, ValueError, "alpha_range"),
        ({"alpha_range": (0.1, None)}, TypeError, "alpha_range"),
        ({"mu_s": 0.0}, ValueError, "mu_s"),
        ({"mu_s": math.nan}, ValueError, "mu_s"),
        ({"mu_s": "1"}, TypeError, "mu_s"),
        ({"mu_s_err": 1.0}, ValueError, "mu_s_err"),
        ({"mu_s_err": -0.1}, ValueError, "mu_s_err"),
        ({"target": "fly"}, ValueError, "target"),
        ({"target": None}, TypeError, "target"),
        ({"body": (0.1, 0.2)}, TypeError, "body"),
        ({"km_range": (0.1, 1.0)}, ValueError, "km_range"),
        ({"rod_range": (-0.1, 0.5)}, ValueError, "rod_range"),
        ({"radius": 0.05}, ValueError, "radius"),
        ({"radius": -1.0, "mass": 1.0}, ValueError, "radius"),
        ({"radius": 1.0, "mass": math.inf}, ValueError, "mass"),
        ({"g": 0.0}, ValueError, "g"),
        ({"error": 0.0}, ValueError, "error"),
        ({"grid": 3}, ValueError, "grid"),
        ({"grid": 65}, ValueError, "grid"),
        ({"grid": 8.0}, TypeError, "grid"),
        ({"max_turns": 0}, ValueError, "max_turns"),
        ({"max_turns": 1001}, ValueError, "max_turns"),
        ({"alpha_range": (0.0, 0.0)}, ValueError, "alpha_range"),  # no JARM at alpha = 0
        ({"min_apex": -0.1}, ValueError, "min_apex"),
        ({"min_apex": math.nan}, ValueError, "min_apex"),
        ({"min_apex": "1"}, TypeError, "min_apex"),
        ({"min_apex": 0.1, "target": "slip"}, ValueError, "min_apex"),
        ({"min_apex": 5.0}, ValueError, "apex"),  # no grid point flies that high
        ({"maximise": "probability"}, ValueError, "tolerances"),
        ({"maximise": "odds", "tolerances": {"chi": 0.01}}, ValueError, "maximise"),
        ({"tolerances": {"mu_k": 0.01}}, ValueError, "mu_k"),
        ({"tolerances": {"alpha": -0.01}}, ValueError, "alpha"),
        ({"tolerances": [0.01]}, TypeError, "tolerances"),
        ({"tolerances": {"chi": 0.01}, "samples": 99}, ValueError, "samples"),
        ({"tolerances": {"chi": 0.01}, "seed": -1}, ValueError, "seed"),
        ({"tolerances": {"chi": 0.01}, "p_target": 1.0}, ValueError, "p_target"),
        ({"tolerances": {"chi": 0.01}, "p_target": 0.0}, ValueError, "p_target"),
        ({"tolerances": {"chi": 0.01}, "p_target": math.nan}, ValueError, "p_target"),
        ({"tolerances": {"chi": 0.01}, "p_target": "0.9"}, TypeError, "p_target"),
        ({"p_target": 0.9}, ValueError, "p_target"),  # without tolerances
        ({"tolerances": {"chi": 0.01}, "p_target": 0.9, "target": "slip"}, ValueError, "p_target"),
    ],
)
def test_bad_input_names_the_parameter(kwargs, exc, name):
    args = {"alpha_range": RANGE, "mu_s": 1.0, "grid": 4, **kwargs}
    with pytest.raises(exc) as info:
        design(args.pop("alpha_range"), args.pop("mu_s"), **args)
    msg = str(info.value)
    assert name in msg and len(msg) <= 200, msg


def test_build_bad_input():
    with pytest.raises(TypeError, match="body"):
        build((0.1, 0.2))
    with pytest.raises(ValueError, match="radius"):
        build(Cylinder(0.1, 0.2), radius=0.0)
    with pytest.raises(ValueError, match="mass"):
        build(Cylinder(0.1, 0.2), mass=math.nan)


def test_the_design_is_deterministic(jump):
    again = design(RANGE, 0.6, 0.1, radius=0.05, mass=0.5, grid=12)
    assert again.to_dict() == jump.to_dict()


def test_a_visible_jump_flies_at_least_min_apex():
    """min_apex: the designed first flight (both rules, simulated again here) reaches it,
    where the unconstrained design of the same ranges does not."""
    rng = (math.radians(40), math.radians(70))
    plain = design(rng, 1.0, grid=8)
    seen = design(rng, 1.0, grid=12, min_apex=0.15)
    assert min(f.apex for f in plain.flights) < 0.15
    assert seen.reasons == {"paper": "JARM", "normal_force": "JARM"}
    for rule in ("paper", "normal_force"):
        run = eccjump.simulate(seen.body, seen.alpha, mu_s=1.0, rule=rule, max_transitions=2)
        assert run.flights[0].apex >= 0.15


def test_a_design_on_the_edge_of_its_range_says_so(jump):
    """The default km_range starts at 0.01, where the example's optimum sits."""
    edge = [n for n in jump.notes if "end of km_range" in n]
    assert (jump.body.km == 0.01) == bool(edge), jump.notes
    assert any("end of" in line for line in jump.sheet().splitlines() if line.startswith("note"))


# --- the probability of success under the lab's tolerances ---------------------------------

TOLERANCES = {"alpha": math.radians(2), "chi": 0.02, "km": 0.01, "mu_s": 0.1}


def test_p_success_agrees_with_an_independent_monte_carlo():
    """The design's P(verdict) against plain rejection sampling of the same normals (the
    truncated law the design samples by its inverse CDF) judged point by point by jarm."""
    d = design(RANGE, 0.6, 0.1, grid=8, tolerances=TOLERANCES, samples=4000, seed=5)
    nominal = {"chi": d.body.chi, "km": d.body.km, "alpha": d.alpha, "mu_s": d.mu_s}
    rng = np.random.default_rng(2026)
    kept: list[dict[str, float]] = []
    while len(kept) < 1500:
        x = {k: rng.normal(v, TOLERANCES[k]) for k, v in nominal.items()}
        body_ok = 0 <= x["chi"] <= 1 and 0 <= x["km"] <= 1 - x["chi"]
        if body_ok and 0 <= x["alpha"] <= math.pi / 2 and x["mu_s"] >= 0:
            kept.append(x)
    hits = sum(verdict(d, x["alpha"], x["chi"], x["km"], x["mu_s"]) for x in kept)
    p_mc, p = hits / len(kept), d.p_success.p
    se = math.sqrt(p * (1 - p) / d.p_success.n_valid + p_mc * (1 - p_mc) / len(kept))
    assert 0.05 < p < 0.99 and abs(p - p_mc) < 4 * se, (p, p_mc, se)
    assert d.p_success.low <= p <= d.p_success.high


def test_maximising_the_probability_never_does_worse_than_the_margin():
    kw = {"grid": 8, "tolerances": TOLERANCES, "samples": 2000, "seed": 1}
    by_margin = design(RANGE, 0.6, 0.1, **kw)
    by_odds = design(RANGE, 0.6, 0.1, maximise="probability", **kw)
    # the same samples: the margin's design is one of the candidates
    assert by_odds.p_success.p >= by_margin.p_success.p
    assert by_odds.reasons == {"paper": "JARM", "normal_force": "JARM"}
    assert design(RANGE, 0.6, 0.1, grid=8).p_success is None


def test_p_success_is_on_the_sheet_and_in_the_json():
    d = design(RANGE, 0.6, 0.1, grid=8, tolerances={"chi": 0.02}, samples=500)
    assert "P(success)" in str(d) and "chi ± 0.02" in str(d)
    assert json.loads(json.dumps(d.to_dict()))["p_success"]["p"] == d.p_success.p


def test_a_bad_tolerance_is_named_as_the_design_calls_it():
    # Issue 46's campaign: design's tolerances were reported as uncertainty's ``sd[...]``.
    body = eccjump.Cylinder(0.26, 0.1776)
    for tolerances, kind in (({"chi": -math.inf}, ValueError), ({"chi": 1j}, TypeError)):
        with pytest.raises(kind, match=r"^tolerances\['chi'\]"):
            eccjump.design((0.785, 0.864), 0.26, 0.2, target="jarm", grid=5, body=body,
                           tolerances=tolerances)  # fmt: skip

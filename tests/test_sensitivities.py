"""``simulate(..., sensitivities=True)`` (issue 38, item 2) against the independent model.

The acceptance of the issue: the derivatives of the transitions' (t, θ) agree with central
differences of an independent route to 1e-4 (full motion). The route is the scipy model of
``tests/reference_motion.py`` (no code shared with the Rust core), run at rtol 1e-12; the
difference is taken only while the transitions of both shifted runs have the base run's
sequence (modes and reasons) and the transition is not ``d_singular``.
"""

from __future__ import annotations

import math
from typing import Any

import numpy as np
import pytest
import reference_motion as rm
from hypothesis import assume, given, settings
from hypothesis import strategies as st
from reference_points import JARM_KW, SLIP_FIRST

import eccjump

PARAMETERS = eccjump.SENSITIVITY_PARAMETERS

#: |exact − central difference| ≤ TOL (1 + |central difference|): the issue's bound.
TOL = 1e-4

#: The relative step of the central differences (the reference's error at rtol 1e-12 over
#: the step is about 1e-7; the truncation error h² about 1e-10).
STEP = 1e-5

#: The reference's tolerances.
REF_TOL = {"rtol": 1e-12, "atol": 1e-14}

#: Cases: the eight parameters (interior values: 0 < e < 1, μ_k < μ_s, k_m < 1 − χ) and the
#: other options of both runs; the number of derivatives to compare (2 × 8 per transition,
#: the start included). The measured worst relative difference in the comment.
CASES: dict[str, tuple[dict[str, float], dict[str, Any], int]] = {
    # the paper's body: roll, lift-off, flight, two bouncing landings (3e-8)
    "roll-liftoff-bounces": (
        {**JARM_KW, "mu_s": 1.0, "mu_k": 0.9, "restitution": 0.4, "theta0": 0.0, "omega0": 0.0},
        {"t_max": 6.0, "max_transitions": 3},
        4 * 16,
    ),
    # from (θ0, θ̇0) ≠ 0 with μ_k < μ_s: slip onset, stick, slip again, lift-off (6e-9)
    "slip-stick-slip": (
        {"alpha": math.radians(25), "chi": 0.3, "km": 0.2, "mu_s": 0.4, "mu_k": 0.3,
         "restitution": 0.5, "theta0": 1.0, "omega0": 0.5},
        {"t_max": 6.0, "max_transitions": 4},
        5 * 16,
    ),
    # a slip up the ramp that stops and reverses, lift-off, a bouncing landing (3e-7)
    "reverse-liftoff-bounce": (
        {"alpha": math.radians(60), "chi": 0.3, "km": 0.5, "mu_s": 0.3, "mu_k": 0.2,
         "restitution": 0.5, "theta0": 0.5, "omega0": 0.3},
        {"slip0": -0.6, "t_max": 8.0, "max_transitions": 3},
        4 * 16,
    ),
    # a fast spin on a gentle ramp: a flight from the start and bounces (8e-10)
    "spin-bounces": (
        {"alpha": math.radians(20), "chi": 0.5, "km": 0.2, "mu_s": 1.0, "mu_k": 0.8,
         "restitution": 0.5, "theta0": 0.0, "omega0": 2.0},
        {"t_max": 3.0, "max_transitions": 4},
        5 * 16,
    ),
}  # fmt: skip


def ours(p: dict[str, float], **kw: Any) -> eccjump.MotionResult:
    body = eccjump.Cylinder(p["chi"], p["km"])
    rest = {k: v for k, v in p.items() if k not in ("alpha", "chi", "km")}
    return eccjump.simulate(body, p["alpha"], sensitivities=True, **rest, **kw)


def reference(p: dict[str, float], **kw: Any) -> dict:
    rest = {k: v for k, v in p.items() if k not in ("alpha", "chi", "km")}
    return rm.simulate_reference(p["chi"], p["km"], p["alpha"], **rest, **kw, **REF_TOL)


def sequence(transitions: list) -> list[tuple]:
    return [tuple(tr[1:4]) for tr in transitions]


def worst_difference(p: dict[str, float], kw: dict[str, Any]) -> tuple[float, int]:
    """The worst relative difference of ``d_transitions`` from central differences of the
    reference, and how many derivatives were compared."""
    m = ours(p, **kw)
    assert m.d_transitions is not None and m.d_singular is not None
    names = [(t.from_mode, t.to_mode, t.reason) for t in m.transitions]
    assert sequence(reference(p, **kw)["transitions"]) == names
    worst, compared = 0.0, 0
    for k, name in enumerate(PARAMETERS):
        if name == "restitution" and p[name] == 0.0:
            continue  # the bound e = 0: no central difference
        h = STEP * max(1.0, abs(p[name]))
        up = reference({**p, name: p[name] + h}, **kw)["transitions"]
        down = reference({**p, name: p[name] - h}, **kw)["transitions"]
        for i in range(len(names)):
            same = sequence(up[: i + 1]) == sequence(down[: i + 1]) == names[: i + 1]
            if not same or m.d_singular[i]:
                break
            for row, col in ((0, 0), (1, 4)):  # t, θ of the reference's transitions
                diff = (up[i][col] - down[i][col]) / (2 * h)
                exact = m.d_transitions[i, row, k]
                err = abs(exact - diff) / (1 + abs(diff))
                assert err <= TOL, (
                    f"transition {i} {names[i]} d{'tθ'[row]}/d{name}: {exact} vs {diff}"
                )
                worst = max(worst, err)
                compared += 1
    return worst, compared


#: The cases of more than a second (16 reference runs each): marked slow.
SLOW = {"roll-liftoff-bounces", "slip-stick-slip"}


@pytest.mark.parametrize(
    "case", [pytest.param(c, marks=pytest.mark.slow) if c in SLOW else c for c in CASES]
)
def test_derivatives_agree_with_central_differences_of_the_reference(case: str) -> None:
    p, kw, minimum = CASES[case]
    worst, compared = worst_difference(p, kw)
    print(f"{case}: worst relative difference {worst:.2e} over {compared} derivatives")
    # every parameter reaches every transition: nothing was skipped
    assert compared >= minimum, compared


#: A landing that sticks (e = 0): roll, lift-off, flight, landing into a slip, stick.
STICKS = (
    {**JARM_KW, "mu_s": 1.0, "mu_k": 0.9, "restitution": 0.0, "theta0": 0.0, "omega0": 0.0},
    {"t_max": 5.5, "max_transitions": 3},
)  # fmt: skip


def test_a_sticking_landing() -> None:
    """At e = 0 the landing map reads e² (its e-derivative is 0), so the landing and what
    follows have their derivatives (7 parameters, e being at its bound)."""
    p, kw = STICKS
    m = ours(p, **kw)
    assert [t.reason for t in m.transitions] == ["start", "liftoff", "impact", "stick"]
    worst, compared = worst_difference(p, kw)
    assert compared >= 4 * 2 * 7, compared  # all four transitions
    print(f"sticks: worst relative difference {worst:.2e} over {compared} derivatives")


def test_the_time_of_a_sticking_landing_has_its_derivatives() -> None:
    p, kw = STICKS
    m = ours(p, **kw)
    assert m.d_singular is not None
    assert not m.d_singular[2]


#: A run that settles on the ramp after its bounces (the Zeno rule).
SETTLES = SLIP_FIRST  # the Fig. 3b body slips first, then bounces and settles
SETTLES_KW: dict[str, Any] = {"mu_s": 1.0, "mu_k": 0.8, "restitution": 0.3, "t_max": 9.0}

#: Bounces that settle into a slip through the normal impulse (flagged from there on).
IMPULSE = (eccjump.Cylinder(0.81050848, 0.08156572), 0.97549785)
IMPULSE_KW: dict[str, Any] = {
    "mu_s": 1.22005392,
    "mu_k": 1.09488566,
    "restitution": 0.07081708,
    "theta0": 5.19246307,
    "omega0": 3.31312160,
    "t_max": 10.0,
}


def test_a_settle_keeps_its_derivatives() -> None:
    m = eccjump.simulate(*SETTLES, **SETTLES_KW, sensitivities=True)
    assert m.d_transitions is not None and m.d_singular is not None
    assert "settle" in [t.reason for t in m.transitions]
    assert not m.d_singular.any() and np.isfinite(m.d_transitions).all()


def test_nan_exactly_where_singular_and_singular_propagates() -> None:
    m = eccjump.simulate(*IMPULSE, **IMPULSE_KW, sensitivities=True)
    assert m.d_transitions is not None and m.d_singular is not None
    n = len(m.transitions)
    assert m.d_transitions.shape == (n, 2, len(PARAMETERS))
    assert m.d_singular.shape == (n,) and m.d_singular.dtype == np.bool_
    assert m.d_singular.any() and not m.d_singular.all()  # the case reaches a flag
    nan = np.isnan(m.d_transitions)
    assert (nan.all(axis=(1, 2)) == m.d_singular).all()
    assert not nan[~m.d_singular].any()
    first = int(np.argmax(m.d_singular))
    assert m.d_singular[first:].all()
    # the slip after the settle went on in the normal impulse: its end is flagged
    assert [t.reason for t in m.transitions[first - 1 : first + 1]] == ["settle", "reverse"]


def test_the_start_row_is_the_unit_vector_of_theta0() -> None:
    m = eccjump.simulate(*SETTLES, **SETTLES_KW, theta0=0.3, omega0=0.2, sensitivities=True)
    assert m.d_transitions is not None
    assert (m.d_transitions[0, 0] == 0.0).all()
    unit = np.zeros(len(PARAMETERS))
    unit[PARAMETERS.index("theta0")] = 1.0
    assert (m.d_transitions[0, 1] == unit).all()


def test_to_si_scales_the_time_row_and_the_omega0_column() -> None:
    m = eccjump.simulate(*SETTLES, **SETTLES_KW, sensitivities=True)
    g, R = 9.81, 0.05
    si = m.to_si(g=g, R=R)
    assert m.d_transitions is not None and si.d_transitions is not None
    scale = np.ones((2, len(PARAMETERS)))
    scale[0] *= math.sqrt(R / g)  # a time
    scale[:, PARAMETERS.index("omega0")] /= math.sqrt(g / R)  # per rad/s of omega0
    np.testing.assert_allclose(si.d_transitions, m.d_transitions * scale, rtol=1e-15)
    assert si.d_singular is not None and m.d_singular is not None
    assert (si.d_singular == m.d_singular).all()


def test_without_sensitivities_both_fields_are_none() -> None:
    m = eccjump.simulate(*SETTLES, **SETTLES_KW)
    assert m.d_transitions is None and m.d_singular is None
    m = eccjump.simulate(*SETTLES, **SETTLES_KW, sensitivities=False)
    assert m.d_transitions is None and m.d_singular is None
    assert m.to_si().d_transitions is None


def test_the_same_bits_twice() -> None:
    a = eccjump.simulate(*SETTLES, **SETTLES_KW, sensitivities=True)
    b = eccjump.simulate(*SETTLES, **SETTLES_KW, sensitivities=True)
    assert a.d_transitions is not None and b.d_transitions is not None
    assert a.d_transitions.tobytes() == b.d_transitions.tobytes()
    assert a == b


@pytest.mark.parametrize("bad", ["yes", 1, None, 1.0])
def test_a_bad_sensitivities_flag_raises_type_error(bad: object) -> None:
    with pytest.raises(TypeError, match="sensitivities"):
        eccjump.simulate(*SETTLES, **SETTLES_KW, sensitivities=bad)  # type: ignore[arg-type]


@settings(max_examples=12, deadline=None)
@given(
    # around the paper's JARM point: every draw rolls to a lift-off (80 of 80 sampled)
    chi=st.floats(0.14, 0.16),
    km=st.floats(0.015, 0.025),
    alpha=st.floats(0.66, 0.74),
    mu_s=st.floats(1.0, 3.0),
    mu_k_frac=st.floats(0.3, 0.99),
    restitution=st.floats(0.1, 0.9),
)
def test_a_first_lift_off_from_rest_does_not_depend_on_friction_or_restitution(
    chi: float, km: float, alpha: float, mu_s: float, mu_k_frac: float, restitution: float
) -> None:
    """Rolling from rest, the energy integral fixes the lift-off angle and time by the body
    and the ramp alone: μ_s, μ_k and e enter neither the rolling nor the lift-off test, so
    their columns are exactly 0 at a first lift-off; every derivative not flagged is
    finite."""
    m = eccjump.simulate(
        eccjump.Cylinder(chi, km),
        alpha,
        mu_s=mu_s,
        mu_k=mu_k_frac * mu_s,
        restitution=restitution,
        t_max=8.0,
        max_transitions=3,
        sensitivities=True,
    )
    assert m.d_transitions is not None and m.d_singular is not None
    assert np.isfinite(m.d_transitions[~m.d_singular]).all()
    reasons = [t.reason for t in m.transitions]
    assume(reasons[:2] == ["start", "liftoff"] and m.transitions[0].to_mode == "ROLL")
    assert not m.d_singular[1]
    friction = [PARAMETERS.index(n) for n in ("mu_s", "mu_k", "restitution")]
    assert (m.d_transitions[1][:, friction] == 0.0).all()
    assert (m.d_transitions[1][0, :3] != 0.0).all()  # the body and the ramp do move it

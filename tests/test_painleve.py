"""Slips through a Painlevé point (issue 38, item 1): ``eccjump.simulate`` against the
independent scipy model (tests/reference_motion.py), which continues such a slip in the
normal impulse with its own formulation and its own switch values.

As D = Ĩ_CM + χ K sin θ → 0⁺ in a slip the normal force grows like 1/D, but written against
the normal impulse the motion stays regular: the slip velocity may reach 0 at a small D (the
run goes on: stick or reversal), or D decays below what float64 resolves with the slip still
on (status ``painleve``, a jam). Both models must agree on which, on the whole sequence of
transitions and on their times; eccjump's energy ledger must close through the continuation.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
import reference_motion as rm

import eccjump

#: Issue 38's reproducer: (chi, km, alpha [rad]) and the options of ``simulate``.
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

#: Random bodies of the Painlevé-prone region (χ 0.87–0.95, k_m ≤ 0.07, α 80–88°, μ = 1),
#: from rest or from a random (θ0, θ̇0): (chi, km, alpha [deg], theta0, omega0). Drawn by a
#: scan of the reference (numpy seeds 1–3) and kept where the outcome is clear: a slip
#: velocity returning to 0 at D ≥ 7e-9 (the reference's D there in the comment), or a jam
#: whose slip velocity would return to 0 only at D ~ 1e-50 or below.
REGION = [
    (0.8835, 0.0283, 80.704, 0.0, 0.0),  # slip, reverse at D 6.6e-7, flight
    (0.8885, 0.0187, 81.882, 0.0, 0.0),  # slip, reverse at D 2.0e-8, flight
    (0.8832, 0.032, 80.506, 0.0, 0.0),  # slip, reverse at D 2.4e-8, flight
    (0.9347, 0.0274, 81.606, 3.8483, 1.351),  # stick at D 1.4e-7, lift-off
    (0.8942, 0.0664, 80.873, 2.7862, 0.8377),  # stick, slip, stick at D 7.4e-9, lift-off
    (0.9362, 0.0291, 84.397, 0.0, 0.0),  # slip, jam
    (0.9416, 0.0276, 84.716, 0.0, 0.0),  # slip, jam
    (0.9109, 0.0668, 81.153, 1.9593, -0.3067),  # jam in the first slip
    (0.9067, 0.0091, 85.131, 3.7256, -0.9596),  # stick, slip, jam
    (0.9299, 0.0338, 81.674, 0.1057, -0.786),  # flight, impact, jam
]

#: Earlier Painlevé ends that stay jams: the reference's own case
#: (tests/test_reference_motion.py) and the ``painleve`` run of tests/test_motion_ledger.py.
JAMS = [
    ((0.9, 0.05, math.radians(85.0)), {"mu_s": 1.0, "t_max": 10.0}),
    (
        (0.9955002834343927, 0.0035667539688122203, 0.9773168482142575),
        {
            "mu_s": 1.4839922141387332,
            "mu_k": 0.49084438262344054,
            "omega0": -1.7081478105864063,
            "slip0": -0.6795759322843109,
            "theta0": 3.848699841633905,
            "t_max": 20.0,
        },
    ),
]

#: E + dissipated − E0 over eccjump's whole run (the reference closes to 3e-9 on these).
LEDGER = 1e-8


def both(args: tuple[float, float, float], kw: dict) -> tuple[eccjump.MotionResult, dict]:
    chi, km, alpha = args
    kw = {**kw, "max_transitions": 30}
    ref = rm.simulate_reference(chi, km, alpha, **kw)
    return eccjump.simulate(eccjump.Cylinder(chi, km), alpha, **kw), ref


def check_same_run(m: eccjump.MotionResult, ref: dict) -> None:
    """Same status, same transitions (modes and reasons), times and angles to 1e-8 and
    θ̇ to 1e-7 (measured: 1.4e-10, 3.7e-10, 2.1e-9), a closed ledger, and a jam that says
    so."""
    print(rm.format_transitions(ref))
    print(m.status, m.message)
    assert m.status == ref["status"], m.message
    ours = [(t.from_mode, t.to_mode, t.reason) for t in m.transitions]
    assert ours == [tuple(tr[1:4]) for tr in ref["transitions"]]
    for a, b in zip(m.transitions, ref["transitions"], strict=True):
        assert a.t == pytest.approx(b[0], abs=1e-8)
        assert a.theta == pytest.approx(b[4], abs=1e-8)
        assert a.omega == pytest.approx(b[5], abs=1e-7)
    residual = np.abs(m.energy + m.dissipated - m.energy0)
    assert residual.max() <= LEDGER, residual.max()
    end = m.energy[-1] + m.dissipated_slip + m.dissipated_impacts - m.energy0
    assert abs(end) <= LEDGER, end
    if m.status == "painleve":
        assert m.message.startswith("Painlevé jam"), m.message
        # t and θ of a jam are sharp, its velocities are not (physics.md)
        assert m.t[-1] == pytest.approx(ref["end"][0], abs=1e-8)
        assert m.theta[-1] == pytest.approx(ref["end"][2], abs=1e-8)


def test_the_issue_38_reproducer_goes_on_to_its_lift_off_and_landing() -> None:
    m, ref = both(*ISSUE38)
    assert ref["impulse_pieces"] >= 1  # the reference did continue in the impulse
    check_same_run(m, ref)
    assert m.status == "t_max"
    names = [(t.from_mode, t.to_mode, t.reason) for t in m.transitions]
    assert names[:4] == [
        (None, "SLIP", "start"),
        ("SLIP", "SLIP", "reverse"),
        ("SLIP", "FLIGHT", "normal_force"),
        ("FLIGHT", "SLIP", "impact"),
    ]
    # the issue's figures, to their printed digits
    assert m.transitions[1].t == pytest.approx(4.1456228514, abs=1e-10)
    assert m.transitions[2].t == pytest.approx(4.1599367580, abs=1e-10)
    assert m.transitions[3].t == pytest.approx(14.028, abs=1e-3)


@pytest.mark.parametrize("case", REGION, ids=[f"region{i}" for i in range(len(REGION))])
def test_the_painleve_prone_region_agrees_with_the_reference(case: tuple) -> None:
    chi, km, alpha_deg, theta0, omega0 = case
    kw = {"mu_s": 1.0, "theta0": theta0, "omega0": omega0, "t_max": 10.0}
    m, ref = both((chi, km, math.radians(alpha_deg)), kw)
    assert ref["impulse_pieces"] >= 1  # the case reaches the impulse form
    check_same_run(m, ref)


@pytest.mark.parametrize("case", JAMS, ids=["reference", "ledger"])
def test_earlier_painleve_ends_are_true_jams(case: tuple) -> None:
    m, ref = both(*case)
    assert ref["status"] == "painleve"
    check_same_run(m, ref)

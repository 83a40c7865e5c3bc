"""The energy ledger of ``simulate`` closes for every status, and friction never works along
the slip (issue 35: a slip reversal that slid the wrong way gained 422 units of energy; a run
stopped by ``max_transitions`` at a landing kept the impact in its totals but not in its
arrays).

E + dissipated = E0 is an identity of the equations of motion, with the sliding work
q̇ = −F_x v integrated as a state of its own and each impact's loss from the velocities
before and after it: the ledger is an independent check of the integration and of the
bookkeeping. Its reach is the integration tolerance on the energies in play: the kinetic and
the potential energy grow like the distance l travelled (sin α per unit of l), so the
tolerance is taken relative to 1 + |E0| + max l + the energy dissipated.
"""

from __future__ import annotations

import math

import numpy as np
import pytest
from hypothesis import HealthCheck, given, settings
from hypothesis import strategies as st
from reference_points import SLIP_FIRST, SLIP_FIRST_BODY

import eccjump
from eccjump.motion.simulation import STATUSES
from eccjump.testing import assert_ledger_closes, ledger_scale, strategies

#: One run for each way a run can end (``landed`` is the motion maps' stop at the first
#: landing, not an option of ``simulate``).
BY_STATUS = {
    "t_max": (SLIP_FIRST_BODY, 30.0, {"mu_s": 1.0, "t_max": 20.0}),
    "l_max": (SLIP_FIRST_BODY, 30.0, {"mu_s": 1.0, "l_max": 25.0}),
    "max_transitions": (SLIP_FIRST_BODY, 30.0, {"mu_s": 1.0, "max_transitions": 2}),
    "painleve": (
        (0.9955002834343927, 0.0035667539688122203),
        math.degrees(0.9773168482142575),
        {
            "mu_s": 1.4839922141387332,
            "mu_k": 0.49084438262344054,
            "omega0": -1.7081478105864063,
            "slip0": -0.6795759322843109,
            "theta0": 3.848699841633905,
            "t_max": 20.0,
        },
    ),
    "jam": (
        (0.8728092085647744, 0.04378042715567146),
        math.degrees(0.9272269067208351),
        {
            "mu_s": 1.0413423413423384,
            "mu_k": 0.9751395432743598,
            "omega0": -0.8675173378589278,
            "slip0": 0.038196972991980216,
            "theta0": 4.808191114973239,
            "t_max": 20.0,
        },
    ),
    "failed": (SLIP_FIRST_BODY, 30.0, {"mu_s": 1.0, "max_steps": 40}),
}


@pytest.mark.parametrize("status", sorted(BY_STATUS))
def test_the_ledger_closes_for_every_status(status: str) -> None:
    (chi, km), alpha_deg, kw = BY_STATUS[status]
    r = eccjump.simulate(eccjump.Cylinder(chi, km), math.radians(alpha_deg), **kw)
    assert r.status == status, r.message
    assert_ledger_closes(r)


def test_every_status_but_the_maps_own_is_covered() -> None:
    assert set(BY_STATUS) == set(STATUSES) - {"landed"}


def test_friction_opposes_the_slip_after_a_reversal() -> None:
    # Issue 35's reproducer: E + dissipated reached 422 with E0 = 8.2, every integrator.
    body = eccjump.Cylinder(0.9967382802532273, 0.0020091263994083857)
    for integrator in ("RK45", "DOP853", "Vern9"):
        r = eccjump.simulate(
            body,
            0.09460139274753544,
            mu_s=1.045495987161698,
            omega0=1.3173152757544075,
            slip0=0.8935712304485395,
            max_transitions=400,
            integrator=integrator,
        )
        assert_ledger_closes(r)
        assert "reverse" in {t.reason for t in r.transitions}


def test_a_run_stopped_by_its_budget_at_a_landing_keeps_arrays_and_totals_in_step() -> None:
    # Issue 35: the ledger by the totals was 0.293 off; the impact is now not made.
    r = eccjump.simulate(*SLIP_FIRST, mu_s=1.0, max_transitions=2)
    assert r.status == "max_transitions"
    assert r.energy[-1] + r.dissipated_slip + r.dissipated_impacts == pytest.approx(
        r.energy0, abs=1e-9
    )
    assert len(r.impacts) == 0 and r.mode[-1] == 2


#: Any body with k_m >= 1e-3, ramp, friction (mu_k >= 0.3 mu_s), restitution and start.
MOTIONS = strategies.motion_inputs(
    body=strategies.bodies(max_chi=0.995, min_km=1e-3),
    friction=strategies.frictions(min_mu_s=0.05, max_mu_s=1.5, min_ratio=0.3),
    start=strategies.starts(min_omega0=-3.0, max_omega0=3.0, max_slip0=1.0),
)


@st.composite
def runs(draw: st.DrawFn) -> tuple[eccjump.Cylinder, float, dict]:
    """A valid run, sometimes with a small transition budget or a distance limit, so that
    every status is drawn."""
    m = draw(MOTIONS)
    kw = {
        **m.keywords(),
        "t_max": 30.0,
        "max_transitions": draw(st.sampled_from([100, 100, 1, 2, 3, 5])),
        "l_max": draw(st.sampled_from([math.inf, math.inf, 2.0, 10.0])),
    }
    return m.body, m.alpha, kw


@settings(max_examples=400, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(runs())
def test_the_ledger_closes_on_random_runs(run: tuple[eccjump.Cylinder, float, dict]) -> None:
    body, alpha, kw = run
    assert_ledger_closes(eccjump.simulate(body, alpha, **kw))


#: The ledger against the energies in play at the loosest tolerances a run accepts (rtol =
#: atol = 1e-6, the core's MAX_MOTION_TOL): 7e-5 was the worst over 150 random runs.
LOOSE_LEDGER = 1e-3


@settings(max_examples=60, deadline=None, suppress_health_check=[HealthCheck.too_slow])
@given(runs())
def test_the_ledger_holds_at_the_loosest_accepted_tolerances(
    run: tuple[eccjump.Cylinder, float, dict],
) -> None:
    # Issue 46: at rtol = atol = 1e-3 the ledger was off by 37 % and `dissipated` fell by
    # 1.1e-4 in a step; the full motion now refuses tolerances above 1e-6.
    body, alpha, kw = run
    r = eccjump.simulate(body, alpha, rtol=1e-6, atol=1e-6, **kw)
    tol = LOOSE_LEDGER * ledger_scale(r)
    assert np.max(np.abs(r.energy + r.dissipated - r.energy0)) <= tol
    assert np.min(np.diff(r.dissipated), initial=0.0) >= -1e-3 * tol


@pytest.mark.parametrize("name", ["rtol", "atol"])
def test_tolerances_looser_than_the_ledger_allows_are_refused(name: str) -> None:
    body, alpha, kw = BY_STATUS["t_max"]
    with pytest.raises(ValueError, match=rf"^{name} = 0.00001 .*1e-6\]") as info:
        eccjump.simulate(eccjump.Cylinder(*body), math.radians(alpha), **{**kw, name: 1e-5})
    assert len(str(info.value)) <= 200
    with pytest.raises(ValueError, match=name):
        eccjump.motion_points(alpha=[0.5], chi=0.3, km=0.2, mu_s=1.0, **{name: 1e-3})

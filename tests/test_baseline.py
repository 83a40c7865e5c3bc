"""The hand-written numpy/scipy baseline of ``benches/`` classifies like eccjump, so that the
region-map benchmark compares the same computation (apples to apples)."""

from __future__ import annotations

import math
import sys
from pathlib import Path

import numpy as np
import pytest
from reference_points import JARM_ALPHA, JARM_BODY, SLIP_FIRST_ALPHA, SLIP_FIRST_BODY

import eccjump

sys.path.insert(0, str(Path(__file__).resolve().parents[1] / "benches"))
import baseline_numpy as bl

MU_S = 1.0


def _robust(alpha, chi, km):
    """Points whose eccjump verdict (is_jarm and reason) survives small nudges of every
    parameter: away from region boundaries, where a sampled scan may legitimately differ."""
    base = eccjump.jarm(alpha, chi, km, MU_S)
    keep = np.ones(alpha.shape, bool)
    for da, dc, dk, dm in [
        (2e-3, 0, 0, 0),
        (-2e-3, 0, 0, 0),
        (0, 2e-3, 0, 0),
        (0, -2e-3, 0, 0),
        (0, 0, 2e-3, 0),
        (0, 0, -2e-3, 0),
        (0, 0, 0, 0.02),
        (0, 0, 0, -0.02),
    ]:
        c = np.clip(chi + dc, 1e-6, 1 - 1e-6)
        k = np.clip(km + dk, 0.0, 1.0 - c)
        r = eccjump.jarm(np.clip(alpha + da, 1e-6, math.pi / 2), c, k, MU_S + dm)
        keep &= r.reason == base.reason
    return keep


@pytest.fixture(scope="module")
def points():
    rng = np.random.default_rng(20240611)
    # random points, away from the slow small-alpha corner (many turns for solve_ivp)
    m = 400
    alpha = rng.uniform(math.radians(5), math.radians(85), m)
    chi = rng.uniform(0.05, 0.95, m)
    km = rng.uniform(0.02, 0.98, m) * (1 - chi)
    keep = _robust(alpha, chi, km)
    idx = np.flatnonzero(keep)[:35]
    # JARM points from a coarse map (random points are rarely JARMs)
    reg = eccjump.region(
        mu_s=MU_S,
        alpha=np.radians(np.linspace(3, 80, 40)),
        chi=np.linspace(0.02, 0.6, 40),
        km_frac=np.linspace(0.0, 0.3, 16),
    )
    ia, ic, ik = np.nonzero(reg.is_jarm)
    ja, jc = reg.alpha[ia], reg.chi[ic]
    jk = reg.km_frac[ik] * (1 - jc)
    jkeep = _robust(ja, jc, jk)
    sel = rng.permutation(np.flatnonzero(jkeep))[:15]
    a = np.concatenate([alpha[idx], ja[sel]])
    c = np.concatenate([chi[idx], jc[sel]])
    k = np.concatenate([km[idx], jk[sel]])
    ref = eccjump.jarm(a, c, k, MU_S)
    assert ref.is_jarm.sum() >= 10 and (~ref.is_jarm).sum() >= 20
    return a, c, k, ref


@pytest.mark.parametrize("method", ["closed_form", "ode"])
def test_baseline_agrees_with_eccjump(points, method):
    a, c, k, ref = points
    out = bl.classify_many(a, c, k, MU_S, method=method)
    reason, theta_j = out[:, 0].astype(int), out[:, 1]
    np.testing.assert_array_equal(reason == 0, ref.is_jarm)
    np.testing.assert_array_equal(reason, ref.reason.astype(int))
    j = ref.is_jarm
    np.testing.assert_allclose(theta_j[j], ref.theta_J[j], rtol=0, atol=1e-6)


def test_reference_points():
    v = bl.classify_closed_form(JARM_ALPHA, *JARM_BODY, 1.0)
    assert v.reason == bl.JARM
    assert math.degrees(v.theta_J) == pytest.approx(334.344, abs=1e-3)
    v = bl.classify_closed_form(SLIP_FIRST_ALPHA, *SLIP_FIRST_BODY, 1.0)
    assert v.reason == bl.SLIP_BEFORE
    assert math.degrees(v.theta_event) == pytest.approx(316.47, abs=1e-2)
    assert bl.classify_closed_form(math.pi / 2, 0.3, 0.2, 1.0).reason == bl.LIFTOFF_EARLIER


@pytest.mark.parametrize("method", ["closed_form", "ode"])
@pytest.mark.parametrize("a_deg, chi", [(79.2, 0.195), (28.8, 0.675), (45.0, 0.075)])
def test_km0_near_tie_is_normal_force_lost(method, a_deg, chi):
    """At k_m = 0 (Ĩ_CM = 0) the slip margin vanishes together with F_y: eccjump calls that a
    loss of normal force, and so must the baseline."""
    a = math.radians(a_deg)
    ref = eccjump.jarm(a, chi, 0.0, MU_S)
    fn = bl.classify_closed_form if method == "closed_form" else bl.classify_ode
    assert int(ref.reason) == bl.NORMAL_FORCE_LOST
    assert fn(a, chi, 0.0, MU_S).reason == bl.NORMAL_FORCE_LOST

"""Short, readable reprs of results: a few lines, never the arrays in full, and a lazy map is
not computed to show it."""

from __future__ import annotations

import numpy as np
import pytest
from reference_points import JARM, JARM_ALPHA, JARM_BODY

import eccjump
from eccjump import Cylinder, Reason, jarm, region, roll
from eccjump.classification.fields import DTYPES, FIELDS, FILL


def test_jarm_result_repr_counts_reasons():
    alpha = np.radians(np.linspace(1.0, 89.0, 100))[:, None]
    r = jarm(alpha, np.linspace(0.05, 0.9, 100), 0.0, 0.8)
    text = repr(r)
    assert r.is_jarm.size == 10_000 and len(text) < 600 and "array" not in text
    assert "(100, 100)" in text and len(text.splitlines()) <= 1 + len(Reason)
    assert f"JARM {int(r.is_jarm.sum())}".split() == next(
        line.split() for line in text.splitlines() if line.split()[0] == "JARM"
    )
    assert sum(r.counts().values()) == 10_000


def test_single_point_repr():
    text = repr(jarm(JARM_ALPHA, *JARM_BODY, 1.0))
    assert text.startswith("JarmResult(JARM, n=1, theta_J=5.8354") and "334.3 deg" in text
    assert repr(jarm(0.0, *JARM_BODY, 1.0)) == "JarmResult(NO_ROOT, n=0)"


def test_region_repr():
    reg = region(
        mu_s=0.7,
        alpha=np.radians(np.linspace(0, 90, 40)),
        chi=np.linspace(0, 1, 25),
        km_frac=np.linspace(0, 1, 10),
        theta0=0.1,
    )
    text = repr(reg)
    assert len(text) < 600 and "array" not in text and len(text.splitlines()) == 5
    for part in ("40 x 25 x 10", "mu_s=0.7", "n=first jump", "rule=paper", "closed_form"):
        assert part in text
    assert "[0, 90] deg x 40" in text and "theta0=0.1" in text
    assert f"JARM fraction {reg.fraction():.6g}" in text


def test_region_repr_names_the_integrator_of_the_ode_route():
    grid = {"alpha": np.radians([20.0, 40.0]), "chi": [0.1, 0.3], "km_frac": [0.0, 0.5]}
    assert "integrator" not in repr(region(mu_s=0.7, **grid))
    for integrator in ("RK45", "DOP853"):
        text = repr(region(mu_s=0.7, **grid, method="ode", integrator=integrator))
        assert f"method=ode, integrator={integrator}" in text


def test_lazy_region_repr_does_not_compute(monkeypatch):
    pytest.importorskip("dask.array")
    calls = []
    monkeypatch.setattr(eccjump._core, "jarm_grid", lambda *a: calls.append(a))
    lazy = region(
        mu_s=1.0, n=2, alpha=np.linspace(0.1, 1.0, 30), chi=[0.1, 0.2], km_frac=[0.5], chunks=7
    )
    text = repr(lazy) + repr(lazy.result)
    assert not calls and "not computed" in text and "n=2" in text and len(text) < 600


def test_roll_result_repr():
    r = roll(*JARM, mu_s=1.0, rtol=1e-12, atol=1e-14)
    text = repr(r)
    assert r.t.size > 50 and len(text) < 400 and "array" not in text
    assert text.splitlines()[1].startswith("  liftoff at t=4.183")
    assert "theta=334.344 deg" in text and f"nfev={r.nfev}" in text
    assert f"{r.t.size - 1} steps" in text and "mu_s=1" in text
    si = repr(r.to_si(g=9.81, R=0.5))
    assert "SI units" in si and " s," in si and "rad/s" in si
    assert "t_max reached" in repr(roll(Cylinder(*JARM_BODY), 0.5, t_max=0.1))


def test_repr_of_points_not_computed():
    empty = eccjump.JarmResult(**{k: np.full((3, 4), FILL[k], dtype=DTYPES[k]) for k in FIELDS})
    assert repr(empty).splitlines()[1].split() == ["code", "255", "12"]
    assert empty.counts() == {255: 12}


def test_uncertainty_repr_is_one_line_with_the_probability():
    u = eccjump.uncertainty(*JARM, 1.0, sd={"chi": 0.02}, n=500, seed=3)
    text = repr(u)
    assert "\n" not in text and len(text) < 200, text
    assert f"p_jarm={u.p_jarm:.4g}" in text and "chi ± 0.02" in text

"""The sensitivities of random full-motion runs against central differences of ``simulate``
itself at rtol 1e-13, every transition and every parameter up to the first flag or the first
change of the sequence of modes: 12 runs per setting in every test run, 200 in the campaign
(``pytest -m campaign``, about a minute).

The differences are Richardson's extrapolation of central differences at h = 4e-7 (1 + |p|)
and h/2: a plain central difference left up to 2.6e-4 of truncation error where derivatives
are of order 10³ (a landing after a long flight).
"""

from __future__ import annotations

import numpy as np
import pytest
from numpy.typing import NDArray

import eccjump


def run(p: np.ndarray, rule: str, sensitivities: bool = False) -> eccjump.MotionResult:
    alpha, chi, km, mu_s, mu_k, e, theta0, omega0 = (float(x) for x in p)
    return eccjump.simulate(
        eccjump.Cylinder(chi, km),
        alpha,
        mu_s=mu_s,
        mu_k=mu_k,
        restitution=e,
        theta0=theta0,
        omega0=omega0,
        rule=rule,  # type: ignore[arg-type]
        t_max=10.0,
        max_transitions=12,
        rtol=1e-13,
        atol=1e-14,
        sensitivities=sensitivities,
    )


def draw(rng: np.random.Generator, restitution: bool) -> np.ndarray:
    chi = rng.uniform(0.05, 0.9)
    km = rng.uniform(0.05, 0.95) * (1 - chi)
    mu_s = rng.uniform(0.1, 2.0)
    e = rng.uniform(0.05, 0.9) if restitution else 0.0
    return np.array(
        [
            rng.uniform(0.1, 1.4),
            chi,
            km,
            mu_s,
            mu_s * rng.uniform(0.3, 0.95),
            e,
            rng.uniform(0.0, 6.28),
            rng.uniform(-2.0, 4.0),
        ]
    )


def sequence(m: eccjump.MotionResult) -> list[tuple[str, str]]:
    return [(t.to_mode, t.reason) for t in m.transitions]


SETTINGS = [("paper", True, 1), ("normal_force", True, 2), ("paper", False, 5)]


@pytest.mark.parametrize(("rule", "restitution", "seed"), SETTINGS)
def test_random_runs_against_central_differences(rule: str, restitution: bool, seed: int) -> None:
    compare(rule, restitution, seed, runs=12, minimum=500)


@pytest.mark.campaign
@pytest.mark.parametrize(("rule", "restitution", "seed"), SETTINGS)
def test_campaign(rule: str, restitution: bool, seed: int) -> None:
    compare(rule, restitution, seed + 100, runs=200, minimum=10_000)


def differences(p: np.ndarray, k: int, h: float, rule: str) -> tuple[list, NDArray]:
    """The sequence of modes common to the runs at p ± h e_k (up to where they part) and
    the central differences of their transitions' (t, θ) there, shape (n, 2)."""
    up, down = p.copy(), p.copy()
    up[k] += h
    down[k] -= h
    ru, rd = run(up, rule), run(down, rule)
    su, sd = sequence(ru), sequence(rd)
    n = next(
        (i for i, (a, b) in enumerate(zip(su, sd, strict=False)) if a != b), min(len(su), len(sd))
    )
    ends = [
        [(u.t - d.t) / (2 * h), (u.theta - d.theta) / (2 * h)]
        for u, d in zip(ru.transitions[:n], rd.transitions[:n], strict=True)
    ]
    return su[:n], np.array(ends).reshape(n, 2)


def compare(rule: str, restitution: bool, seed: int, runs: int, minimum: int) -> None:
    """Every derivative of ``runs`` random runs against Richardson's extrapolation of central
    differences at h and h/2 (error O(h^4): derivatives of order 10^3 after long flights
    left 2e-4 of truncation error in a plain difference), to 1e-4 relative to
    1 + |difference|; at least ``minimum`` compared."""
    rng = np.random.default_rng(seed)
    compared, bad = 0, []
    for _ in range(runs):
        p = draw(rng, restitution)
        m = run(p, rule, sensitivities=True)
        assert m.d_transitions is not None and m.d_singular is not None
        seq = sequence(m)
        for k in range(8):
            if k == 5 and not restitution:
                continue  # e = 0 is its bound: no central difference
            h = 4e-7 * (1 + abs(p[k]))
            (s1, d1), (s2, d2) = differences(p, k, h, rule), differences(p, k, h / 2, rule)
            for i in range(len(seq)):
                same = seq[: i + 1] == s1[: i + 1] == s2[: i + 1]
                if not same or i >= min(len(s1), len(s2)) or m.d_singular[i]:
                    break
                for row in range(2):
                    fd = (4 * d2[i, row] - d1[i, row]) / 3
                    exact = m.d_transitions[i, row, k]
                    compared += 1
                    if abs(exact - fd) > 1e-4 * (1 + abs(fd)):
                        bad.append((p.tolist(), i, row, k, exact, fd))
    print(f"{rule}, e > 0: {restitution}: {compared} derivatives compared")
    assert compared >= minimum, compared
    assert not bad, bad[:5]

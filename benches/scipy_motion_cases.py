"""Deterministic full-motion cases run with the independent scipy reference.

``CASES`` is a list of (name, kwargs) for ``simulate_reference(**kwargs)``
(``tests/reference_motion.py``): the test oracle for ``eccjump.simulate`` and the
straightforward ``solve_ivp`` baseline it is benchmarked against. Angles in radians,
units g = R = M = 1.

    python benches/scipy_motion_cases.py            # every case: transitions and timing
    python benches/scipy_motion_cases.py jarm_paper  # only the named cases
"""

from __future__ import annotations

import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from reference_motion import format_transitions, simulate_reference

D = math.radians
JARM = {"chi": 0.15, "km": 0.02, "alpha": D(40.0), "mu_s": 1.0}
SLIPJ = {"chi": 0.5, "km": 0.4, "alpha": D(30.0), "mu_s": 1.0}
RUN = {"t_max": 20.0, "max_transitions": 40}

CASES: list[tuple[str, dict]] = [
    ("jarm_paper", {**JARM, **RUN}),
    ("jarm_normal_force", {**JARM, **RUN, "rule": "normal_force"}),
    ("jarm_e05", {**JARM, **RUN, "restitution": 0.5}),
    ("jarm_muk05", {**JARM, **RUN, "mu_k": 0.5}),
    ("slipjump_paper", {**SLIPJ, **RUN}),
    ("slipjump_normal_force", {**SLIPJ, **RUN, "rule": "normal_force"}),
    ("slipjump_e05", {**SLIPJ, **RUN, "restitution": 0.5}),
    ("slipjump_e1", {**SLIPJ, **RUN, "restitution": 1.0}),
    ("slipjump_muk06", {**SLIPJ, **RUN, "mu_k": 0.6}),
    ("low_friction_mu02", {**SLIPJ, **RUN, "mu_s": 0.2}),
    ("slip_at_start_mu01", {**RUN, "chi": 0.3, "km": 0.3, "alpha": D(60.0), "mu_s": 0.1}),
    ("alpha0_omega15", {**RUN, "chi": 0.3, "km": 0.3, "alpha": 0.0, "mu_s": 1.0, "omega0": 1.5}),
    (
        "alpha0_omega15_nf",
        {**RUN, "chi": 0.3, "km": 0.3, "alpha": 0.0, "mu_s": 1.0, "omega0": 1.5},
    ),
    ("flies_at_once", {**RUN, "chi": 0.5, "km": 0.2, "alpha": D(20.0), "mu_s": 1.0, "omega0": 2.0}),
    (
        "flies_at_once_e05",
        {
            **RUN,
            "chi": 0.5,
            "km": 0.2,
            "alpha": D(20.0),
            "mu_s": 1.0,
            "omega0": 2.0,
            "restitution": 0.5,
        },
    ),
    ("slip0_forward", {**RUN, "chi": 0.3, "km": 0.3, "alpha": D(30.0), "mu_s": 0.5, "slip0": 1.0}),
    (
        "slip0_backspin",
        {**RUN, "chi": 0.3, "km": 0.3, "alpha": D(30.0), "mu_s": 0.5, "slip0": -2.0},
    ),
    ("theta0_90", {**RUN, "chi": 0.6, "km": 0.1, "alpha": D(20.0), "mu_s": 1.0, "theta0": D(90.0)}),
    ("steep_heavy_point", {**RUN, "chi": 0.9, "km": 0.05, "alpha": D(85.0), "mu_s": 1.0}),
    ("centred_low_mu", {**RUN, "chi": 0.0, "km": 0.5, "alpha": D(30.0), "mu_s": 0.1}),
]
CASES[12][1]["rule"] = "normal_force"


def main(argv: list[str]) -> None:
    wanted = set(argv)
    total = 0.0
    for name, kw in CASES:
        if wanted and name not in wanted:
            continue
        t0 = time.perf_counter()
        res = simulate_reference(**kw)
        dt = time.perf_counter() - t0
        total += dt
        led = res["energy0"] - (
            res["energy_end"] + res["dissipated_slip"] + res["dissipated_impacts"]
        )
        print(f"== {name}: {kw}")
        print(format_transitions(res))
        print(
            f"   {dt * 1e3:.1f} ms, nfev={res['nfev']}, transitions={len(res['transitions']) - 1},"
            f" ledger residual={led:+.1e}"
        )
    print(f"total {total:.2f} s")


if __name__ == "__main__":
    main(sys.argv[1:])

"""Which integrator to pick: the four Runge-Kutta pairs side by side, in one run, on the two
user-level calls that integrate (``roll`` to its first event, ``simulate`` through its first
transitions), at the same tolerances, with the error each gives against a tight reference
(Vern9 at rtol 1e-14 for ``roll``, 1e-13 for ``simulate``).

    python benches/bench_pairs.py [--points 600] [--rtol 1e-10] [--json bench_pairs.json]

The points are random bodies and ramps (χ ∈ [0.05, 0.9], k_m a random share of 1 − χ,
α ∈ [0.1, 1.4] rad, μ_s = 1 for ``roll``, 0.8 for ``simulate`` with 6 transitions and
t_max = 30); the seed is fixed. Time per call: the best of three passes over all points.
Error: ``roll``'s |θ − θ_ref| at its end, ``simulate``'s largest |t − t_ref| over the first
three transitions (where both runs have them).
"""

from __future__ import annotations

import argparse
import time
from collections.abc import Callable
from typing import Any

import numpy as np
import results

import eccjump

PAIRS = ("RK45", "DOP853", "Vern9")


def random_points(n: int, seed: int) -> list[tuple[eccjump.Cylinder, float]]:
    rng = np.random.default_rng(seed)
    out = []
    for _ in range(n):
        chi = rng.uniform(0.05, 0.9)
        km = rng.uniform(0.01, 1.0) * (1.0 - chi)
        out.append((eccjump.Cylinder(chi, km), rng.uniform(0.1, 1.4)))
    return out


def best_pass(call: Callable[[], list[Any]], passes: int = 3) -> tuple[float, list[Any]]:
    """The best wall time of ``passes`` calls, and the last call's results."""
    best, out = float("inf"), []
    for _ in range(passes):
        t0 = time.perf_counter()
        out = call()
        best = min(best, time.perf_counter() - t0)
    return best, out


def roll_errors(out: list[Any], ref: list[Any]) -> np.ndarray:
    return np.array([abs(o.theta[-1] - r.theta[-1]) for o, r in zip(out, ref, strict=True)])


def simulate_errors(out: list[Any], ref: list[Any]) -> np.ndarray:
    errs = []
    for o, r in zip(out, ref, strict=True):
        k = min(len(o.transitions), len(r.transitions), 3)
        errs.append(max(abs(o.transitions[i].t - r.transitions[i].t) for i in range(k)))
    return np.array(errs)


def measure(points: int, rtol: float) -> dict[str, Any]:
    pts = random_points(points, seed=1)
    sim = {"mu_s": 0.8, "max_transitions": 6, "t_max": 30.0}
    calls = {
        "roll": (
            lambda integ, tol: [
                eccjump.roll(b, a, mu_s=1.0, integrator=integ, **tol) for b, a in pts
            ],
            {"rtol": 1e-14, "atol": 1e-16},
            roll_errors,
        ),
        "simulate": (
            lambda integ, tol: [
                eccjump.simulate(b, a, integrator=integ, **sim, **tol) for b, a in pts
            ],
            {"rtol": 1e-13, "atol": 1e-15},
            simulate_errors,
        ),
    }
    rows = []
    for name, (run, tight, errors) in calls.items():
        ref = run("Vern9", tight)
        base = None
        for integ in PAIRS:
            seconds, out = best_pass(lambda: run(integ, {"rtol": rtol}))  # noqa: B023
            err = errors(out, ref)
            base = base or seconds
            rows.append(
                {
                    "call": name,
                    "integrator": integ,
                    "us_per_call": 1e6 * seconds / points,
                    "speed_vs_rk45": base / seconds,
                    "median_error": float(np.median(err)),
                    "p90_error": float(np.quantile(err, 0.9)),
                }
            )
    return {"points": points, "rtol": rtol, "rows": rows}


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.split("\n\n")[0])
    ap.add_argument("--points", type=int, default=600)
    ap.add_argument("--rtol", type=float, default=1e-10)
    results.add_json_option(ap, "pairs")
    args = ap.parse_args()
    res = measure(args.points, args.rtol)
    head = ("call", "pair", "µs/call", "× RK45", "median err", "90% err")
    print("{:9s} {:7s} {:>9s} {:>7s} {:>11s} {:>9s}".format(*head))
    for r in res["rows"]:
        print(
            f"{r['call']:9s} {r['integrator']:7s} {r['us_per_call']:9.1f} "
            f"{r['speed_vs_rk45']:7.2f} {r['median_error']:11.1e} {r['p90_error']:9.1e}"
        )
    results.write(args.json, "pairs", args, **res)


if __name__ == "__main__":
    main()

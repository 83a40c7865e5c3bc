"""The user-level benchmarks of two builds of eccjump side by side, in one run.

Each build is a source tree whose ``python/`` holds a compiled ``eccjump/_core`` (for
example a git worktree of an older commit, built with ``cargo build --release -p eccjump-py
--features pyo3/extension-module`` and the library copied to ``python/eccjump/_core.abi3.so``).
The benchmarks run in fresh interpreters, the builds alternating round by round, and the
best time of each is kept, so that a drift of the machine hits both alike::

    python benches/compare.py --before /work/wt-base --after . --rounds 3

The options are the same for both builds, given explicitly where a default changed between
them (``refine_extrema``, ``max_transitions``); the map functions are called by their
keywords as each version names them (``km`` became ``km_frac`` in 0.2).
"""

from __future__ import annotations

import argparse
import json
import os
import subprocess
import sys
from pathlib import Path

import results

#: Each benchmark: its name, what one run does, and its unit.
BENCHES = {
    "roll RK45 [µs/call]": "roll",
    "roll Vern9 [µs/call]": "roll_vern9",
    "jarm closed form, 10^5 random points [ms]": "jarm_closed",
    "jarm ODE route, 2000 random points [ms]": "jarm_ode",
    "region closed form, 60^3 [ms]": "region_closed",
    "region ODE route, 12^3 [ms]": "region_ode",
    "simulate, 3 runs to t = 100 [ms]": "simulate",
    "motion_map, 20^3 [ms]": "motion_map",
}

RUNNER = r'''
import inspect, json, math, sys, time
import numpy as np
import eccjump

def best(fn, repeat=5, number=1):
    out = math.inf
    for _ in range(repeat):
        t = time.perf_counter()
        for _ in range(number):
            fn()
        out = min(out, (time.perf_counter() - t) / number)
    return out

def grid_call(fn, **axes):
    """A map call by the keywords this version takes (km_frac since 0.2, km before)."""
    names = inspect.signature(fn).parameters
    if "km_frac" not in names:
        axes["km"] = axes.pop("km_frac")
    return fn(**axes)

rng = np.random.default_rng(7)
def points(n):
    a = rng.uniform(0.0, math.pi / 2, n); c = rng.uniform(1e-3, 1.0, n)
    return a, c, rng.uniform(0.0, 1.0, n) * (1.0 - c)

body = eccjump.Cylinder(0.15, 0.02)
a5, c5, k5 = points(100_000)
a3, c3, k3 = points(2_000)
g60 = np.linspace(0.01, 1.5, 60), np.linspace(0.01, 0.99, 60), np.linspace(0.0, 1.0, 60)
g12 = tuple(x[::5] for x in g60)
g20 = tuple(x[::3] for x in g60)
runs = {
    "roll": lambda: best(lambda: eccjump.roll(body, math.radians(40)), 7, 2000) * 1e6,
    "roll_vern9": lambda: best(
        lambda: eccjump.roll(body, math.radians(40), integrator="Vern9"), 7, 2000) * 1e6,
    "jarm_closed": lambda: best(
        lambda: eccjump.jarm(a5, c5, k5, 1.0, refine_extrema=False), 5) * 1e3,
    "jarm_ode": lambda: best(
        lambda: eccjump.jarm(a3, c3, k3, 1.0, method="ode", refine_extrema=False), 3) * 1e3,
    "region_closed": lambda: best(lambda: grid_call(
        eccjump.region, alpha=g60[0], chi=g60[1], km_frac=g60[2], mu_s=1.0), 5) * 1e3,
    "region_ode": lambda: best(lambda: grid_call(
        eccjump.region, alpha=g12[0], chi=g12[1], km_frac=g12[2], mu_s=1.0, method="ode"), 3) * 1e3,
    "simulate": lambda: best(lambda: [eccjump.simulate(
        eccjump.Cylinder(c, k), a, mu_s=0.8, mu_k=0.6, restitution=0.3, t_max=100.0)
        for a, c, k in ((0.7, 0.15, 0.02), (1.1, 0.5, 0.3), (0.4, 0.3, 0.1))], 5) * 1e3,
    "motion_map": lambda: best(lambda: grid_call(
        eccjump.motion_map, alpha=g20[0], chi=g20[1], km_frac=g20[2], mu_s=1.0,
        max_transitions=100), 3) * 1e3,
}
print(json.dumps({k: runs[k]() for k in sys.argv[1:]}))
'''


def measure(tree: Path, keys: list[str]) -> dict[str, float]:
    """The benchmarks ``keys`` with the eccjump of ``tree``, in a fresh interpreter."""
    env = {**os.environ, "PYTHONPATH": str(tree / "python")}
    check = "import eccjump, sys; print(eccjump.__file__)"
    where = subprocess.run(
        [sys.executable, "-c", check], env=env, capture_output=True, text=True, check=True
    ).stdout.strip()
    if not where.startswith(str(tree.resolve())):
        sys.exit(f"{tree}: eccjump comes from {where}, not this tree")
    out = subprocess.run(
        [sys.executable, "-c", RUNNER, *keys], env=env, capture_output=True, text=True, check=True
    )
    return json.loads(out.stdout)


def main() -> None:
    ap = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    ap.add_argument("--before", type=Path, required=True, help="the tree of the older build")
    ap.add_argument("--after", type=Path, default=Path("."), help="the tree of the newer build")
    ap.add_argument("--rounds", type=int, default=3, help="alternating rounds (best kept)")
    ap.add_argument("--only", nargs="*", default=None, help="benchmark keys (default: all)")
    results.add_json_option(ap, "compare")
    args = ap.parse_args()
    keys = args.only or list(BENCHES.values())
    best: dict[str, dict[str, float]] = {"before": {}, "after": {}}
    for _ in range(args.rounds):
        for side in ("before", "after"):
            tree = getattr(args, side).resolve()
            for k, v in measure(tree, keys).items():
                best[side][k] = min(v, best[side].get(k, float("inf")))
    print("| benchmark | before | after | after / before |")
    print("|---|---:|---:|---:|")
    rows = []
    for label, k in BENCHES.items():
        if k in keys:
            b, a = best["before"][k], best["after"][k]
            print(f"| {label} | {b:.4g} | {a:.4g} | {a / b:.3f} |")
            rows.append({"benchmark": label, "key": k, "before": b, "after": a, "ratio": a / b})
    results.write(args.json, "compare", args, rows=rows)


if __name__ == "__main__":
    main()

"""Each performance mechanism of the core, measured side by side in one run on the
user-level benchmarks (docs/performance.md).

    python benches/bench_mechanisms.py [--rounds 3] [--json PATH]

Every configuration runs in its own process with ``ECCJUMP_OFF`` naming the mechanism
switched off; ``base`` switches nothing off. The switches exist only in a build with a
temporary patch that reads ``ECCJUMP_OFF`` at the mechanism measured (without it every
configuration is ``base``): write it, build the extension, point PYTHONPATH at that copy.
The patch of the table in docs/performance.md, made on commit 0f1e809, no longer applies
(two of its mechanisms are gone); it stays in the history: ``git show
c4c8373:benches/mechanism_switches.patch``.
Rounds interleave the configurations, and each figure is the best of its rounds in CPU time
(one thread, so that the figures are per core and hold on a machine shared with other work).
``--configs`` limits the run.
"""

from __future__ import annotations

import argparse
import json
import math
import os
import subprocess
import sys
import time

import results

CONFIGS = ("base", "lanes", "quiet", "skip", "memo", "jmemo", "lanetrig", "roots", "pathskip")
PAIRS = ("DOP853", "Vern9")


def best(fn, repeat: int = 5) -> float:
    out = math.inf
    for _ in range(repeat):
        t0 = time.process_time()
        fn()
        out = min(out, time.process_time() - t0)
    return out


def child(pairs: bool) -> dict[str, float]:
    """The benchmarks of one configuration, in seconds (one thread)."""
    import numpy as np
    from scipy_motion_cases import CASES

    import eccjump

    rng = np.random.default_rng(1)
    n = 50_000
    alpha = rng.uniform(0.0, math.pi / 2, n)
    chi = rng.uniform(1e-3, 1.0, n)
    km = rng.uniform(0.0, 1.0, n) * (1.0 - chi)
    body = eccjump.Cylinder(0.15, 0.02)
    grid = (np.radians(np.linspace(1.0, 89.0, 40)), np.linspace(0.02, 0.98, 40))
    small = (np.radians(np.linspace(1.0, 89.0, 12)), np.linspace(0.02, 0.98, 10))
    frac, frac_small = np.linspace(0.02, 0.98, 20), np.linspace(0.02, 0.98, 10)
    mgrid = np.linspace(0.05, 0.95, 12)
    default = os.environ.get("BENCH_INTEGRATOR", "RK45")
    cases = CASES[:6]
    calls = [(eccjump.Cylinder(kw["chi"], kw["km"]), kw) for _, kw in cases]

    def roll(integ: str = default) -> None:
        for _ in range(200):
            eccjump.roll(body, math.radians(40), integrator=integ)

    def jarm_ode(integ: str = default) -> None:
        eccjump.jarm(
            alpha[:2000], chi[:2000], km[:2000], 0.6, method="ode", n_threads=1, integrator=integ
        )

    def simulate(integ: str = default) -> None:
        for _ in range(10):
            for b, kw in calls:
                opts = {k: v for k, v in kw.items() if k not in ("chi", "km", "alpha")}
                eccjump.simulate(
                    b, kw["alpha"], **{**opts, "max_transitions": 5, "integrator": integ}
                )

    def motion_map(integ: str = default) -> None:
        eccjump.motion_map(
            alpha=np.radians(mgrid * 90),
            chi=mgrid,
            km_frac=mgrid,
            mu_s=1.0,
            n_threads=1,
            integrator=integ,
        )

    res = {
        "roll": best(roll) / 200,
        "jarm_closed": best(lambda: eccjump.jarm(alpha, chi, km, 0.6, n_threads=1)),
        "jarm_ode": best(jarm_ode),
        "region_closed": best(lambda: eccjump.region(*grid, frac, 0.6, n_threads=1)),
        "region_ode": best(
            lambda: eccjump.region(
                *small, frac_small, 0.6, method="ode", n_threads=1, integrator=default
            )
        ),
        "simulate": best(simulate) / (10 * len(calls)),
        "motion_map": best(motion_map, 3),
    }
    if pairs:
        for integ in PAIRS:
            res[f"roll_{integ}"] = best(lambda i=integ: roll(i)) / 200
            res[f"jarm_ode_{integ}"] = best(lambda i=integ: jarm_ode(i))
            res[f"simulate_{integ}"] = best(lambda i=integ: simulate(i)) / (10 * len(calls))
            res[f"motion_map_{integ}"] = best(lambda i=integ: motion_map(i), 3)
    return res


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--rounds", type=int, default=3)
    p.add_argument("--configs", default=",".join(CONFIGS))
    results.add_json_option(p, "mechanisms")
    p.add_argument("--integrator", default="RK45", help="the pair of every benchmark (RK45)")
    p.add_argument("--child", default=None, help=argparse.SUPPRESS)
    args = p.parse_args()
    if args.child is not None:
        print(json.dumps(child(args.child == "base")))
        return
    configs = args.configs.split(",")
    table: dict[str, dict[str, float]] = {}
    for r in range(args.rounds):
        for c in configs:
            env = {
                **os.environ,
                "ECCJUMP_OFF": "" if c == "base" else c,
                "BENCH_INTEGRATOR": args.integrator,
            }
            out = subprocess.run(
                [sys.executable, __file__, "--child", c if args.integrator == "RK45" else "-"],
                env=env,
                capture_output=True,
                text=True,
                check=True,
            )
            got = json.loads(out.stdout.strip().splitlines()[-1])
            row = table.setdefault(c, {})
            for k, v in got.items():
                row[k] = min(row.get(k, math.inf), v)
            print(
                f"round {r + 1} {c}: " + ", ".join(f"{k} {v:.4g}" for k, v in got.items()),
                flush=True,
            )
    base = table.get("base", {})
    print("\nslowdown with the mechanism off (time off / time on):")
    keys = [k for k in base if k.split("_")[-1] not in PAIRS]
    print("config".ljust(10) + "".join(k.rjust(14) for k in keys))
    for c, row in table.items():
        print(c.ljust(10) + "".join(f"{row[k] / base[k]:14.3f}" for k in keys))
    for integ in PAIRS:
        print(
            f"{integ}: "
            + ", ".join(
                f"{k} {base[k] / base[f'{k}_{integ}']:.2f}x"
                for k in ("roll", "jarm_ode", "simulate", "motion_map")
                if f"{k}_{integ}" in base
            )
        )
    results.write(args.json, "mechanisms", args, table=table)


if __name__ == "__main__":
    main()

"""eccjump.simulate against the straightforward scipy solve_ivp event-driven model
(tests/reference_motion.py), side by side in one run, on the cases of
benches/scipy_motion_cases.py cut to their first transitions (from rest to the first landing
and beyond).

    python benches/bench_simulate.py [--transitions 5] [--repeat 200] [--integrator DOP853]
                                     [--cases jarm_paper,...] [--json PATH]

Per case: both transition sequences (they must agree), the largest difference of the
transition angles, and the time per run of each: scipy's the best of three runs, eccjump's
the best of five batches of ``--repeat`` calls, each batch's time divided by its calls.
Only the call is timed: the body and the options of a case are made once, before the
batches, as a caller running many starts or tolerances on one body would (making a
``Cylinder`` costs about 0.8 µs). The figures also go to ``--json`` (default
bench_simulate.json in the current directory).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

import results
from bench_roll import best_time
from reference_motion import simulate_reference
from scipy_motion_cases import CASES

import eccjump

INTEGRATORS = ("RK45", "DOP853", "Vern9")


def eccjump_call(kw: dict, transitions: int, integrator: str = "RK45"):
    """The call of one case, its body and options made once."""
    body = eccjump.Cylinder(kw["chi"], kw["km"])
    opts = {k: v for k, v in kw.items() if k not in ("chi", "km", "alpha")}
    opts["max_transitions"] = transitions
    opts["integrator"] = integrator
    alpha = kw["alpha"]
    return lambda: eccjump.simulate(body, alpha, **opts)


def sequence_of(transitions) -> list[tuple[str, str]]:
    return [(t[2], t[3]) for t in transitions]


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--transitions", type=int, default=5)
    p.add_argument("--repeat", type=int, default=200)
    p.add_argument("--integrator", default="RK45", choices=INTEGRATORS)
    p.add_argument("--cases", default="", help="comma-separated case names (default: all 20)")
    results.add_json_option(p, "simulate")
    args = p.parse_args(argv)
    n = args.transitions
    wanted = set(filter(None, args.cases.split(",")))
    unknown = wanted - {name for name, _ in CASES}
    if unknown:
        p.error(f"unknown cases: {', '.join(sorted(unknown))}")
    head = ("case", "same", "max dθ", "scipy ms", "eccjump µs", "x")
    print("{:28s} {:>4s} {:>9s} {:>9s} {:>11s} {:>7s}".format(*head))
    ratios = []
    rows = []
    for name, kw in CASES:
        if wanted and name not in wanted:
            continue
        ref = simulate_reference(**{**kw, "max_transitions": n})
        t_ref = best_time(lambda kw=kw: simulate_reference(**{**kw, "max_transitions": n}), 3, 1)
        call = eccjump_call(kw, n, args.integrator)
        res = call()
        t_ecc = best_time(call, 5, args.repeat)
        ours = [(t.to_mode, t.reason) for t in res.transitions]
        theirs = sequence_of(ref["transitions"])
        k = min(len(ours), len(theirs))
        same = ours[:k] == theirs[:k] and k >= min(n + 1, len(theirs), len(ours))
        dtheta = max(
            (
                abs(a.theta - b[4])
                for a, b in zip(res.transitions, ref["transitions"], strict=False)
            ),
            default=math.nan,
        )
        ratios.append(t_ref / t_ecc)
        rows.append(
            {
                "case": name,
                "same_sequence": same,
                "max_dtheta_rad": dtheta,
                "scipy_ms_per_run": t_ref * 1e3,
                "eccjump_us_per_run": t_ecc * 1e6,
                "speed_up": t_ref / t_ecc,
            }
        )
        print(
            f"{name:28s} {'yes' if same else 'NO':>4s} {dtheta:9.1e} {t_ref * 1e3:9.2f} "
            f"{t_ecc * 1e6:11.1f} {t_ref / t_ecc:7.0f}"
        )
    ratios.sort()
    median, low = ratios[len(ratios) // 2], ratios[0]
    print(f"speed-up: median {median:.0f}x, min {low:.0f}x")
    results.write(
        args.json,
        "simulate",
        args,
        rows=rows,
        same_sequence=sum(r["same_sequence"] for r in rows),
        cases=len(rows),
        speed_up_median=median,
        speed_up_min=low,
        speed_up_max=ratios[-1],
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

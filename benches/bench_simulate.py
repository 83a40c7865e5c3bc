"""eccjump.simulate against the straightforward scipy solve_ivp event-driven model
(tests/reference_motion.py), side by side in one run, on the cases of
benches/scipy_motion_cases.py cut to their first transitions (from rest to the first landing
and beyond).

    python benches/bench_simulate.py [--transitions 5] [--repeat 200] [--integrator DOP853]

Per case: both transition sequences (they must agree), the largest difference of the
transition angles, and the time per run of each: scipy's the best of three runs, eccjump's
the best of five batches of ``--repeat`` calls, each batch's time divided by its calls.
Only the call is timed: the body and the options of a case are made once, before the
batches, as a caller running many starts or tolerances on one body would (making a
``Cylinder`` costs about 0.8 µs).
"""

from __future__ import annotations

import argparse
import math
import sys
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))
sys.path.insert(0, str(Path(__file__).resolve().parent))

from bench_roll import best_time
from reference_motion import simulate_reference
from scipy_motion_cases import CASES

import eccjump


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
    p.add_argument("--integrator", default="RK45", choices=("RK45", "DOP853"))
    args = p.parse_args(argv)
    n = args.transitions
    head = ("case", "same", "max dθ", "scipy ms", "eccjump µs", "x")
    print("{:28s} {:>4s} {:>9s} {:>9s} {:>11s} {:>7s}".format(*head))
    ratios = []
    for name, kw in CASES:
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
        print(
            f"{name:28s} {'yes' if same else 'NO':>4s} {dtheta:9.1e} {t_ref * 1e3:9.2f} "
            f"{t_ecc * 1e6:11.1f} {t_ref / t_ecc:7.0f}"
        )
    ratios.sort()
    print(f"speed-up: median {ratios[len(ratios) // 2]:.0f}x, min {ratios[0]:.0f}x")
    return 0


if __name__ == "__main__":
    sys.exit(main())

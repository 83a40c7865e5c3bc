"""Deterministic full-motion cases run with the independent scipy reference.

``CASES`` is a list of (name, kwargs) for ``simulate_reference(**kwargs)``
(``tests/reference_motion.py``): the test oracle for ``eccjump.simulate`` and the
straightforward ``solve_ivp`` baseline it is benchmarked against. Angles in radians,
units g = R = M = 1.

    python benches/scipy_motion_cases.py            # every case: transitions and timing
    python benches/scipy_motion_cases.py jarm_paper  # only the named cases
    python benches/scipy_motion_cases.py --table     # one compact line per case

Each run also writes its per-case figures to ``--json PATH`` (default
bench_scipy_motion_cases.json in the current directory).
"""

from __future__ import annotations

import argparse
import math
import sys
import time
from pathlib import Path

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

import results
from reference_motion import format_transitions, simulate_reference

D = math.radians
JARM = {"chi": 0.15, "km": 0.02, "alpha": D(40.0), "mu_s": 1.0}
SLIPJ = {"chi": 0.5, "km": 0.4, "alpha": D(30.0), "mu_s": 1.0}
RUN = {"t_max": 20.0, "max_transitions": 40}

A0 = {"chi": 0.3, "km": 0.3, "alpha": 0.0, "mu_s": 1.0, "omega0": 1.5}  # flat, moving
FLY = {"chi": 0.5, "km": 0.2, "alpha": D(20.0), "mu_s": 1.0, "omega0": 2.0}  # χθ̇0² > cos α
S30 = {"chi": 0.3, "km": 0.3, "alpha": D(30.0), "mu_s": 0.5}


def case(name: str, base: dict, **over) -> tuple[str, dict]:
    return name, {**base, **RUN, **over}


CASES: list[tuple[str, dict]] = [
    case("jarm_paper", JARM),
    case("jarm_normal_force", JARM, rule="normal_force"),
    case("jarm_e05", JARM, restitution=0.5),
    case("jarm_muk05", JARM, mu_k=0.5),
    case("slipjump_paper", SLIPJ),
    case("slipjump_normal_force", SLIPJ, rule="normal_force"),
    case("slipjump_e05", SLIPJ, restitution=0.5),
    case("slipjump_e1", SLIPJ, restitution=1.0),
    case("slipjump_muk06", SLIPJ, mu_k=0.6),
    case("low_friction_mu02", SLIPJ, mu_s=0.2),
    case("slip_at_start_mu01", {"chi": 0.3, "km": 0.3, "alpha": D(60.0), "mu_s": 0.1}),
    case("alpha0_omega15", A0),
    case("alpha0_omega15_mu01", A0, mu_s=0.1),
    case("flies_at_once", FLY),
    case("flies_at_once_e05", FLY, restitution=0.5),
    case("slip0_forward", S30, slip0=1.0),
    case("slip0_backspin", S30, slip0=-2.0),
    case("theta0_90", {"chi": 0.6, "km": 0.1, "alpha": D(20.0), "mu_s": 1.0, "theta0": D(90.0)}),
    case("steep_heavy_point", {"chi": 0.9, "km": 0.05, "alpha": D(85.0), "mu_s": 1.0}),
    case("centred_low_mu", {"chi": 0.0, "km": 0.5, "alpha": D(30.0), "mu_s": 0.1}),
]


SHORT = {"ROLL": "R", "SLIP": "S", "FLIGHT": "F", None: "-"}


def compact(res: dict, n: int = 8) -> str:
    """The first ``n`` transitions as R -liftoff-> F -impact-> S ..., with runs of identical
    FLIGHT -> FLIGHT bounces folded into one (×k)."""
    out = [SHORT[res["transitions"][0][2]]]
    last, count = None, 0
    for tr in res["transitions"][1:]:
        key = (tr[3], SHORT[tr[2]])
        if key == last and key == ("impact", "F"):
            count += 1
            continue
        if count > 1:
            out[-1] += f"(x{count})"
        last, count = key, 1
        out.append(f"-{key[0]}->{key[1]}")
        if len(out) > n:
            out.append(" ...")
            break
    if count > 1 and not out[-1].endswith("..."):
        out[-1] += f"(x{count})"
    return "".join(out)


def main(argv: list[str] | None = None) -> None:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("names", nargs="*", help="only these cases (default: all)")
    p.add_argument("--table", action="store_true", help="one compact line per case")
    results.add_json_option(p, "scipy_motion_cases")
    args = p.parse_args(argv)
    wanted = set(args.names)
    total = 0.0
    rows = []
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
        rows.append(
            {
                "case": name,
                "sequence": compact(res),
                "status": res["status"],
                "ms": dt * 1e3,
                "nfev": res["nfev"],
                "transitions": len(res["transitions"]) - 1,
                "ledger_residual": led,
            }
        )
        if args.table:
            print(
                f"{name:<22} {compact(res):<95} {res['status']:<15} {dt * 1e3:6.1f} ms "
                f"nfev={res['nfev']:<6} n={len(res['transitions']) - 1:<3} ledger={led:+.0e}"
            )
            continue
        print(f"== {name}: {kw}")
        print(format_transitions(res))
        print(
            f"   {dt * 1e3:.1f} ms, nfev={res['nfev']}, transitions={len(res['transitions']) - 1},"
            f" ledger residual={led:+.1e}"
        )
    print(f"total {total:.2f} s")
    results.write(args.json, "scipy_motion_cases", args, rows=rows, total_s=total)


if __name__ == "__main__":
    main()

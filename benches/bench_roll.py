"""One pure-rolling run from rest at theta = 0 to lift-off: eccjump against scipy.

Both integrate the same equation with Dormand–Prince 5(4) (scipy's ``RK45``), the same
tolerances and the same terminal lift-off event (chi theta'^2 cos theta - cos alpha, rising);
Python call overhead is included on both sides. Run:

    python benches/bench_roll.py [--rtol 1e-10] [--atol 1e-12] [--number 200] [--json PATH]

Time per call: the best mean of rounds of ``--number`` calls (five rounds for eccjump, three
rounds of three calls for scipy). Results also go to ``--json`` (default bench_roll.json).
"""

from __future__ import annotations

import argparse
import math
import platform
import time

import numpy as np
import results
from scipy.integrate import solve_ivp

import eccjump


def scipy_roll(
    alpha: float, chi: float, ic: float, rtol: float, atol: float, method: str = "RK45"
) -> float:
    sa, ca = math.sin(alpha), math.cos(alpha)

    def rhs(_t, y):
        th, w = y
        s, c = math.sin(th), math.cos(th)
        return [w, (chi * w * w * s + chi * (sa * c + ca * s) + sa) / (ic + 1 + 2 * chi * c)]

    def liftoff(_t, y):
        return chi * y[1] * y[1] * math.cos(y[0]) - ca

    liftoff.terminal = True
    liftoff.direction = 1
    sol = solve_ivp(rhs, (0, 1e3), [0.0, 0.0], method=method, rtol=rtol, atol=atol, events=liftoff)
    return float(sol.y_events[0][0][0])


def best_time(fn, repeat: int, number: int) -> float:
    """Best mean seconds per call over `repeat` rounds of `number` calls."""
    best = math.inf
    for _ in range(repeat):
        t0 = time.perf_counter()
        for _ in range(number):
            fn()
        best = min(best, (time.perf_counter() - t0) / number)
    return best


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument("--atol", type=float, default=1e-12)
    p.add_argument("--number", type=int, default=200, help="eccjump calls per round (200)")
    results.add_json_option(p, "roll")
    args = p.parse_args()
    body = eccjump.Cylinder(0.15, 0.02)
    alpha = math.radians(40)
    ours = eccjump.roll(body, alpha, rtol=args.rtol, atol=args.atol)
    theirs = scipy_roll(alpha, body.chi, body.Ic, args.rtol, args.atol)
    t_ours = best_time(
        lambda: eccjump.roll(body, alpha, rtol=args.rtol, atol=args.atol), 5, max(1, args.number)
    )
    t_scipy = best_time(lambda: scipy_roll(alpha, body.chi, body.Ic, args.rtol, args.atol), 3, 3)
    print(
        f"machine: {platform.machine()}, {results.cpu_model()}, "
        f"python {platform.python_version()}, numpy {np.__version__}"
    )
    print(
        f"problem: alpha = 40 deg, chi = 0.15, km = 0.02, from rest to lift-off, "
        f"rtol = {args.rtol:g}, atol = {args.atol:g}"
    )
    print(f"{'route':<22}{'theta_J [deg]':>18}{'time per call':>18}{'speed-up':>10}")
    print(
        f"{'scipy solve_ivp RK45':<22}{math.degrees(theirs):>18.12f}"
        f"{t_scipy * 1e3:>15.3f} ms{1.0:>10.0f}"
    )
    print(
        f"{'eccjump.roll':<22}{math.degrees(ours.theta[-1]):>18.12f}"
        f"{t_ours * 1e6:>15.3f} us{t_scipy / t_ours:>9.0f}x"
    )
    results.write(
        args.json,
        "roll",
        args,
        case={"alpha_deg": 40.0, "chi": body.chi, "km": body.km, "integrator": "RK45"},
        rows=[
            {
                "route": "scipy solve_ivp RK45",
                "theta_J_deg": math.degrees(theirs),
                "us_per_call": t_scipy * 1e6,
                "speed_up": 1.0,
            },
            {
                "route": "eccjump.roll",
                "theta_J_deg": math.degrees(ours.theta[-1]),
                "us_per_call": t_ours * 1e6,
                "speed_up": t_scipy / t_ours,
            },
        ],
    )


if __name__ == "__main__":
    main()

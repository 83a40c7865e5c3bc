"""One pure-rolling run from rest at theta = 0 to lift-off: eccjump against scipy.

Both integrate the same equation with Dormand–Prince 5(4) (scipy's ``RK45``), the same
tolerances and the same terminal lift-off event (chi theta'^2 cos theta - cos alpha, rising);
Python call overhead is included on both sides. Run:  python benches/bench_roll.py
"""

from __future__ import annotations

import argparse
import math
import platform
import time

import numpy as np
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
    p = argparse.ArgumentParser(description=__doc__)
    p.add_argument("--rtol", type=float, default=1e-10)
    p.add_argument("--atol", type=float, default=1e-12)
    args = p.parse_args()
    body = eccjump.Cylinder(0.15, 0.02)
    alpha = math.radians(40)
    ours = eccjump.roll(body, alpha, rtol=args.rtol, atol=args.atol)
    theirs = scipy_roll(alpha, body.chi, body.Ic, args.rtol, args.atol)
    t_ours = best_time(lambda: eccjump.roll(body, alpha, rtol=args.rtol, atol=args.atol), 5, 200)
    t_scipy = best_time(lambda: scipy_roll(alpha, body.chi, body.Ic, args.rtol, args.atol), 3, 3)
    print(
        f"machine: {platform.machine()}, {platform.processor() or 'cpu'}, "
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


if __name__ == "__main__":
    main()

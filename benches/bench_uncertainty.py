"""Uncertainty studies (eccjump.uncertainty): 10^5 samples of the JARM question (closed form)
and 10^6 samples of the full motion to the first landing, on every core; and the map of P(JARM)
(eccjump.uncertainty_map) on 20 x 20 x 4 grid points with 2000 samples each (3.2e6
classifications).

    python benches/bench_uncertainty.py [--jarm 100000] [--motion 1000000] [--map 2000]
                                        [--threads 0] [--integrator RK45] [--json PATH]

The study: the paper's JARM point (alpha = 40 deg, chi = 0.15, k_m = 0.02, mu_s = 1) with
normal tolerances of 2 deg on alpha, 0.02 on chi, 0.01 on k_m, 0.15 on mu_s (and, for the
motion, 0.2 on e and 2 deg on theta0), random sampling. The map: alpha 30 ... 50 deg, chi
0.05 ... 0.3, km_frac 0 ... 0.1, mu_s = 1, tolerances 0.25 deg on alpha and 0.002 on chi.
The time includes the sampling and the summaries. The figures also go to ``--json`` (default
bench_uncertainty.json).
"""

from __future__ import annotations

import argparse
import math
import os
import time

import numpy as np
import results

import eccjump

SD = {"alpha": math.radians(2), "chi": 0.02, "km": 0.01, "mu_s": 0.15}
MOTION_SD = {**SD, "restitution": 0.2, "theta0": math.radians(2)}


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--jarm", type=int, default=100_000, help="samples of the JARM question")
    p.add_argument("--motion", type=int, default=1_000_000, help="samples of the full motion")
    p.add_argument("--map", type=int, default=2000, help="samples per point of the map (0: none)")
    p.add_argument("--threads", type=int, default=0, help="threads (0: every core)")
    p.add_argument("--integrator", default="RK45", choices=("RK45", "DOP853", "Vern9"))
    results.add_json_option(p, "uncertainty")
    args = p.parse_args(argv)
    body = eccjump.Cylinder(0.15, 0.02)
    eccjump.uncertainty(body, math.radians(40), 1.0, sd=SD, n=10)  # imports scipy
    t0 = time.perf_counter()
    j = eccjump.uncertainty(body, math.radians(40), 1.0, sd=SD, n=args.jarm, n_threads=args.threads)
    t_jarm = time.perf_counter() - t0
    print(f"cores: {os.cpu_count()}, load {os.getloadavg()[0]:.1f}")
    print(f"jarm    {args.jarm:>8} samples {t_jarm:8.2f} s   P(JARM) = {j.p_jarm:.5f}")
    t0 = time.perf_counter()
    m = eccjump.uncertainty(body, math.radians(40), 1.0, sd=MOTION_SD, n=args.motion,
                            question="motion", integrator=args.integrator,
                            n_threads=args.threads)  # fmt: skip
    t_motion = time.perf_counter() - t0
    print(f"motion  {args.motion:>8} samples {t_motion:8.2f} s   P(JARM) = {m.p_jarm:.5f}  "
          f"({args.integrator}, {t_motion / args.motion * 1e6:.1f} us per sample)")  # fmt: skip
    t_map, mean = _map(args.map, args.threads)
    results.write(
        args.json,
        "uncertainty",
        args,
        jarm_samples=args.jarm,
        jarm_s=t_jarm,
        motion_samples=args.motion,
        motion_s=t_motion,
        p_jarm_closed_form=j.p_jarm,
        p_jarm_motion=m.p_jarm,
        map_samples=args.map,
        map_s=t_map,
        map_mean_p_jarm=mean,
        load=os.getloadavg()[0],
    )
    return 0


def _map(n: int, threads: int) -> tuple[float, float]:
    """Seconds and mean P(JARM) of the 20 x 20 x 4 map with ``n`` samples per point."""
    if n <= 0:
        return math.nan, math.nan
    axes = (np.radians(np.linspace(30, 50, 20)), np.linspace(0.05, 0.3, 20), np.linspace(0, 0.1, 4))
    sd = {"alpha": math.radians(0.25), "chi": 0.002}
    t0 = time.perf_counter()
    u = eccjump.uncertainty_map(*axes, 1.0, sd=sd, n=n, n_threads=threads)
    seconds = time.perf_counter() - t0
    calls = 1600 * n
    print(f"map     {calls:>8} samples {seconds:8.2f} s   mean P(JARM) = {u.fraction():.5f}")
    return seconds, u.fraction()


if __name__ == "__main__":
    raise SystemExit(main())

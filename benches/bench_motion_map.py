"""Motion maps (eccjump.motion_map, each point to its first landing) against the
straightforward scipy solve_ivp event-driven model of tests/reference_motion.py, side by side
in one run.

    python benches/bench_motion_map.py [--grid 100] [--sample 40] [--threads 0]
                                       [--integrator DOP853] [--json PATH]

eccjump maps the whole grid (alpha in [1, 89] deg, chi and the km fraction in [0.02, 0.98],
mu_s = 1; --grid 100 is 10^6 points) with every core; the scipy model runs a random sample
of the same points one after the other, each to the same transition as eccjump's run (the
mode after the first landing), and its rate is extrapolated. Also checked on the sample: both
give the same sequence of modes. Memory: the map holds 73 bytes per point. The figures also
go to ``--json`` (default bench_motion_map.json in the current directory).
"""

from __future__ import annotations

import argparse
import os
import sys
import time
from pathlib import Path

import numpy as np
import results

sys.path.insert(0, str(Path(__file__).resolve().parent.parent / "tests"))

from reference_motion import simulate_reference

import eccjump
from eccjump.motion.fields import sequence_name


def main(argv: list[str] | None = None) -> int:
    p = argparse.ArgumentParser(description=__doc__.splitlines()[0])
    p.add_argument("--grid", type=int, default=100, help="points per axis (100: 10^6 points)")
    p.add_argument("--sample", type=int, default=40, help="points run by the scipy model")
    p.add_argument("--threads", type=int, default=0, help="eccjump threads (0: every core)")
    p.add_argument("--integrator", default="RK45", choices=("RK45", "DOP853", "Vern9"))
    results.add_json_option(p, "motion_map")
    args = p.parse_args(argv)
    n = args.grid
    alpha = np.radians(np.linspace(1.0, 89.0, n))
    chi = np.linspace(0.02, 0.98, n)
    frac = np.linspace(0.02, 0.98, n)
    t0 = time.perf_counter()
    m = eccjump.motion_map(
        alpha=alpha,
        chi=chi,
        km_frac=frac,
        mu_s=1.0,
        n_threads=args.threads,
        integrator=args.integrator,
    )
    t_map = time.perf_counter() - t0
    assert isinstance(m, eccjump.MotionMap)
    points = m.jarm.size
    rate = points / t_map
    print(
        f"cores: {os.cpu_count()}, grid {n}^3 = {points} points, mu_s = 1, e = 0, {args.integrator}"
    )
    print(f"eccjump  {t_map:8.2f} s   {rate:12.0f} points/s")

    rng = np.random.default_rng(7)
    idx = [tuple(rng.integers(0, n, 3)) for _ in range(args.sample)]
    same = 0
    t_ref = 0.0
    for ia, ic, ik in idx:
        c = chi[ic]
        km = frac[ik] * (1.0 - c)
        want = int(m.n_modes[ia, ic, ik])
        t0 = time.perf_counter()
        ref = simulate_reference(
            c, km, alpha[ia], mu_s=1.0, t_max=100.0, max_transitions=max(1, want - 1)
        )
        t_ref += time.perf_counter() - t0
        modes = [tr[2] for tr in ref["transitions"]][:8]
        same += "→".join(modes) == sequence_name(m.sequence[ia, ic, ik])
    ref_rate = args.sample / t_ref if t_ref > 0 else float("nan")
    print(f"scipy    {t_ref / args.sample * 1e3:8.2f} ms/point {ref_rate:9.1f} points/s (1 core)")
    print(f"same sequence on {same} of {args.sample} sampled points")
    print(f"speed-up: {rate / ref_rate:.0f}x points/s")
    top = list(m.sequences().values())[:5]
    print("sequences:", ", ".join(f"{nm or '-'} {k}" for nm, k in top))
    results.write(
        args.json,
        "motion_map",
        args,
        points=points,
        threads=args.threads or os.cpu_count(),
        eccjump_s=t_map,
        eccjump_points_per_s=rate,
        scipy_ms_per_point=t_ref / args.sample * 1e3 if args.sample else None,
        scipy_points_per_s=ref_rate,
        same_sequence=same,
        sampled=args.sample,
        speed_up=rate / ref_rate,
        top_sequences=[{"sequence": nm or "-", "points": k} for nm, k in top],
    )
    return 0


if __name__ == "__main__":
    sys.exit(main())

"""Region map (the paper's Fig. 4 computation): eccjump.region against hand-written numpy/scipy.

For each route (``closed_form``, ``ode``) eccjump maps the full N x N x N grid
(alpha = i pi/(2N), i = 1..N; chi = (j + 1/2)/N; k_m/(1 - chi) = l/N; mu_s = 1, automatic n,
paper's rule, from rest at theta0 = 0) and the baseline of ``baseline_numpy.py`` classifies a
random subsample of the same grid, point by point. Prints points per second on both sides,
the speed-up, eccjump's peak RSS, and how often the two agree on the subsample.

Run:  python benches/bench_region.py [--grid 100] [--baseline-points 300] [--ode-points 50]
                                    [--repeat 3] [--routes closed_form,ode] [--json PATH]

The figures also go to --json (default bench_region.json in the current directory).
"""

from __future__ import annotations

import argparse
import math
import os
import platform
import sys
import time
from pathlib import Path

import numpy as np
import results

import eccjump
from eccjump.classification.classify import FIELDS

sys.path.insert(0, str(Path(__file__).resolve().parent))
import baseline_numpy as bl

MU_S = 1.0


def grid(n: int) -> tuple[np.ndarray, np.ndarray, np.ndarray]:
    # linspace ends exactly at pi/2; i * (pi / 2n) overshot it by an ulp for i = n, and those
    # 1 % of the points came back INVALID_PARAMS.
    alpha = np.linspace(math.pi / (2 * n), math.pi / 2, n)
    chi = (np.arange(n) + 0.5) / n
    frac = np.arange(n) / n
    return alpha, chi, frac


def _proc_status(key: str) -> float:
    """VmRSS / VmHWM of this process [MiB] (Linux), NaN elsewhere."""
    try:
        with open("/proc/self/status") as f:
            for line in f:
                if line.startswith(key + ":"):
                    return int(line.split()[1]) / 1024
    except OSError:
        pass
    return math.nan


def _reset_peak_rss() -> bool:
    """Reset VmHWM to the current RSS (Linux >= 4.0: write 5 to clear_refs)."""
    try:
        with open("/proc/self/clear_refs", "w") as f:
            f.write("5")
        return True
    except OSError:
        return False


def time_eccjump(method: str, alpha, chi, frac, threads: int, repeat: int):
    """(wall, CPU) seconds of the fastest of `repeat` eccjump.region runs (CPU summed over
    threads), the last Region, RSS before and peak RSS during the runs [MiB] (NaN if the
    peak cannot be reset)."""
    eccjump.region(
        mu_s=MU_S, alpha=alpha[:4], chi=chi[:4], km_frac=frac[:4], method=method
    )  # warm-up
    rss0 = _proc_status("VmRSS")
    can_reset = _reset_peak_rss()
    best, reg = (math.inf, math.inf), None
    for _ in range(repeat):
        reg = None  # free the previous map first
        t0, c0 = time.perf_counter(), time.process_time()
        reg = eccjump.region(
            mu_s=MU_S, alpha=alpha, chi=chi, km_frac=frac, method=method, n_threads=threads
        )
        best = min(best, (time.perf_counter() - t0, time.process_time() - c0))
    peak = _proc_status("VmHWM") if can_reset else math.nan
    return best, reg, rss0, peak


def subsample(alpha, chi, frac, k: int, seed: int):
    rng = np.random.default_rng(seed)
    n = alpha.size * chi.size * frac.size
    flat = rng.choice(n, size=min(k, n), replace=False)
    ia, ic, ik = np.unravel_index(flat, (alpha.size, chi.size, frac.size))
    return ia, ic, ik


def time_baseline(method: str, a, c, k):
    fn = bl.classify_closed_form if method == "closed_form" else bl.classify_ode
    reasons = np.empty(a.size, int)
    thj = np.empty(a.size)
    t0, c0 = time.perf_counter(), time.process_time()
    for i in range(a.size):
        v = fn(float(a[i]), float(c[i]), float(k[i]), MU_S)
        reasons[i], thj[i] = v.reason, v.theta_J
    return (time.perf_counter() - t0, time.process_time() - c0), reasons, thj


def main() -> None:
    p = argparse.ArgumentParser(description=__doc__, formatter_class=argparse.RawTextHelpFormatter)
    p.add_argument("--grid", type=int, default=100, help="N of the N x N x N grid (100)")
    p.add_argument(
        "--baseline-points", type=int, default=300, help="closed-form baseline subsample (300)"
    )
    p.add_argument("--ode-points", type=int, default=50, help="solve_ivp baseline subsample (50)")
    p.add_argument("--threads", type=int, default=0, help="eccjump threads, 0 = all cores (0)")
    p.add_argument("--repeat", type=int, default=3, help="eccjump runs, best time (3)")
    p.add_argument("--seed", type=int, default=1)
    p.add_argument(
        "--routes", default="closed_form,ode", help="comma-separated routes (closed_form,ode)"
    )
    results.add_json_option(p, "region")
    args = p.parse_args()
    load = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3

    alpha, chi, frac = grid(args.grid)
    npts = alpha.size * chi.size * frac.size
    print(
        f"machine: {platform.machine()}, {os.cpu_count()} logical CPUs, "
        f"python {platform.python_version()}, numpy {np.__version__}, "
        f"eccjump {eccjump.__version__}"
    )
    print(
        f"grid: {args.grid}^3 = {npts} points, alpha in (0, 90 deg], chi in (0, 1), "
        f"frac in [0, 1), mu_s = {MU_S:g}, automatic n, rule = paper; "
        f"eccjump threads = {args.threads or os.cpu_count()}"
    )
    rows = []
    notes = []
    for method in args.routes.split(","):
        k = args.baseline_points if method == "closed_form" else args.ode_points
        (t_ecc, c_ecc), reg, rss0, peak = time_eccjump(
            method, alpha, chi, frac, args.threads, max(1, args.repeat)
        )
        invalid = int(np.sum(reg.result.reason == eccjump.Reason.INVALID_PARAMS))
        stub = invalid == npts
        if invalid and not stub:  # a grid point out of range is not a classified point
            raise SystemExit(f"{method}: {invalid} grid points are INVALID_PARAMS: fix the grid")
        njarm = int(reg.is_jarm.sum())
        ia, ic, ik = subsample(alpha, chi, frac, k, args.seed)
        a, c = alpha[ia], chi[ic]
        km = frac[ik] * (1.0 - c)
        (t_bl, c_bl), reasons, thj = time_baseline(method, a, c, km)
        # agreement with eccjump on the subsample (the closed-form map if this route is a stub)
        ref_reason = reg.result.reason[ia, ic, ik].astype(int)
        ref_thj = reg.result.theta_J[ia, ic, ik]
        if stub:
            ref = eccjump.jarm(a, c, km, MU_S)
            ref_reason, ref_thj = ref.reason.astype(int), ref.theta_J
            notes.append(
                f"{method}: eccjump returns INVALID_PARAMS for every point (route not "
                "implemented in this checkout); its time is of the stub, no speed-up given; "
                "baseline agreement is against the closed-form route"
            )
        same_j = int(np.sum((reasons == 0) == (ref_reason == 0)))
        same_r = int(np.sum(reasons == ref_reason))
        both = (reasons == 0) & (ref_reason == 0)
        dth = float(np.max(np.abs(thj[both] - ref_thj[both]))) if both.any() else math.nan
        pps_ecc = npts / t_ecc
        pps_bl = k / t_bl
        out_mib = sum(getattr(reg.result, f).nbytes for f in FIELDS) / 2**20
        del reg  # so that the next route's RSS starts without this map
        rows.append(
            dict(m=method, te=t_ecc, pe=pps_ecc, nj=njarm, k=k, tb=t_bl, pb=pps_bl, stub=stub)
            | dict(ce=c_ecc, cb=c_bl)
            | dict(
                sj=same_j,
                sr=same_r,
                dth=dth,
                nboth=int(both.sum()),
                peak=peak,
                rss0=rss0,
                out=out_mib,
            )
        )

    print()
    hdr = (
        f"{'route':<12}{'side':<10}{'points':>9}{'wall s':>9}{'CPU s':>9}{'pts/s (wall)':>14}"
        f"{'pts/CPU-s':>12}{'speed-up wall':>15}{'per CPU-s':>11}{'JARMs':>7}{'agree':>14}"
    )
    print(hdr)
    print("-" * len(hdr))
    for r in rows:
        pc_e, pc_b = npts / r["ce"], r["k"] / r["cb"]
        if r["stub"]:
            sw = sc = "n/a (stub)"
        else:
            sw, sc = f"{r['pe'] / r['pb']:,.0f}x", f"{pc_e / pc_b:,.0f}x"
        print(
            f"{r['m']:<12}{'eccjump':<10}{npts:>9}{r['te']:>9.3f}{r['ce']:>9.3f}{r['pe']:>14,.0f}"
            f"{pc_e:>12,.0f}{sw:>15}{sc:>11}{r['nj']:>7}"
        )
        agree = f"{r['sj']}/{r['k']}, {r['sr']}/{r['k']}"
        print(
            f"{'':<12}{'baseline':<10}{r['k']:>9}{r['tb']:>9.3f}{r['cb']:>9.3f}{r['pb']:>14,.1f}"
            f"{pc_b:>12,.1f}{'':>15}{'':>11}{'':>7}{agree:>14}"
        )
    print(
        "agree: baseline = eccjump on is_jarm, on the reason code (subsample); largest "
        "|theta_J difference| of common JARMs: "
        + ", ".join(f"{r['m']} {r['dth']:.1e} rad ({r['nboth']} JARMs)" for r in rows)
    )
    print()
    for r in rows:
        print(
            f"{r['m']}: eccjump peak RSS {r['peak']:.0f} MiB (RSS before the map "
            f"{r['rss0']:.0f} MiB, so +{r['peak'] - r['rss0']:.0f} MiB; the returned arrays "
            f"are {r['out']:.0f} MiB)"
        )
    load2 = os.getloadavg() if hasattr(os, "getloadavg") else (math.nan,) * 3
    print(f"load average (1 min) at start {load[0]:.2f}, at end {load2[0]:.2f}")
    for n in notes:
        print("note:", n)
    results.write(
        args.json,
        "region",
        args,
        grid_points=npts,
        threads=args.threads or os.cpu_count(),
        routes=[
            {
                "route": r["m"],
                "eccjump": {
                    "points": npts,
                    "wall_s": r["te"],
                    "cpu_s": r["ce"],
                    "points_per_s": r["pe"],
                    "points_per_cpu_s": npts / r["ce"],
                    "jarms": r["nj"],
                    "rss_before_mib": r["rss0"],
                    "peak_rss_mib": r["peak"],
                    "returned_arrays_mib": r["out"],
                    "stub": r["stub"],
                },
                "baseline": {
                    "points": r["k"],
                    "wall_s": r["tb"],
                    "cpu_s": r["cb"],
                    "points_per_s": r["pb"],
                    "points_per_cpu_s": r["k"] / r["cb"],
                },
                "speed_up_wall": None if r["stub"] else r["pe"] / r["pb"],
                "speed_up_per_cpu_s": None if r["stub"] else (npts / r["ce"]) / (r["k"] / r["cb"]),
                "agree_is_jarm": r["sj"],
                "agree_reason": r["sr"],
                "max_theta_J_diff_rad": r["dth"],
                "common_jarms": r["nboth"],
            }
            for r in rows
        ],
        load_average_end=load2[0],
        notes=notes,
    )


if __name__ == "__main__":
    main()
